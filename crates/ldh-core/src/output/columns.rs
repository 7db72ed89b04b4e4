//! The column dictionary: every column of `recordings.csv`, `strides.csv` and `events.csv` with
//! its unit and meaning, in words a clinician or a data scientist can use (issue 39). One table
//! in code ([`columns`]); the gait parameters' columns come from their one definition
//! ([`Parameter::definition`], issue 48); `docs/columns.md` is generated from it ([`markdown`])
//! and `ldh columns [NAME]` prints it. A test checks that every column the writers emit is here exactly once and that
//! the committed docs/columns.md is what [`markdown`] writes.

use std::borrow::Cow;
use std::fmt::Write;

use crate::domain::{Parameter, WalkValue};

/// Which output table a column belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Table {
    /// `recordings.csv`: one row per subject (and trial) and side.
    Recordings,
    /// `strides.csv`: one row per stride.
    Strides,
    /// `events.csv`: both legs' heel strikes and toe offs in time order.
    Events,
}

impl Table {
    /// The file name.
    pub fn file(self) -> &'static str {
        match self {
            Table::Recordings => "recordings.csv",
            Table::Strides => "strides.csv",
            Table::Events => "events.csv",
        }
    }
}

/// One column: table, name, unit ("" for text) and meaning.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ColumnDoc {
    /// The table.
    pub table: Table,
    /// The column name as written.
    pub name: &'static str,
    /// The unit ("" for text and flags).
    pub unit: &'static str,
    /// What it means.
    pub meaning: Cow<'static, str>,
}

/// A column of [`LAYOUT`], or the place of a table's parameter columns.
enum Entry {
    /// A column that is no gait parameter.
    C(Table, &'static str, &'static str, &'static str),
    /// The table's parameter columns, from their [`Parameter`] definitions: in recordings.csv
    /// every parameter (STA followed by `sta_per_stride` and `sta_status`), in strides.csv those
    /// with a per-stride value.
    P(Table),
}

const fn c(table: Table, name: &'static str, unit: &'static str, meaning: &'static str) -> Entry {
    Entry::C(table, name, unit, meaning)
}

/// A walk value's column of recordings.csv, from its one definition ([`WalkValue`]).
const fn w(v: WalkValue) -> Entry {
    Entry::C(R, v.column(), v.unit(), v.description())
}

use Entry::P;
use Table::{Events as E, Recordings as R, Strides as S};

/// Every output column, in each table's column order.
const LAYOUT: &[Entry] = &[
    c(R, "subject_id", "", "The person (manifest `subject_id`, or the folder name)."),
    c(R, "side", "", "`left` or `right`: the leg this row is about."),
    c(R, "model", "", "Attitude model: `fusion` (adaptive Kalman fusion of gyroscope and accelerometer, the default) or `acc` (accelerometer only, for comparison)."),
    c(R, "group", "", "The group label as given in the manifest (`healthy`, `ldh` or any other label); empty when not given."),
    c(R, "affected_side", "", "The LDH subject's affected side as given: `left`, `right`, `none`, or empty when unknown."),
    c(R, "side_role", "", "This side's role in the cohort comparison: `affected` (LDHE), `unaffected` (LDHH), `healthy` (H), or empty."),
    c(R, "source", "", "The file this side was read from."),
    c(R, "status", "", "`ok`; `no_valid_strides` (analysed, but no stride passed the checks: every parameter withheld); `error` (not analysed; see `error`)."),
    c(R, "error", "", "Why the recording could not be analysed (status `error`)."),
    c(R, "warnings", "", "What the quality checks found, most severe first, as `code [severity]: message` joined by ` | ` (docs/quality.md lists every code)."),
    c(R, "withheld", "", "Parameters withheld by a check, as `column: reason` joined by ` | `; their cells are empty."),
    c(R, "fs_hz", "Hz", "Sampling rate of the recording."),
    c(R, "duration_s", "s", "Length of the recording."),
    c(R, "strides_total", "strides", "Strides found (heel strike to the next heel strike of the same leg)."),
    c(R, "strides_valid", "strides", "Strides the parameters are means of (not a turn, not at a bout's edge, steady walking, passed the checks)."),
    P(R),
    c(R, "mirrored", "", "`true` when the device is mounted with its y axis backwards (as a device worn on the lateral side of the right shank is); corrected for."),
    c(R, "axial_rotation_deg", "deg", "How far the device is turned about the shank axis from its nominal mounting; corrected for."),
    c(R, "outliers_replaced", "samples", "Samples replaced as outliers (3 SD of |a|) or clipped."),
    c(R, "clipped_samples", "samples", "Samples at the sensor's range (clipped)."),
    c(R, "trial_id", "", "The trial of the person (manifest `trial_id`); empty for a single recording pair. Statistics and classifiers average a person's trials first."),
    c(R, "setting", "", "`overground`, `treadmill`, or empty (analysed as overground)."),
    w(WalkValue::Cadence),
    w(WalkValue::SteadyStart),
    w(WalkValue::SteadyEnd),
    c(R, "steady_excluded_start", "strides", "Valid strides of this leg excluded before the walk's steady window (speeding up: belt start-up, gait initiation)."),
    c(R, "steady_excluded_end", "strides", "Valid strides of this leg excluded after the walk's steady window (slowing down, or walking at another pace)."),
    c(R, "belt_speed_mps", "m/s", "Treadmill belt speed as given in the manifest (`belt_speed_mps`); empty when not given."),
    c(R, "visit", "", "The visit of the recording as given in the manifest (`visit`: a label or a date); empty when not given."),
    c(R, "recorded_at", "", "When the recording started, as its file says it (a header line such as `// Start Time:` or `# start:`, Xsens' `UTC_Year` … `UTC_Second` columns, the first ISO 8601 or Unix timestamp), ISO 8601 to the second, `Z` when UTC; empty when the file does not say (docs/input.md)."),
    c(S, "subject_id", "", "The person."),
    c(S, "side", "", "`left` or `right`."),
    c(S, "model", "", "Attitude model (`fusion` or `acc`)."),
    c(S, "stride_index", "", "Stride number within the recording, from 0."),
    c(S, "bout", "", "Walking bout (a pause or a turn ends one), from 0."),
    c(S, "hs_time_s", "s", "Heel strike that begins the stride, from the recording's first sample."),
    c(S, "to_time_s", "s", "Toe off within the stride; empty when not found."),
    c(S, "next_hs_time_s", "s", "Heel strike that ends the stride."),
    P(S),
    c(S, "heading_change_deg", "deg", "Change of walking direction over the stride (turn detection; not a clinical value)."),
    c(S, "valid", "", "`true` when the stride counts in the means; `false` with its reason (a turn, a bout's edge, not steady walking, a check)."),
    c(S, "reason", "", "Why the stride is not valid, or why one of its values is withheld; reasons joined by `; `."),
    c(S, "reason_codes", "", "The same reasons as stable codes, one per reason in the same order, joined by `; ` (empty when `reason` is): `stride_time_out_of_range`, `toe_off`, `turn`, `bout_edge`, `not_steady`, `angles_out_of_bounds`, `unsure_hs_no_impact`, `unsure_hs_two_landings`, `unsure_to_two_push_offs` exclude the stride; `length_<check>` (`length_drift`, `length_clipped`, `length_tilt_correction`, `length_floor`, `length_pendulum`, `length_bout_median`, `length_other_leg`, `length_acc_only`, `length_not_integrable`) and `length_not_vouched` withhold its length only; a quality finding is its warning code (docs/quality.md) when it excludes the stride (`channel_fault`), else the code with what it withholds (`no_quiet_standing:angles`, `lr_disagreement:length`, `…:angles_and_length`). Group or filter strides by these, not by `reason`'s text."),
    c(S, "trial_id", "", "The trial of the person (manifest `trial_id`)."),
    c(E, "subject_id", "", "The person."),
    c(E, "time_s", "s", "Time of the event, from the recordings' first sample."),
    c(E, "side", "", "`left` or `right`."),
    c(E, "event", "", "`HS` (heel strike) or `TO` (toe off)."),
    c(E, "order", "", "Where the left/right alternation breaks, why; empty otherwise."),
    c(E, "trial_id", "", "The trial of the person (manifest `trial_id`)."),
    c(E, "confidence", "", "How surely the signals place the event, 0–1 (docs/quality.md \"Unsure events\"): a heel strike at its own impact 0.5–1 (by the impact's prominence), 0.5 where the walk shows no impacts, 0.3 without an impact in a walk that shows them (at the walk's median delay) or with one at the zero crossing (at the leg's), 0.2 with two candidate landings; a toe off 1 − its rival push-off peak over its own. Below 0.25 the strides the event bounds are withheld. Empty when the detector gives none."),
];

/// Labels that appear in the cohort statistics and reports rather than as columns.
pub const LABELS: &[(&str, &str)] = &[
    ("LDHE", "the affected side of the LDH subjects"),
    ("LDHH", "the unaffected side of the LDH subjects"),
    ("H", "healthy subjects (mean of both legs)"),
    ("HE", "the paired comparison of the two LDH sides"),
    ("H-H", "LDHH against H"),
    ("E-H", "LDHE against H"),
    ("LR", "healthy left against right"),
];

/// STA's companion columns in recordings.csv (after `sta_per_s`).
const STA_COMPANIONS: [(&str, &str, &str); 2] = [
    (
        "sta_per_stride",
        "1/stride",
        "STA × mean stride time: the same divergence per stride.",
    ),
    (
        "sta_status",
        "",
        "Why STA is empty (too few strides, not computed, a fault).",
    ),
];

fn parameter_columns(t: Table, out: &mut Vec<ColumnDoc>) {
    for p in Parameter::TABLE_ORDER {
        let d = p.definition();
        let meaning = match t {
            Table::Recordings => format!("{} ({}): {}", d.code, d.name, d.description),
            _ => match d.per_stride {
                Some(m) => m.to_string(),
                None => continue,
            },
        };
        out.push(ColumnDoc {
            table: t,
            name: d.column,
            unit: d.unit.as_str(),
            meaning: meaning.into(),
        });
        if t == Table::Recordings && p == Parameter::Sta {
            for (name, unit, meaning) in STA_COMPANIONS {
                out.push(ColumnDoc {
                    table: t,
                    name,
                    unit,
                    meaning: meaning.into(),
                });
            }
        }
    }
}

/// Every output column, in each table's column order: the dictionary.
pub fn columns() -> &'static [ColumnDoc] {
    static ALL: std::sync::OnceLock<Vec<ColumnDoc>> = std::sync::OnceLock::new();
    ALL.get_or_init(|| {
        let mut out = Vec::new();
        for e in LAYOUT {
            match *e {
                Entry::C(table, name, unit, meaning) => out.push(ColumnDoc {
                    table,
                    name,
                    unit,
                    meaning: meaning.into(),
                }),
                Entry::P(t) => parameter_columns(t, &mut out),
            }
        }
        out
    })
}

/// The columns called `name` (case-insensitive), in every table that has one.
pub fn lookup(name: &str) -> Vec<&'static ColumnDoc> {
    columns()
        .iter()
        .filter(|c| c.name.eq_ignore_ascii_case(name.trim()))
        .collect()
}

/// Column names that contain `part` (case-insensitive), for a "did you mean".
pub fn similar(part: &str) -> Vec<&'static str> {
    let part = part.trim().to_ascii_lowercase();
    let mut v: Vec<&str> = columns()
        .iter()
        .map(|c| c.name)
        .filter(|n| !part.is_empty() && (n.contains(&part) || part.contains(n)))
        .collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// One column as a few lines of text (`ldh columns NAME`).
pub fn describe(c: &ColumnDoc) -> String {
    let unit = if c.unit.is_empty() { "text" } else { c.unit };
    format!("{} ({}; {unit})\n  {}\n", c.name, c.table.file(), c.meaning)
}

/// The whole dictionary as Markdown (docs/columns.md).
pub fn markdown() -> String {
    let mut s = String::from(
        "# Output columns\n\nGenerated from `crates/ldh-core/src/output/columns.rs` and the gait parameters' one definition in\n`crates/ldh-core/src/domain/parameter.rs` (`ldh columns` prints it, `ldh columns NAME` one column); a\ntest keeps this file and the writers in step. Stance, swing and the CVs are fractions (× 100 = %).\nAn empty cell is a value that was not measured: the `withheld` column (recordings) or `reason`\n(strides) says why.\n",
    );
    for t in [Table::Recordings, Table::Strides, Table::Events] {
        let _ = write!(
            s,
            "\n## {}\n\n| column | unit | meaning |\n|---|---|---|\n",
            t.file()
        );
        for c in columns().iter().filter(|c| c.table == t) {
            let _ = writeln!(s, "| `{}` | {} | {} |", c.name, c.unit, c.meaning);
        }
    }
    s.push_str(
        "\n## Labels in the cohort statistics and reports\n\n| label | meaning |\n|---|---|\n",
    );
    for (l, m) in LABELS {
        let _ = writeln!(s, "| {l} | {m} |");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The header line a writer emits for `rows`.
    fn header<T: serde::Serialize>(rows: &[T]) -> Vec<String> {
        let text = crate::output::to_csv(rows, &[]).unwrap();
        text.lines()
            .next()
            .unwrap()
            .split(',')
            .map(String::from)
            .collect()
    }

    #[test]
    fn every_written_column_is_documented_once_in_order() {
        let inputs = crate::pipeline::demo_inputs().unwrap();
        let params = crate::pipeline::AnalysisParams {
            compute_sta: false,
            ..Default::default()
        };
        let analysis = crate::pipeline::Analysis::new(params.check().unwrap());
        let results: Vec<_> = inputs[..1].iter().map(|i| analysis.subject(i)).collect();
        for (t, written) in [
            (
                Table::Recordings,
                header(&crate::output::recording_rows(&results)),
            ),
            (
                Table::Strides,
                header(&crate::output::stride_rows(&results)),
            ),
            (Table::Events, header(&crate::output::event_rows(&results))),
        ] {
            let documented: Vec<String> = columns()
                .iter()
                .filter(|c| c.table == t)
                .map(|c| c.name.to_string())
                .collect();
            assert_eq!(written, documented, "{}", t.file());
        }
    }

    #[test]
    fn docs_columns_md_is_generated() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/columns.md");
        if std::env::var_os("LDH_PIN_WRITE").is_some() {
            std::fs::write(path, markdown()).unwrap();
        }
        let committed = std::fs::read_to_string(path).unwrap_or_default();
        assert!(
            committed == markdown(),
            "docs/columns.md is not what output::columns::markdown() writes: regenerate with LDH_PIN_WRITE=1 cargo test -p ldh-core columns"
        );
    }

    #[test]
    fn lookup_and_similar() {
        assert_eq!(lookup("WQK_DEG").len(), 2);
        assert_eq!(lookup("steady_end_s")[0].table, Table::Recordings);
        assert!(lookup("wqk").is_empty());
        assert!(similar("wqk").contains(&"wqk_deg"));
        assert!(describe(lookup("stance_ratio")[0]).contains("fraction of the gait cycle"));
    }
}
