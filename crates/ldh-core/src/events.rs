//! Gait events: heel strike (HS) and toe off (TO) of one shank (paper §3.2; SPEC §3.4).
//!
//! Every detector starts from the same skeleton: mid-swing, the large negative peaks of the
//! sagittal angular velocity ω_s (the foot swings forward, so the shank inclination θ falls at
//! 300–450 deg/s). Between a mid-swing and its neighbours:
//!
//! * [`EventDetector::PitchPeaks`] — the paper's method: HS at the trough of θ after mid-swing,
//!   TO at the peak of θ before it, on the sample grid, uncorrected.
//! * [`EventDetector::GyroZeroCrossing`] — the same two landmarks found as the zero crossings of
//!   ω_s (θ̇ = 0), linearly interpolated between samples, then shifted by a systematic offset
//!   expressed as a fraction of the stride time.
//! * [`EventDetector::Salarian`] — Salarian et al. 2004 (IEEE TBME 51:1434): HS at the first local
//!   maximum of ω_s after mid-swing (in ldh's sign, the loading-response peak), TO at the largest
//!   local maximum before it (late stance), parabolically interpolated, then offset-corrected.
//! * [`EventDetector::GyroLandmarks`] — HS as in `GyroZeroCrossing`; TO from three landmarks
//!   around it: the late-stance peak of ω_s (t_s), the pitch peak (t_p, ω_s = 0) and mid-swing
//!   (t_m): TO = t_p + a·T + b·(t_m − t_p) + c·(t_p − t_s), T the median stride time. The pitch
//!   peak alone drifts relative to TO with the subject's swing knee flexion; the two intervals
//!   measure the local phase speed on either side of it and cancel most of that drift.
//! * [`EventDetector::GyroBracket`] (default) — HS at each strike's own impact (the onset of the
//!   step in the shank's acceleration after the zero crossing) where the walk shows impacts
//!   (`events/impact.rs`; a strike without one at the crossing plus the walk's median delay,
//!   unsure), else as in `GyroZeroCrossing`; every event with a confidence
//!   (`events/confidence.rs`); TO at a fraction of
//!   the bracket [t_s, t_p], raised on the leg whose swing arc is shorter than the subject's
//!   other leg's (further when its landmark geometry is stiffer too), placed per subject by
//!   [`place_bilateral`]
//!   (`events/bracket.rs`).
//!
//! The offsets and coefficients were fitted on a simulated tuning cohort (family A seed 100)
//! against its ground truth (docs/accuracy.md).
//!
//! Without offsets the literature's landmarks miss toe off on both simulators: the late-stance
//! peak t_s (Aminian et al. 2002, J Biomech 35:689; Salarian et al. 2004) comes 40–100 ms early,
//! the pitch peak t_p 60–115 ms late; the true toe off lies at 0.41–0.46 of the way between them
//! in normal gait on both families. The three-landmark model carries family A's landmark
//! geometry and is 13–18 ms late on family B's normal walkers; the bracket rule, with the other
//! leg as the reference for the geometry, is not, and halves family B's TO and stance errors for
//! 1–2 ms on family A: the comparison and the decision are in docs/accuracy.md "Toe off without
//! fitted offsets" (`data-fixtures/scripts/toe_off_landmarks.py`).

mod bracket;
mod calibration;
mod confidence;
mod impact;
mod landmarks;
pub mod matching;
pub mod offset;
mod peaks;
#[cfg(test)]
mod tests;

pub use bracket::{
    bracket_fraction, bracket_toe_off_s, landmark_geometry, place_bilateral, LegGeometry,
    BRACKET_ARC_SLOPE, BRACKET_K0, BRACKET_MAX, BRACKET_SLOPE, MIN_BRACKETS,
    SAME_WALK_STRIDE_TOLERANCE,
};
pub use calibration::{EventCalibration, MAX_CALIBRATION_SHIFT_S};
pub use confidence::{hs_confidence_at, to_confidence_at, unsure_events, UnsureEvent};
pub use impact::{
    impacts, shift_to_impacts, Impact, GYRO_ONLY_CONFIDENCE, IMPACT_MIN_G, IMPACT_MIN_STRIKES,
    IMPACT_RATIO, IMPACT_SHARE, IMPACT_WINDOW_STRIDE, MIN_EVENT_CONFIDENCE, NO_IMPACT_CONFIDENCE,
    SECOND_CANDIDATE_GAP_S, SECOND_CANDIDATE_SHARE, TWO_CANDIDATES_CONFIDENCE,
};
pub use matching::{match_events, match_groups, summarize, EventMatch, MatchSummary};
pub use offset::{estimate_clock_offset, polish_offset, ClockOffset, OffsetCandidate};

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};
use landmarks::{
    heel_strike, landmarks_s, late_stance_confidence, median_stride_s, midswings, parabolic,
    toe_off_s, Signals,
};

/// Event detection method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum EventDetector {
    /// The paper's plain peak picker on the pitch angle.
    PitchPeaks,
    /// Zero crossings of the sagittal angular velocity with offset correction.
    GyroZeroCrossing,
    /// Salarian et al. 2004 local maxima with offset correction.
    Salarian,
    /// HS from the ω_s zero crossing, TO from three landmarks with a model fitted on family A.
    GyroLandmarks,
    /// HS at each strike's impact where the walk shows impacts (else the ω_s zero crossing
    /// plus an offset), TO at a fraction of the bracket between the late-stance
    /// peak of ω_s and the pitch peak, raised on the leg whose swing arc is shorter than the
    /// subject's other leg's, further when its landmark geometry is stiffer too (default).
    #[default]
    GyroBracket,
}

impl std::str::FromStr for EventDetector {
    type Err = LdhError;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "pitch-peaks" => Ok(EventDetector::PitchPeaks),
            "gyro-zero-crossing" => Ok(EventDetector::GyroZeroCrossing),
            "salarian" => Ok(EventDetector::Salarian),
            "gyro-landmarks" => Ok(EventDetector::GyroLandmarks),
            "gyro-bracket" => Ok(EventDetector::GyroBracket),
            o => Err(LdhError::param(
                "detector",
                o,
                "expected gyro-bracket, gyro-landmarks, gyro-zero-crossing, salarian or pitch-peaks",
            )),
        }
    }
}

impl EventDetector {
    /// Default (HS, TO) offsets as fractions of the stride time, added to the detected times.
    ///
    /// Measured on the tuning cohort as the median of (true − detected) / stride time. The paper's
    /// plain method is left uncorrected. For `GyroLandmarks` the TO offset is the constant `a`
    /// of its landmark model ([`TO_LANDMARK_COEFFS`]); `GyroBracket` places TO inside the
    /// bracket with no offset.
    pub fn offsets(self) -> (f64, f64) {
        match self {
            EventDetector::GyroBracket => (0.0160, 0.0),
            EventDetector::PitchPeaks => (0.0, 0.0),
            EventDetector::GyroZeroCrossing => (0.0160, -0.0779),
            EventDetector::Salarian => (-0.0515, 0.0590),
            EventDetector::GyroLandmarks => (0.0160, TO_LANDMARK_COEFFS[0]),
        }
    }

    /// Name as accepted by `FromStr`.
    pub fn as_str(self) -> &'static str {
        match self {
            EventDetector::PitchPeaks => "pitch-peaks",
            EventDetector::GyroZeroCrossing => "gyro-zero-crossing",
            EventDetector::Salarian => "salarian",
            EventDetector::GyroLandmarks => "gyro-landmarks",
            EventDetector::GyroBracket => "gyro-bracket",
        }
    }
}

/// Coefficients (a, b, c) of the TO landmark model of [`EventDetector::GyroLandmarks`]:
/// TO = t_p + a·T + b·(t_m − t_p) + c·(t_p − t_s). Least squares on the tuning cohort.
pub const TO_LANDMARK_COEFFS: [f64; 3] = [-0.10139, 0.56902, -0.60292];

impl EventDetector {
    /// All detectors, default first.
    pub const ALL: [EventDetector; 5] = [
        EventDetector::GyroBracket,
        EventDetector::GyroLandmarks,
        EventDetector::GyroZeroCrossing,
        EventDetector::Salarian,
        EventDetector::PitchPeaks,
    ];
}

/// Event detection parameters (unchecked).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EventParams {
    /// Detector. Default gyro-bracket.
    pub detector: EventDetector,
    /// Offset added to every HS, fraction of the stride time; `None`: the detector's default (for
    /// `gyro-bracket`, replaced by the walk's own delay to the impact where it shows impacts;
    /// a value given here always applies).
    pub hs_offset_stride: Option<f64>,
    /// Offset added to every TO, fraction of the stride time; `None`: the detector's default.
    pub to_offset_stride: Option<f64>,
    /// Smallest mid-swing peak of −ω_s, deg/s. Default 100. With `adaptive_midswing` this is an
    /// upper bound: the threshold used is 35 % of the recording's 99th percentile of −ω_s,
    /// clamped to [30, this] (slow, pathological gait swings at well under 100 deg/s).
    pub min_midswing_dps: f64,
    /// Adapt the mid-swing threshold to the recording (see `min_midswing_dps`). Default true.
    pub adaptive_midswing: bool,
    /// Shortest plausible stride, s; mid-swings closer than 0.8 × this are merged. Default 0.7.
    pub min_stride_s: f64,
    /// Longest plausible stride, s. Default 2.5.
    pub max_stride_s: f64,
    /// Heel strikes at their own impact in the acceleration, where the walk shows impacts
    /// ([`shift_to_impacts`]); `gyro-bracket` only,
    /// and not when `hs_offset_stride` is given (an explicit offset wins). Default true.
    pub hs_impact: bool,
    /// Shifts measured against a laboratory's reference by `ldh agree --write-params`
    /// ([`EventCalibration`]), added to every event after detection. Default: none. Not
    /// written when absent, so an uncalibrated run's `params.json` is unchanged.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub calibration: Option<EventCalibration>,
}

impl Default for EventParams {
    fn default() -> Self {
        EventParams {
            detector: EventDetector::default(),
            hs_offset_stride: None,
            to_offset_stride: None,
            min_midswing_dps: 100.0,
            adaptive_midswing: true,
            min_stride_s: 0.7,
            max_stride_s: 2.5,
            hs_impact: true,
            calibration: None,
        }
    }
}

impl EventParams {
    /// Set the detector.
    pub fn detector(mut self, d: EventDetector) -> Self {
        self.detector = d;
        self
    }
    /// Validate.
    pub fn check(&self) -> Result<ValidEventParams> {
        if !(self.min_midswing_dps.is_finite() && self.min_midswing_dps > 0.0) {
            return Err(LdhError::param(
                "min_midswing_dps",
                self.min_midswing_dps,
                "must be > 0",
            ));
        }
        // At most 600 deg/s: a walking shank's mid-swing peaks at 300-500 deg/s, so a higher
        // threshold finds no stride.
        crate::align::within(
            "events.min_midswing_dps",
            self.min_midswing_dps,
            0.0,
            600.0,
            "deg/s",
        )?;
        crate::gait::check_stride_range(self.min_stride_s, self.max_stride_s)?;
        for (n, v) in [
            ("hs_offset_stride", self.hs_offset_stride),
            ("to_offset_stride", self.to_offset_stride),
        ] {
            if let Some(v) = v {
                if !(v.is_finite() && v.abs() < 0.3) {
                    return Err(LdhError::param(n, v, "must lie in (−0.3, 0.3)"));
                }
            }
        }
        if let Some(c) = &self.calibration {
            c.check(self.detector)?;
        }
        let (h, t) = self.detector.offsets();
        Ok(ValidEventParams {
            p: self.clone(),
            hs_offset: self.hs_offset_stride.unwrap_or(h),
            to_offset: self.to_offset_stride.unwrap_or(t),
        })
    }
}

/// Checked event parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidEventParams {
    p: EventParams,
    hs_offset: f64,
    to_offset: f64,
}

impl ValidEventParams {
    /// The parameters.
    pub fn params(&self) -> &EventParams {
        &self.p
    }
}

/// Find the impact after each heel strike of `ev` in the raw acceleration `acc_g` (g, sampled
/// at `fs_hz` on the events' clock) into `ev.hs_impacts`, when the parameters place
/// heel strikes by impacts (`hs_impact` with `gyro-bracket` and no `hs_offset_stride`);
/// [`place_bilateral`] then uses them. The number of strikes with an impact.
pub fn find_impacts(
    ev: &mut Events,
    acc_g: [&[f64]; 3],
    fs_hz: f64,
    params: &ValidEventParams,
) -> usize {
    if !uses_impacts(params) {
        return 0;
    }
    ev.hs_impacts = impacts(ev, acc_g, fs_hz, params.hs_offset * ev.median_stride_s);
    ev.hs_impacts.iter().flatten().count()
}

/// Whether heel strikes are placed by impacts with these parameters.
fn uses_impacts(params: &ValidEventParams) -> bool {
    params.p.hs_impact
        && params.p.detector == EventDetector::GyroBracket
        && params.p.hs_offset_stride.is_none()
}

/// Events of one shank, in seconds from the first sample (sub-sample precision).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Events {
    /// Heel strikes.
    pub hs_s: Vec<f64>,
    /// Toe offs.
    pub to_s: Vec<f64>,
    /// Mid-swings (negative peaks of ω_s).
    pub midswing_s: Vec<f64>,
    /// Median interval between mid-swings, s (the upper median for an even count).
    pub median_stride_s: f64,
    /// The landmarks of each toe off of [`EventDetector::GyroBracket`] (same order as `to_s`):
    /// the late-stance peak of ω_s t_s, the pitch peak t_p and mid-swing t_m, s. Empty for the
    /// other detectors. Not serialised (what [`place_bilateral`] reads).
    #[serde(skip)]
    pub to_landmarks_s: Vec<[f64; 3]>,
    /// The shank's swing arc after each toe off of [`EventDetector::GyroBracket`] (same order
    /// as `to_s`): −∫ω_s dt from the pitch peak t_p to the next heel strike's zero crossing,
    /// deg; NaN when that heel strike was not found (or not after t_p). Empty for the other
    /// detectors. Not
    /// serialised (what [`place_bilateral`] reads).
    #[serde(skip)]
    pub to_swing_arc_deg: Vec<f64>,
    /// The impact after each heel strike's zero crossing (same order as `hs_s`); empty unless
    /// [`find_impacts`] ran. Not serialised (what [`place_bilateral`] reads).
    #[serde(skip)]
    pub hs_impacts: Vec<Option<Impact>>,
    /// The walk's median delay from the zero crossing to the impact, s, when its heel strikes
    /// were placed by impacts ([`shift_to_impacts`]). Not serialised.
    #[serde(skip)]
    pub hs_impact_delay_s: Option<f64>,
    /// Confidence of each heel strike, 0–1 (same order as `hs_s`; `events/impact.rs`): 1 −
    /// ½·ratio⁻¹·4 at its own impact, 0.5 where the walk shows no impacts, 0.2 with two
    /// candidate landings, 0.3 without an impact in a walk that shows them or with one at the
    /// zero crossing (`events/impact.rs`, "A strike at the crossing"). Empty for the
    /// detectors that do not place heel strikes by impacts. Strides bounded by a strike below
    /// [`MIN_EVENT_CONFIDENCE`] are withheld.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hs_confidence: Vec<f64>,
    /// Confidence of each toe off, 0–1 (same order as `to_s`; `events/bracket.rs`): 1 − the
    /// second-largest late-stance peak of ω_s over the largest (two candidate push-offs make it
    /// small). Empty for the detectors other than `gyro-bracket`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub to_confidence: Vec<f64>,
}

/// Lowest adaptive mid-swing threshold, deg/s.
pub const MIN_ADAPTIVE_MIDSWING_DPS: f64 = 30.0;

/// The mid-swing threshold used on this recording (`neg` = −ω_s), deg/s.
pub fn midswing_threshold_dps(neg: &[f64], p: &EventParams) -> f64 {
    if !p.adaptive_midswing || neg.is_empty() {
        return p.min_midswing_dps;
    }
    let mut v: Vec<f64> = neg.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return p.min_midswing_dps;
    }
    let k = ((v.len() as f64 * 0.99) as usize).min(v.len() - 1);
    let (_, p99, _) = v.select_nth_unstable_by(k, f64::total_cmp);
    (0.35 * *p99).clamp(
        MIN_ADAPTIVE_MIDSWING_DPS.min(p.min_midswing_dps),
        p.min_midswing_dps,
    )
}

/// Why a leg has no strides, in words (for its warning), from −ω_s and the parameters.
pub fn no_strides_reason(omega_s_dps: &[f64], ev: &Events, p: &EventParams) -> String {
    let neg: Vec<f64> = omega_s_dps.iter().map(|w| -w).collect();
    let peak = neg.iter().copied().fold(f64::NAN, f64::max);
    let thr = midswing_threshold_dps(&neg, p);
    match ev.midswing_s.len() {
        0 | 1 => format!(
            "no strides: {} mid-swing peak(s) of the sagittal angular velocity above {thr:.0} deg/s (largest swing rate {peak:.0} deg/s); no walking, or a sensor not on the shank",
            ev.midswing_s.len()
        ),
        n => format!(
            "no strides: {n} mid-swings found but no heel strike pairs (HS {}, TO {}) within [{}, {}] s",
            ev.hs_s.len(),
            ev.to_s.len(),
            p.min_stride_s,
            p.max_stride_s
        ),
    }
}

/// Detect HS and TO from the pitch θ (deg) and the sagittal angular velocity ω_s (deg/s).
pub fn detect(
    pitch_deg: &[f64],
    omega_s_dps: &[f64],
    fs_hz: f64,
    params: &ValidEventParams,
) -> Result<Events> {
    let n = pitch_deg.len();
    if omega_s_dps.len() != n {
        return Err(LdhError::signal(
            "events",
            format!(
                "pitch has {n} samples, angular velocity {}",
                omega_s_dps.len()
            ),
        ));
    }
    let p = &params.p;
    let neg: Vec<f64> = omega_s_dps.iter().map(|w| -w).collect();
    let mid = midswings(&neg, p, fs_hz);
    if mid.len() < 2 {
        return Ok(Events {
            midswing_s: mid.iter().map(|&i| i as f64 / fs_hz).collect(),
            ..Events::default()
        });
    }
    let t_med = median_stride_s(&mid, fs_hz, p.max_stride_s);
    let half = ((0.5 * t_med) * fs_hz) as usize;
    let sig = Signals {
        pitch_deg,
        omega_s_dps,
        neg: &neg,
        fs_hz,
    };
    let mut hs = Vec::new();
    let mut to = Vec::new();
    let mut marks = Vec::new();
    let mut arcs = Vec::new();
    let mut to_conf = Vec::new();
    for &m in &mid {
        // HS: after mid-swing, within half a stride.
        let end = (m + half).min(n - 1);
        let hs_i = heel_strike(&sig, p.detector, m, end);
        if let Some(i) = hs_i {
            hs.push(i / fs_hz + params.hs_offset * t_med);
        }
        // TO: before mid-swing, within half a stride.
        let start = m.saturating_sub(half).max(1);
        if p.detector == EventDetector::GyroBracket {
            if let Some(lm) = landmarks_s(&sig, start, m) {
                to.push(bracket_toe_off_s(lm, BRACKET_K0, params.to_offset * t_med).min(lm[2]));
                to_conf.push(late_stance_confidence(omega_s_dps, start, m));
                marks.push(lm);
                arcs.push(hs_i.map_or(f64::NAN, |h| {
                    bracket::swing_arc_deg(omega_s_dps, fs_hz, lm[1], h)
                }));
            }
        } else if let Some(t) = toe_off_s(&sig, params, t_med, start, m) {
            to.push(t);
        }
    }
    Ok(Events {
        hs_s: hs,
        to_s: to,
        midswing_s: mid.iter().map(|&i| parabolic(&neg, i) / fs_hz).collect(),
        median_stride_s: t_med,
        to_landmarks_s: marks,
        to_swing_arc_deg: arcs,
        to_confidence: to_conf,
        ..Events::default()
    })
}
