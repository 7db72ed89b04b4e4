//! The result tables of `ldh analyze` (SPEC §6): per stride and per recording, as CSV and JSON
//! with stable column names that carry their units. A value that could not be computed is an
//! empty CSV cell and a JSON `null`, never a made-up number; the `reason`, `sta_status` and
//! `error` columns say why.
//!
//! The parameters' columns are their definitions' ([`Parameter::definition`]; docs/columns.md
//! lists them), written by one loop over [`Parameter::TABLE_ORDER`] ([`crate::domain::block`]).
//!
//! [`RecordingRow`] is the typed per-recording value that cohort, ml and report consume, and
//! also its own serialisation (see its doc for why there is no separate `Features` struct):
//! label columns are enums ([`labels`]), parameters are reached by [`Parameter`].

use serde::{Deserialize, Serialize};

use crate::domain::{ParameterBlock, PerParameter};
use crate::error::{LdhError, Result};
use crate::pipeline::quality::flat;
use crate::pipeline::{SubjectResult, Warning, WarningList, WithheldList};

pub mod columns;
pub mod cycle;
pub mod labels;
pub mod names;
mod parameter;
pub mod results;
mod row_serde;
pub mod run;
mod sink;
#[cfg(test)]
pub(crate) mod test_rows;
pub mod trace;

use labels::empty_is_none;
pub use labels::{AffectedSide, Known, Label, SideRole, Status};
pub use parameter::{Parameter, UnknownParameter};
pub use results::{GaitEvent, LdhResults, LdhStride, STRIDE_PARAMETERS};
pub use run::{read_marker, OutputRun, RunKind, RunMarker, RunWriter, MARKER};
pub use sink::{finish_tables, RenderedRows, TableSink};

fn num(x: f64, decimals: i32) -> Option<f64> {
    if x.is_finite() {
        let k = 10f64.powi(decimals);
        Some((x * k).round() / k)
    } else {
        None
    }
}

/// A row of the per-stride table (strides.csv/json). The parameters' values are one block,
/// [`StrideRow::values`], written by one loop over [`Parameter::PER_STRIDE`] between the
/// row's own columns ([`row_serde`]'s hand-written `Serialize` and `Deserialize`: a derived
/// `flatten` would write a map, which the CSV writer refuses), so a parameter given a
/// per-stride value ([`crate::domain::Definition::per_stride`] and its arm of
/// [`crate::gait::Stride::value`]) is a new column with no edit here.
#[derive(Debug, Clone, PartialEq)]
pub struct StrideRow {
    /// Subject.
    pub subject_id: String,
    /// `left` or `right` (any other text as read).
    pub side: Label<crate::Side>,
    /// Attitude model (`fusion` or `acc`; any other text as read).
    pub model: Label<crate::attitude::AttitudeModel>,
    /// Stride number within the recording.
    pub stride_index: usize,
    /// Walking bout.
    pub bout: usize,
    /// Heel strike, s from the recording's first sample.
    pub hs_time_s: Option<f64>,
    /// Toe off, s.
    pub to_time_s: Option<f64>,
    /// Next heel strike, s.
    pub next_hs_time_s: Option<f64>,
    /// The stride's value of each parameter of [`Parameter::PER_STRIDE`] (`None`: empty,
    /// withheld or not measured), under the parameter's column; `None` for the parameters
    /// without a per-stride value. Read it with [`StrideRow::value`].
    pub values: PerParameter<Option<f64>>,
    /// Heading change over the stride, deg.
    pub heading_change_deg: Option<f64>,
    /// Used for the per-side means.
    pub valid: bool,
    /// Why not valid, or why a value is withheld: the reasons' text, joined by `; `.
    pub reason: String,
    /// The same reasons as typed codes, in the same order ([`crate::gait::StrideCode`]; text
    /// joined by `; `): what a program groups or filters strides by. Empty in a table
    /// written before the column existed.
    pub reason_codes: crate::gait::StrideCodes,
    /// Trial of the person (manifest `trial_id`), empty for a single recording pair (and in a
    /// table written before the column existed).
    pub trial_id: String,
}

impl StrideRow {
    /// The stride's value of `p` (`None`: empty, or `p` has no per-stride value).
    pub fn value(&self, p: Parameter) -> Option<f64> {
        self.values[p]
    }
}

/// A row of the per-recording table (one per subject and side): the typed per-recording value
/// that cohort, ml and report consume, and its serialisation (field order = column order).
///
/// Why one type and not a `Features` value beside a string row: the row is the only thing that
/// both the pipeline writes and `ldh stats`/`train`/`report` read back from `recordings.json`,
/// so typing its fields (labels as enums in [`labels`], parameters reached by
/// [`Parameter`]) gives the consumers their types without a second struct and a
/// conversion in each direction; serde attributes keep the bytes of the CSV and JSON as they
/// were. The parameters are one [`ParameterBlock`] (a new parameter is a new column with no
/// edit here); its columns sit between the row's other columns, so the row is written by
/// [`row_serde`]'s hand-written `Serialize` (a derived `flatten` would write a map, which
/// the CSV writer refuses) and read by the derived `Deserialize` (JSON only).
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct RecordingRow {
    /// Subject.
    pub subject_id: String,
    /// `left` or `right`.
    pub side: Label<crate::Side>,
    /// Attitude model.
    pub model: Label<crate::attitude::AttitudeModel>,
    /// `healthy`, `ldh`, another label, or empty (`None`).
    #[serde(with = "empty_is_none")]
    pub group: Option<crate::pipeline::Group>,
    /// `left`, `right`, `none` or empty.
    #[serde(with = "empty_is_none")]
    pub affected_side: Option<Label<AffectedSide>>,
    /// `affected`, `unaffected`, `healthy` or empty: this side's role in the cohort analysis.
    #[serde(with = "empty_is_none")]
    pub side_role: Option<Label<SideRole>>,
    /// The file.
    pub source: String,
    /// `ok`, `no_valid_strides` (analysed, but no stride passed the checks: every parameter
    /// withheld) or `error`.
    pub status: Label<Status>,
    /// The error, when status is `error`.
    pub error: String,
    /// What the quality checks found, most severe first (docs/quality.md): the leg's (sensor
    /// faults, attitude, running, few strides, a device convention), the pair's (clocks, rates,
    /// identical files, disagreement, a possible swap) and the reader's (code `input`). JSON: a
    /// list of `{code, severity, message, affects}`; CSV: one cell, `code [severity]: message`
    /// joined by ` | `.
    #[serde(default)]
    pub warnings: WarningList,
    /// Parameters withheld by a check (their cells are empty): JSON an object column → reason;
    /// CSV one cell, `column: reason` joined by ` | `.
    #[serde(default)]
    pub withheld: WithheldList,
    /// Sampling rate, Hz.
    pub fs_hz: Option<f64>,
    /// Duration, s.
    pub duration_s: Option<f64>,
    /// Strides found.
    pub strides_total: Option<usize>,
    /// Valid strides.
    pub strides_valid: Option<usize>,
    /// Every parameter's value (empty when not measured) with STA's per-stride value and
    /// status: the columns of [`Parameter::TABLE_ORDER`], STA's followed by `sta_per_stride`
    /// and `sta_status` ([`crate::domain::block`]). Read as the rest of the row's fields.
    #[serde(flatten)]
    pub parameters: ParameterBlock,
    /// Device mounted mirrored.
    pub mirrored: Option<bool>,
    /// Device rotation about the shank, deg.
    pub axial_rotation_deg: Option<f64>,
    /// Samples replaced as outliers or clipped.
    pub outliers_replaced: Option<usize>,
    /// Clipped samples.
    pub clipped_samples: Option<usize>,
    /// Trial of the person (manifest `trial_id`), empty for a single recording pair. The
    /// cohort statistics and classifiers average a person's trials first.
    #[serde(default)]
    pub trial_id: String,
    /// `overground`, `treadmill`, or empty when not said (analysed as overground).
    #[serde(default, with = "empty_is_none")]
    pub setting: Option<Label<crate::Setting>>,
    /// The walk's cadence, steps/min, both legs' steps ([`crate::domain::WalkValue::Cadence`]):
    /// one value per walk, the same on both legs' rows.
    #[serde(default)]
    pub walk_cadence_steps_per_min: Option<f64>,
    /// Start of the walk's steady window the means and CVs are of, s on the left recording's
    /// clock ([`crate::domain::WalkValue::SteadyStart`]), the same on both legs' rows.
    #[serde(default)]
    pub steady_start_s: Option<f64>,
    /// End of the walk's steady window, s ([`crate::domain::WalkValue::SteadyEnd`]).
    #[serde(default)]
    pub steady_end_s: Option<f64>,
    /// Valid strides excluded at the start as not steady (speeding up).
    #[serde(default)]
    pub steady_excluded_start: Option<usize>,
    /// Valid strides excluded at the end as not steady (slowing down).
    #[serde(default)]
    pub steady_excluded_end: Option<usize>,
    /// Treadmill belt speed, m/s (manifest `belt_speed_mps`), empty when not given.
    #[serde(default)]
    pub belt_speed_mps: Option<f64>,
    /// The visit of the recording (manifest `visit`), empty when not given.
    #[serde(default)]
    pub visit: String,
    /// When the recording started, where its file says it (ISO 8601, `Z` when UTC:
    /// `io::RecordedAt`); empty when the file does not.
    #[serde(default)]
    pub recorded_at: String,
    /// Set on a person's row that is the mean of several trials
    /// ([`crate::cohort::person_row`]), whose `trial_id` is then this value's text. Not a
    /// column: what a program tests instead of reading `trial_id`.
    #[serde(skip)]
    pub trial_mean: Option<TrialMean>,
}

/// A person's row made as the mean of several trials ([`crate::cohort::person_row`]): the
/// trials averaged, in order. Shown as `mean of 2 trials (t1, t2)`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct TrialMean {
    /// The trials averaged (their `trial_id`).
    pub trial_ids: Vec<String>,
    /// The parameters that only some of the trials measured, each with those trials (in
    /// order): their "mean" is of those trials alone (issue 50: on a page of three belt
    /// speeds the step time and double support came from the slowest belt only, under "the
    /// mean of 3 trials").
    pub partial: Vec<(Parameter, Vec<String>)>,
}

impl TrialMean {
    /// The trials that measured `p`, when fewer than all those averaged (`None`: every trial
    /// did, or none).
    pub fn only_from(&self, p: Parameter) -> Option<&[String]> {
        self.partial
            .iter()
            .find(|(q, _)| *q == p)
            .map(|(_, ids)| ids.as_slice())
    }
}

impl std::fmt::Display for TrialMean {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "mean of {} trials ({})",
            self.trial_ids.len(),
            self.trial_ids.join(", ")
        )
    }
}

impl RecordingRow {
    /// A value of the walk this row's leg belongs to (the same on both legs' rows).
    pub fn walk(&self, v: crate::domain::WalkValue) -> Option<f64> {
        use crate::domain::WalkValue;
        match v {
            WalkValue::Cadence => self.walk_cadence_steps_per_min,
            WalkValue::SteadyStart => self.steady_start_s,
            WalkValue::SteadyEnd => self.steady_end_s,
        }
    }
    /// The recording was analysed (`status` is `ok` or `no_valid_strides`, not `error`).
    pub fn is_ok(&self) -> bool {
        matches!(
            self.status.known(),
            Some(Status::Ok | Status::NoValidStrides)
        )
    }
}

/// The per-stride rows of a set of results.
pub fn stride_rows(results: &[SubjectResult]) -> Vec<StrideRow> {
    let mut out = Vec::new();
    for r in results {
        for (side, leg) in r.legs() {
            let Ok(leg) = leg else { continue };
            for s in &leg.strides {
                out.push(StrideRow {
                    subject_id: r.subject_id.clone(),
                    side: side.into(),
                    model: r.model.into(),
                    stride_index: s.stride_index,
                    bout: s.bout,
                    hs_time_s: num(s.hs_time_s, 4),
                    to_time_s: num(s.to_time_s, 4),
                    next_hs_time_s: num(s.next_hs_time_s, 4),
                    values: PerParameter::from_fn(|p| {
                        s.value(p).and_then(|v| num(v, p.decimals()))
                    }),
                    heading_change_deg: num(s.heading_change_deg, 2),
                    valid: s.valid,
                    reason: s.reason.clone(),
                    reason_codes: s.codes(),
                    trial_id: r.trial_id.clone().unwrap_or_default(),
                });
            }
        }
    }
    out
}

/// The walk's cadence of a subject, steps/min, from its legs' final mean stride times
/// ([`crate::domain::walk_cadence_steps_per_min`]), rounded as the table writes it.
fn walk_cadence(r: &SubjectResult) -> Option<f64> {
    let st = |leg: &std::result::Result<crate::pipeline::LegResult, String>| {
        leg.as_ref()
            .ok()
            .map(|l| l.parameters[Parameter::StrideTime])
    };
    crate::domain::walk_cadence_steps_per_min(st(&r.left), st(&r.right)).and_then(|c| num(c, 2))
}

/// The per-recording rows of a set of results (failed legs included, with their error).
pub fn recording_rows(results: &[SubjectResult]) -> Vec<RecordingRow> {
    let mut out = Vec::new();
    for r in results {
        for (side, leg) in r.legs() {
            use crate::pipeline::Group;
            let role = match (&r.group, r.affected_side) {
                (Some(Group::Healthy), _) => Some(SideRole::Healthy),
                (Some(Group::Ldh), Some(a)) if a == side => Some(SideRole::Affected),
                (Some(Group::Ldh), Some(_)) => Some(SideRole::Unaffected),
                _ => None,
            };
            let mut row = RecordingRow {
                subject_id: r.subject_id.clone(),
                side: side.into(),
                model: r.model.into(),
                group: r.group.clone(),
                affected_side: match (&r.group, r.affected_side) {
                    (_, Some(s)) => Some(AffectedSide::from(s).into()),
                    (Some(_), None) if !r.affected_side_unknown => {
                        Some(AffectedSide::Neither.into())
                    }
                    _ => None,
                },
                side_role: role.map(Label::from),
                source: String::new(),
                status: Status::Ok.into(),
                error: String::new(),
                warnings: WarningList::default(),
                withheld: WithheldList::default(),
                fs_hz: None,
                duration_s: None,
                strides_total: None,
                strides_valid: None,
                parameters: ParameterBlock::default(),
                mirrored: None,
                axial_rotation_deg: None,
                outliers_replaced: None,
                clipped_samples: None,
                trial_id: r.trial_id.clone().unwrap_or_default(),
                setting: r.setting.map(Label::from),
                walk_cadence_steps_per_min: walk_cadence(r),
                steady_start_s: None,
                steady_end_s: None,
                steady_excluded_start: None,
                steady_excluded_end: None,
                belt_speed_mps: r.belt_speed_mps,
                visit: r.visit.clone().unwrap_or_default(),
                recorded_at: String::new(),
                trial_mean: None,
            };
            match leg {
                Err(e) => {
                    row.status = Status::Error.into();
                    row.error = e.clone();
                }
                Ok(l) => {
                    let p = &l.parameters;
                    let mut w: Vec<Warning> = crate::pipeline::all_leg_warnings(l);
                    w.extend(r.warnings.iter().cloned());
                    w.sort_by_key(|x| std::cmp::Reverse(x.severity));
                    row.warnings = WarningList(w);
                    row.withheld = WithheldList(p.withheld.clone());
                    row.source = l.source.clone();
                    row.recorded_at = l.read.recorded_at.map_or(String::new(), |r| r.at.iso());
                    row.fs_hz = num(l.read.fs_hz, 4);
                    row.duration_s = num(l.read.duration_s, 3);
                    row.strides_total = Some(p.strides_total);
                    row.strides_valid = Some(p.strides_valid);
                    if p.strides_valid == 0 {
                        row.status = Status::NoValidStrides.into();
                    }
                    row.parameters = ParameterBlock {
                        values: PerParameter::from_fn(|q| num(p[q], q.decimals())),
                        sta_per_stride: num(p.sta_per_stride, 4),
                        sta_status: p.sta_status.clone(),
                    };
                    row.mirrored = Some(l.alignment.mirrored);
                    row.axial_rotation_deg = num(l.alignment.axial_rotation_deg, 1);
                    row.outliers_replaced = Some(l.outliers_replaced);
                    row.clipped_samples = Some(l.read.saturated_samples);
                    if let Some(w) = &l.steady {
                        row.steady_start_s = num(w.start_s, 3);
                        row.steady_end_s = num(w.end_s, 3);
                        row.steady_excluded_start = Some(w.excluded_start);
                        row.steady_excluded_end = Some(w.excluded_end);
                    }
                }
            }
            out.push(row);
        }
    }
    out
}

/// A row of the bilateral event table (`events.csv`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EventRow {
    /// Subject.
    pub subject_id: String,
    /// Time, s from the recordings' first sample.
    pub time_s: f64,
    /// `left` or `right` (any other text as read).
    pub side: Label<crate::Side>,
    /// `HS` or `TO`.
    pub event: String,
    /// Where the alternation breaks, why; else empty.
    pub order: String,
    /// Trial of the person (manifest `trial_id`), empty for a single recording pair.
    #[serde(default)]
    pub trial_id: String,
    /// The event's confidence, 0–1, two decimals (`events::confidence`; below 0.25 the strides
    /// it bounds are withheld); empty when the detector gives none.
    #[serde(default)]
    pub confidence: Option<f64>,
}

/// Rows grouped by subject in one pass, subjects in the order they first appear (a batch of
/// 10 000 recordings is grouped in linear time, not by a search per subject).
pub fn rows_by_subject(rows: &[RecordingRow]) -> Vec<(&str, Vec<&RecordingRow>)> {
    let mut index: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    let mut out: Vec<(&str, Vec<&RecordingRow>)> = Vec::new();
    for r in rows {
        let i = *index.entry(r.subject_id.as_str()).or_insert_with(|| {
            out.push((r.subject_id.as_str(), Vec::new()));
            out.len() - 1
        });
        out[i].1.push(r);
    }
    out
}

/// The bilateral event rows of a set of results, per subject in time order.
pub fn event_rows(results: &[SubjectResult]) -> Vec<EventRow> {
    let mut out = Vec::new();
    for r in results {
        for e in r.bilateral_events() {
            out.push(EventRow {
                subject_id: r.subject_id.clone(),
                time_s: (e.time_s * 1e4).round() / 1e4,
                side: e.side.into(),
                event: match e.event {
                    crate::pipeline::EventKind::HeelStrike => "HS".into(),
                    crate::pipeline::EventKind::ToeOff => "TO".into(),
                },
                order: e.order,
                trial_id: r.trial_id.clone().unwrap_or_default(),
                confidence: e.confidence.map(|c| (c * 100.0).round() / 100.0),
            });
        }
    }
    out
}

/// The three result tables of a set of results (what `ldh analyze` writes as separate files).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Tables {
    /// Per-stride rows.
    pub strides: Vec<StrideRow>,
    /// Per-recording rows.
    pub recordings: Vec<RecordingRow>,
    /// Bilateral event rows.
    pub events: Vec<EventRow>,
}

impl Tables {
    /// All three tables of `results`.
    pub fn of(results: &[SubjectResult]) -> Tables {
        Tables {
            strides: stride_rows(results),
            recordings: recording_rows(results),
            events: event_rows(results),
        }
    }
}

/// Rows as CSV text (header from the field names).
pub fn to_csv<T: Serialize>(rows: &[T], header_if_empty: &[&str]) -> Result<String> {
    let mut w = csv::WriterBuilder::new()
        .has_headers(true)
        .from_writer(Vec::new());
    if rows.is_empty() {
        w.write_record(header_if_empty)?;
    }
    for r in rows {
        flat(|| w.serialize(r))?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| LdhError::signal("csv", e.to_string()))?;
    String::from_utf8(bytes).map_err(|e| LdhError::signal("csv", e.to_string()))
}

/// The per-stride table's own columns before the parameters'.
const STRIDE_HEAD: [&str; 8] = [
    "subject_id",
    "side",
    "model",
    "stride_index",
    "bout",
    "hs_time_s",
    "to_time_s",
    "next_hs_time_s",
];

/// The per-stride table's own columns after the parameters'.
const STRIDE_TAIL: [&str; 5] = [
    "heading_change_deg",
    "valid",
    "reason",
    "reason_codes",
    "trial_id",
];

/// How many columns the per-stride table has.
const STRIDE_COLUMN_COUNT: usize =
    STRIDE_HEAD.len() + Parameter::PER_STRIDE_COUNT + STRIDE_TAIL.len();

/// Column names of the per-stride table: its own, with the columns of
/// [`Parameter::PER_STRIDE`] after `next_hs_time_s`.
pub const STRIDE_COLUMNS: [&str; STRIDE_COLUMN_COUNT] = {
    let mut out = [""; STRIDE_COLUMN_COUNT];
    let mut i = 0;
    while i < STRIDE_COLUMN_COUNT {
        let h = STRIDE_HEAD.len();
        let p = Parameter::PER_STRIDE_COUNT;
        out[i] = if i < h {
            STRIDE_HEAD[i]
        } else if i < h + p {
            Parameter::PER_STRIDE[i - h].column()
        } else {
            STRIDE_TAIL[i - h - p]
        };
        i += 1;
    }
    out
};

/// Column names of the bilateral event table.
pub const EVENT_COLUMNS: [&str; 6] = ["subject_id", "time_s", "side", "event", "order", "trial_id"];

/// Read a per-stride table (`strides.csv`) as runs of consecutive rows of the same subject,
/// one run at a time (what `ldh analyze` writes: each subject's rows together).
pub fn stride_groups(
    path: &std::path::Path,
) -> Result<impl Iterator<Item = Result<(String, Vec<StrideRow>)>>> {
    let mut it =
        crate::io::table::deserialize_stream::<StrideRow>(path, "a stride table")?.peekable();
    Ok(std::iter::from_fn(move || {
        let first = match it.next()? {
            Ok(r) => r,
            Err(e) => return Some(Err(e)),
        };
        let id = first.subject_id.clone();
        let mut rows = vec![first];
        while let Some(Ok(next)) = it.peek() {
            if next.subject_id != id {
                break;
            }
            rows.push(it.next().expect("peeked").expect("peeked ok"));
        }
        Some(Ok((id, rows)))
    }))
}

/// The per-recording table (`recordings.json`) of an `ldh analyze` output folder.
pub fn read_recordings(results: &std::path::Path) -> Result<Vec<RecordingRow>> {
    let path = results.join("recordings.json");
    let text = crate::io::read_text_limited(&path, crate::io::MAX_TABLE_MB, "an output table")?;
    serde_json::from_str(&text).map_err(|e| LdhError::Format {
        name: path.display().to_string(),
        reason: format!("not an ldh recordings table: {e}"),
    })
}
