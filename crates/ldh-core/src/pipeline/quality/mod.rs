//! The quality layer (docs/quality.md): checks per leg and per pair, each with a stable code, a
//! severity and the parameters it withholds. A clinical tool may fail to measure something; it
//! may never hand over a wrong number: a parameter a check cannot vouch for is NaN (an empty
//! cell, JSON `null`) with its reason in [`SideParameters::withheld`].
//!
//! - [`sensor`]: gyroscope scale faults and clipping, accelerometer clipping (raw recording);
//! - [`faults`]: one channel frozen, dropped to zero or spiking for part of the walk, with its
//!   span (the strides overlapping it are withheld);
//! - [`attitude`]: attitude health (stance pitch stride to stride, anatomical bounds);
//! - [`height`]: a stride length that used an assumed sensor height;
//! - this module: the leg's gait (running, a time base that cannot be right, few strides, a
//!   device convention);
//! - [`pair`]: the two legs together (clocks, identical files, disagreement, a possible swap);
//! - [`clocks`]: two sensors not on one clock, from the walk's two double supports;
//! - [`noise`]: stride length variability against the measurement noise the two legs show.

use crate::align::Alignment;
use crate::domain::Parameter;
use crate::gait::{FindingEffect, SideParameters, Stride, StrideCode, StrideFinding};

use super::LegResult;

mod agreement;
mod attitude;
mod clocks;
mod faults;
mod height;
mod noise;
mod pair;
mod sensor;
mod steady;
mod warning;

pub use crate::domain::WarningCode;
pub use agreement::{withhold_disagreeing_lengths, MAX_LEG_DISAGREEMENT};
pub use attitude::{
    attitude_checks, MAX_BDK_DEG, MAX_PITCH_DEG, MIN_PITCH_EXCURSION_DEG, OUT_OF_BOUNDS_SHARE,
    STANCE_PITCH_MAX_DEG, STANCE_PITCH_SPREAD_DEG,
};
pub use clocks::{
    balance as clock_balance, clock_warning, two_clocks_warning, DsBalance, BETWEEN_LEGS,
    MAX_UNBACKED_STEP_SHARE, MIN_BALANCE_STRIDES, MIN_DS_SHARE,
};
pub use faults::{
    detect_faults, fault_warning, withhold_faulty_strides, ChannelFault, FaultKind, CHANNEL_NAMES,
    MAX_SPIKE_S, MIN_FROZEN_S, MIN_ZERO_S, MOVING_ACC_G, MOVING_GYRO_DPS, SPIKE_BAND_WIDTHS,
    SPIKE_MERGE_S,
};
pub use height::sensor_height_warning;
pub use noise::{
    check_length_variability, noise_share, unchecked_warning, variability_warning, walk_noise,
    withhold_unchecked, SV_MAX_INFLATION, SV_MIN_PAIRS,
};
pub use pair::{
    pair_warnings, swapped_mounting, LR_STRIDE_LENGTH_TOL, LR_STRIDE_TIME_TOL, MEDIAL_FACE_DEG,
    MIRROR_TOL_DEG,
};
pub use sensor::{
    sensor_checks, SensorFindings, GYRO_CLIP_SHARE, SCALE_FAULT_SHARE, SHANK_MAX_DPS,
};
pub use steady::{apply_steady, apply_steady_walk, steady_warning};
pub use warning::{codes, flat, params, Severity, Warning, WarningList, WithheldList};

/// Shortest median stride time of walking, s (0.7 s = 171 steps/min, beyond the fastest
/// self-selected walking, ≈ 120–150 steps/min; Tudor-Locke et al., IJBNPA 2011;8:79).
pub const RUNNING_STRIDE_TIME_S: f64 = 0.7;

/// Smallest median stance share of walking (0.45): walking keeps 55–65 % stance (Perry, Gait
/// Analysis, 1992), running 20–40 % (Novacheck, Gait Posture 1998;7:77–95), so stance below
/// 45 % means a flight phase.
pub const RUNNING_STANCE_MAX: f64 = 0.45;

/// Stance share that only walking has (0.55): with a stride shorter than
/// [`RUNNING_STRIDE_TIME_S`] and stance at least this, the gait is neither walking nor running:
/// the time base is wrong.
pub const WALKING_STANCE_MIN: f64 = 0.55;

/// The (upper) median of the finite values (`None` for fewer than 3).
pub(crate) fn finite_median(mut v: Vec<f64>) -> Option<f64> {
    v.retain(|x| x.is_finite());
    if v.len() < 3 {
        return None;
    }
    crate::stats::median(&mut v, crate::stats::EvenMedian::Upper)
}

/// Findings about one leg's gait (after the sensor and attitude checks): a device convention
/// (x axis down the shank: a note), running (a flight phase, or strides and stance both beyond
/// walking), a time base that cannot be right (strides too short for walking with walking
/// stance: a fault), and fewer than three valid strides.
/// `fs_hz` is the sampling rate the recording states.
pub fn leg_warnings(al: &Alignment, st: &[Stride], p: &SideParameters, fs_hz: f64) -> Vec<Warning> {
    let mut w = Vec::new();
    if al.shank_axis_tilt_deg > 90.0 {
        w.push(Warning::new(codes::UPSIDE_DOWN, Severity::Note, format!(
            "the device's x axis points down the shank ({:.0} deg from the shank axis found from gravity): a convention of some devices, or an upside-down mounting; the alignment corrects for it either way",
            al.shank_axis_tilt_deg
        )));
    }
    let stride_time = finite_median(st.iter().map(|s| s.stride_time_s).collect());
    let stance = finite_median(st.iter().map(|s| s.stance_ratio).collect());
    if let (Some(t), Some(stance)) = (stride_time, stance) {
        if t < RUNNING_STRIDE_TIME_S && stance >= WALKING_STANCE_MIN {
            w.push(
                Warning::new(codes::IMPLAUSIBLE_CADENCE_FOR_RATE, Severity::Fault, format!(
                    "median stride time {t:.2} s ({:.0} steps/min) with {:.0} % stance over {} detected strides: no human gait is that fast with that much stance, so the sampling rate is probably wrong (a stride of 1.05 s would mean {:.1} Hz instead of the {:.1} Hz stated); no parameter of this leg is measured",
                    120.0 / t,
                    stance * 100.0,
                    st.len(),
                    fs_hz * t / 1.05,
                    fs_hz,
                ))
                .withholding(&params::ALL),
            );
        } else if stance < RUNNING_STANCE_MAX || t < RUNNING_STRIDE_TIME_S {
            w.push(Warning::new(codes::RUNNING, Severity::Warning, format!(
                "this looks like running, not walking: median stride time {t:.2} s ({:.0} steps/min), median stance {:.0} % of the stride over {} detected strides (walking keeps 55-65 % stance); the gait parameters and their reference values are defined for walking",
                120.0 / t,
                stance * 100.0,
                st.len()
            )));
        }
    }
    if p.strides_valid < 3 {
        w.push(
            Warning::new(codes::FEW_STRIDES, Severity::Warning, format!(
                "only {} valid stride(s) of {}: a mean of fewer than three strides is not a per-side parameter, so none is reported",
                p.strides_valid, p.strides_total
            ))
            .withholding(&params::ALL),
        );
    }
    w
}

/// Largest change of WQK and PBI measured when a simulated walk loses its quiet standing, deg
/// (docs/quality.md `no_quiet_standing`: 8.8–12.0° on 20 legs of family A, with or without
/// sensor bias; the stated pitch accuracy is 1.5°).
pub const NO_STANDING_ANGLE_ERROR_DEG: f64 = 12.0;

/// A leg without quiet standing ([`crate::align`] found none): its shank axis is the mean
/// acceleration of the whole walk, which leans by the shank's mean inclination over a stride,
/// so every pitch is offset by ≈ 10° (WQK low, PBI high; measured 8.8–12° on simulated walks,
/// the gyroscope bias adds < 1°). That is far beyond the angles' stated accuracy (pitch RMSE
/// ≤ 1.5°), so WQK and PBI are withheld with the reason; BDK (a frontal excursion, < 1° off)
/// and the stride times and lengths (< 0.5 %) are kept.
pub fn standing_warning(al: &Alignment) -> Option<Warning> {
    let note = al.no_standing_note()?;
    let what = note.split(':').next().unwrap_or(note);
    Some(
        Warning::new(codes::NO_QUIET_STANDING, Severity::Warning, format!(
            "{what}: without a moment of standing still, the sensor's tilt on the shank is not known and the shank angles would be about 10 deg off: WQK and PBI withheld (BDK, stride times and stride length are not affected). Record at least 1 s of standing still at the start or the end"
        ))
        .withholding(&params::INCLINATIONS),
    )
}

/// Everything the checks of one leg found, in order of severity (most severe first).
pub struct LegChecks {
    /// The warnings.
    pub warnings: Vec<Warning>,
    /// The gyroscope is faulty: the leg's heel strikes are not lent to the other leg.
    pub gyro_fault: bool,
}

/// Run every check of one leg on its recording, alignment, attitude and strides; strides are
/// invalidated or lose values as the checks say. `sensor` is what [`sensor_checks`] found on
/// the recording; `p` are the leg's parameters before the checks.
pub fn leg_checks(
    rec: &crate::recording::Recording,
    sensor: SensorFindings,
    al: &crate::align::Aligned,
    att: &crate::attitude::Attitude,
    st: &mut [Stride],
    p: &SideParameters,
) -> LegChecks {
    let mut warnings = sensor.warnings;
    // Strides over a partial channel fault are withheld first, so the checks below count
    // only the others.
    withhold_faulty_strides(st, &sensor.faults);
    if !sensor.gyro_fault {
        warnings.extend(attitude_checks(al, att, st));
        let p = crate::gait::side_parameters(st, None);
        warnings.extend(leg_warnings(&al.alignment, st, &p, rec.fs_hz));
        warnings.extend(standing_warning(&al.alignment));
    } else {
        warnings.extend(
            leg_warnings(&al.alignment, &[], p, rec.fs_hz)
                .into_iter()
                .filter(|w| w.code == codes::UPSIDE_DOWN),
        );
    }
    apply_to_strides(st, &warnings);
    warnings.sort_by_key(|x| std::cmp::Reverse(x.severity));
    LegChecks {
        warnings,
        gyro_fault: sensor.gyro_fault,
    }
}

/// Whether a finding says the leg's attitude cannot be vouched for (a faulty or clipped
/// gyroscope, a gyroscope channel frozen, zeroed or spiking for part of the walk, a drifting
/// attitude, angles outside anatomical bounds): its yaw, and so every
/// heading change computed from it, is then not a measurement either, so it neither decides
/// turns nor is reported per stride.
pub fn discredits_attitude(w: &Warning) -> bool {
    [
        codes::GYRO_SCALE_FAULT,
        codes::GYRO_CLIPPING,
        codes::ATTITUDE_DIVERGENCE,
        codes::IMPLAUSIBLE_ANGLE,
    ]
    .contains(&w.code)
        // A gyroscope channel fault (it withholds the angles; an accelerometer's does not).
        || (w.code == codes::CHANNEL_FAULT && !w.affects.is_empty())
}

/// Per-stride consequences of leg-level findings: a finding about a span of the walk
/// (`channel_fault`) withholds the strides over it; a finding that withholds every parameter
/// invalidates every stride; one that withholds angles or stride length blanks them per stride
/// (the strides table must not show what the recordings table withholds).
pub fn apply_to_strides(st: &mut [Stride], warnings: &[Warning]) {
    for w in warnings {
        // A finding about part of the walk: the strides over it only.
        faults::withhold_span(st, w);
        let has = |c: Parameter| w.withholds(c);
        if w.affects.is_empty() {
            continue;
        }
        let all = params::ALL.iter().all(|&c| has(c));
        for s in st.iter_mut() {
            if all {
                // What else was found about this stride came from the same faulty signals.
                s.valid = false;
                s.replace_findings(StrideFinding::new(
                    StrideCode::Finding {
                        code: w.code,
                        effect: FindingEffect::Excludes,
                    },
                    w.code.plain(),
                ));
            }
            // A blanked cell says why (the strides table gets "an empty cell with a reason").
            let angles = [s.wqk_deg, s.pbi_deg, s.bdk_deg]
                .iter()
                .any(|v| v.is_finite());
            let length = s.stride_length_m.is_finite();
            if has(Parameter::Wqk) {
                s.wqk_deg = f64::NAN;
            }
            if has(Parameter::Pbi) {
                s.pbi_deg = f64::NAN;
            }
            if has(Parameter::Bdk) {
                s.bdk_deg = f64::NAN;
            }
            if has(Parameter::StrideLength) {
                s.stride_length_m = f64::NAN;
            }
            if has(Parameter::Speed) {
                s.speed_mps = f64::NAN;
            }
            if discredits_attitude(w) {
                s.heading_change_deg = f64::NAN;
            }
            let effect = match (
                angles && has(Parameter::Wqk),
                length && has(Parameter::StrideLength),
            ) {
                _ if all => None,
                (true, true) => Some((FindingEffect::AnglesAndLength, "angles and stride length")),
                (true, false) => Some((FindingEffect::Angles, "angles")),
                (false, true) => Some((FindingEffect::Length, "stride length")),
                (false, false) => None,
            };
            if let Some((effect, what)) = effect {
                s.push_once(StrideFinding::new(
                    StrideCode::Finding {
                        code: w.code,
                        effect,
                    },
                    format!("{what} withheld: {}", w.code.plain()),
                ));
            }
        }
    }
}

/// Withhold the parameters the warnings affect: NaN value and the reason in `withheld` (the
/// first finding that withholds a parameter gives its reason, unless a later one is a fault).
pub fn withhold(p: &mut SideParameters, warnings: &[Warning]) {
    for w in warnings {
        for &c in &w.affects {
            if c == Parameter::Sta {
                p.sta_status = format!("not measured: {}", w.reason());
            }
            // A sensor fault is the reason that matters: it replaces a reason found in the
            // faulty signals themselves (e.g. a stride length withheld for velocity drift).
            p.withhold(c, w.withheld_reason(), w.severity == Severity::Fault);
        }
    }
}

/// The warnings of a leg, its reader's included (as code `input`), most severe first.
pub fn all_leg_warnings(l: &LegResult) -> Vec<Warning> {
    let mut v: Vec<Warning> = l.warnings.clone();
    v.extend(l.read.warnings.iter().map(|t| Warning::from_reader(t)));
    v.sort_by_key(|x| std::cmp::Reverse(x.severity));
    v
}

#[cfg(test)]
pub(crate) mod tests;
