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
//!   the bracket [t_s, t_p], raised on the leg whose landmark geometry and swing arc are both
//!   stiffer than the subject's other leg's, placed per subject by [`place_bilateral`]
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
pub mod matching;
pub mod offset;
mod peaks;
#[cfg(test)]
mod tests_matching;

pub use bracket::{
    bracket_fraction, bracket_toe_off_s, landmark_geometry, place_bilateral, LegGeometry,
    BRACKET_K0, BRACKET_MAX, BRACKET_SLOPE, MIN_BRACKETS, SAME_WALK_STRIDE_TOLERANCE,
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
    /// peak of ω_s and the pitch peak, raised on the leg whose landmark geometry and swing arc
    /// are both stiffer than the subject's other leg's (default).
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
    /// candidate landings, 0.3 without an impact in a walk that shows them. Empty for the
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

/// Parabolic sub-sample position of an extremum at `i`.
fn parabolic(y: &[f64], i: usize) -> f64 {
    if i == 0 || i + 1 >= y.len() {
        return i as f64;
    }
    let (a, b, c) = (y[i - 1], y[i], y[i + 1]);
    let den = a - 2.0 * b + c;
    if den.abs() < 1e-12 {
        return i as f64;
    }
    i as f64 + (0.5 * (a - c) / den).clamp(-0.5, 0.5)
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

/// The late-stance landmarks before the mid-swing at `m`, searched in `[start, m)`: the
/// late-stance peak of ω_s (index `l`, Aminian et al. 2002 and Salarian et al. 2004 take the
/// largest such peak before mid-swing as the toe-off landmark; Trojaniello et al. 2014 likewise
/// take the largest one in the search window) and the first downward zero crossing after it
/// (index `z`, ω_s[z] ≥ 0 > ω_s[z + 1]: the pitch peak).
///
/// The peak is the largest positive local maximum of the window, not the last one: a stiff-knee
/// swing can pause the shank just after toe off, and the small bump of ω_s that pause makes
/// (with a second zero crossing) lies 100–200 ms after the toe off. `None` when the window has
/// no positive local maximum followed by a zero crossing before `m`.
fn late_stance(omega_s_dps: &[f64], start: usize, m: usize) -> Option<(usize, usize)> {
    let start = start.max(1);
    let l = (start..m)
        .filter(|&i| {
            omega_s_dps[i] > 0.0
                && omega_s_dps[i] >= omega_s_dps[i + 1]
                && omega_s_dps[i] > omega_s_dps[i - 1]
        })
        .max_by(|&a, &b| omega_s_dps[a].total_cmp(&omega_s_dps[b]))?;
    let z = (l..m).find(|&i| omega_s_dps[i] >= 0.0 && omega_s_dps[i + 1] < 0.0)?;
    Some((l, z))
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

/// The confidence of the toe off before the mid-swing at `m` (window `[start, m)`): 1 − the
/// largest other positive peak of ω_s over the late-stance peak the bracket starts from, where
/// "other" means separated from it by a dip below half its own height (a wobble on one peak is
/// not a second candidate). Two push-off peaks of nearly one height (a shuffle, a hesitation
/// before the swing) leave the bracket's start, and the toe off with it, unsure.
fn late_stance_confidence(omega_s_dps: &[f64], start: usize, m: usize) -> f64 {
    let w = omega_s_dps;
    let (a, b) = (start.max(1), m.min(w.len().saturating_sub(1)));
    let peaks: Vec<usize> = (a..b)
        .filter(|&i| w[i] > 0.0 && w[i] >= w[i + 1] && w[i] > w[i - 1])
        .collect();
    let Some(&l) = peaks.iter().max_by(|&&x, &&y| w[x].total_cmp(&w[y])) else {
        return 0.0;
    };
    let second = peaks
        .iter()
        .filter(|&&i| {
            let (lo, hi) = (i.min(l), i.max(l));
            i != l && w[lo..=hi].iter().copied().fold(f64::INFINITY, f64::min) < 0.5 * w[i]
        })
        .map(|&i| w[i])
        .fold(0.0, f64::max);
    1.0 - second / w[l]
}

/// The signals the event rules read: pitch (deg), ω_s (deg/s), −ω_s and the rate (Hz).
struct Signals<'a> {
    pitch_deg: &'a [f64],
    omega_s_dps: &'a [f64],
    neg: &'a [f64],
    fs_hz: f64,
}

/// Mid-swing samples: peaks of −ω_s above the threshold (height and prominence), at least 0.8 ×
/// the shortest stride apart, in order (`find_peaks`' peaks, found in linear time: [`peaks`]).
fn midswings(neg: &[f64], p: &EventParams, fs_hz: f64) -> Vec<usize> {
    let min_dist = ((p.min_stride_s * 0.8) * fs_hz).max(1.0) as usize;
    let threshold = midswing_threshold_dps(neg, p);
    peaks::peaks(neg, threshold, threshold, min_dist)
}

/// The median interval between mid-swings no longer than `max_stride_s`, s (1.1 s when none).
fn median_stride_s(mid: &[usize], fs_hz: f64, max_stride_s: f64) -> f64 {
    let mut iv: Vec<f64> = mid
        .windows(2)
        .map(|w| (w[1] - w[0]) as f64 / fs_hz)
        .filter(|d| *d <= max_stride_s)
        .collect();
    crate::stats::median(&mut iv, crate::stats::EvenMedian::Upper).unwrap_or(1.1)
}

/// The heel strike after the mid-swing at sample `m` and before `end`, as a fractional sample.
fn heel_strike(sig: &Signals, detector: EventDetector, m: usize, end: usize) -> Option<f64> {
    let (pitch_deg, omega_s_dps) = (sig.pitch_deg, sig.omega_s_dps);
    match detector {
        EventDetector::PitchPeaks => (m..=end)
            .min_by(|&a, &b| {
                pitch_deg[a]
                    .partial_cmp(&pitch_deg[b])
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .filter(|&i| i > m && i < end)
            .map(|i| i as f64),
        EventDetector::GyroZeroCrossing
        | EventDetector::GyroLandmarks
        | EventDetector::GyroBracket => (m..end)
            .find(|&i| omega_s_dps[i] < 0.0 && omega_s_dps[i + 1] >= 0.0)
            .map(|i| i as f64 + (-omega_s_dps[i]) / (omega_s_dps[i + 1] - omega_s_dps[i])),
        EventDetector::Salarian => {
            let zc = (m..end).find(|&i| omega_s_dps[i] < 0.0 && omega_s_dps[i + 1] >= 0.0);
            zc.and_then(|z| {
                (z + 1..end).find(|&i| {
                    omega_s_dps[i] >= omega_s_dps[i - 1] && omega_s_dps[i] > omega_s_dps[i + 1]
                })
            })
            .map(|i| parabolic(omega_s_dps, i))
        }
    }
}

/// The toe-off landmarks before the mid-swing at `m` (searched from `start`), s: the late-stance
/// peak of ω_s t_s (parabolic), the pitch peak t_p (the zero crossing after it, linear) and
/// mid-swing t_m (parabolic).
fn landmarks_s(sig: &Signals, start: usize, m: usize) -> Option<[f64; 3]> {
    let (w, fs_hz) = (sig.omega_s_dps, sig.fs_hz);
    let (l, z) = late_stance(w, start, m)?;
    let tp = (z as f64 + w[z] / (w[z] - w[z + 1])) / fs_hz;
    let ts = parabolic(w, l) / fs_hz;
    let tm = parabolic(sig.neg, m) / fs_hz;
    Some([ts, tp, tm])
}

/// The toe off between sample `start` and the mid-swing at sample `m`, s, offsets applied
/// (`t_med`: the median stride time, s).
fn toe_off_s(
    sig: &Signals,
    params: &ValidEventParams,
    t_med: f64,
    start: usize,
    m: usize,
) -> Option<f64> {
    let (pitch_deg, omega_s_dps, fs_hz) = (sig.pitch_deg, sig.omega_s_dps, sig.fs_hz);
    let to_idx: Option<f64> = match params.p.detector {
        EventDetector::GyroLandmarks => {
            let [ts, tp, tm] = landmarks_s(sig, start, m)?;
            let [_, b, c] = TO_LANDMARK_COEFFS;
            return Some(tp + params.to_offset * t_med + b * (tm - tp) + c * (tp - ts));
        }
        // `detect` places these itself (it keeps their landmarks); the same toe off.
        EventDetector::GyroBracket => {
            let lm = landmarks_s(sig, start, m)?;
            return Some(bracket_toe_off_s(lm, BRACKET_K0, params.to_offset * t_med).min(lm[2]));
        }
        EventDetector::PitchPeaks => (start..=m)
            .max_by(|&a, &b| {
                pitch_deg[a]
                    .partial_cmp(&pitch_deg[b])
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .filter(|&i| i > start && i < m)
            .map(|i| i as f64),
        EventDetector::GyroZeroCrossing => late_stance(omega_s_dps, start, m)
            .map(|(_, z)| z as f64 + omega_s_dps[z] / (omega_s_dps[z] - omega_s_dps[z + 1])),
        EventDetector::Salarian => {
            late_stance(omega_s_dps, start, m).map(|(l, _)| parabolic(omega_s_dps, l))
        }
    };
    to_idx.map(|i| i / fs_hz + params.to_offset * t_med)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One stride of ω_s at 100 Hz around a mid-swing at sample 100: a late-stance peak of
    /// 80 deg/s at 60, its zero crossing at 70, then (stiff-knee swing) a 9 deg/s bump at 85
    /// with a second zero crossing at 90 before the −300 deg/s mid-swing.
    fn stiff_knee_swing() -> Vec<f64> {
        let bump = |i: f64, c: f64, w: f64, a: f64| a * (-((i - c) / w).powi(2)).exp();
        (0..140)
            .map(|i| {
                let i = i as f64;
                bump(i, 60.0, 6.0, 80.0) - bump(i, 76.0, 3.0, 40.0) + bump(i, 85.0, 2.5, 25.0)
                    - bump(i, 100.0, 6.0, 300.0)
            })
            .collect()
    }

    #[test]
    fn late_stance_takes_the_largest_peak_and_its_own_zero_crossing() {
        let w = stiff_knee_swing();
        // The swing bump is a positive local maximum followed by a zero crossing.
        assert!(w[85] > 0.0 && w[85] > w[84] && w[85] >= w[86], "{}", w[85]);
        let (l, z) = late_stance(&w, 30, 100).expect("landmarks");
        assert_eq!(l, 60);
        assert!((66..76).contains(&z), "zero crossing at {z}");
        assert!(w[z] >= 0.0 && w[z + 1] < 0.0);
        // No positive peak in the window: no landmark.
        let neg: Vec<f64> = w.iter().map(|x| -x.abs() - 1.0).collect();
        assert_eq!(late_stance(&neg, 30, 100), None);
    }
}
