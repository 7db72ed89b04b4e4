//! Why a reference file, or its use against an `ldh analyze` output folder, is refused.

use crate::error::{clip, clip_to, LdhError, Location};

/// A reference file (`ldh agree --reference`) that cannot be used, or a comparison that cannot
/// be made. Each case names the file and, where there is one, the line (and column): what
/// `docs/agreement.md`, "Command line and Python", lists. [`crate::LdhError::Reference`] wraps
/// it (boxed). A fault of the table itself — a missing or unknown column, a cell that is not
/// what its column holds, a row of the wrong length — is not here: it is the one table
/// reader's [`LdhError`] (`MissingColumn`, `UnknownColumn`, `InvalidValue`, `NotANumber`,
/// `NonFinite`, `FieldCount`), worded as for every other table ldh reads.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ReferenceError {
    /// The file has no data rows.
    #[error("{loc}: the reference file has no data rows")]
    Empty {
        /// The file.
        loc: Location,
    },
    /// A subject (or subject and trial) the results do not have.
    #[error(
        "{loc}: subject '{}'{} is not in the results ({known})",
        clip(subject_id),
        trial_note(trial_id)
    )]
    UnknownSubject {
        /// File, line, column.
        loc: Location,
        /// The subject.
        subject_id: String,
        /// The trial, empty when the file has none.
        trial_id: String,
        /// What the results have (a few ids).
        known: String,
    },
    /// The subject has several trials in the results and the row does not say which.
    #[error(
        "{loc}: subject '{}' has several trials in the results ({trials}): add a trial_id column",
        clip(subject_id)
    )]
    AmbiguousTrial {
        /// File and line.
        loc: Location,
        /// The subject.
        subject_id: String,
        /// Its trials in the results.
        trials: String,
    },
    /// A time outside the recording (its duration, widened by the largest clock offset).
    #[error("{loc}: column '{column}': {value} s is outside the recording, [{low} s, {high} s] (its duration ± max_clock_offset_s)")]
    OutOfRange {
        /// File, line, column.
        loc: Location,
        /// The column.
        column: &'static str,
        /// The time, s.
        value: f64,
        /// Lowest allowed, s.
        low: f64,
        /// Highest allowed, s.
        high: f64,
    },
    /// A time earlier than the previous row's of the same subject, trial, side (and event).
    #[error("{loc}: {what}: {value} s is earlier than {previous} s on line {previous_line}; list the times of each subject, trial, side (and event) in ascending order")]
    OutOfOrder {
        /// File, line, column.
        loc: Location,
        /// The series, e.g. `S01 left HS`.
        what: String,
        /// The time, s.
        value: f64,
        /// The previous time, s.
        previous: f64,
        /// The previous row's line.
        previous_line: u64,
    },
    /// The same row twice (same time, or same stride, or the same recording).
    #[error("{loc}: duplicate row: {what} was already given on line {first_line}")]
    Duplicate {
        /// File and line.
        loc: Location,
        /// What is duplicated.
        what: String,
        /// The first row's line.
        first_line: u64,
    },
    /// Two rows of one trial give different clock offsets.
    #[error("{loc}: offset_s {value} s differs from {first} s given for the same trial on line {first_line}")]
    OffsetConflict {
        /// File, line, column.
        loc: Location,
        /// The offset, s.
        value: f64,
        /// The first offset, s.
        first: f64,
        /// Its line.
        first_line: u64,
    },
    /// The clock offset of a trial could not be estimated, or is ambiguous.
    #[error(
        "clock offset of subject '{}'{}: {reason}; give it with --offset-s or an offset_s column",
        clip(subject_id),
        trial_note(trial_id)
    )]
    Offset {
        /// The subject.
        subject_id: String,
        /// The trial.
        trial_id: String,
        /// Why.
        reason: String,
    },
    /// A walkway column map (`--walkway-map`) that cannot be used with its export: the TOML
    /// itself, or a column it names that the export's header lacks.
    #[error("{loc}: walkway column map: {}", clip_to(reason, 400))]
    Map {
        /// The map file (with the TOML's line and column), or the export's header line.
        loc: Location,
        /// What is wrong.
        reason: String,
    },
}

impl ReferenceError {
    /// Move the error's line and column (and the earlier line it cites) through `line` and
    /// `column` (1-based; `column` may drop it): a walkway export read through its column map
    /// is checked as long-form text, whose lines and columns are moved back to the export's
    /// (`walkway.rs`).
    pub(crate) fn relocate(
        &mut self,
        line: impl Fn(u64) -> u64,
        column: impl Fn(u32) -> Option<u32>,
    ) {
        use ReferenceError::*;
        let cited = match self {
            OutOfOrder { previous_line, .. } => Some(previous_line),
            Duplicate { first_line, .. } | OffsetConflict { first_line, .. } => Some(first_line),
            _ => None,
        };
        if let Some(l) = cited {
            *l = line(*l);
        }
        let loc = match self {
            Empty { loc }
            | UnknownSubject { loc, .. }
            | AmbiguousTrial { loc, .. }
            | OutOfRange { loc, .. }
            | OutOfOrder { loc, .. }
            | Duplicate { loc, .. }
            | OffsetConflict { loc, .. }
            | Map { loc, .. } => loc,
            Offset { .. } => return,
        };
        move_location(loc, line, column);
    }
}

/// [`ReferenceError::relocate`] for any error of the long-form reader: a reference error, or
/// a table fault of the one table reader (its location moved the same way).
pub(crate) fn relocate(
    e: LdhError,
    line: impl Fn(u64) -> u64,
    column: impl Fn(u32) -> Option<u32>,
) -> LdhError {
    let mut e = e;
    match &mut e {
        LdhError::Reference(b) => b.relocate(line, column),
        LdhError::MissingColumn { loc, .. }
        | LdhError::UnknownColumn { loc, .. }
        | LdhError::InvalidValue { loc, .. }
        | LdhError::NotANumber { loc, .. }
        | LdhError::NonFinite { loc, .. }
        | LdhError::FieldCount { loc, .. } => move_location(loc, line, column),
        _ => {}
    }
    e
}

fn move_location(
    loc: &mut Location,
    line: impl Fn(u64) -> u64,
    column: impl Fn(u32) -> Option<u32>,
) {
    use std::num::{NonZeroU32, NonZeroU64};
    loc.line = loc.line.and_then(|l| NonZeroU64::new(line(l.get())));
    loc.column = loc
        .column
        .and_then(|c| column(c.get()).and_then(NonZeroU32::new));
}

fn trial_note(trial_id: &str) -> String {
    if trial_id.is_empty() {
        String::new()
    } else {
        format!(", trial '{}'", clip(trial_id))
    }
}

/// A [`ReferenceError`] as an [`LdhError`].
pub(crate) fn boxed(e: ReferenceError) -> LdhError {
    LdhError::Reference(Box::new(e))
}
