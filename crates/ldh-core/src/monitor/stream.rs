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
    /// A row that failed to parse, held until the next line says whether it was the last.
    pending_bad: Option<(u64, String)>,
    bad_rows: u64,
    first_bad: Option<(u64, String)>,
    truncated_last: Option<u64>,
    done: bool,
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
            pending_bad: None,
            bad_rows: 0,
            first_bad: None,
            truncated_last: None,
            done: false,
        })
    }

    fn parse(&self, line: &str, fields: &mut Vec<f64>) -> bool {
        fields.clear();
        for cell in line.split(self.delim as char) {
            match cell.trim().parse::<f64>() {
                Ok(v) if v.is_finite() => fields.push(v),
                _ => fields.push(f64::NAN),
            }
        }
        self.cols
            .iter()
            .all(|&c| fields.get(c).is_some_and(|v| v.is_finite()))
    }

    fn bad(&mut self, n: u64, line: String) {
        self.bad_rows += 1;
        if self.first_bad.is_none() {
            self.first_bad = Some((n, crate::error::clip(&line).into_owned()));
        }
    }
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
                if let Some((n, _)) = self.pending_bad.take() {
                    self.truncated_last = Some(n);
                }
                break;
            };
            let t = line.trim();
            let skip = t.is_empty() || t.starts_with(['#', '/', '%', ';']);
            let line = t.to_string();
            if let Some((bn, bl)) = self.pending_bad.take() {
                self.bad(bn, bl);
            }
            if skip {
                continue;
            }
            if !self.parse(&line, &mut fields) {
                self.pending_bad = Some((n, line));
                continue;
            }
            let c = self.cols;
            out.push(Sample {
                t_s: fields[c[0]],
                acc_g: [fields[c[1]], fields[c[2]], fields[c[3]]],
                gyro_dps: [fields[c[4]], fields[c[5]], fields[c[6]]],
            });
        }
        Ok(out.len())
    }
    fn notes(&self) -> Vec<String> {
        let mut notes = Vec::new();
        if let Some(n) = self.truncated_last {
            notes.push(format!(
                "{}:{n}: the last line is incomplete (the recorder stopped mid-write); it was dropped",
                self.path.display()
            ));
        }
        if let Some((n, l)) = &self.first_bad {
            notes.push(format!(
                "{}: {} row(s) were not six numbers and a time and were skipped, the first at line {n}: '{l}'",
                self.path.display(),
                self.bad_rows
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
