//! The cohort manifest (SPEC §2; docs/input.md "Cohort manifest"): one CSV row per recording
//! pair, read with the `csv` crate (quoted fields may hold commas), recognised by its header
//! (`subject_id` and `left` and/or `right`).
//!
//! Columns (case-insensitive, any order; every other name is refused, naming it):
//! `subject_id` (required), `left`, `right` (paths relative to the manifest), `group` (a free
//! label; `healthy` is the reference group and `ldh` enables the affected/unaffected analysis),
//! `affected_side` (`left` | `right` | `none`; empty = unknown, which is said), `sensor_height_m`
//! (both legs) and `left_sensor_height_m` / `right_sensor_height_m` (one leg; a value that
//! differs from the row's `sensor_height_m` is refused, [`super::heights`]),
//! `setting` (`overground` | `treadmill`), `format` / `left_format` / `right_format` (a built-in
//! format name or a TOML column map relative to the manifest; the side's own column wins), and
//! `trial_id` (or `trial`): several rows of one `subject_id` are that person's trials, analysed
//! one by one and averaged per person before any statistic ([`crate::cohort::Cohort`]);
//! `belt_speed_mps` (the treadmill's belt speed, m/s, 0 < v ≤ 5; only with `setting`
//! `treadmill`), `visit` (a free label of the session, e.g. `pre` or `2026-03-01`: the
//! reports keep a person's visits apart) and `clocks` (`one`: the two sensors were
//! synchronised, so the timings between the legs are vouched for; `two`; empty: from the files,
//! one file for both legs is one clock, two files are two: [`SubjectInput::clocks`]).

use std::collections::HashMap;
use std::path::Path;

use super::heights::SensorHeights;
use super::subject_input::{Clocks, Source, SubjectInput};
use crate::domain::Group;
use crate::error::{LdhError, Location, Result};
use crate::io::table::{Row, Table, TableFormat};
use crate::io::FormatSpec;
use crate::recording::{Setting, Side};

/// The columns a manifest may have.
pub const MANIFEST_COLUMNS: [&str; 17] = [
    "subject_id",
    "trial_id",
    "trial",
    "group",
    "affected_side",
    "left",
    "right",
    "sensor_height_m",
    "left_sensor_height_m",
    "right_sensor_height_m",
    "setting",
    "format",
    "left_format",
    "right_format",
    "belt_speed_mps",
    "visit",
    "clocks",
];

/// The fastest treadmill belt speed a manifest may give, m/s (a sprint; faster is a typo).
pub const MAX_BELT_SPEED_MPS: f64 = 5.0;

/// The first row of `text` that is not empty or a `#` comment, split as CSV and lower-cased.
fn header_of(text: &str) -> Option<Vec<String>> {
    let line = text
        .lines()
        .map(|l| l.trim_start_matches('\u{feff}'))
        .find(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))?;
    let t = Table::parse(line, Path::new(""), &manifest_format()).ok()?;
    Some(
        t.header
            .iter()
            .map(|c| c.trim_matches('"').to_string())
            .collect(),
    )
}

/// How a manifest is split: fields trimmed, `#` comment lines, header names in lower case.
fn manifest_format() -> TableFormat {
    TableFormat {
        trim: true,
        comment: Some(b'#'),
        lowercase_header: true,
        ..TableFormat::default()
    }
}

/// Whether `text` is a manifest: its header holds `subject_id` and `left` or `right`.
pub fn is_manifest_text(text: &str) -> bool {
    header_of(text).is_some_and(|h| {
        h.iter().any(|c| c == "subject_id") && h.iter().any(|c| c == "left" || c == "right")
    })
}

/// Parse a cohort manifest; `source` turns a path cell into a [`Source`], `format` a format
/// cell into a [`FormatSpec`] (both relative to the manifest's folder).
pub(crate) fn parse_manifest(
    text: &str,
    path: &Path,
    source: &dyn Fn(&str) -> Source,
    format: &dyn Fn(&str) -> Result<FormatSpec>,
) -> Result<Vec<SubjectInput>> {
    let text = text.trim_start_matches('\u{feff}');
    // A line longer than a recording's may be (a runaway label) is refused with its line: its
    // value would be copied into every output table of the subject.
    if let Some(i) = text
        .split('\n')
        .position(|l| l.len() + 1 > crate::io::MAX_LINE_BYTES)
    {
        return Err(LdhError::LineTooLong {
            loc: Location::line(path, i as u64 + 1),
            limit_bytes: crate::io::MAX_LINE_BYTES,
        });
    }
    const QUOTE_HINT: &str = "; a path or label holding a comma must be in double quotes";
    let table =
        Table::parse(text, path, &manifest_format()).map_err(|f| f.into_error(QUOTE_HINT))?;
    if table.header.iter().all(|c| c.is_empty()) {
        return Err(LdhError::EmptyFile {
            path: path.to_path_buf(),
        });
    }
    let cols = &table.header;
    check_header(cols, path, table.header_line)?;
    let trial_col = ["trial_id", "trial"]
        .into_iter()
        .find(|c| cols.iter().any(|x| x == c));
    let mut formats: HashMap<String, FormatSpec> = HashMap::new();
    let mut out: Vec<SubjectInput> = Vec::new();
    let mut seen: HashMap<(String, String), u64> = HashMap::new();
    for row in table.rows() {
        let row = row.map_err(|f| f.into_error(QUOTE_HINT))?;
        let line = row.line;
        if row.record.iter().all(|f| f.is_empty()) {
            continue;
        }
        let mut s = parse_row(&row, &mut formats, source, format)?;
        s.trial_id = trial_col
            .map(|c| row.get(c).to_string())
            .filter(|t| !t.is_empty());
        let key = (s.subject_id.clone(), s.trial_id.clone().unwrap_or_default());
        if let Some(first) = seen.insert(key, line) {
            let expected = match trial_col {
                None => format!("a subject id not used on line {first}; several trials of one person need a trial_id column"),
                Some(c) => format!("a ({}, {c}) pair not used on line {first}", "subject_id"),
            };
            return Err(row.invalid_value("subject_id", &s.subject_id, expected));
        }
        if let Some(prev) = out.iter().find(|p| p.subject_id == s.subject_id) {
            if prev.group != s.group || prev.affected_side != s.affected_side {
                return Err(row.invalid(
                    if prev.group != s.group {
                        "group"
                    } else {
                        "affected_side"
                    },
                    format!(
                        "the same group and affected side as the earlier trials of '{}'",
                        s.subject_id
                    ),
                ));
            }
        }
        out.push(s);
    }
    if out.is_empty() {
        // Nothing to analyse is a mistake (a wrong file, an export that lost its rows), not an
        // empty result (issue 37).
        return Err(LdhError::signal(
            path.display().to_string(),
            "the manifest has no subjects: a header row but no subject rows",
        ));
    }
    // A person's trials together (first-appearance order of persons kept): the tables then
    // hold each person's rows in one run.
    let mut order: Vec<&str> = Vec::new();
    for s in &out {
        if !order.contains(&s.subject_id.as_str()) {
            order.push(&s.subject_id);
        }
    }
    let rank: HashMap<String, usize> = order
        .iter()
        .enumerate()
        .map(|(i, id)| (id.to_string(), i))
        .collect();
    out.sort_by_key(|s| rank[&s.subject_id]);
    Ok(out)
}

/// Refuse duplicated, unknown and missing columns, naming them.
fn check_header(cols: &[String], path: &Path, line: u64) -> Result<()> {
    let loc = || Location::line(path, line);
    for (i, c) in cols.iter().enumerate() {
        if let Some(j) = cols[i + 1..].iter().position(|x| x == c) {
            return Err(LdhError::DuplicateColumn {
                loc: loc(),
                column: c.clone(),
                positions: vec![i + 1, i + j + 2],
            });
        }
        if !MANIFEST_COLUMNS.contains(&c.as_str()) {
            return Err(LdhError::UnknownColumn {
                loc: Location::cell(path, line, i + 1),
                column: c.clone(),
                what: "the cohort manifest".into(),
                accepted: MANIFEST_COLUMNS.join(", "),
            });
        }
    }
    let has = |n: &str| cols.iter().any(|c| c == n);
    let mut missing = Vec::new();
    if !has("subject_id") {
        missing.push("subject_id".to_string());
    }
    if !has("left") && !has("right") {
        missing.push("left".to_string());
        missing.push("right".to_string());
    }
    if !missing.is_empty() {
        return Err(LdhError::MissingColumn {
            loc: loc(),
            missing,
            by: "the cohort manifest (subject_id and at least one of left, right)".into(),
        });
    }
    if has("trial_id") && has("trial") {
        return Err(LdhError::InvalidValue {
            loc: loc(),
            column: "trial_id, trial".into(),
            value: "both".into(),
            expected: "one trial column, trial_id or trial".into(),
        });
    }
    Ok(())
}

fn parse_row(
    row: &Row,
    formats: &mut HashMap<String, FormatSpec>,
    source: &dyn Fn(&str) -> Source,
    format: &dyn Fn(&str) -> Result<FormatSpec>,
) -> Result<SubjectInput> {
    let id = row.get("subject_id");
    if id.is_empty() {
        return Err(row.invalid_value("subject_id", "", "a non-empty subject id"));
    }
    let group = Some(row.get("group"))
        .filter(|g| !g.is_empty())
        .map(|g| Group::from(g.to_string()));
    let side_cell = row.get("affected_side");
    let (affected_side, unknown) = match side_cell.to_ascii_lowercase().as_str() {
        "left" => (Some(Side::Left), false),
        "right" => (Some(Side::Right), false),
        "none" => (None, false),
        // Healthy controls have no affected side: empty is not "unknown" for them.
        "" => (None, group != Some(Group::Healthy)),
        other => {
            return Err(row.invalid_value(
                "affected_side",
                other,
                "'left', 'right', 'none' or empty (unknown)",
            ))
        }
    };
    let height = |name: &str| -> Result<Option<f64>> {
        let h = row.get(name);
        if h.is_empty() {
            return Ok(None);
        }
        match h.parse::<f64>() {
            Ok(v) if v.is_finite() && v > 0.0 => Ok(Some(v)),
            _ => Err(row.invalid_value(name, h, "a height in metres > 0")),
        }
    };
    let heights = SensorHeights {
        both_m: height("sensor_height_m")?,
        left_m: height("left_sensor_height_m")?,
        right_m: height("right_sensor_height_m")?,
    };
    if let Some(c) = heights.conflict() {
        let v = row.get(c.column());
        return Err(row.invalid_value(
            c.column(),
            v,
            format!(
                "the row's sensor_height_m ({}) or an empty sensor_height_m: one sensor cannot \
                 have two heights (leave sensor_height_m empty when the legs differ)",
                c.both_m
            ),
        ));
    }
    let st = row.get("setting");
    let setting =
        if st.is_empty() {
            None
        } else {
            Some(st.parse::<Setting>().map_err(|_| {
                row.invalid_value("setting", st, "'overground', 'treadmill' or empty")
            })?)
        };
    let mut spec = |name: &str| -> Result<Option<FormatSpec>> {
        let v = row.get(name);
        if v.is_empty() {
            return Ok(None);
        }
        if let Some(f) = formats.get(v) {
            return Ok(Some(f.clone()));
        }
        let f = format(v).map_err(|e| {
            row.invalid_value(
                name,
                v,
                format!("a built-in format name or a TOML column map ({e})"),
            )
        })?;
        formats.insert(v.to_string(), f.clone());
        Ok(Some(f))
    };
    let belt_speed_mps = belt_speed(row, setting)?;
    let visit = Some(row.get("visit"))
        .filter(|v| !v.is_empty())
        .map(str::to_string);
    let clocks = Some(row.get("clocks"))
        .filter(|v| !v.is_empty())
        .map(|v| {
            v.parse::<Clocks>().map_err(|_| {
                row.invalid_value("clocks", v, "'one' (synchronised sensors), 'two' or empty")
            })
        })
        .transpose()?;
    let both = spec("format")?;
    let left_format = spec("left_format")?.or_else(|| both.clone());
    let right_format = spec("right_format")?.or(both);
    let side = |n: &str| Some(row.get(n)).filter(|v| !v.is_empty()).map(source);
    Ok(SubjectInput {
        subject_id: id.to_string(),
        group,
        affected_side,
        affected_side_unknown: unknown,
        left: side("left"),
        right: side("right"),
        sensor_height_m: heights.both_m,
        left_sensor_height_m: heights.left_m,
        right_sensor_height_m: heights.right_m,
        setting,
        left_format,
        right_format,
        trial_id: None,
        belt_speed_mps,
        visit,
        clocks,
        ..SubjectInput::default()
    })
}

/// The row's `belt_speed_mps`: finite, 0 < v ≤ [`MAX_BELT_SPEED_MPS`], and only on a treadmill.
fn belt_speed(row: &Row, setting: Option<Setting>) -> Result<Option<f64>> {
    let v = row.get("belt_speed_mps");
    if v.is_empty() {
        return Ok(None);
    }
    let speed = match v.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 && x <= MAX_BELT_SPEED_MPS => x,
        _ => {
            return Err(row.invalid_value(
                "belt_speed_mps",
                v,
                format!("a belt speed in m/s, > 0 and at most {MAX_BELT_SPEED_MPS}"),
            ))
        }
    };
    if setting != Some(Setting::Treadmill) {
        return Err(row.invalid_value(
            "belt_speed_mps",
            v,
            "empty unless the row's setting is 'treadmill' (a belt speed is a treadmill's)",
        ));
    }
    Ok(Some(speed))
}

/// A format cell of a manifest in `dir`: a path to a TOML map (a name ending in `.toml`, or an
/// existing file; relative to `dir`), else a built-in format's name.
pub(crate) fn resolve_format_in(dir: &Path, name: &str) -> Result<FormatSpec> {
    let p = dir.join(name);
    if Path::new(name).extension().is_some_and(|e| e == "toml") || p.is_file() {
        FormatSpec::from_toml_file(p)
    } else {
        FormatSpec::builtin(name)
    }
}
