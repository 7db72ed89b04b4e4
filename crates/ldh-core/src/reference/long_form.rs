//! Reference files of `ldh agree`: a laboratory system's events or parameters in long, tidy
//! CSV (`docs/agreement.md`, "Command line and Python").
//!
//! - **Events** (the file has an `event` column): `subject_id[, trial_id], side, event, time_s`
//!   with `side` `left`|`right` and `event` `HS`|`TO`; one row per event.
//! - **Parameters** (no `event` column): `subject_id[, trial_id], side` and any of the
//!   parameter columns of `recordings.csv` (`stride_time_s`, `stride_length_m`, `stance_ratio`,
//!   `speed_mps`, …). With a `time_s` column (the stride's first heel strike; optional
//!   `end_time_s`, the heel strike ending it) or a `stride` column (ldh's stride number) a row
//!   is one stride, and only the per-stride parameters of `strides.csv` may appear; without
//!   either a row is one recording (one leg of one trial).
//! - Either kind may have an `offset_s` column: the clock offset of the trial, ldh clock −
//!   reference clock, s (the same on every row of a trial, or empty).
//!
//! Every row is checked against the results before anything is compared or written: an unknown
//! subject or trial, a time outside the recording (its duration ± `max_clock_offset_s`), times
//! out of order within a subject, trial, side (and event), duplicate rows, an empty file, an
//! unknown side or event, a cell that is not a finite number — each a [`ReferenceError`] naming
//! the file, the line and the column.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::error::{LdhError, Location, Result};
use crate::io::table::{CsvFault, Row, Table, TableFormat};
use crate::output::Parameter;
use crate::pipeline::EventKind;
use crate::Side;

use super::error::boxed;
use super::ReferenceError;
use crate::output::results::{GaitEvent, LdhResults, STRIDE_PARAMETERS};
use crate::stats::agreement::ValidAgreementParams;

/// One row of reference parameters: a stride, or a recording (one leg of one trial).
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceValues {
    /// Subject.
    pub subject_id: String,
    /// Trial, as in the results (empty without one).
    pub trial_id: String,
    /// Leg.
    pub side: Side,
    /// ldh's stride number, when the file gives one.
    pub stride: Option<usize>,
    /// The stride's first heel strike on the reference clock, s.
    pub time_s: Option<f64>,
    /// The heel strike ending the stride, s.
    pub end_time_s: Option<f64>,
    /// The values given (NaN: an empty cell).
    pub values: Vec<(Parameter, f64)>,
    /// File and line of the row.
    pub at: Location,
}

/// A trial's clock offset from a reference file's `offset_s` column.
#[derive(Debug, Clone, PartialEq)]
pub struct ReferenceOffset {
    /// Subject.
    pub subject_id: String,
    /// Trial.
    pub trial_id: String,
    /// ldh clock − reference clock, s.
    pub offset_s: f64,
    /// Where it was given.
    pub at: Location,
}

/// The reference files of one comparison, checked against the results.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Reference {
    /// The files read.
    pub files: Vec<PathBuf>,
    /// Events, in file order.
    pub events: Vec<GaitEvent>,
    /// Per-stride parameter rows.
    pub strides: Vec<ReferenceValues>,
    /// Per-recording parameter rows.
    pub recordings: Vec<ReferenceValues>,
    /// Clock offsets given per trial.
    pub offsets: Vec<ReferenceOffset>,
}

/// The key and option columns a reference file may have besides parameters.
const KEY_COLUMNS: [&str; 8] = [
    "subject_id",
    "trial_id",
    "side",
    "event",
    "time_s",
    "end_time_s",
    "stride",
    "offset_s",
];

/// Read reference files (events and/or parameters) and check them against `results`.
pub fn read_reference(
    paths: &[PathBuf],
    results: &LdhResults,
    params: &ValidAgreementParams,
) -> Result<Reference> {
    let mut reference = Reference::default();
    for p in paths {
        let text = crate::io::read_text_limited(p, crate::io::MAX_TABLE_MB, "a reference table")?;
        parse_reference(&text, p, results, params, &mut reference)?;
    }
    Ok(reference)
}

/// Header positions of one file.
struct Columns {
    subject: usize,
    trial: Option<usize>,
    side: usize,
    event: Option<usize>,
    time: Option<usize>,
    end_time: Option<usize>,
    stride: Option<usize>,
    offset: Option<usize>,
    params: Vec<(Parameter, usize)>,
}

/// One reference file's text (`file` names it in errors), checked against `results` and added
/// to `into`. Nothing is added when it fails.
pub fn parse_reference(
    text: &str,
    file: &Path,
    results: &LdhResults,
    params: &ValidAgreementParams,
    into: &mut Reference,
) -> Result<()> {
    if text.trim_start_matches('\u{feff}').trim().is_empty() {
        return Err(boxed(ReferenceError::Empty {
            loc: Location::file(file),
        }));
    }
    let format = TableFormat {
        trim: true,
        lowercase_header: true,
        ..TableFormat::default()
    };
    let unreadable = |f: CsvFault| f.into_error("");
    let table = Table::parse(text, file, &format).map_err(unreadable)?;
    let cols = columns(&table.header, file)?;
    let mut ctx = Checker::new(file, results, params);
    let mut out = Reference::default();
    for row in table.rows() {
        ctx.row(&row.map_err(unreadable)?, &cols, &mut out)?;
    }
    if ctx.rows == 0 {
        return Err(boxed(ReferenceError::Empty {
            loc: Location::file(file),
        }));
    }
    for o in out.offsets {
        merge_offset(&mut into.offsets, o)?;
    }
    into.files.push(file.to_path_buf());
    into.events.extend(out.events);
    into.strides.extend(out.strides);
    into.recordings.extend(out.recordings);
    Ok(())
}

/// Add a trial's offset unless the trial has one; a different one is an error.
fn merge_offset(offsets: &mut Vec<ReferenceOffset>, o: ReferenceOffset) -> Result<()> {
    match offsets
        .iter()
        .find(|x| x.subject_id == o.subject_id && x.trial_id == o.trial_id)
    {
        Some(x) if x.offset_s != o.offset_s => Err(boxed(ReferenceError::OffsetConflict {
            first: x.offset_s,
            first_line: x.at.line.map_or(0, |l| l.get()),
            value: o.offset_s,
            loc: o.at,
        })),
        Some(_) => Ok(()),
        None => {
            offsets.push(o);
            Ok(())
        }
    }
}

/// Resolve the header: the key columns, the parameters, and what kind of file it is.
fn columns(header: &[String], file: &Path) -> Result<Columns> {
    let find = |name: &str| header.iter().position(|h| h == name);
    let known = || {
        let mut k: Vec<&str> = KEY_COLUMNS.to_vec();
        k.extend(Parameter::columns());
        k.join(", ")
    };
    let mut params = Vec::new();
    for (i, h) in header.iter().enumerate() {
        if let Some(first) = header[..i].iter().position(|x| x == h) {
            return Err(boxed(ReferenceError::Duplicate {
                loc: Location::cell(file, 1, i + 1),
                what: format!("column '{h}' (column {})", first + 1),
                first_line: 1,
            }));
        }
        let alias = if h == "stride_index" { "stride" } else { h };
        if KEY_COLUMNS.contains(&alias) {
            continue;
        }
        match Parameter::from_column(h) {
            Ok(p) => params.push((p, i)),
            Err(_) => {
                return Err(LdhError::UnknownColumn {
                    loc: Location::cell(file, 1, i + 1),
                    column: h.clone(),
                    what: "a reference file".into(),
                    accepted: known(),
                })
            }
        }
    }
    let missing = |column: &'static str, why: &'static str| LdhError::MissingColumn {
        loc: Location::line(file, 1),
        missing: vec![column.to_string()],
        by: format!("{why}; the header has: {}", header.join(",")),
    };
    let cols = Columns {
        subject: find("subject_id").ok_or_else(|| missing("subject_id", "every row's subject"))?,
        trial: find("trial_id"),
        side: find("side").ok_or_else(|| missing("side", "every row's leg: left or right"))?,
        event: find("event"),
        time: find("time_s"),
        end_time: find("end_time_s"),
        stride: find("stride").or_else(|| find("stride_index")),
        offset: find("offset_s"),
        params,
    };
    if cols.event.is_some() {
        if cols.time.is_none() {
            return Err(missing("time_s", "an event file gives each event's time"));
        }
        if let Some(&(p, i)) = cols.params.first() {
            return Err(LdhError::UnknownColumn {
                loc: Location::cell(file, 1, i + 1),
                column: p.column().to_string(),
                what: "an event file (give parameters in a file of their own)".into(),
                accepted: "subject_id, trial_id, side, event, time_s, offset_s".into(),
            });
        }
    } else {
        if cols.params.is_empty() {
            return Err(missing(
                "event",
                "or a parameter column such as stride_time_s: a reference file holds events or parameters",
            ));
        }
        if cols.end_time.is_some() && cols.time.is_none() {
            return Err(missing(
                "time_s",
                "end_time_s ends a stride that time_s starts",
            ));
        }
        if cols.time.is_some() || cols.stride.is_some() {
            if let Some(&(p, i)) = cols
                .params
                .iter()
                .find(|(p, _)| !STRIDE_PARAMETERS.contains(p))
            {
                return Err(LdhError::UnknownColumn {
                    loc: Location::cell(file, 1, i + 1),
                    column: p.column().to_string(),
                    what: "a per-stride file (with time_s or stride)".into(),
                    accepted: STRIDE_PARAMETERS.map(|p| p.column()).join(", "),
                });
            }
        }
    }
    Ok(cols)
}

/// The checks of one file, row by row.
struct Checker<'a> {
    file: &'a Path,
    trials: HashMap<&'a str, Vec<&'a str>>,
    range: HashMap<(&'a str, &'a str), (f64, f64)>,
    max_offset_s: f64,
    /// Last time and line of each event series or per-stride series.
    last: HashMap<String, (f64, u64)>,
    /// First line of each stride number or recording.
    seen: HashMap<String, u64>,
    offsets: HashMap<(String, String), (f64, u64)>,
    rows: usize,
}

impl<'a> Checker<'a> {
    fn new(file: &'a Path, results: &'a LdhResults, params: &ValidAgreementParams) -> Self {
        let mut trials: HashMap<&str, Vec<&str>> = HashMap::new();
        let mut range = HashMap::new();
        let m = params.params().max_clock_offset_s;
        for (s, t) in results.trials() {
            trials.entry(s).or_default().push(t);
            let high = results.duration_s(s, t).map_or(f64::INFINITY, |d| d + m);
            range.insert((s, t), (-m, high));
        }
        Checker {
            file,
            trials,
            range,
            max_offset_s: m,
            last: HashMap::new(),
            seen: HashMap::new(),
            offsets: HashMap::new(),
            rows: 0,
        }
    }

    fn bad(
        &self,
        line: u64,
        col: usize,
        column: &'static str,
        value: &str,
        expected: &'static str,
    ) -> LdhError {
        LdhError::InvalidValue {
            loc: Location::cell(self.file, line, col + 1),
            column: column.to_string(),
            value: value.to_string(),
            expected: expected.to_string(),
        }
    }

    /// A finite number, `None` for an empty cell.
    fn number(&self, row: &Row, col: usize, column: &'static str) -> Result<Option<f64>> {
        row.number_at(col, column)
    }

    /// A time inside the trial's recording (± the largest clock offset).
    fn time(
        &self,
        row: &Row,
        col: usize,
        column: &'static str,
        key: (&str, &str),
    ) -> Result<Option<f64>> {
        let line = row.line;
        let Some(v) = self.number(row, col, column)? else {
            return Ok(None);
        };
        let (low, high) = self
            .range
            .get(&key)
            .copied()
            .unwrap_or((-self.max_offset_s, f64::INFINITY));
        if v < low || v > high {
            return Err(boxed(ReferenceError::OutOfRange {
                loc: Location::cell(self.file, line, col + 1),
                column,
                value: v,
                low,
                high,
            }));
        }
        Ok(Some(v))
    }

    /// The subject and trial of a row, as the results name them.
    fn who(&self, row: &Row, cols: &Columns) -> Result<(String, String)> {
        let line = row.line;
        let subject = row.at(cols.subject);
        if subject.is_empty() {
            return Err(self.bad(line, cols.subject, "subject_id", subject, "a subject id"));
        }
        let trial = cols.trial.map_or("", |c| row.at(c));
        let known = || {
            let mut ids: Vec<&str> = self.trials.keys().copied().collect();
            ids.sort_unstable();
            let n = ids.len();
            ids.truncate(8);
            format!(
                "{n} subjects: {}{}",
                ids.join(", "),
                if n > 8 { ", …" } else { "" }
            )
        };
        let unknown = |col: usize| {
            boxed(ReferenceError::UnknownSubject {
                loc: Location::cell(self.file, line, col + 1),
                subject_id: subject.to_string(),
                trial_id: trial.to_string(),
                known: known(),
            })
        };
        let Some(trials) = self.trials.get(subject) else {
            return Err(unknown(cols.subject));
        };
        if !trial.is_empty() {
            if !trials.contains(&trial) {
                return Err(unknown(cols.trial.unwrap_or(cols.subject)));
            }
            return Ok((subject.to_string(), trial.to_string()));
        }
        match trials.as_slice() {
            [one] => Ok((subject.to_string(), one.to_string())),
            _ => Err(boxed(ReferenceError::AmbiguousTrial {
                loc: Location::line(self.file, line),
                subject_id: subject.to_string(),
                trials: trials.join(", "),
            })),
        }
    }

    /// A time that must come after the series' previous one.
    fn ascending(&mut self, series: String, v: f64, line: u64, col: usize) -> Result<()> {
        if let Some(&(previous, previous_line)) = self.last.get(&series) {
            if v == previous {
                return Err(boxed(ReferenceError::Duplicate {
                    loc: Location::line(self.file, line),
                    what: format!("{series} at {v} s"),
                    first_line: previous_line,
                }));
            }
            if v < previous {
                return Err(boxed(ReferenceError::OutOfOrder {
                    loc: Location::cell(self.file, line, col + 1),
                    what: series,
                    value: v,
                    previous,
                    previous_line,
                }));
            }
        }
        self.last.insert(series, (v, line));
        Ok(())
    }

    /// A key that may occur once.
    fn once(&mut self, what: String, line: u64) -> Result<()> {
        if let Some(&first_line) = self.seen.get(&what) {
            return Err(boxed(ReferenceError::Duplicate {
                loc: Location::line(self.file, line),
                what,
                first_line,
            }));
        }
        self.seen.insert(what, line);
        Ok(())
    }

    fn row(&mut self, row: &Row, cols: &Columns, out: &mut Reference) -> Result<()> {
        self.rows += 1;
        let line = row.line;
        let (subject_id, trial_id) = self.who(row, cols)?;
        let side_text = row.at(cols.side);
        let side: Side = side_text
            .parse()
            .map_err(|_| self.bad(line, cols.side, "side", side_text, "left or right"))?;
        let key = (subject_id.as_str(), trial_id.as_str());
        let label = if trial_id.is_empty() {
            format!("{subject_id} {side}")
        } else {
            format!("{subject_id} trial {trial_id} {side}")
        };
        if let Some(c) = cols.offset {
            if let Some(v) = self.number(row, c, "offset_s")? {
                let k = (subject_id.clone(), trial_id.clone());
                match self.offsets.get(&k) {
                    Some(&(first, first_line)) if first != v => {
                        return Err(boxed(ReferenceError::OffsetConflict {
                            loc: Location::cell(self.file, line, c + 1),
                            value: v,
                            first,
                            first_line,
                        }))
                    }
                    Some(_) => {}
                    None => {
                        self.offsets.insert(k, (v, line));
                        out.offsets.push(ReferenceOffset {
                            subject_id: subject_id.clone(),
                            trial_id: trial_id.clone(),
                            offset_s: v,
                            at: Location::cell(self.file, line, c + 1),
                        });
                    }
                }
            }
        }
        if let Some(ec) = cols.event {
            let text = row.at(ec);
            let event: EventKind = text
                .parse()
                .map_err(|_| self.bad(line, ec, "event", text, "HS or TO"))?;
            let tc = cols.time.expect("checked with the header");
            let time_s = self
                .time(row, tc, "time_s", key)?
                .ok_or_else(|| self.bad(line, tc, "time_s", "", "a finite number"))?;
            self.ascending(format!("{label} {event}"), time_s, line, tc)?;
            out.events.push(GaitEvent {
                subject_id,
                trial_id,
                side,
                event,
                time_s,
            });
            return Ok(());
        }
        let mut values = Vec::with_capacity(cols.params.len());
        for &(p, c) in &cols.params {
            values.push((p, self.number(row, c, p.column())?.unwrap_or(f64::NAN)));
        }
        let stride =
            match cols.stride {
                Some(c) => {
                    let s = row.at(c);
                    Some(s.parse::<usize>().map_err(|_| {
                        self.bad(line, c, "stride", s, "a stride number (0, 1, 2, …)")
                    })?)
                }
                None => None,
            };
        let time_s = match cols.time {
            Some(c) => {
                let t = self.time(row, c, "time_s", key)?;
                let t = t.ok_or_else(|| self.bad(line, c, "time_s", "", "a finite number"))?;
                self.ascending(format!("{label} strides"), t, line, c)?;
                Some(t)
            }
            None => None,
        };
        let end_time_s = match cols.end_time {
            Some(c) => self.time(row, c, "end_time_s", key)?,
            None => None,
        };
        if let Some(s) = stride {
            self.once(format!("{label} stride {s}"), line)?;
        }
        let per_stride = stride.is_some() || time_s.is_some();
        if !per_stride {
            self.once(format!("{label} (one row per recording)"), line)?;
        }
        let row = ReferenceValues {
            subject_id,
            trial_id,
            side,
            stride,
            time_s,
            end_time_s,
            values,
            at: Location::line(self.file, line),
        };
        if per_stride {
            out.strides.push(row);
        } else {
            out.recordings.push(row);
        }
        Ok(())
    }
}
