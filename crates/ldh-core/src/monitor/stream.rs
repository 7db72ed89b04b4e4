//! Samples of a long recording, a chunk at a time: ldh's CSV (`time_s, acc_x … gyro_z`, g and
//! deg/s, as `ldh simulate` and `ldh convert` write it) streamed line by line through the
//! reader's text layer (`io::text::Lines`: binary bytes, NUL, UTF-16, invalid UTF-8 and
//! overlong lines refused with the line), so only one chunk of samples is ever held.
//!
//! The lab reader (`io::read_recording`) reads a walk whole and fits one uniform grid to it;
//! a week cannot be held, so this reader yields the rows as they are and the monitor's leg
//! tracker (`monitor::leg`) handles what a week brings: gaps, jumps and rate. A row that is
//! not a row of numbers is skipped and counted (the first one named with its line), and a
//! truncated last line (a recorder stopped mid-write) is said and dropped: one bad line never
//! loses the week.

use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};

use crate::error::{LdhError, Location, Result};
use crate::io::start_time::start_in_comment;
use crate::io::text::Lines;
use crate::io::DateTime;

/// One sample: time on the file's own clock (s) and the six channels (g, deg/s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sample {
    /// Time, s, on the recording's own clock.
    pub t_s: f64,
    /// Acceleration x, y, z, g.
    pub acc_g: [f64; 3],
    /// Angular velocity x, y, z, deg/s.
    pub gyro_dps: [f64; 3],
}

/// A source of samples in time order, read a chunk at a time (ldh's CSV: [`CsvSamples`]; a
/// binary long-recording reader implements the same trait).
pub trait SampleSource: Send {
    /// A label for messages and tables (the file).
    fn label(&self) -> String;
    /// When the recording started, where the file says it.
    fn start(&self) -> Option<DateTime>;
    /// Clear `out` and fill it with up to `max` next samples; `Ok(0)`: the end.
    fn next_chunk(&mut self, max: usize, out: &mut Vec<Sample>) -> Result<usize>;
    /// What the reader skipped or assumed, one sentence each (read after the end).
    fn notes(&self) -> Vec<String>;
}

/// The columns of ldh's CSV, in channel order after the time.
const CHANNELS: [&str; 6] = ["acc_x", "acc_y", "acc_z", "gyro_x", "gyro_y", "gyro_z"];

/// ldh's CSV read a chunk at a time.
pub struct CsvSamples {
    lines: Lines<'static, BufReader<Box<dyn Read + Send>>>,
    path: PathBuf,
    delim: u8,
    /// Column of the time, then of each channel of [`CHANNELS`].
    cols: [usize; 7],
    start: Option<DateTime>,
    bad: BadRows,
    done: bool,
}

/// The rows that were not a time and six numbers.
#[derive(Default)]
struct BadRows {
    /// A row that failed to parse, held until the next line says whether it was the last.
    pending: Option<(u64, String)>,
    count: u64,
    first: Option<(u64, String)>,
    truncated_last: Option<u64>,
}

impl BadRows {
    /// A line followed the pending row: it was a bad row, not a truncated last line.
    fn settle(&mut self) {
        if let Some((n, line)) = self.pending.take() {
            self.count += 1;
            if self.first.is_none() {
                self.first = Some((n, crate::error::clip(&line).into_owned()));
            }
        }
    }
}

impl CsvSamples {
    /// Open `path` and read its header (comment lines before it may state the start date).
    ///
    /// # Errors
    /// The file cannot be opened or is not text, or no header names `time_s` and the six
    /// channels ([`LdhError::MissingColumn`] with the file).
    pub fn open(path: &Path) -> Result<Self> {
        let (file, _) = crate::io::open_regular(path, "recording")?;
        Self::from_reader(Box::new(file), path)
    }

    /// Read from any byte stream (`path` names it in messages).
    pub fn from_reader(src: Box<dyn Read + Send>, path: &Path) -> Result<Self> {
        // The label outlives the reader: leaked once per opened file (a few bytes).
        let leaked: &'static Path = Box::leak(path.to_path_buf().into_boxed_path());
        let mut lines = Lines::new(BufReader::with_capacity(1 << 18, src), leaked, None)?;
        let mut start = None;
        let (header, lineno) = loop {
            match lines.next_line()? {
                None => {
                    return Err(LdhError::EmptyFile {
                        path: path.to_path_buf(),
                    })
                }
                Some((n, l)) => {
                    let t = l.trim();
                    if t.is_empty() {
                        continue;
                    }
                    if t.starts_with(['#', '/', '%', ';']) {
                        start = start.or_else(|| start_in_comment(t));
                        continue;
                    }
                    break (t.to_string(), n);
                }
            }
        };
        let delim = crate::io::text::detect_delimiter(&header);
        let names: Vec<String> = header
            .split(delim as char)
            .map(|h| {
                let h = h.trim().trim_matches('"').to_ascii_lowercase();
                h.split([' ', '[', '(']).next().unwrap_or("").to_string()
            })
            .collect();
        let find = |want: &[&str]| names.iter().position(|n| want.contains(&n.as_str()));
        let mut cols = [0usize; 7];
        cols[0] = find(&["time_s", "time", "t", "timestamp_s"])
            .ok_or_else(|| missing(path, lineno, "time_s", &names))?;
        for (k, c) in CHANNELS.iter().enumerate() {
            cols[k + 1] = find(&[c]).ok_or_else(|| missing(path, lineno, c, &names))?;
        }
        Ok(CsvSamples {
            lines,
            path: path.to_path_buf(),
            delim,
            cols,
            start,
            bad: BadRows::default(),
            done: false,
        })
    }
}

/// `s.trim()`, without scanning for Unicode whitespace when both ends are ASCII and not
/// whitespace (every data row of ldh's CSV): the same slice in every case.
fn trim_ws(s: &str) -> &str {
    // char::is_whitespace among ASCII: \t \n \x0B \x0C \r and the space
    let plain = |c: u8| c < 0x80 && !matches!(c, b' ' | b'\t'..=b'\r');
    match s.as_bytes() {
        [f, .., l] if plain(*f) && plain(*l) => s,
        [c] if plain(*c) => s,
        _ => s.trim(),
    }
}

/// One cell as `cell.trim().parse::<f64>()` gives it, finite, else NaN; the common plain
/// decimal (`[-]digits[.digits]`, no spaces) by the reader's exact fast path (the same bits).
fn parse_cell(cell: &str) -> f64 {
    if let Some(v) = crate::io::number::parse_plain_decimal(cell) {
        return v;
    }
    match cell.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => v,
        _ => f64::NAN,
    }
}

/// A data row's sample: the time and six channels at `cols`, each a finite number; `None`
/// otherwise. `fields` is scratch space.
fn parse_row(line: &str, delim: u8, cols: &[usize; 7], fields: &mut Vec<f64>) -> Option<Sample> {
    fields.clear();
    // the cells after the last one used are never read
    let used = cols.iter().max().map_or(0, |c| c + 1);
    fields.extend(line.split(delim as char).take(used).map(parse_cell));
    if !cols
        .iter()
        .all(|&c| fields.get(c).is_some_and(|v| v.is_finite()))
    {
        return None;
    }
    let f = |k: usize| fields[cols[k]];
    Some(Sample {
        t_s: f(0),
        acc_g: [f(1), f(2), f(3)],
        gyro_dps: [f(4), f(5), f(6)],
    })
}

fn missing(path: &Path, line: u64, want: &str, names: &[String]) -> LdhError {
    LdhError::signal(
        Location::line(path, line).to_string(),
        format!(
            "`ldh monitor` reads ldh's CSV (time_s, acc_x … gyro_z in g and deg/s); no column '{want}' in the header ({}); convert a vendor file first with `ldh convert`",
            names.join(", ")
        ),
    )
}

impl SampleSource for CsvSamples {
    fn label(&self) -> String {
        self.path.display().to_string()
    }
    fn start(&self) -> Option<DateTime> {
        self.start
    }
    fn next_chunk(&mut self, max: usize, out: &mut Vec<Sample>) -> Result<usize> {
        out.clear();
        let mut fields = Vec::with_capacity(8);
        while out.len() < max && !self.done {
            let Some((n, line)) = self.lines.next_line()? else {
                self.done = true;
                if let Some((n, _)) = self.bad.pending.take() {
                    self.bad.truncated_last = Some(n);
                }
                break;
            };
            let t = trim_ws(line);
            self.bad.settle();
            if t.is_empty() || t.starts_with(['#', '/', '%', ';']) {
                continue;
            }
            match parse_row(t, self.delim, &self.cols, &mut fields) {
                Some(s) => out.push(s),
                None => self.bad.pending = Some((n, t.to_string())),
            }
        }
        Ok(out.len())
    }
    fn notes(&self) -> Vec<String> {
        let mut notes = Vec::new();
        if let Some(n) = self.bad.truncated_last {
            notes.push(format!(
                "{}:{n}: the last line is incomplete (the recorder stopped mid-write); it was dropped",
                self.path.display()
            ));
        }
        if let Some((n, l)) = &self.bad.first {
            notes.push(format!(
                "{}: {} row(s) were not six numbers and a time and were skipped, the first at line {n}: '{l}'",
                self.path.display(),
                self.bad.count
            ));
        }
        notes
    }
}

/// Samples already in memory (tests, Python arrays): yielded a chunk at a time.
#[derive(Debug, Clone)]
pub struct MemorySamples {
    /// The label.
    pub label: String,
    /// The samples.
    pub samples: Vec<Sample>,
    /// The start date, if any.
    pub start: Option<DateTime>,
    pos: usize,
}

impl MemorySamples {
    /// These samples under this label.
    pub fn new(label: impl Into<String>, samples: Vec<Sample>) -> Self {
        MemorySamples {
            label: label.into(),
            samples,
            start: None,
            pos: 0,
        }
    }
}

impl SampleSource for MemorySamples {
    fn label(&self) -> String {
        self.label.clone()
    }
    fn start(&self) -> Option<DateTime> {
        self.start
    }
    fn next_chunk(&mut self, max: usize, out: &mut Vec<Sample>) -> Result<usize> {
        out.clear();
        let end = (self.pos + max).min(self.samples.len());
        out.extend_from_slice(&self.samples[self.pos..end]);
        self.pos = end;
        Ok(out.len())
    }
    fn notes(&self) -> Vec<String> {
        Vec::new()
    }
}

#[cfg(test)]
mod tests {
    use super::{parse_cell, trim_ws};

    /// The fast trim is `str::trim` on every kind of end: ASCII whitespace (the vertical tab
    /// and form feed too), Unicode whitespace, non-ASCII text, one character, nothing.
    #[test]
    fn the_fast_trim_is_str_trim() {
        for s in [
            "",
            " ",
            "a",
            "é",
            "1.5,2",
            " 1,2 ",
            "\t1,2\r",
            "\x0b1,2\x0c",
            "1,2\u{a0}",
            "\u{2003}1,2",
            "é,1",
            "1,é",
            "\u{85}",
            "x\u{3000}",
            "#c",
            "\x1f1,2",
        ] {
            assert_eq!(trim_ws(s), s.trim(), "{s:?}");
        }
    }

    /// A cell gives `trim().parse::<f64>()`'s bits when finite, NaN otherwise.
    #[test]
    fn cells_parse_to_the_standard_librarys_bits() {
        for c in [
            "0",
            "-0",
            "-0.0000",
            "1.25",
            "12345.6789",
            "0.1",
            "-9.80665",
            "123456789012345",
            "1234567890123456",
            "0.30000000000000004",
            " 2.5",
            "2.5 ",
            "1e3",
            "+1",
            ".5",
            "5.",
            "1.2.3",
            "--1",
            "-",
            "",
            "nan",
            "inf",
            "-inf",
            "1e400",
            "abc",
            "\u{a0}3.5",
        ] {
            let want = match c.trim().parse::<f64>() {
                Ok(v) if v.is_finite() => v.to_bits(),
                _ => f64::NAN.to_bits(),
            };
            let got = parse_cell(c);
            if want == f64::NAN.to_bits() {
                assert!(got.is_nan(), "{c:?}");
            } else {
                assert_eq!(got.to_bits(), want, "{c:?}");
            }
        }
    }
}
