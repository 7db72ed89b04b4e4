//! The analysis of one leg: recording → preprocessed → aligned → attitude → events → strides
//! → parameters (SPEC §3).

use super::*;
use crate::domain::Parameter;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::time::Instant;

use crate::align::{align, Aligned, Alignment};
use crate::attitude::{estimate, Attitude};
use crate::error::Result;
use crate::events::{detect, Events};
use crate::gait::{
    height_sensitivity_measured, heights_to_measure, side_parameters, strides_at_heights,
    withhold_unvouched_lengths, SideParameters, Stride,
};
use crate::io::ReadReport;
use crate::nonlinear::{gait_sta, GaitStaParams};
use crate::preprocess::preprocess;
use crate::recording::{Recording, Side};
use crate::timings::{Stage, StageTimings};

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
    /// What the quality checks found (the reader's free-text findings are in
    /// `read.warnings`), most severe first; the parameters they withhold are NaN with the reason
    /// in `parameters.withheld` (docs/quality.md).
    #[serde(default)]
    pub warnings: Vec<Warning>,
    /// The steady-walking window the means and CVs are of (`None`: the rule is disabled or the
    /// leg has no stride).
    #[serde(default)]
    pub steady: Option<crate::gait::SteadySpan>,
}

/// One leg up to its events: what [`leg_back`] continues from. A subject places each leg's
/// events with the other leg's in between (`pipeline::subject`).
#[derive(Debug, Clone)]
pub struct LegFront {
    /// Samples replaced as outliers or clipped.
    pub outliers_replaced: usize,
    /// The preprocessed signals in the anatomical frame.
    pub aligned: Aligned,
    /// The attitude.
    pub attitude: Attitude,
    /// The sagittal angular velocity ω_s, deg/s (events and STA read it).
    pub omega_s_dps: Vec<f64>,
    /// The events.
    pub events: Events,
    /// What the sensor checks found on the recording (a faulty gyroscope's events are not lent
    /// to the other leg).
    pub sensor: quality::SensorFindings,
}

/// `sta_status` of a run with STA turned off (`--no-sta`, Python `compute_sta=False`): said as
/// such, in words a clinical page can show (it read "(--no-sta, or compute_sta=False in
/// Python)" on a HuGaDB page until 2026-12-03).
pub const STA_TURNED_OFF: &str = "not computed: turned off for this run";

/// Preprocess, align, estimate the attitude and detect the events of one recording, adding
/// 1 to `t.recordings` and the stages' wall time.
pub fn leg_front(
    rec: &Recording,
    v: &ValidAnalysisParams,
    t: &mut StageTimings,
) -> Result<LegFront> {
    let params = v.params();
    t.recordings += 1;
    let mut clock = Instant::now();
    // The fields are public: a recording built by hand may break the invariants.
    rec.validate()?;
    let pp = params.preprocess.check(rec.fs_hz)?;
    let pre = preprocess(rec, &pp)?;
    t.lap(Stage::Preprocess, &mut clock);
    let al = align(&pre, v.align())?;
    t.lap(Stage::Align, &mut clock);
    let att = estimate(&al, v.attitude())?;
    t.lap(Stage::Attitude, &mut clock);
    // Events come from the gyroscope's sagittal rate in both models (the ACC-only model replaces
    // the attitude only, so the comparison isolates it; SPEC §3.7).
    let omega = al.gyro_dps[1].clone();
    let mut ev = detect(&att.pitch_deg, &omega, rec.fs_hz, v.events())?;
    let a = &rec.acc_g;
    crate::events::find_impacts(&mut ev, [&a[0], &a[1], &a[2]], rec.fs_hz, v.events());
    t.lap(Stage::Events, &mut clock);
    // Counted with the strides' checks, where it ran before the subject needed it here.
    let sensor = quality::sensor_checks(rec);
    t.lap(Stage::Strides, &mut clock);
    Ok(LegFront {
        outliers_replaced: pre.replaced.len(),
        aligned: al,
        attitude: att,
        omega_s_dps: omega,
        events: ev,
        sensor,
    })
}

/// From a leg's events to its strides, checks, parameters and STA: its result and the heel
/// strikes it lends to the other leg.
pub fn leg_back(
    rec: &Recording,
    side: Side,
    v: &ValidAnalysisParams,
    sensor_height_m: Option<f64>,
    front: LegFront,
    t: &mut StageTimings,
) -> Result<AnalysedLeg> {
    let params = v.params();
    let mut clock = Instant::now();
    let fs = rec.fs_hz;
    let LegFront {
        outliers_replaced,
        aligned: al,
        attitude: att,
        omega_s_dps: omega,
        events: mut ev,
        sensor,
    } = front;
    v.events().calibrate(&mut ev, rec.duration_s());
    let sp = v.strides(sensor_height_m)?;
    // With an assumed sensor height, each stride is also measured at the ends of the range
    // of heights, for the check below.
    let heights = heights_to_measure(&sp, att.model);
    let (mut st, at_heights) = strides_at_heights(side, &al, &att, &ev, &sp, heights)?;
    let before = side_parameters(&st, None);
    let mut checks = leg_checks(rec, sensor, &al, &att, &mut st, &before);
    withhold_unvouched_lengths(&mut st);
    // A length from an assumed sensor height: said, or withheld when it depends on it.
    if let Some(h) = height_sensitivity_measured(&sp, att.model, &st, &at_heights) {
        let w = quality::sensor_height_warning(&h);
        quality::apply_to_strides(&mut st, std::slice::from_ref(&w));
        checks.warnings.push(w);
        checks
            .warnings
            .sort_by_key(|x| std::cmp::Reverse(x.severity));
    }
    // Means and CVs of steady walking only (belt start-up, initiation, termination out; a
    // subject applies it again after re-segmenting its legs for turns).
    let steady = quality::apply_steady(&mut st, &mut checks.warnings, v.steady());
    let mut parameters = side_parameters(&st, None);
    t.lap(Stage::Strides, &mut clock);
    if params.compute_sta && !checks.gyro_fault {
        fill_sta(
            &mut parameters,
            &st,
            &omega,
            fs,
            &params.sta,
            params.sta_max_strides,
        );
        t.lap(Stage::Sta, &mut clock);
    } else if !params.compute_sta {
        // Said as such, not a bare "not computed" a reader takes for a failure; in plain
        // words, as it reaches the clinical pages (the switch, `--no-sta` or
        // `compute_sta=False`, is the user's own and named in docs/pipeline.md).
        parameters.sta_status = STA_TURNED_OFF.into();
    }
    withhold(&mut parameters, &checks.warnings);
    // A faulty gyroscope's events are not lent to the other leg's step time (nor, issue 49,
    // to its double support).
    let (hs, to) = if checks.gyro_fault {
        (Vec::new(), Vec::new())
    } else {
        (ev.hs_s.clone(), ev.to_s.clone())
    };
    let mut warnings = checks.warnings;
    if let Some(d) = ev.hs_impact_delay_s {
        // Which rule placed the heel strikes (they move 15-30 ms with it on real walks).
        warnings.push(quality::Warning::new(
            codes::HS_AT_IMPACT,
            quality::Severity::Note,
            format!(
                "heel strikes at each strike's own impact (median {:.0} ms after the gyroscope's zero crossing; a strike without one there is unsure), instead of the crossing + the fitted {:.1} % of the stride",
                d * 1e3,
                100.0 * v.events().params().detector.offsets().0
            ),
        ));
    }
    if st.is_empty() {
        // Why no stride was found (too slow for the mid-swing threshold, too short…).
        let reason = crate::events::no_strides_reason(&omega, &ev, v.events().params());
        warnings.push(quality::Warning::new(
            quality::codes::NO_STRIDES,
            quality::Severity::Warning,
            reason,
        ));
    }
    t.lap(Stage::Strides, &mut clock);
    Ok(AnalysedLeg {
        leg: LegResult {
            side,
            source: rec.label(),
            t0_s: rec.t0_s,
            read: memory_report(rec),
            outliers_replaced,
            alignment: al.alignment.clone(),
            events: ev,
            strides: st,
            parameters,
            attitude: Some(att),
            signals: Some(al),
            warnings,
            steady,
        },
        lent: LentHeelStrikes { hs_s: hs, to_s: to },
    })
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
    let mean_st = p[Parameter::StrideTime];
    match gait_sta(&omega[i0..i1], fs, mean_st, params) {
        Ok(r) => {
            p[Parameter::Sta] = r.lambda_per_s;
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
        columns: vec![],
        recorded_at: rec.recorded_at,
        notes: vec![],
        warnings: crate::io::flat_channel_warnings(&rec.acc_g, &rec.gyro_dps, rec.fs_hz, rec.t0_s),
    }
}
