//! The one error type of ldh-core.
//!
//! Every variant says what went wrong and where: the file (when there is one), the line and
//! column (1-based, counted in the file as a text editor shows it), and the offending value.
//! The CLI prints these messages as they are; the Python binding maps them onto `ValueError`,
//! `FileNotFoundError`/`OSError` and the `ldh.LdhError` family by [`LdhError::kind`].
//!
//! A value echoed from the input (a cell, a column name, an id, a parameter's value) is cut to
//! [`ECHO_CHARS`] characters by [`clip`] when the message is printed, and a free-text reason
//! that may quote the input (a TOML or JSON parser's message) to [`REASON_CHARS`]: a 50 MB cell
//! makes a one-line message, not 50 MB of output.

use std::num::{NonZeroU32, NonZeroU64};
use std::path::{Path, PathBuf};

/// Result alias used throughout ldh-core.
pub type Result<T, E = LdhError> = std::result::Result<T, E>;

/// The most characters of a value echoed in a message (a cell, a column name, an id): 60.
pub const ECHO_CHARS: usize = 60;
/// The most characters of the first row of a file without a header row echoed in its message:
/// 200 (enough to see what the file holds).
const FIRST_ROW_CHARS: usize = 200;
/// The most characters of a free-text reason that may quote the input (a parser's message): 600.
pub const REASON_CHARS: usize = 600;

/// `s` as a message echoes it: itself when it has at most `max_chars` characters, else its
/// first `max_chars` characters, `…` and its length (`1234567… (52428800 characters)`). Every
/// message that echoes input uses it (with [`ECHO_CHARS`] for a value, [`REASON_CHARS`] for a
/// reason); what a message says must stay short whatever the input holds.
pub fn clip_to(s: &str, max_chars: usize) -> std::borrow::Cow<'_, str> {
    match s.char_indices().nth(max_chars) {
        None => std::borrow::Cow::Borrowed(s),
        Some((cut, _)) => {
            std::borrow::Cow::Owned(format!("{}… ({} characters)", &s[..cut], s.chars().count()))
        }
    }
}

/// A value as a message echoes it: [`clip_to`] with [`ECHO_CHARS`].
pub fn clip(s: &str) -> std::borrow::Cow<'_, str> {
    clip_to(s, ECHO_CHARS)
}

/// The operating system's error as messages say it: one wording for a path that does not exist
/// (`no such file or folder`) and for a refused permission (`permission denied`), whichever
/// command or platform meets them; other errors as the system words them.
fn io_reason(e: &std::io::Error) -> std::borrow::Cow<'_, str> {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file or folder".into(),
        std::io::ErrorKind::PermissionDenied => "permission denied".into(),
        _ => std::borrow::Cow::Owned(clip_to(&e.to_string(), REASON_CHARS).into_owned()),
    }
}

/// Names as a message lists them (`["a", "b"]`), each cut by [`clip`], at most 12 of them (then
/// `… (N in all)`).
fn clip_names(names: &[String]) -> String {
    let mut v: Vec<String> = names
        .iter()
        .take(12)
        .map(|n| format!("{:?}", clip(n)))
        .collect();
    if names.len() > 12 {
        v.push(format!("… ({} in all)", names.len()));
    }
    format!("[{}]", v.join(", "))
}

/// Positions as a message lists them, at most 12 (then `… (N in all)`).
fn clip_positions(p: &[usize]) -> String {
    let mut v: Vec<String> = p.iter().take(12).map(|n| n.to_string()).collect();
    if p.len() > 12 {
        v.push(format!("… ({} in all)", p.len()));
    }
    format!("[{}]", v.join(", "))
}

/// Where in an input file something was found.
///
/// `line` and `column` are 1-based; `column` counts delimited fields, not characters.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file (or a label such as `<memory>` for in-memory input).
    pub file: PathBuf,
    /// 1-based line number in the file, if known.
    pub line: Option<NonZeroU64>,
    /// 1-based field (column) number, if known.
    pub column: Option<NonZeroU32>,
}

impl Location {
    /// A location naming only the file.
    pub fn file(file: impl AsRef<Path>) -> Self {
        Location {
            file: file.as_ref().to_path_buf(),
            line: None,
            column: None,
        }
    }
    /// A location naming file and line.
    pub fn line(file: impl AsRef<Path>, line: u64) -> Self {
        Location {
            line: NonZeroU64::new(line),
            ..Location::file(file)
        }
    }
    /// A location naming file, line and column.
    pub fn cell(file: impl AsRef<Path>, line: u64, column: usize) -> Self {
        Location {
            line: NonZeroU64::new(line),
            column: NonZeroU32::new(u32::try_from(column).unwrap_or(u32::MAX)),
            ..Location::file(file)
        }
    }
}

impl std::fmt::Display for Location {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(l) = self.line {
            write!(f, ":{l}")?;
            if let Some(c) = self.column {
                write!(f, ":{c}")?;
            }
        }
        Ok(())
    }
}

/// Broad class of an error, used by the bindings to choose an exception type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// The file does not exist.
    NotFound,
    /// Any other operating-system I/O failure (permissions, a directory, a loop of links…).
    Io,
    /// The file's content is not a usable recording (format, values, timing).
    Data,
    /// A parameter or argument is invalid.
    Param,
}

/// Everything that can go wrong in ldh-core.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LdhError {
    /// A file is larger than the reader's limit (`max_file_size_mb`).
    #[error("{}: the file has {size_mb:.0} MB, above the limit of {limit_mb} MB (raise it with --max-file-size-mb or `max_file_size_mb`)", path.display())]
    FileTooLarge {
        /// The file.
        path: PathBuf,
        /// Its size, MB (at least this much when the size was not known in advance).
        size_mb: f64,
        /// The limit, MB.
        limit_mb: f64,
    },
    /// A recording has more samples than `max_samples` (the memory of its analysis grows with
    /// them); refused while reading, before the samples past the limit are stored.
    #[error("{}: {rows} data rows, above the limit of {limit} samples per recording (the analysis takes about 150 bytes of memory per sample); raise it with --max-samples or `max_samples`, or split the recording", path.display())]
    TooManySamples {
        /// The file.
        path: PathBuf,
        /// Its data rows (counted to the end of the file).
        rows: u64,
        /// The limit, samples.
        limit: usize,
    },
    /// A file read whole (a parameter file, column map, manifest, model, or a table read back) is
    /// larger than its kind's limit (docs/robustness.md, "Size limits").
    #[error("{}: {what} of {size_mb:.1} MB, above the limit of {limit_mb} MB for {what} (docs/robustness.md, \"Size limits\")", path.display())]
    TextTooLarge {
        /// The file.
        path: PathBuf,
        /// Its role (`a model file`).
        what: &'static str,
        /// Its size, MB (at least this much when the size was not known in advance).
        size_mb: f64,
        /// The limit, MB.
        limit_mb: f64,
    },
    /// A line of a recording (or of a cohort manifest) is longer than
    /// [`crate::io::MAX_LINE_BYTES`]; a recording's is refused while it streams, before more than
    /// the limit is held.
    #[error("{loc}: the line is longer than {limit_bytes} bytes, the most a line of a recording or manifest may hold (a row of either has a few hundred): a file without line ends, or a runaway cell?")]
    LineTooLong {
        /// The file and the line.
        loc: Location,
        /// The limit, bytes (line ending included).
        limit_bytes: usize,
    },
    /// The memory to read a file could not be had (its buffers are reserved fallibly, so one
    /// huge recording fails alone instead of aborting the batch).
    #[error("{}: not enough memory to read it ({needed_mb:.0} MB more were needed); analyse it alone, on a machine with more memory, or split it", path.display())]
    OutOfMemory {
        /// The file.
        path: PathBuf,
        /// The allocation that failed, MB.
        needed_mb: f64,
    },
    /// Opening or reading a file failed.
    #[error("{}: cannot read: {}", path.display(), io_reason(source))]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// The file holds no data at all.
    #[error("{}: the file is empty", path.display())]
    EmptyFile {
        /// The file.
        path: PathBuf,
    },
    /// The file looks like binary data, not text: a control byte in its first 64 KiB, or a NUL
    /// byte anywhere.
    #[error("{loc}: this is not a text file (byte 0x{byte:02x} at offset {offset}); expected a CSV export")]
    Binary {
        /// The file and the line of the byte.
        loc: Location,
        /// Offset of the first offending byte.
        offset: u64,
        /// The offending byte.
        byte: u8,
    },
    /// The text is not valid UTF-8.
    #[error("{loc}: the text is not valid UTF-8 (offset {offset}); re-export the file as UTF-8")]
    NotUtf8 {
        /// Where.
        loc: Location,
        /// Byte offset of the first invalid sequence.
        offset: u64,
    },
    /// The text is UTF-16 (with or without a byte-order mark), a common spreadsheet export.
    #[error("{}: the text is UTF-16 ({}), not valid UTF-8; re-export the file as UTF-8", path.display(), if *big_endian { "big-endian" } else { "little-endian" })]
    Utf16 {
        /// The file.
        path: PathBuf,
        /// Byte order.
        big_endian: bool,
    },
    /// No header row with the expected columns was found.
    #[error("{}: no header row with the expected columns; missing {} (format '{}'){}. First row seen: {:?}", path.display(), clip_names(missing), clip_to(format, REASON_CHARS), clip_to(hint, REASON_CHARS), clip_to(first_row, FIRST_ROW_CHARS))]
    NoHeader {
        /// The file.
        path: PathBuf,
        /// The format that was tried (the closest one, when detecting).
        format: String,
        /// The columns that were not found.
        missing: Vec<String>,
        /// The header's names closest to the missing ones (`; closest in the header: ...`).
        hint: String,
        /// The first non-comment row of the file, for the message.
        first_row: String,
    },
    /// Required columns are missing from the header.
    #[error(
        "{loc}: missing column(s) {} required by {}",
        clip_names(missing),
        clip_to(by, REASON_CHARS)
    )]
    MissingColumn {
        /// Where (the header line).
        loc: Location,
        /// The columns not found.
        missing: Vec<String>,
        /// What requires them, then the header's closest names or what is accepted
        /// (`format 'ldh'; closest in the header: acc_x → AccX`).
        by: String,
    },
    /// A header names a column that is not accepted there (a typo would otherwise be ignored).
    #[error(
        "{loc}: unknown column '{}' in {}; accepted: {}",
        clip(column),
        clip_to(what, REASON_CHARS),
        clip_to(accepted, REASON_CHARS)
    )]
    UnknownColumn {
        /// Where (the header line and column).
        loc: Location,
        /// The column name.
        column: String,
        /// What the header belongs to (`the cohort manifest`).
        what: String,
        /// The accepted names, comma-separated.
        accepted: String,
    },
    /// A given map's fixed delimiter does not split a row that holds its columns at another
    /// delimiter (an Xsens map with tabs on a comma-separated export).
    #[error("{loc}: {}", clip_to(detail, REASON_CHARS))]
    DelimiterMismatch {
        /// Where (the header line).
        loc: Location,
        /// What differs and the fix, in words.
        detail: String,
    },
    /// A column the format reads occurs more than once in the header: neither may silently win.
    #[error("{loc}: column '{}' occurs {} times in the header (columns {}); rename the copies or, for one block of columns per sensor, set [sensor] block in the format", clip(column), positions.len(), clip_positions(positions))]
    DuplicateColumn {
        /// Where (the header line).
        loc: Location,
        /// The column name.
        column: String,
        /// Its 1-based positions.
        positions: Vec<usize>,
    },
    /// A row has fewer or more fields than the header.
    #[error(
        "{loc}: row has {found} fields, the header has {expected}{}",
        clip_to(hint, REASON_CHARS)
    )]
    FieldCount {
        /// Where.
        loc: Location,
        /// Fields in this row.
        found: usize,
        /// Fields in the header.
        expected: usize,
        /// Extra advice (e.g. about decimal commas), empty or starting with "; ".
        hint: String,
    },
    /// A cell that must hold a number does not.
    #[error(
        "{loc}: column '{}': '{}' is not a number{}",
        clip(column),
        clip(value),
        clip_to(hint, REASON_CHARS)
    )]
    NotANumber {
        /// Where.
        loc: Location,
        /// Column name.
        column: String,
        /// The text found.
        value: String,
        /// Extra advice (e.g. about decimal commas), empty or starting with "; ".
        hint: String,
    },
    /// A cell holds a value that is not one of the accepted ones.
    #[error(
        "{loc}: column '{}': '{}' is not valid; expected {}",
        clip(column),
        clip(value),
        clip_to(expected, REASON_CHARS)
    )]
    InvalidValue {
        /// Where.
        loc: Location,
        /// Column name.
        column: String,
        /// The text found.
        value: String,
        /// What is accepted.
        expected: String,
    },
    /// A cell holds NaN or an infinity.
    #[error("{loc}: column '{}': non-finite value '{}'", clip(column), clip(value))]
    NonFinite {
        /// Where.
        loc: Location,
        /// Column name.
        column: String,
        /// The text found.
        value: String,
    },
    /// A finite value far beyond any sensor's range (above [`crate::io::MAX_ABS_SIGNAL`] in
    /// magnitude, e.g. `1e308`): a corrupted cell; it would overflow the arithmetic.
    #[error("{loc}: column '{}': value '{}' is beyond any sensor's range (magnitude above 1e12): a corrupted cell?", clip(column), clip(value))]
    OutOfRange {
        /// Where.
        loc: Location,
        /// Column name.
        column: String,
        /// The text found.
        value: String,
    },
    /// Timestamps go backwards or repeat.
    #[error("{loc}: timestamp {value} s is not after the previous one ({previous} s): timestamps must increase")]
    NonMonotonicTime {
        /// Where.
        loc: Location,
        /// This row's time.
        value: f64,
        /// The previous row's time.
        previous: f64,
    },
    /// A gap longer than the allowed maximum, with the reject policy.
    #[error("{loc}: gap of {gap_s:.3} s in the timestamps (from {from_s:.3} s) exceeds max_gap_s = {max_gap_s} s; use gap_policy = \"split\" to keep the longest segment")]
    Gap {
        /// Where (the row after the gap).
        loc: Location,
        /// Length of the gap.
        gap_s: f64,
        /// Time before the gap.
        from_s: f64,
        /// The allowed maximum.
        max_gap_s: f64,
    },
    /// Too few samples or too short a duration for gait analysis.
    #[error("{}: recording is too short: {duration_s:.2} s ({samples} samples); at least {min_s:.2} s are needed to hold three strides", path.display())]
    TooShort {
        /// The file.
        path: PathBuf,
        /// Its duration.
        duration_s: f64,
        /// Its number of samples.
        samples: usize,
        /// The required minimum.
        min_s: f64,
    },
    /// The sampling rate cannot be determined or is implausible.
    #[error("{}: sampling rate problem: {}", path.display(), clip_to(reason, REASON_CHARS))]
    SamplingRate {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// A value in the data is physically implausible (e.g. a unit mix-up).
    #[error("{}: implausible data: {}", path.display(), clip_to(reason, REASON_CHARS))]
    Implausible {
        /// The file.
        path: PathBuf,
        /// What is wrong and what to check.
        reason: String,
    },
    /// A format (column map) description is invalid.
    #[error(
        "format '{}': {}",
        clip_to(name, REASON_CHARS),
        clip_to(reason, REASON_CHARS)
    )]
    Format {
        /// The format's name or file.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// A parameter is outside its valid range.
    #[error(
        "invalid parameter {name} = {}: {}",
        clip(value),
        clip_to(reason, REASON_CHARS)
    )]
    Param {
        /// Parameter name (with unit).
        name: &'static str,
        /// The offending value, formatted.
        value: String,
        /// The rule it breaks.
        reason: String,
    },
    /// A signal is unusable for an algorithm (too short, wrong length…).
    #[error(
        "{}: {}",
        clip_to(context, REASON_CHARS),
        clip_to(reason, REASON_CHARS)
    )]
    Signal {
        /// Which step and signal.
        context: String,
        /// What is wrong.
        reason: String,
    },
    /// A model file is damaged, edited or does not fit the input (see [`crate::ml::model_check`]).
    #[error(transparent)]
    Model(Box<crate::ml::ModelError>),
    /// A statistical test is undefined for its input (see [`crate::stats`]).
    #[error(transparent)]
    Stats(#[from] crate::stats::StatsError),
    /// An agreement or reliability statistic, or an event matching, is undefined for its input
    /// (see [`crate::stats::agreement`]).
    #[error(transparent)]
    Agreement(#[from] crate::stats::agreement::AgreementError),
    /// A unit in a recording's header that ldh cannot use (unknown, of another quantity,
    /// missing or mixed; [`crate::io::UnitError`]), with its file, line and column.
    #[error(transparent)]
    Unit(Box<crate::io::UnitError>),
    /// A reference file for `ldh agree` that cannot be used, or a comparison that cannot be made
    /// (see [`crate::reference::ReferenceError`]).
    #[error(transparent)]
    Reference(Box<crate::reference::ReferenceError>),
    /// A nonlinear-dynamics computation is undefined for its input (see [`crate::nonlinear`]).
    #[error(transparent)]
    Nonlinear(#[from] crate::nonlinear::NonlinearError),
    /// A table could not be read or written as CSV.
    #[error("csv: {}", clip_to(&.0.to_string(), REASON_CHARS))]
    Csv(#[from] csv::Error),
    /// A value could not be read or written as JSON.
    #[error("json: {}", clip_to(&.0.to_string(), REASON_CHARS))]
    Json(#[from] serde_json::Error),
    /// The MLP classifier refused its parameters or data.
    #[error("mlp: {0}")]
    Mlp(#[from] crate::ml::mlp::MlpError),
    /// Writing output failed.
    #[error("{}: cannot write: {}", path.display(), clip_to(reason, REASON_CHARS))]
    Write {
        /// The file.
        path: PathBuf,
        /// What failed.
        reason: String,
    },
}

impl LdhError {
    /// Broad class of the error, for choosing an exception type in bindings.
    pub fn kind(&self) -> ErrorKind {
        match self {
            LdhError::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
                ErrorKind::NotFound
            }
            LdhError::Io { .. } | LdhError::Write { .. } => ErrorKind::Io,
            LdhError::Param { .. }
            | LdhError::Nonlinear(crate::nonlinear::NonlinearError::InvalidParameter { .. })
            | LdhError::Stats(crate::stats::StatsError::InvalidArgument { .. })
            | LdhError::Agreement(crate::stats::agreement::AgreementError::InvalidParam {
                ..
            }) => ErrorKind::Param,
            _ => ErrorKind::Data,
        }
    }

    /// Shorthand for a parameter error.
    pub fn param(
        name: &'static str,
        value: impl std::fmt::Display,
        reason: impl Into<String>,
    ) -> Self {
        LdhError::Param {
            name,
            value: value.to_string(),
            reason: reason.into(),
        }
    }

    /// Shorthand for a signal error.
    pub fn signal(context: impl Into<String>, reason: impl Into<String>) -> Self {
        LdhError::Signal {
            context: context.into(),
            reason: reason.into(),
        }
    }
}

impl From<crate::ml::ModelError> for LdhError {
    fn from(e: crate::ml::ModelError) -> Self {
        LdhError::Model(Box::new(e))
    }
}

#[cfg(test)]
mod tests;
