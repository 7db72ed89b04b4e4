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
//! ([`super::reference::parse_reference`]) and every error's line and column (and the earlier
//! line it cites) moved back to the export's, so each error names the export file, its line and
//! its column (a subject or trial given on the command line has no column).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Location, Result};
use crate::output::Parameter;

use super::reference::{parse_reference, Reference};
use super::results::{boxed, LdhResults, STRIDE_PARAMETERS};
use super::{ReferenceError, ValidAgreementParams};

/// A unit of a walkway column, converted to ldh's unit of the key by a factor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum WalkwayUnit {
    /// Seconds.
    #[serde(rename = "s")]
    Seconds,
    /// Milliseconds (÷ 1000).
    #[serde(rename = "ms")]
    Milliseconds,
    /// Metres.
    #[serde(rename = "m")]
    Metres,
    /// Centimetres (÷ 100).
    #[serde(rename = "cm")]
    Centimetres,
    /// Millimetres (÷ 1000).
    #[serde(rename = "mm")]
    Millimetres,
    /// Metres per second.
    #[serde(rename = "m/s")]
    MetresPerSecond,
    /// Centimetres per second (÷ 100).
    #[serde(rename = "cm/s")]
    CentimetresPerSecond,
    /// A fraction, 0–1.
    #[serde(rename = "ratio")]
    Ratio,
    /// Per cent (÷ 100).
    #[serde(rename = "%")]
    Percent,
    /// Degrees.
    #[serde(rename = "deg")]
    Degrees,
}

impl WalkwayUnit {
    /// The unit as the map writes it.
    pub fn name(self) -> &'static str {
        use WalkwayUnit::*;
        match self {
            Seconds => "s",
            Milliseconds => "ms",
            Metres => "m",
            Centimetres => "cm",
            Millimetres => "mm",
            MetresPerSecond => "m/s",
            CentimetresPerSecond => "cm/s",
            Ratio => "ratio",
            Percent => "%",
            Degrees => "deg",
        }
    }

    /// (ldh's unit this converts to, the divisor: value in ldh's unit = value / divisor, a
    /// division so that e.g. 131.2 cm is the double nearest 1.312 m).
    fn to_ldh(self) -> (&'static str, f64) {
        use WalkwayUnit::*;
        match self {
            Seconds => ("s", 1.0),
            Milliseconds => ("s", 1e3),
            Metres => ("m", 1.0),
            Centimetres => ("m", 1e2),
            Millimetres => ("m", 1e3),
            MetresPerSecond => ("m/s", 1.0),
            CentimetresPerSecond => ("m/s", 1e2),
            Ratio => ("ratio", 1.0),
            Percent => ("ratio", 1e2),
            Degrees => ("deg", 1.0),
        }
    }
}

/// One mapped column: its name in the export's header and its unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MappedColumn {
    /// The export's column (matched trimmed, without regard to case).
    pub column: String,
    /// Its unit.
    pub unit: WalkwayUnit,
}

/// The foot column and its values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SideColumn {
    /// The export's column.
    pub column: String,
    /// Values meaning the left foot (without regard to case), e.g. `["L", "Left"]`.
    pub left: Vec<String>,
    /// Values meaning the right foot.
    pub right: Vec<String>,
}

/// Which heel strike a footfall's stride values belong to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StrideAnchor {
    /// The stride starts at this footfall's heel strike.
    #[default]
    Start,
    /// The stride ends at this footfall's heel strike (GAITRite, Zeno): it starts at the same
    /// foot's previous heel strike.
    End,
}

/// The column map of a per-step walkway export (TOML; `data-fixtures/agreement/` has one for a
/// GAITRite-like export).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WalkwayMap {
    /// Short name.
    pub name: String,
    /// Where the format comes from.
    #[serde(default)]
    pub description: String,
    /// Field delimiter: `,` (default), `;` or a tab.
    #[serde(default = "comma")]
    pub delimiter: String,
    /// Lines above the header row (a title block).
    #[serde(default)]
    pub skip_rows_before_header: usize,
    /// The subject's column (else `--subject-id`).
    #[serde(default)]
    pub subject_column: Option<String>,
    /// The trial's column (else `--trial-id`, or none).
    #[serde(default)]
    pub trial_column: Option<String>,
    /// The foot.
    pub side: SideColumn,
    /// First contact (heel strike), a time.
    #[serde(default)]
    pub heel_strike: Option<MappedColumn>,
    /// Last contact (toe off), a time.
    #[serde(default)]
    pub toe_off: Option<MappedColumn>,
    /// Which heel strike the stride values belong to.
    #[serde(default)]
    pub stride_anchor: StrideAnchor,
    /// Stride parameters: a column of `strides.csv` (`stride_time_s`, `stride_length_m`,
    /// `speed_mps`, `stance_ratio`, …) → its export column.
    #[serde(default)]
    pub strides: std::collections::BTreeMap<String, MappedColumn>,
}

fn comma() -> String {
    ",".into()
}

/// The subject and trial of an export whose map has no column for them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WalkwayIds {
    /// The subject (`--subject-id`).
    pub subject_id: Option<String>,
    /// The trial (`--trial-id`).
    pub trial_id: Option<String>,
}

impl WalkwayMap {
    /// Read and check a map. Errors name the file, and the TOML's line and column.
    pub fn from_toml_str(text: &str, file: &Path) -> Result<WalkwayMap> {
        let bad = |loc: Location, reason: String| boxed(ReferenceError::Map { loc, reason });
        let map: WalkwayMap = toml::from_str(text).map_err(|e| {
            let loc = match e.span() {
                Some(span) => {
                    let before = &text[..span.start.min(text.len())];
                    let line = before.matches('\n').count() as u64 + 1;
                    let col = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
                    Location::cell(file, line, col)
                }
                None => Location::file(file),
            };
            bad(loc, e.message().to_string())
        })?;
        map.check().map_err(|r| bad(Location::file(file), r))?;
        Ok(map)
    }

    /// Read a map file.
    pub fn from_toml_file(path: &Path) -> Result<WalkwayMap> {
        let text = crate::io::read_text_limited(path, crate::io::MAX_FORMAT_MB, "a column map")?;
        WalkwayMap::from_toml_str(&text, path)
    }

    fn delimiter_byte(&self) -> Option<u8> {
        match self.delimiter.as_str() {
            "," => Some(b','),
            ";" => Some(b';'),
            "\t" => Some(b'\t'),
            _ => None,
        }
    }

    /// Every stride key a per-stride parameter, every unit that parameter's (or a time).
    fn check(&self) -> std::result::Result<(), String> {
        if self.delimiter_byte().is_none() {
            return Err(format!(
                "delimiter '{}' is not ',', ';' or a tab",
                self.delimiter
            ));
        }
        for (what, c) in [
            ("heel_strike", &self.heel_strike),
            ("toe_off", &self.toe_off),
        ] {
            if let Some(c) = c {
                if c.unit.to_ldh().0 != "s" {
                    return Err(format!(
                        "{what}: unit '{:?}' is not a time (s or ms)",
                        c.unit
                    ));
                }
            }
        }
        if self.heel_strike.is_none() && self.toe_off.is_none() && self.strides.is_empty() {
            return Err("the map names no heel_strike, toe_off or strides column".into());
        }
        if !self.strides.is_empty() && self.heel_strike.is_none() {
            return Err("strides need the heel_strike column (each stride's time)".into());
        }
        for (key, c) in &self.strides {
            let p = Parameter::from_column(key)
                .ok()
                .filter(|p| STRIDE_PARAMETERS.contains(p))
                .ok_or_else(|| {
                    format!(
                        "strides.{key}: not a per-stride parameter; known: {}",
                        STRIDE_PARAMETERS.map(|p| p.column()).join(", ")
                    )
                })?;
            if c.unit.to_ldh().0 != p.unit() {
                return Err(format!(
                    "strides.{key}: unit '{}' does not convert to {}",
                    c.unit.name(),
                    p.unit()
                ));
            }
        }
        Ok(())
    }
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
        match e {
            LdhError::Reference(mut b) => {
                b.relocate(
                    |l| self.export_line(l, header_line),
                    |c| {
                        let i = self.origin.get(c as usize - 1).copied().flatten()?;
                        u32::try_from(i + 1).ok()
                    },
                );
                LdhError::Reference(b)
            }
            other => other,
        }
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

/// The export as three long-form tables: heel strikes, toe offs, strides.
fn convert(
    text: &str,
    file: &Path,
    map: &WalkwayMap,
    ids: &WalkwayIds,
) -> Result<(Vec<Table>, u64)> {
    let mut rdr = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .delimiter(map.delimiter_byte().unwrap_or(b','))
        .from_reader(text.trim_start_matches('\u{feff}').as_bytes());
    let unreadable = |e: csv::Error| {
        boxed(ReferenceError::Unreadable {
            loc: Location::line(file, e.position().map_or(1, |p| p.line())),
            reason: e.to_string(),
        })
    };
    let mut records = rdr.records();
    let mut header = None;
    for _ in 0..=map.skip_rows_before_header {
        header = records.next().transpose().map_err(unreadable)?;
    }
    let Some(header) = header else {
        return Err(boxed(ReferenceError::Empty {
            loc: Location::file(file),
        }));
    };
    let header_line = header.position().map_or(1, |p| p.line());
    let names: Vec<String> = header.iter().map(|h| h.to_ascii_lowercase()).collect();
    let find = |name: &str| -> Result<usize> {
        names
            .iter()
            .position(|h| *h == name.trim().to_ascii_lowercase())
            .ok_or_else(|| {
                boxed(ReferenceError::Map {
                    loc: Location::line(file, header_line),
                    reason: format!(
                        "the map's column '{name}' is not in the header ({})",
                        header.iter().collect::<Vec<_>>().join(", ")
                    ),
                })
            })
    };
    let id_column = |column: &Option<String>| column.as_deref().map(find).transpose();
    let subject_col = id_column(&map.subject_column)?;
    let trial_col = id_column(&map.trial_column)?;
    if subject_col.is_none() && ids.subject_id.is_none() {
        return Err(boxed(ReferenceError::Map {
            loc: Location::file(file),
            reason: "no subject: give the subject id (--subject-id) or a subject_column in the map"
                .into(),
        }));
    }
    let side_col = find(&map.side.column)?;
    let hs = map
        .heel_strike
        .as_ref()
        .map(|c| Ok::<_, LdhError>((find(&c.column)?, c.unit.to_ldh().1)))
        .transpose()?;
    let to = map
        .toe_off
        .as_ref()
        .map(|c| Ok::<_, LdhError>((find(&c.column)?, c.unit.to_ldh().1)))
        .transpose()?;
    let mut params = Vec::new();
    for p in STRIDE_PARAMETERS {
        if let Some(c) = map.strides.get(p.column()) {
            params.push((p.column(), find(&c.column)?, c.unit.to_ldh().1));
        }
    }
    let key_origin = vec![subject_col, trial_col, Some(side_col)];
    let event_table = |col: Option<(usize, f64)>| {
        let mut o = key_origin.clone();
        o.extend([col.map(|c| c.0), col.map(|c| c.0)]);
        Table::new(&["subject_id", "trial_id", "side", "event", "time_s"], o)
    };
    let mut heel = event_table(hs);
    let mut toe = event_table(to);
    let mut header_s: Vec<&str> = vec!["subject_id", "trial_id", "side", "time_s", "end_time_s"];
    let mut origin = key_origin.clone();
    origin.extend([hs.map(|c| c.0), hs.map(|c| c.0)]);
    for (name, c, _) in &params {
        header_s.push(name);
        origin.push(Some(*c));
    }
    let mut strides = Table::new(&header_s, origin);
    let mut previous_hs: HashMap<(String, String, String), f64> = HashMap::new();
    for rec in records {
        let rec = rec.map_err(unreadable)?;
        let line = rec.position().map_or(0, |p| p.line());
        if rec.len() != header.len() {
            return Err(boxed(ReferenceError::Unreadable {
                loc: Location::line(file, line),
                reason: format!("{} cells under a header of {}", rec.len(), header.len()),
            }));
        }
        let cell = |c: usize| rec.get(c).unwrap_or("").to_string();
        let bad = |c: usize, expected: String| {
            boxed(ReferenceError::MappedValue {
                loc: Location::cell(file, line, c + 1),
                column: header.get(c).unwrap_or("").to_string(),
                value: cell(c),
                expected,
            })
        };
        let number = |c: usize, factor: f64| -> Result<Option<String>> {
            let s = cell(c);
            if s.is_empty() {
                return Ok(None);
            }
            match s.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(Some(format!("{}", v / factor))),
                _ => Err(bad(c, "a finite number".into())),
            }
        };
        let subject = subject_col.map_or_else(|| ids.subject_id.clone().unwrap_or_default(), cell);
        let trial = trial_col.map_or_else(|| ids.trial_id.clone().unwrap_or_default(), cell);
        let foot = cell(side_col);
        let is = |list: &[String]| list.iter().any(|v| v.eq_ignore_ascii_case(&foot));
        let side = if is(&map.side.left) {
            "left"
        } else if is(&map.side.right) {
            "right"
        } else {
            let listed = map.side.left.iter().chain(&map.side.right);
            return Err(bad(
                side_col,
                format!(
                    "a foot the map lists ({})",
                    listed.cloned().collect::<Vec<_>>().join(", ")
                ),
            ));
        };
        let keys = vec![subject.clone(), trial.clone(), side.to_string()];
        let hs_time = match hs {
            Some((c, f)) => number(c, f)?,
            None => None,
        };
        for (table, col, event) in [(&mut heel, hs, "HS"), (&mut toe, to, "TO")] {
            let Some((c, f)) = col else { continue };
            if let Some(t) = number(c, f)? {
                let mut row = keys.clone();
                row.extend([event.to_string(), t]);
                table.rows.push((line, row));
            }
        }
        // Every mapped cell is read, used or not: a typo is refused wherever it is.
        let values = params
            .iter()
            .map(|&(_, c, f)| Ok(number(c, f)?.unwrap_or_default()))
            .collect::<Result<Vec<String>>>()?;
        let Some(hs_time) = hs_time else { continue };
        let this: f64 = hs_time.parse().expect("formatted from a number");
        let (start, end) = match map.stride_anchor {
            StrideAnchor::Start => (Some(hs_time.clone()), String::new()),
            StrideAnchor::End => (
                previous_hs
                    .insert((subject, trial, side.to_string()), this)
                    .map(|p| format!("{p}")),
                hs_time.clone(),
            ),
        };
        let Some(start) = start else { continue };
        if params.is_empty() {
            continue;
        }
        let mut row = keys;
        row.extend([start, end]);
        row.extend(values);
        strides.rows.push((line, row));
    }
    Ok((vec![heel, toe, strides], header_line))
}
