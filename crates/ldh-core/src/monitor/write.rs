//! The monitor's tables: bouts.csv, days.csv, summary.csv and periods.csv (one row per
//! bout, day, period of a person and visit, and wear/rest period), written with the `csv`
//! crate. A withheld value is an empty cell; its reason is in the row's `withheld` cell.

use std::path::Path;

use super::bouts::BoutRow;
use super::days::{gait_values, DayRow, PeriodRow, GAIT_AGGREGATES};
use super::MonitorResult;
use crate::error::{LdhError, Result};

fn num(v: f64) -> String {
    if v.is_finite() {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        if s.is_empty() || s == "-0" {
            "0".into()
        } else {
            s.to_string()
        }
    } else {
        String::new()
    }
}

fn id_cells(r: &MonitorResult) -> Vec<String> {
    vec![r.subject_id.clone(), r.visit.clone().unwrap_or_default()]
}

/// Header of bouts.csv.
pub const BOUT_COLUMNS: [&str; 22] = [
    "subject_id",
    "visit",
    "bout",
    "day",
    "start_s",
    "end_s",
    "duration_s",
    "steps",
    "legs",
    "strides_left",
    "strides_right",
    "cadence_steps_per_min",
    "speed_mps",
    "stride_time_s",
    "stride_length_m",
    "stride_time_cv",
    "step_time_asymmetry_pct",
    "kind",
    "stair_strides",
    "stride_rise_m",
    "clock_offset_s",
    "withheld",
];

fn gait_columns(prefix: &str) -> Vec<String> {
    let mut v = Vec::new();
    for c in GAIT_AGGREGATES {
        v.push(format!("{prefix}{c}_median"));
        v.push(format!("{prefix}{c}_p90"));
    }
    v
}

fn gait_cells(med: &[f64; 6], p90: &[f64; 6]) -> Vec<String> {
    (0..6).flat_map(|k| [num(med[k]), num(p90[k])]).collect()
}

type Rows = Vec<Vec<String>>;

/// The four tables' headers and rows.
pub fn tables(results: &[MonitorResult]) -> [(&'static str, Vec<String>, Rows); 4] {
    let mut bouts = Vec::new();
    let mut days = Vec::new();
    let mut summary = Vec::new();
    let mut periods = Vec::new();
    for r in results {
        bouts.extend(r.bouts.iter().map(|b| bout_cells(r, b)));
        days.extend(r.days.iter().map(|d| day_cells(r, d)));
        summary.push(summary_cells(r));
        periods.extend(r.periods.iter().map(|p| period_cells(r, p)));
    }
    [
        ("bouts.csv", head(&BOUT_COLUMNS), bouts),
        ("days.csv", day_header(), days),
        ("summary.csv", summary_header(), summary),
        ("periods.csv", head(&PERIOD_COLUMNS), periods),
    ]
}

fn head(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

/// One row of bouts.csv: bout `b` of person `r`.
fn bout_cells(r: &MonitorResult, b: &BoutRow) -> Vec<String> {
    let day_of = |t: f64| {
        r.days
            .iter()
            .rev()
            .find(|d| d.start_s <= t)
            .map_or(String::new(), |d| d.day.to_string())
    };
    let mut row = id_cells(r);
    row.extend([
        b.bout.to_string(),
        day_of(b.start_s),
        num(b.start_s),
        num(b.end_s),
        num(b.duration_s),
        b.steps.to_string(),
        b.legs.to_string(),
        b.strides_left.to_string(),
        b.strides_right.to_string(),
    ]);
    // The six bout values in GAIT_AGGREGATES' order, as the header has them.
    row.extend(gait_values(b).map(num));
    row.extend([
        b.kind.to_string(),
        b.stair_strides.to_string(),
        num(b.stride_rise_m),
        num(b.clock_offset_s),
        b.withheld.clone(),
    ]);
    row
}

/// The header of days.csv.
fn day_header() -> Vec<String> {
    let mut h = head(&[
        "subject_id",
        "visit",
        "day",
        "date",
        "start_s",
        "valid",
        "recorded_h",
        "wear_h",
        "waking_wear_h",
        "non_wear_h",
        "lying_h",
        "sitting_h",
        "standing_h",
        "cycling_min",
        "running_min",
        "walking_min",
        "steps",
        "bouts",
        "bouts_10_30s",
        "bouts_30_60s",
        "bouts_over_60s",
        "longest_bout_s",
        "long_bouts",
    ]);
    h.extend(gait_columns("long_bout_"));
    h.push("withheld".into());
    h
}

/// One row of days.csv: day `d` of person `r`.
fn day_cells(r: &MonitorResult, d: &DayRow) -> Vec<String> {
    let mut row = id_cells(r);
    row.extend([
        d.day.to_string(),
        d.date.clone(),
        num(d.start_s),
        d.valid.to_string(),
        num(d.recorded_h),
        num(d.wear_h),
        num(d.waking_wear_h),
        num(d.non_wear_h),
        num(d.lying_h),
        num(d.sitting_h),
        num(d.standing_h),
        num(d.cycling_min),
        num(d.running_min),
        num(d.walking_min),
        num(d.steps),
        num(d.bouts),
        num(d.bouts_10_30s),
        num(d.bouts_30_60s),
        num(d.bouts_over_60s),
        num(d.longest_bout_s),
        d.long_bouts.to_string(),
    ]);
    row.extend(gait_cells(&d.gait_median, &d.gait_p90));
    row.push(d.withheld.clone());
    row
}

/// The header of summary.csv.
fn summary_header() -> Vec<String> {
    let mut h = head(&[
        "subject_id",
        "visit",
        "days",
        "valid_days",
        "valid",
        "wear_h_per_day",
        "walking_min_per_day",
        "steps_per_day",
        "bouts_per_day",
        "longest_bout_s",
        "long_bouts",
    ]);
    h.extend(gait_columns("long_bout_"));
    h.extend(head(&[
        "drift_ppm",
        "drift_s_per_day",
        "bouts_total",
        "withheld",
        "errors",
    ]));
    h
}

/// The row of summary.csv of person `r`.
fn summary_cells(r: &MonitorResult) -> Vec<String> {
    let s = &r.summary;
    let mut row = id_cells(r);
    row.extend([
        s.days.to_string(),
        s.valid_days.to_string(),
        s.valid.to_string(),
    ]);
    row.extend(
        [
            s.wear_h_per_day,
            s.walking_min_per_day,
            s.steps_per_day,
            s.bouts_per_day,
            s.longest_bout_s,
        ]
        .map(num),
    );
    row.push(s.long_bouts.to_string());
    row.extend(gait_cells(&s.gait_median, &s.gait_p90));
    row.extend([
        num(s.drift_ppm),
        num(s.drift_s_per_day),
        r.bouts.len().to_string(),
        s.withheld.clone(),
        r.errors.join("; "),
    ]);
    row
}

/// Header of periods.csv.
const PERIOD_COLUMNS: [&str; 6] = [
    "subject_id",
    "visit",
    "start_s",
    "end_s",
    "duration_min",
    "state",
];

/// One row of periods.csv: wear/rest period `p` of person `r`.
fn period_cells(r: &MonitorResult, p: &PeriodRow) -> Vec<String> {
    let mut row = id_cells(r);
    row.extend([
        num(p.start_s),
        num(p.end_s),
        num(p.duration_min),
        p.state.clone(),
    ]);
    row
}

/// Write the four tables into `dir` (created if missing); returns the files written.
pub fn write_tables(dir: &Path, results: &[MonitorResult]) -> Result<Vec<std::path::PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|source| LdhError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut files = Vec::new();
    for (name, head, rows) in tables(results) {
        let path = dir.join(name);
        write_csv(&path, &head, &rows)?;
        files.push(path);
    }
    Ok(files)
}

/// One table written atomically with the `csv` crate.
fn write_csv<H: AsRef<[u8]>>(path: &Path, head: &[H], rows: &Rows) -> Result<()> {
    let mut buf = Vec::new();
    {
        let mut w = csv::Writer::from_writer(&mut buf);
        w.write_record(head)?;
        for r in rows {
            w.write_record(r)?;
        }
        w.flush().map_err(|source| LdhError::Io {
            path: path.to_path_buf(),
            source,
        })?;
    }
    crate::io::write_atomic(path, &buf)
}

/// Header of changes.csv.
pub const CHANGE_COLUMNS: [&str; 13] = [
    "subject_id",
    "from_visit",
    "to_visit",
    "measure",
    "unit",
    "days_from",
    "days_to",
    "mean_from",
    "mean_to",
    "change",
    "noise",
    "beyond_noise",
    "withheld",
];

/// changes.csv's rows (one per person, later period and daily measure) as text cells in
/// [`CHANGE_COLUMNS`] order: what `ldh monitor` writes and `ldh.monitor` returns.
pub fn change_rows(changes: &[super::VisitChange]) -> Rows {
    changes
        .iter()
        .map(|c| {
            vec![
                c.subject_id.clone(),
                c.from_visit.clone(),
                c.to_visit.clone(),
                c.measure.clone(),
                c.unit.clone(),
                c.days_from.to_string(),
                c.days_to.to_string(),
                num(c.mean_from),
                num(c.mean_to),
                num(c.change),
                num(c.noise),
                c.beyond_noise.map_or(String::new(), |b| b.to_string()),
                c.withheld.clone(),
            ]
        })
        .collect()
}

/// Write changes.csv (one row per person, later period and daily measure) into `dir`.
pub fn write_changes(dir: &Path, changes: &[super::VisitChange]) -> Result<std::path::PathBuf> {
    let path = dir.join("changes.csv");
    write_csv(&path, &CHANGE_COLUMNS, &change_rows(changes))?;
    Ok(path)
}
