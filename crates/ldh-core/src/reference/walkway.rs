//! Per-step walkway exports (GAITRite, Zeno/PKMAS and the like) as `ldh agree` references,
//! through a column map (`docs/agreement.md`, "Walkway exports").
//!
//! Such an export lists one row per footfall: the foot (`L`/`R`), the first and last contact
//! (heel strike and toe off, s) and per-footfall parameters (stride length in cm, stride time,
//! velocity in cm/s, stance %). A [`WalkwayMap`] (TOML, like the IMU readers' `--format` maps)
//! names those columns, the reference key each one is (`side`, the heel strike, the toe off, the
//! stride parameters of `strides.csv`), and each one's unit; the subject and trial come from a
//! column or from the command line ([`WalkwayIds`]).
//!
//! Each footfall becomes a heel strike, a toe off and a stride row of the long-form reference
//! files, in the export's units converted to ldh's (cm → m, ms → s, % → ratio, cm/s → m/s).
//! A walkway reports a stride on the footfall that **ends** it (GAITRite: from the previous
//! contact of the same foot to this one): with `stride_anchor = "end"` the stride's `time_s` is
//! the previous footfall's heel strike of that foot and its `end_time_s` this one's, and a
//! foot's first footfall gives no stride.
//!
//! The converted rows are checked by the reader of the long-form files
//! ([`super::long_form::parse_reference`]) and every error's line and column (and the earlier
//! line it cites) moved back to the export's, so each error names the export file, its line and
//! its column (a subject or trial given on the command line has no column).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::error::{LdhError, Location, Result};
use crate::io::table::{CsvFault, Row, Table as CsvTable, TableFormat};

use super::walkway_map::{MappedColumn, StrideAnchor, WalkwayMap};

use super::error::boxed;
use super::long_form::{parse_reference, Reference};
use super::ReferenceError;
use crate::output::results::{LdhResults, STRIDE_PARAMETERS};
use crate::stats::agreement::ValidAgreementParams;

/// The subject and trial of an export whose map has no column for them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WalkwayIds {
    /// The subject (`--subject-id`).
    pub subject_id: Option<String>,
    /// The trial (`--trial-id`).
    pub trial_id: Option<String>,
}

/// Where a converted cell came from: the export's column (0-based), none for a given id.
type Origin = Vec<Option<usize>>;

/// One long-form table built from the export: header, origin of each column, rows by line.
struct Table {
    header: Vec<String>,
    origin: Origin,
    rows: Vec<(u64, Vec<String>)>,
}

impl Table {
    fn new(header: &[&str], origin: Origin) -> Table {
        Table {
            header: header.iter().map(|s| s.to_string()).collect(),
            origin,
            rows: Vec::new(),
        }
    }

    /// The text: the header, then one line per row (no cell holds a line break: each came
    /// from one CSV field and is written quoted when needed).
    fn text(&self) -> String {
        let record = |cells: &[String]| {
            let mut w = csv::WriterBuilder::new().from_writer(Vec::new());
            w.write_record(cells).expect("in memory");
            String::from_utf8(w.into_inner().expect("in memory")).expect("UTF-8 cells")
        };
        let mut out = record(&self.header);
        for (_, cells) in &self.rows {
            out.push_str(&record(cells));
        }
        out
    }

    /// The export's line of a line of [`Self::text`] (the header is the export's header).
    fn export_line(&self, line: u64, header_line: u64) -> u64 {
        match line {
            0 | 1 => header_line,
            l => self.rows.get(l as usize - 2).map_or(l, |r| r.0),
        }
    }

    /// An error of the long-form reader moved back to the export's line and column.
    fn relocate(&self, e: LdhError, header_line: u64) -> LdhError {
        super::error::relocate(
            e,
            |l| self.export_line(l, header_line),
            |c| {
                let i = self.origin.get(c as usize - 1).copied().flatten()?;
                u32::try_from(i + 1).ok()
            },
        )
    }
}

/// Read a walkway export through `map`, check it against `results` and add its events and
/// strides to `into` (nothing is added when it fails). Errors name the export, its line and
/// its column.
pub fn read_walkway(
    path: &Path,
    map: &WalkwayMap,
    ids: &WalkwayIds,
    results: &LdhResults,
    params: &ValidAgreementParams,
    into: &mut Reference,
) -> Result<()> {
    let text = crate::io::read_text_limited(path, crate::io::MAX_TABLE_MB, "a walkway export")?;
    parse_walkway(&text, path, map, ids, results, params, into)
}

/// [`read_walkway`] on the export's text (`file` names it in errors).
pub fn parse_walkway(
    text: &str,
    file: &Path,
    map: &WalkwayMap,
    ids: &WalkwayIds,
    results: &LdhResults,
    params: &ValidAgreementParams,
    into: &mut Reference,
) -> Result<()> {
    let (tables, header_line) = convert(text, file, map, ids)?;
    let mut out = Reference::default();
    for t in tables.iter().filter(|t| !t.rows.is_empty()) {
        parse_reference(&t.text(), file, results, params, &mut out)
            .map_err(|e| t.relocate(e, header_line))?;
    }
    if out.events.is_empty() && out.strides.is_empty() {
        return Err(boxed(ReferenceError::Empty {
            loc: Location::file(file),
        }));
    }
    into.files.push(PathBuf::from(file));
    into.events.extend(out.events);
    into.strides.extend(out.strides);
    Ok(())
}

/// The export as three long-form tables (heel strikes, toe offs, strides) and its header's
/// line.
fn convert(
    text: &str,
    file: &Path,
    map: &WalkwayMap,
    ids: &WalkwayIds,
) -> Result<(Vec<Table>, u64)> {
    let format = TableFormat {
        delimiter: map.delimiter_byte().unwrap_or(b','),
        trim: true,
        skip_rows_before_header: map.skip_rows_before_header,
        flexible: true,
        ..TableFormat::default()
    };
    let unreadable = |f: CsvFault| f.into_error("");
    let table = CsvTable::parse(text, file, &format).map_err(unreadable)?;
    if table.header.is_empty() {
        return Err(boxed(ReferenceError::Empty {
            loc: Location::file(file),
        }));
    }
    let mut c = Converter::new(file, map, ids, &table)?;
    for row in table.rows() {
        c.row(&row.map_err(unreadable)?)?;
    }
    let line = c.header_line;
    Ok((vec![c.heel, c.toe, c.strides], line))
}

/// The columns a map names, found in the export's header, and the tables being filled.
struct Converter<'a> {
    file: &'a Path,
    map: &'a WalkwayMap,
    ids: &'a WalkwayIds,
    header: &'a [String],
    header_line: u64,
    subject: Option<usize>,
    trial: Option<usize>,
    side: usize,
    /// (column, divisor) of the heel strike and the toe off.
    hs: Option<(usize, f64)>,
    to: Option<(usize, f64)>,
    /// (key, column, divisor) of each stride parameter.
    params: Vec<(&'static str, usize, f64)>,
    heel: Table,
    toe: Table,
    strides: Table,
    /// The last heel strike of each (subject, trial, side), for `stride_anchor = "end"`.
    previous_hs: HashMap<(String, String, String), f64>,
}

impl<'a> Converter<'a> {
    /// Find the map's columns in `header`. Errors: a column not in the header, no subject.
    fn new(
        file: &'a Path,
        map: &'a WalkwayMap,
        ids: &'a WalkwayIds,
        table: &'a CsvTable,
    ) -> Result<Self> {
        let (header, header_line) = (&table.header, table.header_line);
        let find = |name: &str| -> Result<usize> {
            header
                .iter()
                .position(|h| h.eq_ignore_ascii_case(name.trim()))
                .ok_or_else(|| {
                    boxed(ReferenceError::Map {
                        loc: Location::line(file, header_line),
                        reason: format!(
                            "the map's column '{name}' is not in the header ({})",
                            header.join(", ")
                        ),
                    })
                })
        };
        let subject = map.subject_column.as_deref().map(find).transpose()?;
        let trial = map.trial_column.as_deref().map(find).transpose()?;
        if subject.is_none() && ids.subject_id.is_none() {
            return Err(boxed(ReferenceError::Map {
                loc: Location::file(file),
                reason:
                    "no subject: give the subject id (--subject-id) or a subject_column in the map"
                        .into(),
            }));
        }
        let side = find(&map.side.column)?;
        let time = |c: &Option<MappedColumn>| {
            c.as_ref()
                .map(|c| Ok::<_, LdhError>((find(&c.column)?, c.unit.to_ldh().1)))
                .transpose()
        };
        let (hs, to) = (time(&map.heel_strike)?, time(&map.toe_off)?);
        let mut params = Vec::new();
        for p in STRIDE_PARAMETERS {
            if let Some(c) = map.strides.get(p.column()) {
                params.push((p.column(), find(&c.column)?, c.unit.to_ldh().1));
            }
        }
        let keys = vec![subject, trial, Some(side)];
        let event_table = |col: Option<(usize, f64)>| {
            let mut o = keys.clone();
            o.extend([col.map(|c| c.0), col.map(|c| c.0)]);
            Table::new(&["subject_id", "trial_id", "side", "event", "time_s"], o)
        };
        let mut names: Vec<&str> = vec!["subject_id", "trial_id", "side", "time_s", "end_time_s"];
        let mut origin = keys.clone();
        origin.extend([hs.map(|c| c.0), hs.map(|c| c.0)]);
        for (name, c, _) in &params {
            names.push(name);
            origin.push(Some(*c));
        }
        Ok(Converter {
            heel: event_table(hs),
            toe: event_table(to),
            strides: Table::new(&names, origin),
            file,
            map,
            ids,
            header,
            header_line,
            subject,
            trial,
            side,
            hs,
            to,
            params,
            previous_hs: HashMap::new(),
        })
    }

    /// A cell that the map cannot read.
    fn bad(&self, row: &Row, c: usize, expected: String) -> LdhError {
        LdhError::InvalidValue {
            loc: row.loc_at(c),
            column: self.header.get(c).map_or("", String::as_str).to_string(),
            value: row.at(c).to_string(),
            expected,
        }
    }

    /// A number in ldh's unit, written back as text (`None`: an empty cell).
    fn number(&self, row: &Row, (c, divisor): (usize, f64)) -> Result<Option<String>> {
        let column = self.header.get(c).map_or("", String::as_str);
        Ok(row
            .number_at(c, column)?
            .map(|v| format!("{}", v / divisor)))
    }

    /// The foot of a row, `left` or `right`.
    fn foot(&self, row: &Row) -> Result<&'static str> {
        let foot = row.at(self.side);
        let is = |list: &[String]| list.iter().any(|v| v.eq_ignore_ascii_case(foot));
        if is(&self.map.side.left) {
            Ok("left")
        } else if is(&self.map.side.right) {
            Ok("right")
        } else {
            let listed: Vec<&str> = self
                .map
                .side
                .left
                .iter()
                .chain(&self.map.side.right)
                .map(String::as_str)
                .collect();
            let expected = format!("a foot the map lists ({})", listed.join(", "));
            Err(self.bad(row, self.side, expected))
        }
    }

    /// One footfall: its heel strike, toe off and stride rows.
    fn row(&mut self, row: &Row) -> Result<()> {
        let (rec, line) = (row.record, row.line);
        if rec.len() != self.header.len() {
            return Err(LdhError::FieldCount {
                loc: Location::line(self.file, line),
                found: rec.len(),
                expected: self.header.len(),
                hint: String::new(),
            });
        }
        let id = |col: Option<usize>, given: &Option<String>| match col {
            Some(c) => row.at(c).to_string(),
            None => given.clone().unwrap_or_default(),
        };
        let subject = id(self.subject, &self.ids.subject_id);
        let trial = id(self.trial, &self.ids.trial_id);
        let side = self.foot(row)?;
        let keys = vec![subject.clone(), trial.clone(), side.to_string()];
        let hs_time = self.hs.map(|c| self.number(row, c)).transpose()?.flatten();
        let to_time = self.to.map(|c| self.number(row, c)).transpose()?.flatten();
        // Every mapped cell is read, used or not: a typo is refused wherever it is.
        let values = self
            .params
            .iter()
            .map(|&(_, c, f)| Ok(self.number(row, (c, f))?.unwrap_or_default()))
            .collect::<Result<Vec<String>>>()?;
        for (table, time, event) in [
            (&mut self.heel, &hs_time, "HS"),
            (&mut self.toe, &to_time, "TO"),
        ] {
            if let Some(t) = time {
                let mut row = keys.clone();
                row.extend([event.to_string(), t.clone()]);
                table.rows.push((line, row));
            }
        }
        let Some(hs_time) = hs_time else {
            return Ok(());
        };
        let (start, end) = match self.map.stride_anchor {
            StrideAnchor::Start => (Some(hs_time), String::new()),
            StrideAnchor::End => {
                let this: f64 = hs_time.parse().expect("formatted from a number");
                let previous = self.previous_hs.insert((subject, trial, side.into()), this);
                (previous.map(|p| format!("{p}")), hs_time)
            }
        };
        if let (Some(start), false) = (start, self.params.is_empty()) {
            let mut row = keys;
            row.extend([start, end]);
            row.extend(values);
            self.strides.rows.push((line, row));
        }
        Ok(())
    }
}
