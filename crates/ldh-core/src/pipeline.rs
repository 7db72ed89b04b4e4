//! The per-recording pipeline (SPEC §3): recording → preprocessed → aligned → attitude →
//! events → strides → parameters, for one subject's two legs, and the discovery of inputs
//! (a pair of files, a subject folder, a cohort folder, a manifest, or the embedded demo).
//!
//! One bad recording never stops the other leg or the other subjects: each side's outcome is a
//! `Result`, with the error message naming the file.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

use crate::align::{align, AlignParams, Aligned, Alignment};
use crate::attitude::{estimate, Attitude, AttitudeModel, AttitudeParams};
use crate::error::{LdhError, Result};
use crate::events::{detect, EventParams, Events};
use crate::gait::{side_parameters, strides, SideParameters, Stride, StrideParams};
use crate::io::{read_recording, read_recording_bytes, FormatSpec, ReadReport, ValidReadParams};
use crate::nonlinear::{gait_sta, GaitStaParams};
use crate::preprocess::{preprocess, PreprocessParams};
use crate::recording::{Recording, Side};
use crate::simulate::Group;

/// All analysis parameters (each stage's own type; validated by [`AnalysisParams::check`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AnalysisParams {
    /// Preprocessing (paper §3.1).
    pub preprocess: PreprocessParams,
    /// Sensor-to-segment alignment.
    pub align: AlignParams,
    /// Attitude model and filter.
    pub attitude: AttitudeParams,
    /// Event detection.
    pub events: EventParams,
    /// Strides and stride length. `sensor_height_m` is overridden per subject by the manifest.
    pub strides: StrideParams,
    /// Gait stability (STA).
    pub sta: GaitStaParams,
    /// Compute STA. Default true.
    pub compute_sta: bool,
    /// Most strides STA is computed over: the first `sta_max_strides` of the longest run of
    /// valid strides. Default 150. The exponent depends on the length of the series, so a fixed
    /// number of strides keeps recordings of different lengths comparable (Bruijn et al., J
    /// Neurosci Methods 2009;178:327–333, who advise ≥ 150 strides and equal numbers across
    /// subjects), and it bounds the cost of a 2-hour recording. 0 = no limit.
    pub sta_max_strides: usize,
}

impl Default for AnalysisParams {
    fn default() -> Self {
        AnalysisParams {
            preprocess: PreprocessParams::default(),
            align: AlignParams::default(),
            attitude: AttitudeParams::default(),
            events: EventParams::default(),
            strides: StrideParams::default(),
            sta: GaitStaParams::default(),
            compute_sta: true,
            sta_max_strides: 150,
        }
    }
}

impl AnalysisParams {
    /// With another attitude model.
    pub fn model(mut self, m: AttitudeModel) -> Self {
        self.attitude.model = m;
        self
    }
    /// These parameters with the options of a command line or an API call applied (each `None`
    /// keeps the current value), then checked. One place for the CLI and the Python binding.
    pub fn with_options(
        mut self,
        model: Option<&str>,
        detector: Option<&str>,
        sensor_height_m: Option<f64>,
        compute_sta: Option<bool>,
    ) -> Result<Self> {
        if let Some(m) = model {
            self.attitude.model = m.parse()?;
        }
        if let Some(d) = detector {
            self.events.detector = d.parse()?;
        }
        if let Some(h) = sensor_height_m {
            self.strides.sensor_height_m = h;
        }
        if let Some(c) = compute_sta {
            self.compute_sta = c;
        }
        self.check()?;
        Ok(self)
    }

    /// Validate every stage's parameters that do not depend on the recording.
    pub fn check(&self) -> Result<()> {
        self.align.check()?;
        self.attitude.check()?;
        self.events.check()?;
        self.strides.check()?;
        Ok(())
    }
}

/// Where a recording comes from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Source {
    /// A file.
    Path(PathBuf),
    /// A file of the embedded demo cohort (relative path).
    Embedded(String),
}

impl Source {
    /// A label for messages and tables.
    pub fn label(&self) -> String {
        match self {
            Source::Path(p) => p.display().to_string(),
            Source::Embedded(r) => format!("<demo>/{r}"),
        }
    }
    /// Read the recording.
    pub fn read(
        &self,
        format: Option<&FormatSpec>,
        params: &ValidReadParams,
    ) -> Result<(Recording, ReadReport)> {
        match self {
            Source::Path(p) => read_recording(p, format, params),
            Source::Embedded(rel) => {
                let text = crate::demo::file(rel)
                    .ok_or_else(|| LdhError::signal("demo", format!("no embedded file {rel}")))?;
                read_recording_bytes(text.as_bytes(), Path::new(&self.label()), format, params)
            }
        }
    }
}

/// One subject to analyse.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubjectInput {
    /// Identifier.
    pub subject_id: String,
    /// Group, when a manifest gives it.
    pub group: Option<Group>,
    /// Affected side, when a manifest gives it (`None` for healthy or unknown).
    pub affected_side: Option<Side>,
    /// Left recording.
    pub left: Option<Source>,
    /// Right recording.
    pub right: Option<Source>,
    /// Sensor height above the ankle, m (manifest column `sensor_height_m`).
    pub sensor_height_m: Option<f64>,
}

/// Parse a cohort manifest (SPEC §2): `subject_id, group, affected_side, left, right` and the
/// optional `sensor_height_m`; paths relative to the manifest's folder.
pub fn read_manifest(path: &Path) -> Result<Vec<SubjectInput>> {
    let text = std::fs::read_to_string(path).map_err(|source| LdhError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_manifest(&text, path, &|rel| {
        Source::Path(path.parent().unwrap_or(Path::new(".")).join(rel))
    })
}

fn parse_manifest(
    text: &str,
    path: &Path,
    resolve: &dyn Fn(&str) -> Source,
) -> Result<Vec<SubjectInput>> {
    use crate::error::Location;
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let Some((hl, header)) = lines.next() else {
        return Err(LdhError::EmptyFile {
            path: path.to_path_buf(),
        });
    };
    let header = header.trim_start_matches('\u{feff}');
    let cols: Vec<String> = header
        .split(',')
        .map(|c| c.trim().to_ascii_lowercase())
        .collect();
    let col = |name: &str| cols.iter().position(|c| c == name);
    let need = ["subject_id", "group", "affected_side", "left", "right"];
    for n in need {
        if col(n).is_none() {
            return Err(LdhError::MissingColumn {
                loc: Location::line(path, hl as u64 + 1),
                column: n.into(),
                format: "cohort manifest".into(),
                header: cols.clone(),
            });
        }
    }
    let mut out = Vec::new();
    for (i, line) in lines {
        let f: Vec<&str> = line.split(',').map(|x| x.trim()).collect();
        let get = |n: &str| col(n).and_then(|c| f.get(c).copied()).unwrap_or("");
        let lineno = i as u64 + 1;
        let group = match get("group").to_ascii_lowercase().as_str() {
            "healthy" | "h" | "control" => Group::Healthy,
            "ldh" => Group::Ldh,
            other => {
                return Err(LdhError::InvalidValue {
                    loc: Location::cell(path, lineno, col("group").unwrap() + 1),
                    column: "group".into(),
                    value: other.into(),
                    expected: "'healthy' or 'ldh'".into(),
                })
            }
        };
        let affected_side = match get("affected_side").to_ascii_lowercase().as_str() {
            "left" => Some(Side::Left),
            "right" => Some(Side::Right),
            "none" | "" => None,
            other => {
                return Err(LdhError::InvalidValue {
                    loc: Location::cell(path, lineno, col("affected_side").unwrap() + 1),
                    column: "affected_side".into(),
                    value: other.into(),
                    expected: "'left', 'right' or 'none'".into(),
                })
            }
        };
        let h = get("sensor_height_m");
        let sensor_height_m = if h.is_empty() {
            None
        } else {
            Some(h.parse::<f64>().map_err(|_| LdhError::NotANumber {
                loc: Location::cell(path, lineno, col("sensor_height_m").unwrap() + 1),
                column: "sensor_height_m".into(),
                value: h.into(),
                hint: String::new(),
            })?)
        };
        let side = |n: &str| {
            let v = get(n);
            (!v.is_empty()).then(|| resolve(v))
        };
        let id = get("subject_id");
        if id.is_empty() {
            return Err(LdhError::InvalidValue {
                loc: Location::cell(path, lineno, col("subject_id").unwrap() + 1),
                column: "subject_id".into(),
                value: String::new(),
                expected: "a non-empty subject id".into(),
            });
        }
        if out.iter().any(|s: &SubjectInput| s.subject_id == id) {
            return Err(LdhError::InvalidValue {
                loc: Location::cell(path, lineno, col("subject_id").unwrap() + 1),
                column: "subject_id".into(),
                value: id.into(),
                expected: "a subject id not used on an earlier line".into(),
            });
        }
        out.push(SubjectInput {
            subject_id: id.to_string(),
            group: Some(group),
            affected_side,
            left: side("left"),
            right: side("right"),
            sensor_height_m,
        });
    }
    Ok(out)
}

/// The embedded demo cohort as inputs.
pub fn demo_inputs() -> Result<Vec<SubjectInput>> {
    let text = crate::demo::file("manifest.csv").expect("embedded manifest");
    parse_manifest(text, Path::new("<demo>/manifest.csv"), &|rel| {
        Source::Embedded(rel.to_string())
    })
}

/// Turn command-line inputs into subjects: no input → the embedded demo; a manifest CSV; a
/// folder with `manifest.csv`; a subject folder with `left.csv` / `right.csv`; a cohort folder
/// of such subject folders; or files (two files are a left/right pair, by name or in order).
pub fn discover(inputs: &[PathBuf]) -> Result<Vec<SubjectInput>> {
    if inputs.is_empty() {
        return demo_inputs();
    }
    let is_manifest = |p: &Path| {
        p.is_file()
            && std::fs::read_to_string(p)
                .map(|t| {
                    t.lines()
                        .next()
                        .unwrap_or("")
                        .trim_start_matches('\u{feff}')
                        .to_ascii_lowercase()
                        .starts_with("subject_id,")
                })
                .unwrap_or(false)
    };
    let subject_dir = |d: &Path| -> Option<SubjectInput> {
        let (l, r) = (d.join("left.csv"), d.join("right.csv"));
        (l.exists() || r.exists()).then(|| SubjectInput {
            subject_id: d
                .file_name()
                .map(|n| n.to_string_lossy().to_string())
                .unwrap_or_else(|| "subject".into()),
            group: None,
            affected_side: None,
            left: l.exists().then(|| Source::Path(l)),
            right: r.exists().then(|| Source::Path(r)),
            sensor_height_m: None,
        })
    };
    let files: Vec<&PathBuf> = inputs
        .iter()
        .filter(|p| !p.is_dir() && !is_manifest(p))
        .collect();
    let mut out = Vec::new();
    for p in inputs {
        if p.is_dir() {
            if p.join("manifest.csv").is_file() {
                out.extend(read_manifest(&p.join("manifest.csv"))?);
            } else if let Some(s) = subject_dir(p) {
                out.push(s);
            } else {
                let mut subs: Vec<PathBuf> = std::fs::read_dir(p)
                    .map_err(|source| LdhError::Io {
                        path: p.clone(),
                        source,
                    })?
                    .filter_map(|e| e.ok().map(|e| e.path()))
                    .filter(|e| e.is_dir())
                    .collect();
                subs.sort();
                let found: Vec<SubjectInput> = subs.iter().filter_map(|d| subject_dir(d)).collect();
                if found.is_empty() {
                    return Err(LdhError::signal(
                        p.display().to_string(),
                        "no manifest.csv, no left.csv/right.csv and no subject folders with them",
                    ));
                }
                out.extend(found);
            }
        } else if is_manifest(p) {
            out.extend(read_manifest(p)?);
        }
    }
    if !files.is_empty() {
        if files.len() > 2 {
            return Err(LdhError::signal(
                "inputs",
                format!("{} loose files: give one subject's left and right files, or a folder or manifest", files.len()),
            ));
        }
        let name = |p: &Path| {
            p.file_name()
                .map(|n| n.to_string_lossy().to_ascii_lowercase())
                .unwrap_or_default()
        };
        let (mut left, mut right) = (None, None);
        for (i, f) in files.iter().enumerate() {
            let n = name(f);
            if n.contains("right") || (i == 1 && !n.contains("left")) {
                right = Some(Source::Path((*f).clone()));
            } else {
                left = Some(Source::Path((*f).clone()));
            }
        }
        let id = files[0]
            .parent()
            .and_then(|d| d.file_name())
            .map(|n| n.to_string_lossy().to_string())
            .filter(|s| !s.is_empty())
            .unwrap_or_else(|| "subject".into());
        out.push(SubjectInput {
            subject_id: id,
            group: None,
            affected_side: None,
            left,
            right,
            sensor_height_m: None,
        });
    }
    let mut seen = std::collections::BTreeSet::new();
    for s in &out {
        if !seen.insert(s.subject_id.as_str()) {
            return Err(LdhError::signal(
                "inputs",
                format!("subject id '{}' appears twice (two folders or manifests with the same subject): rename one", s.subject_id),
            ));
        }
    }
    Ok(out)
}

/// The analysis of one leg.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LegResult {
    /// The leg.
    pub side: Side,
    /// The file.
    pub source: String,
    /// Time of the first sample in the file's own clock, s (event times count from it; the two
    /// legs are paired on this common clock).
    pub t0_s: f64,
    /// What the reader found.
    pub read: ReadReport,
    /// Samples replaced as outliers or clipped.
    pub outliers_replaced: usize,
    /// What the alignment found.
    pub alignment: Alignment,
    /// Detected events.
    pub events: Events,
    /// Strides.
    pub strides: Vec<Stride>,
    /// Per-side parameters.
    pub parameters: SideParameters,
    /// The attitude over time (kept for reports and evaluation; not serialised).
    #[serde(skip)]
    pub attitude: Option<Attitude>,
    /// The preprocessed signals in the anatomical frame (kept for the report's signal plots;
    /// not serialised). Dropped with the result, so a batch never holds more than the subjects
    /// in flight.
    #[serde(skip)]
    pub signals: Option<Aligned>,
    /// Problems the analysis found that did not stop it (the reader's are in `read.warnings`):
    /// a device mounted upside down, gait that looks like running, too few valid strides.
    #[serde(default)]
    pub warnings: Vec<String>,
}

/// Kind of a gait event.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum EventKind {
    /// Heel strike.
    #[serde(rename = "HS")]
    HeelStrike,
    /// Toe off.
    #[serde(rename = "TO")]
    ToeOff,
}

/// One event of the bilateral sequence.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BilateralEvent {
    /// Time, s from the recordings' first sample (both sensors share a clock).
    pub time_s: f64,
    /// The leg.
    pub side: Side,
    /// HS or TO.
    pub event: EventKind,
    /// Where the expected order (… HS_L, TO_R, HS_R, TO_L, HS_L …) is broken, why; else "".
    pub order: String,
}

/// Both legs' events merged into one time-ordered sequence. In walking the sequence cycles
/// HS(a) → TO(b) → HS(b) → TO(a) → HS(a) (the other leg leaves the ground after the loading
/// response and lands before this leg's push-off): each event is checked against its
/// predecessor — a HS must follow the same leg's TO, a TO the other leg's HS — and breaks are
/// marked, e.g. at gait initiation and termination, pauses or missed events.
pub fn bilateral_events(left: Option<&Events>, right: Option<&Events>) -> Vec<BilateralEvent> {
    bilateral_events_on_clock(left.map(|e| (e, 0.0)), right.map(|e| (e, 0.0)))
}

/// As [`bilateral_events`], each leg's events shifted by its offset (s) onto a common clock.
pub fn bilateral_events_on_clock(
    left: Option<(&Events, f64)>,
    right: Option<(&Events, f64)>,
) -> Vec<BilateralEvent> {
    let mut v: Vec<BilateralEvent> = Vec::new();
    for (side, ev) in [(Side::Left, left), (Side::Right, right)] {
        let Some((ev, offset)) = ev else { continue };
        for &t in &ev.hs_s {
            v.push(BilateralEvent {
                time_s: t + offset,
                side,
                event: EventKind::HeelStrike,
                order: String::new(),
            });
        }
        for &t in &ev.to_s {
            v.push(BilateralEvent {
                time_s: t + offset,
                side,
                event: EventKind::ToeOff,
                order: String::new(),
            });
        }
    }
    v.sort_by(|a, b| {
        a.time_s
            .partial_cmp(&b.time_s)
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    for i in 1..v.len() {
        let (p, c) = (&v[i - 1], &v[i]);
        let (want_side, want_event) = match c.event {
            EventKind::HeelStrike => (c.side, EventKind::ToeOff),
            EventKind::ToeOff => (c.side.other(), EventKind::HeelStrike),
        };
        if p.side != want_side || p.event != want_event {
            let name = |e: EventKind| {
                if e == EventKind::HeelStrike {
                    "HS"
                } else {
                    "TO"
                }
            };
            v[i].order = format!(
                "follows {} {} (expected {} {})",
                p.side,
                name(p.event),
                want_side,
                name(want_event)
            );
        }
    }
    v
}

impl SubjectResult {
    /// The bilateral event sequence of this subject (see [`bilateral_events`]).
    pub fn bilateral_events(&self) -> Vec<BilateralEvent> {
        bilateral_events(
            self.left.as_ref().ok().map(|l| &l.events),
            self.right.as_ref().ok().map(|r| &r.events),
        )
    }
}

/// The analysis of one subject.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubjectResult {
    /// Identifier.
    pub subject_id: String,
    /// Group (from the manifest).
    pub group: Option<Group>,
    /// Affected side (from the manifest).
    pub affected_side: Option<Side>,
    /// Attitude model used.
    pub model: AttitudeModel,
    /// Left leg, or the error that stopped it.
    pub left: std::result::Result<LegResult, String>,
    /// Right leg, or the error that stopped it.
    pub right: std::result::Result<LegResult, String>,
    /// Problems of the pair (different clocks, rates or lengths; left and right possibly
    /// swapped); see [`pair_warnings`].
    #[serde(default)]
    pub warnings: Vec<String>,
}

impl SubjectResult {
    /// Both legs' results or errors, left first.
    pub fn legs(&self) -> [(Side, &std::result::Result<LegResult, String>); 2] {
        [(Side::Left, &self.left), (Side::Right, &self.right)]
    }
}

/// Analyse one recording up to its strides (no bilateral parameters yet).
pub fn analyze_leg(
    rec: &Recording,
    side: Side,
    params: &AnalysisParams,
    sensor_height_m: Option<f64>,
) -> Result<(LegResult, Vec<f64>)> {
    // The fields are public: a recording built by hand may break the invariants.
    rec.validate()?;
    let pp = params.preprocess.check(rec.fs_hz)?;
    let pre = preprocess(rec, &pp)?;
    let al = align(&pre, &params.align.check()?)?;
    let att = estimate(&al, &params.attitude.check()?)?;
    let fs = rec.fs_hz;
    // Events come from the gyroscope's sagittal rate in both models (the ACC-only model replaces
    // the attitude only, so the comparison isolates it; SPEC §3.7).
    let omega = al.gyro_dps[1].clone();
    let ev_params = params.events.clone();
    let ev = detect(&att.pitch_deg, &omega, fs, &ev_params.check()?)?;
    let mut sp = params.strides.clone();
    if let Some(h) = sensor_height_m {
        sp.sensor_height_m = h;
    }
    let st = strides(side, &al, &att, &ev, &sp.check()?)?;
    let mut parameters = side_parameters(&st, None);
    if params.compute_sta {
        fill_sta(
            &mut parameters,
            &st,
            &omega,
            fs,
            &params.sta,
            params.sta_max_strides,
        );
    }
    let hs = ev.hs_s.clone();
    let warnings = leg_warnings(&al.alignment, &st, &parameters);
    Ok((
        LegResult {
            side,
            source: rec.label(),
            t0_s: rec.t0_s,
            read: memory_report(rec),
            outliers_replaced: pre.replaced.len(),
            alignment: al.alignment.clone(),
            events: ev,
            strides: st,
            parameters,
            attitude: Some(att),
            signals: Some(al),
            warnings,
        },
        hs,
    ))
}

/// Shortest mean stride time of walking, s: below it (a cadence above 150 steps/min) the gait
/// looks like running.
pub const RUNNING_STRIDE_TIME_S: f64 = 0.8;

/// Warnings about one leg's analysis: a device mounted upside down (corrected by the
/// alignment, but worth checking), gait that looks like running (the median time of all detected
/// strides below [`RUNNING_STRIDE_TIME_S`], or their median stance below half the stride, i.e. a
/// flight phase — running strides are usually refused as too short, so all strides are used),
/// and fewer than three valid strides.
pub fn leg_warnings(al: &Alignment, st: &[Stride], p: &SideParameters) -> Vec<String> {
    let mut w = Vec::new();
    if al.shank_axis_tilt_deg > 90.0 {
        w.push(format!(
            "device mounted upside down: its x axis points down the shank ({:.0} deg from the shank axis found from gravity at rest); the alignment corrected for it — check the mounting if this is unexpected",
            al.shank_axis_tilt_deg
        ));
    }
    let median = |mut v: Vec<f64>| -> Option<f64> {
        v.retain(|x| x.is_finite());
        v.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        (v.len() >= 3).then(|| v[v.len() / 2])
    };
    let stride_time = median(st.iter().map(|s| s.stride_time_s).collect());
    let stance = median(st.iter().map(|s| s.stance_ratio).collect());
    if let Some(t) = stride_time {
        let stance = stance.unwrap_or(f64::NAN);
        if t < RUNNING_STRIDE_TIME_S || stance < 0.5 {
            w.push(format!(
                "this looks like running, not walking: median stride time {t:.2} s ({:.0} steps/min) over {} detected strides, median stance {:.0} % of the stride; the gait parameters and their reference values are defined for walking",
                120.0 / t,
                st.len(),
                stance * 100.0
            ));
        }
    }
    if p.strides_valid < 3 {
        w.push(format!(
            "only {} valid stride(s) of {}: the per-side parameters are unreliable or missing",
            p.strides_valid, p.strides_total
        ));
    }
    w
}

/// Warnings about a pair of legs read from two files: sampling rates that differ by more than
/// 0.5 % (different settings, or a clock running fast), recordings that do not overlap in time
/// (different clocks: step time is then not computed), different lengths or starts (more than
/// 1 s and 5 %), and the left sensor mounted mirrored while the right one is not — the opposite
/// of identical devices worn on the lateral side of both shanks, so the files may be swapped.
/// Returns the warnings and whether the legs share a time span (to pair their heel strikes).
pub fn pair_warnings(l: &LegResult, r: &LegResult) -> (Vec<String>, bool) {
    let mut w = Vec::new();
    let (lf, rf) = (l.read.fs_hz, r.read.fs_hz);
    if (lf - rf).abs() > 0.005 * lf.max(rf) {
        w.push(format!(
            "the two sensors' sampling rates differ: left {lf:.3} Hz, right {rf:.3} Hz ({:+.1} %): different device settings, or a clock that runs fast or slow; each leg is analysed at its own rate",
            (rf / lf - 1.0) * 100.0
        ));
    }
    let (ld, rd) = (l.read.duration_s, r.read.duration_s);
    let (la, lb, ra, rb) = (l.t0_s, l.t0_s + ld, r.t0_s, r.t0_s + rd);
    let overlap = lb.min(rb) - la.max(ra);
    let overlapping = overlap > 0.0;
    if !overlapping {
        w.push(format!(
            "the two recordings do not overlap in time (left {la:.2}–{lb:.2} s, right {ra:.2}–{rb:.2} s, each on its file's clock): different clocks or different sessions? Step time and step frequency, which pair the legs, are not computed"
        ));
    } else {
        let tol = |a: f64, b: f64| (a - b).abs() > 1.0_f64.max(0.05 * a.abs().max(b.abs()));
        if tol(ld, rd) || (la - ra).abs() > 1.0_f64.max(0.05 * ld.max(rd)) {
            w.push(format!(
                "the two recordings differ in length or start: left {la:.2}–{lb:.2} s ({ld:.1} s), right {ra:.2}–{rb:.2} s ({rd:.1} s), overlap {overlap:.1} s: the sensors were not started and stopped together, or a file is cut; the legs are paired only where they overlap"
            ));
        }
    }
    if l.alignment.mirrored && !r.alignment.mirrored {
        w.push(
            "the left sensor is mounted mirrored (its y axis points backwards) and the right one is not — the opposite of identical devices worn on the lateral side of both shanks: are the left and right files swapped? (This check assumes identical devices worn laterally; the results keep the sides as given.)".to_string(),
        );
    }
    (w, overlapping)
}

/// STA over the longest run of consecutive valid strides (its first `max_strides` when that is
/// not 0).
fn fill_sta(
    p: &mut SideParameters,
    st: &[Stride],
    omega: &[f64],
    fs: f64,
    params: &GaitStaParams,
    max_strides: usize,
) {
    let mut best: Option<(usize, usize)> = None;
    let mut i = 0;
    while i < st.len() {
        if !st[i].valid {
            i += 1;
            continue;
        }
        let s = i;
        while i + 1 < st.len()
            && st[i + 1].valid
            && (st[i + 1].hs_time_s - st[i].next_hs_time_s).abs() < 1e-9
        {
            i += 1;
        }
        if best.is_none_or(|(a, b)| i - s > b - a) {
            best = Some((s, i));
        }
        i += 1;
    }
    let Some((a, mut b)) = best else {
        p.sta_status = "no valid strides".into();
        return;
    };
    if max_strides > 0 && b - a + 1 > max_strides {
        b = a + max_strides - 1;
    }
    let (i0, i1) = (
        (st[a].hs_time_s * fs).round() as usize,
        ((st[b].next_hs_time_s * fs).round() as usize).min(omega.len()),
    );
    let mean_st = p.stride_time_s;
    match gait_sta(&omega[i0..i1], fs, mean_st, params) {
        Ok(r) => {
            p.sta_per_s = r.lambda_per_s;
            p.sta_per_stride = r.lambda_per_stride;
            p.sta_status = String::new();
        }
        Err(e) => {
            p.sta_status = format!(
                "{} strides ({:.1} s): {e}",
                b - a + 1,
                (i1 - i0) as f64 / fs
            )
        }
    }
}

/// The read report of a recording that came from memory (no file).
pub fn memory_report(rec: &Recording) -> ReadReport {
    ReadReport {
        file: rec
            .source
            .clone()
            .unwrap_or_else(|| PathBuf::from("<memory>")),
        format: "memory".into(),
        format_detected: false,
        delimiter: String::new(),
        bom: false,
        header_line: 0,
        rows: rec.len(),
        fs_hz: rec.fs_hz,
        max_jitter_ms: 0.0,
        resampled: false,
        gaps: vec![],
        dropped_segments: vec![],
        saturated_per_channel: [0; 6],
        saturated_samples: rec.saturated_count(),
        samples: rec.len(),
        duration_s: rec.duration_s(),
        notes: vec![],
        warnings: crate::io::flat_channel_warnings(&rec.acc_g, &rec.gyro_dps, rec.fs_hz, rec.t0_s),
    }
}

/// Analyse one subject: read both legs, run the pipeline, pair the legs for step time and
/// frequency. Errors are per leg and name the file.
pub fn analyze_subject(
    input: &SubjectInput,
    params: &AnalysisParams,
    format: Option<&FormatSpec>,
    read: &ValidReadParams,
) -> SubjectResult {
    let load = |src: &Option<Source>,
                side: Side|
     -> std::result::Result<(Recording, ReadReport, String), String> {
        let src = src
            .as_ref()
            .ok_or_else(|| format!("no {side} recording given"))?;
        let (rec, report) = src.read(format, read).map_err(|e| e.to_string())?;
        Ok((rec, report, src.label()))
    };
    analyze_pair(
        input,
        load(&input.left, Side::Left),
        load(&input.right, Side::Right),
        params,
    )
}

/// The read outcome of one leg: the recording, what the reader found and a label, or the error.
pub type LoadedLeg = std::result::Result<(Recording, ReadReport, String), String>;

/// Analyse one subject from recordings already read (or their read errors).
pub fn analyze_pair(
    input: &SubjectInput,
    left: LoadedLeg,
    right: LoadedLeg,
    params: &AnalysisParams,
) -> SubjectResult {
    let run =
        |loaded: LoadedLeg, side: Side| -> std::result::Result<(LegResult, Vec<f64>), String> {
            let (rec, report, label) = loaded?;
            let (mut leg, hs) = analyze_leg(&rec, side, params, input.sensor_height_m)
                .map_err(|e| format!("{label}: {e}"))?;
            leg.read = report;
            leg.source = label;
            Ok((leg, hs))
        };
    let l = run(left, Side::Left);
    let r = run(right, Side::Right);
    // The other leg's heel strikes on this leg's clock: event times count from each file's own
    // first sample, and the two files may start at different times.
    let t0 = |x: &std::result::Result<(LegResult, Vec<f64>), String>| {
        x.as_ref().ok().map(|(leg, _)| leg.t0_s)
    };
    let shifted = |x: &std::result::Result<(LegResult, Vec<f64>), String>, to: Option<f64>| {
        x.as_ref().ok().map(|(leg, hs)| {
            hs.iter()
                .map(|t| t + leg.t0_s - to.unwrap_or(leg.t0_s))
                .collect::<Vec<f64>>()
        })
    };
    let (lt0, rt0) = (t0(&l), t0(&r));
    let (warnings, overlapping) = match (&l, &r) {
        (Ok((ll, _)), Ok((rl, _))) => pair_warnings(ll, rl),
        _ => (Vec::new(), true),
    };
    let (lhs, rhs) = if overlapping {
        (shifted(&l, rt0), shifted(&r, lt0))
    } else {
        (None, None)
    };
    let finish = |x: std::result::Result<(LegResult, Vec<f64>), String>,
                  other: Option<Vec<f64>>| {
        x.map(|(mut leg, _)| {
            let sta = (
                leg.parameters.sta_per_s,
                leg.parameters.sta_per_stride,
                leg.parameters.sta_status.clone(),
            );
            leg.parameters = side_parameters(&leg.strides, other.as_deref());
            (
                leg.parameters.sta_per_s,
                leg.parameters.sta_per_stride,
                leg.parameters.sta_status,
            ) = sta;
            leg
        })
    };
    SubjectResult {
        subject_id: input.subject_id.clone(),
        group: input.group,
        affected_side: input.affected_side,
        model: params.attitude.model,
        left: finish(l, rhs),
        right: finish(r, lhs),
        warnings,
    }
}

/// Analyse a simulated subject in memory (for evaluation and tests).
pub fn analyze_simulated(
    s: &crate::simulate::SimSubject,
    params: &AnalysisParams,
) -> SubjectResult {
    let input = SubjectInput {
        subject_id: s.params.subject_id.clone(),
        group: Some(s.params.group),
        affected_side: s.params.affected_side,
        left: None,
        right: None,
        sensor_height_m: Some((s.left.truth.sensor_height_m + s.right.truth.sensor_height_m) / 2.0),
    };
    let leg = |l: &crate::simulate::SimLeg| -> LoadedLeg {
        let rec = l.recording.clone();
        let report = memory_report(&rec);
        Ok((
            rec,
            report,
            format!("{}/{}", s.params.subject_id, l.truth.side),
        ))
    };
    analyze_pair(&input, leg(&s.left), leg(&s.right), params)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::CohortParams;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]
        /// Detected events alternate HS/TO and increase, on any simulated subject.
        #[test]
        fn events_alternate_and_increase(seed in 0u64..10_000, ldh in any::<bool>()) {
            let c = CohortParams { healthy: usize::from(!ldh), ldh: usize::from(ldh), duration_s: 20.0, seed, ..CohortParams::default() };
            let r = analyze_simulated(&c.simulate(0).unwrap(), &AnalysisParams { compute_sta: false, ..AnalysisParams::default() });
            for (_, leg) in r.legs() {
                let leg = leg.as_ref().unwrap();
                let mut ev: Vec<(f64, u8)> = leg.events.hs_s.iter().map(|&t| (t, 0)).chain(leg.events.to_s.iter().map(|&t| (t, 1))).collect();
                ev.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap());
                prop_assert!(ev.len() >= 16);
                for w in ev.windows(2) {
                    prop_assert!(w[1].0 > w[0].0);
                    prop_assert_ne!(w[0].1, w[1].1, "two {} in a row at {} s", if w[0].1 == 0 { "HS" } else { "TO" }, w[1].0);
                }
                for s in &leg.strides {
                    prop_assert!(s.hs_time_s < s.to_time_s || !s.to_time_s.is_finite());
                    prop_assert!(s.valid == s.reason.is_empty());
                }
            }
        }
    }

    #[test]
    fn bilateral_sequence_alternates_in_steady_walking() {
        let c = CohortParams {
            healthy: 0,
            ldh: 1,
            duration_s: 30.0,
            seed: 5,
            turn: false,
            ..CohortParams::default()
        };
        let r = analyze_simulated(
            &c.simulate(0).unwrap(),
            &AnalysisParams {
                compute_sta: false,
                ..AnalysisParams::default()
            },
        );
        let seq = r.bilateral_events();
        assert!(seq.len() > 60);
        let breaks: Vec<&BilateralEvent> = seq.iter().filter(|e| !e.order.is_empty()).collect();
        // Only where gait starts (the first leg's TO has no HS before it) may it break.
        assert!(breaks.len() <= 2, "{breaks:?}");
        assert!(
            seq.iter()
                .filter(|e| e.event == EventKind::HeelStrike)
                .count()
                > 30
        );
        // With one leg, every TO lacks the other leg's HS before it.
        let one = bilateral_events(r.left.as_ref().ok().map(|l| &l.events), None);
        assert!(one
            .iter()
            .skip(1)
            .filter(|e| e.event == EventKind::ToeOff)
            .all(|e| e.order.contains("expected right HS")));
    }

    #[test]
    fn manifests_are_parsed_and_bad_rows_named() {
        let d = tempfile::tempdir().unwrap();
        let m = d.path().join("manifest.csv");
        std::fs::write(&m, "subject_id,group,affected_side,left,right,sensor_height_m\nS1,ldh,right,a/l.csv,a/r.csv,0.12\nS2,healthy,none,b/l.csv,b/r.csv,\n").unwrap();
        let v = read_manifest(&m).unwrap();
        assert_eq!(v.len(), 2);
        assert_eq!(v[0].affected_side, Some(Side::Right));
        assert_eq!(v[0].sensor_height_m, Some(0.12));
        assert_eq!(v[0].left, Some(Source::Path(d.path().join("a/l.csv"))));
        assert_eq!(v[1].group, Some(Group::Healthy));
        std::fs::write(
            &m,
            "subject_id,group,affected_side,left,right\nS1,sick,right,a,b\n",
        )
        .unwrap();
        let e = read_manifest(&m).unwrap_err().to_string();
        assert!(
            e.contains("manifest.csv:2:2") && e.contains("'sick'"),
            "{e}"
        );
        std::fs::write(&m, "subject_id,group,left,right\n").unwrap();
        assert!(read_manifest(&m)
            .unwrap_err()
            .to_string()
            .contains("affected_side"));
        assert_eq!(discover(&[]).unwrap().len(), 4);
        // A missing file is kept as an input: reading it fails per recording, naming it.
        let v = discover(&[d.path().join("nothing-here.csv")]).unwrap();
        let r = analyze_subject(
            &v[0],
            &AnalysisParams::default(),
            None,
            &crate::io::ReadParams::default().check().unwrap(),
        );
        assert!(r
            .left
            .unwrap_err()
            .contains("nothing-here.csv: cannot read"));
        assert!(r.right.unwrap_err().contains("no right recording"));
        std::fs::create_dir(d.path().join("empty")).unwrap();
        let e = discover(&[d.path().join("empty")]).unwrap_err().to_string();
        assert!(e.contains("empty") && e.contains("no manifest.csv"), "{e}");
    }
}
