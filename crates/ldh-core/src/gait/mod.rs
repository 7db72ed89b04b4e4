//! Strides and gait parameters (paper §3.2 and Table 2; SPEC §3.5–3.6).
//!
//! **Strides** run from a heel strike to the next heel strike of the same leg, with the toe off
//! between them. A stride is kept in the table but flagged invalid, with the reason, when its
//! toe off is missing, its time is outside [`StrideParams::min_stride_s`, `max_stride_s`], it is
//! part of a turn (heading change over the stride above `turn_deg`; with both legs, the other
//! leg must turn too — [`crate::pipeline::analyze_pair`] — and on a treadmill nothing is a
//! turn), or it is the first or last
//! stride of a walking bout (bouts are separated by pauses longer than a stride and by turns).
//!
//! **Stride length** (the paper: "estimated by fusing three-axis acceleration"): the
//! acceleration is rotated to the world with the fused attitude, gravity removed, and integrated
//! twice between consecutive mid-stances (the minimum of |ω| between HS and TO), with linear
//! de-drifting of the velocity. The sensor is not at rest at mid-stance: the shank pivots about
//! the ankle, which is at rest. The sensor's velocity there is ω × r (r the sensor's position from
//! the ankle, `sensor_height_m` along the shank), used as the boundary velocity, and the change
//! of r over the stride is removed from the displacement, so the result is the ankle's horizontal
//! displacement: the stride length.
//!
//! **Parameters** per stride: stride time, stance ratio, stride length, speed, WQK (max pitch),
//! PBI (−min pitch), BDK (range of anatomical roll from TO to the next HS); per side, the means
//! over valid strides and SV, STV (SD / mean), SF, STT (needs both legs) and STA
//! ([`crate::nonlinear::gait_sta`]).

mod length;

use serde::{Deserialize, Serialize};

use crate::align::Aligned;
use crate::attitude::{Attitude, AttitudeModel};
use crate::error::{LdhError, Result};
use crate::events::Events;
use crate::recording::Side;
pub use length::{
    pendulum_length_m, stride_length, zero_velocity_sample, LengthEstimate, ZeroVelocity,
    MAX_DRIFT_MPS, MAX_VERTICAL_M, PENDULUM_GAIN, SHANK_LENGTH_M,
};

/// Default sensor height above the ankle joint, m (SPEC: "just above the ankle").
pub const DEFAULT_SENSOR_HEIGHT_M: f64 = 0.10;

/// Stride segmentation and stride-length parameters (unchecked).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StrideParams {
    /// Shortest physiological stride, s. Default 0.7.
    pub min_stride_s: f64,
    /// Longest physiological stride, s. Default 2.5.
    pub max_stride_s: f64,
    /// Heading change over one stride above which the stride is part of a turn, deg. Default 20;
    /// 180 turns the detection off (a treadmill: the heading drift of the gyroscope is no turn).
    pub turn_deg: f64,
    /// Height of the sensor above the ankle joint along the shank, m. Default 0.10.
    pub sensor_height_m: f64,
    /// Flag the first and last stride of every bout. Default true.
    pub drop_bout_edges: bool,
    /// How the zero-velocity instant of each stance is found. Default foot-flat.
    pub zero_velocity: ZeroVelocity,
    /// A stride whose length differs from its bout's median by more than this fraction is
    /// invalid (stride length withheld). Default 0.25.
    pub max_length_deviation: f64,
}

impl Default for StrideParams {
    fn default() -> Self {
        StrideParams {
            min_stride_s: 0.7,
            max_stride_s: 2.5,
            turn_deg: 20.0,
            sensor_height_m: DEFAULT_SENSOR_HEIGHT_M,
            drop_bout_edges: true,
            zero_velocity: ZeroVelocity::default(),
            max_length_deviation: 0.25,
        }
    }
}

impl StrideParams {
    /// Set the sensor height, m.
    pub fn sensor_height_m(mut self, h: f64) -> Self {
        self.sensor_height_m = h;
        self
    }
    /// Validate.
    pub fn check(&self) -> Result<ValidStrideParams> {
        check_stride_range(self.min_stride_s, self.max_stride_s)?;
        if !(self.turn_deg > 0.0 && self.turn_deg <= 180.0) {
            return Err(LdhError::param(
                "turn_deg",
                self.turn_deg,
                "must lie in (0, 180] (180: no stride is a turn, as on a treadmill)",
            ));
        }
        if !(self.sensor_height_m.is_finite() && (0.0..=0.5).contains(&self.sensor_height_m)) {
            return Err(LdhError::param(
                "sensor_height_m",
                self.sensor_height_m,
                "must lie in [0, 0.5] m",
            ));
        }
        if !(self.max_length_deviation > 0.0 && self.max_length_deviation <= 1.0) {
            return Err(LdhError::param(
                "max_length_deviation",
                self.max_length_deviation,
                "must lie in (0, 1]",
            ));
        }
        Ok(ValidStrideParams(self.clone()))
    }
}

/// Check a physiological stride-time range: 0 < min < max < ∞ (shared by events and strides).
pub fn check_stride_range(min_stride_s: f64, max_stride_s: f64) -> Result<()> {
    if min_stride_s > 0.0 && max_stride_s > min_stride_s && max_stride_s.is_finite() {
        Ok(())
    } else {
        Err(LdhError::param(
            "min_stride_s/max_stride_s",
            format!("{min_stride_s}/{max_stride_s}"),
            "need 0 < min < max",
        ))
    }
}

/// Checked stride parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidStrideParams(StrideParams);

impl ValidStrideParams {
    /// The parameters.
    pub fn params(&self) -> &StrideParams {
        &self.0
    }
}

/// One stride of one leg: a row of the per-stride table (SPEC §6).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stride {
    /// Number within the leg's recording, from 0.
    pub stride_index: usize,
    /// Heel strike, s from the recording's first sample.
    pub hs_time_s: f64,
    /// Toe off, s (NaN when missing).
    pub to_time_s: f64,
    /// Next heel strike, s.
    pub next_hs_time_s: f64,
    /// Stride time, s.
    pub stride_time_s: f64,
    /// Stance ratio (TO − HS) / stride time.
    pub stance_ratio: f64,
    /// Stride length, m (NaN when it could not be integrated).
    pub stride_length_m: f64,
    /// Speed, m/s.
    pub speed_mps: f64,
    /// Max pitch (forward shank inclination) in the stride, deg (WQK).
    pub wqk_deg: f64,
    /// −min pitch (backward inclination) in the stride, deg (PBI).
    pub pbi_deg: f64,
    /// Range of anatomical roll from TO to the next HS, deg (BDK).
    pub bdk_deg: f64,
    /// Heading change over the stride, deg (for turn detection; not a clinical feature).
    pub heading_change_deg: f64,
    /// Walking bout number.
    pub bout: usize,
    /// Valid for the per-side means.
    pub valid: bool,
    /// Why not valid, and why a value of the stride is withheld (its length: "stride length
    /// withheld: …"; the stride may then still be valid for its timing and angles); several
    /// reasons joined by "; ", "" when valid with every value reported.
    pub reason: String,
}

/// Per-side parameters (SPEC §3.6): means over valid strides.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SideParameters {
    /// Strides found.
    pub strides_total: usize,
    /// Valid strides used.
    pub strides_valid: usize,
    /// ST, mean stride time, s.
    pub stride_time_s: f64,
    /// STT, mean step time (contralateral HS to ipsilateral HS), s; NaN with one leg.
    pub step_time_s: f64,
    /// SF, step frequency, steps/s: 1 / mean STT, or 2 / mean ST with one leg.
    pub step_frequency_hz: f64,
    /// STP, mean stance ratio.
    pub stance_ratio: f64,
    /// SWP, 1 − STP.
    pub swing_ratio: f64,
    /// SL, mean stride length, m.
    pub stride_length_m: f64,
    /// SS, mean speed, m/s.
    pub speed_mps: f64,
    /// SV, SD / mean of stride length.
    pub stride_length_cv: f64,
    /// STV, SD / mean of stride time.
    pub stride_time_cv: f64,
    /// STA, short-term maximum Lyapunov exponent of ω_s, 1/s (NaN when not computed).
    pub sta_per_s: f64,
    /// STA per stride (λ · mean stride time).
    pub sta_per_stride: f64,
    /// Why STA is missing ("" when present).
    pub sta_status: String,
    /// WQK, mean max pitch, deg.
    pub wqk_deg: f64,
    /// PBI, mean −min pitch, deg.
    pub pbi_deg: f64,
    /// BDK, mean roll excursion in swing, deg.
    pub bdk_deg: f64,
    /// Parameters withheld by a quality check: column name (as in recordings.csv, e.g.
    /// `stride_length_m`) → reason. A withheld parameter's value is NaN and must be shown as
    /// "not measured: <reason>", never as a number. Empty when every parameter is vouched for.
    #[serde(default, skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub withheld: std::collections::BTreeMap<String, String>,
}

fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        f64::NAN
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}

fn cv(v: &[f64]) -> f64 {
    if v.len() < 2 {
        return f64::NAN;
    }
    let m = mean(v);
    let sd = (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt();
    sd / m
}

/// Anatomical roll (positive: knee lateral to the ankle) from the ZYX roll of frame F.
pub fn anatomical_roll_deg(roll_zyx_deg: f64, side: Side) -> f64 {
    match side {
        Side::Left => -roll_zyx_deg,
        Side::Right => roll_zyx_deg,
    }
}

/// Segment one leg into strides and compute the per-stride parameters.
pub fn strides(
    side: Side,
    al: &Aligned,
    att: &Attitude,
    ev: &Events,
    params: &ValidStrideParams,
) -> Result<Vec<Stride>> {
    let turn_deg = params.0.turn_deg;
    strides_with_turns(side, al, att, ev, params, &|_, _, d| d.abs() > turn_deg)
}

/// Why the ACC-only model never reports a stride length: its attitude is the accelerometer's
/// own tilt, which walking accelerations corrupt, so gravity cannot be removed before the
/// integration. On both simulator families its few lengths that passed the per-stride checks
/// were 86-99 % short (docs/accuracy.md); the paper uses this model for angles only.
pub const ACC_ONLY_LENGTH: &str = "stride length withheld: the ACC-only attitude cannot separate gravity from motion, so the acceleration is not integrated";

/// The turn test of [`strides_with_turns`]: (HS time s, next HS time s, this leg's heading
/// change over the stride deg) → the stride is part of a turn.
pub type TurnTest<'a> = dyn Fn(f64, f64, f64) -> bool + 'a;

/// As [`strides`], with the turn decision made by `is_turn` (e.g. from both legs: a turn
/// rotates both shanks at the same time, yaw drift on one leg does not; none on a treadmill).
pub fn strides_with_turns(
    side: Side,
    al: &Aligned,
    att: &Attitude,
    ev: &Events,
    params: &ValidStrideParams,
    is_turn: &TurnTest,
) -> Result<Vec<Stride>> {
    let p = &params.0;
    let fs = al.fs_hz;
    let n = att.pitch_deg.len();
    let idx = |t: f64| ((t * fs).round().max(0.0) as usize).min(n.saturating_sub(1));
    let mut hs = ev.hs_s.clone();
    hs.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    let mut out: Vec<Stride> = Vec::new();
    // Mid-stance (zero-velocity) sample after each HS.
    let w_norm: Vec<f64> = (0..n)
        .map(|i| {
            (al.gyro_dps[0][i].powi(2) + al.gyro_dps[1][i].powi(2) + al.gyro_dps[2][i].powi(2))
                .sqrt()
        })
        .collect();
    let zv_after = |h: f64| -> Option<usize> {
        let to = ev
            .to_s
            .iter()
            .copied()
            .find(|&t| t > h && t - h < 0.75 * p.max_stride_s);
        let end = to.unwrap_or(h + 0.6 * ev.median_stride_s.max(0.5));
        zero_velocity_sample(p.zero_velocity, al, &w_norm, idx(h), idx(end))
    };
    // Why a stride's length is withheld (the stride stays valid for its timing and angles).
    let mut length_notes: Vec<Option<String>> = Vec::new();
    for (k, w) in hs.windows(2).enumerate() {
        let (h0, h1) = (w[0], w[1]);
        let st = h1 - h0;
        let mut reasons: Vec<String> = Vec::new();
        if st < p.min_stride_s || st > p.max_stride_s {
            reasons.push(format!(
                "stride time {st:.2} s outside [{}, {}] s",
                p.min_stride_s, p.max_stride_s
            ));
        }
        let tos: Vec<f64> = ev
            .to_s
            .iter()
            .copied()
            .filter(|&t| t > h0 && t < h1)
            .collect();
        let to = match tos.as_slice() {
            [] => {
                reasons.push("no toe off".into());
                f64::NAN
            }
            [t] => *t,
            [t, ..] => {
                reasons.push(format!("{} toe offs", tos.len()));
                *t
            }
        };
        let (a, b) = (idx(h0), idx(h1));
        let (mut mx, mut mn) = (f64::MIN, f64::MAX);
        for i in a..b.max(a + 1).min(n) {
            mx = mx.max(att.pitch_deg[i]);
            mn = mn.min(att.pitch_deg[i]);
        }
        let bdk = if to.is_finite() {
            let (mut rmx, mut rmn) = (f64::MIN, f64::MAX);
            for i in idx(to)..b.max(idx(to) + 1).min(n) {
                let r = anatomical_roll_deg(att.roll_deg[i], side);
                rmx = rmx.max(r);
                rmn = rmn.min(r);
            }
            rmx - rmn
        } else {
            f64::NAN
        };
        let mut dpsi = att.yaw_deg[b.min(n - 1)] - att.yaw_deg[a];
        dpsi = (dpsi + 180.0).rem_euclid(360.0) - 180.0;
        if is_turn(h0, h1, dpsi) {
            reasons.push(format!("turning ({dpsi:.0} deg heading change)"));
        }
        let est = match (zv_after(h0), zv_after(h1)) {
            (Some(z0), Some(z1)) if z1 > z0 + 1 => {
                stride_length(al, att, z0, z1, p.sensor_height_m)
            }
            _ => LengthEstimate {
                length_m: f64::NAN,
                drift_mps: f64::NAN,
                vertical_m: f64::NAN,
                clipped_samples: 0,
            },
        };
        let pendulum = if to.is_finite() {
            pendulum_length_m(att.pitch_deg[a], att.pitch_deg[idx(to)], (to - h0) / st)
        } else {
            f64::NAN
        };
        let mut length = est.length_m;
        let note = if att.model == AttitudeModel::Acc {
            Some(ACC_ONLY_LENGTH.to_string())
        } else {
            est.implausible(pendulum)
        };
        if note.is_some() {
            length = f64::NAN;
        }
        length_notes.push(note);
        out.push(Stride {
            stride_index: k,
            hs_time_s: h0,
            to_time_s: to,
            next_hs_time_s: h1,
            stride_time_s: st,
            stance_ratio: (to - h0) / st,
            stride_length_m: length,
            speed_mps: length / st,
            wqk_deg: mx,
            pbi_deg: -mn,
            bdk_deg: bdk,
            heading_change_deg: dpsi,
            bout: 0,
            valid: true,
            reason: reasons.join("; "),
        });
    }
    // Bouts: split at pauses (a stride too long) and at turns.
    let mut bout = 0usize;
    let mut prev_break = true;
    for s in out.iter_mut() {
        let breaks = s.stride_time_s > p.max_stride_s || s.reason.contains("turning");
        if breaks {
            if !prev_break {
                bout += 1;
            }
            s.bout = usize::MAX;
            prev_break = true;
            continue;
        }
        s.bout = bout;
        prev_break = false;
    }
    if p.drop_bout_edges {
        let m = out.len();
        for i in 0..m {
            if out[i].bout == usize::MAX {
                continue;
            }
            let first = i == 0 || out[i - 1].bout != out[i].bout;
            let last = i + 1 == m || out[i + 1].bout != out[i].bout;
            if first || last {
                let r = if first {
                    "first stride of a walking bout"
                } else {
                    "last stride of a walking bout"
                };
                out[i].reason = if out[i].reason.is_empty() {
                    r.to_string()
                } else {
                    format!("{}; {r}", out[i].reason)
                };
            }
        }
    }
    for s in out.iter_mut() {
        if s.bout == usize::MAX {
            s.bout = 0;
        }
        s.valid = s.reason.is_empty();
    }
    for (s, note) in out.iter_mut().zip(length_notes) {
        if let Some(r) = note {
            append_reason(s, r);
        }
    }
    withhold_length_outliers(&mut out, p.max_length_deviation);
    Ok(out)
}

fn append_reason(s: &mut Stride, r: String) {
    s.reason = if s.reason.is_empty() {
        r
    } else {
        format!("{}; {r}", s.reason)
    };
}

/// Valid strides whose length differs from the median length of their bout's valid strides by
/// more than `max_dev` (fraction): the length (and speed) is withheld with the reason; the
/// stride stays valid for its timing and angles. Bouts with fewer than 3 lengths are left alone
/// (no median to trust).
fn withhold_length_outliers(out: &mut [Stride], max_dev: f64) {
    let bouts: std::collections::BTreeSet<usize> = out.iter().map(|s| s.bout).collect();
    for b in bouts {
        let mut l: Vec<f64> = out
            .iter()
            .filter(|s| s.bout == b && s.valid && s.stride_length_m.is_finite())
            .map(|s| s.stride_length_m)
            .collect();
        if l.len() < 3 {
            continue;
        }
        l.sort_by(f64::total_cmp);
        let med = l[l.len() / 2];
        for s in out.iter_mut().filter(|s| s.bout == b && s.valid) {
            let dev = (s.stride_length_m - med) / med;
            if s.stride_length_m.is_finite() && dev.abs() > max_dev {
                let r = format!(
                    "stride length withheld: {:.2} m is {:+.0} % from its bout's median {med:.2} m",
                    s.stride_length_m,
                    dev * 100.0
                );
                append_reason(s, r);
                s.stride_length_m = f64::NAN;
                s.speed_mps = f64::NAN;
            }
        }
    }
}

/// Per-side parameters from the strides of one leg and, when available, the other leg's HS.
pub fn side_parameters(strides: &[Stride], other_hs_s: Option<&[f64]>) -> SideParameters {
    let valid: Vec<&Stride> = strides.iter().filter(|s| s.valid).collect();
    let col = |f: fn(&Stride) -> f64| -> Vec<f64> {
        valid
            .iter()
            .map(|s| f(s))
            .filter(|v| v.is_finite())
            .collect()
    };
    let st = col(|s| s.stride_time_s);
    let sl = col(|s| s.stride_length_m);
    let mean_st = mean(&st);
    let stt: Vec<f64> = match other_hs_s {
        Some(other) => valid
            .iter()
            .filter_map(|s| {
                other
                    .iter()
                    .copied()
                    .rfind(|&c| c < s.hs_time_s && s.hs_time_s - c < 0.75 * mean_st)
                    .map(|c| s.hs_time_s - c)
            })
            .collect(),
        None => vec![],
    };
    let mean_stt = mean(&stt);
    let stance = mean(&col(|s| s.stance_ratio));
    let mut out = SideParameters {
        strides_total: strides.len(),
        strides_valid: valid.len(),
        stride_time_s: mean_st,
        step_time_s: mean_stt,
        step_frequency_hz: if mean_stt.is_finite() {
            1.0 / mean_stt
        } else {
            2.0 / mean_st
        },
        stance_ratio: stance,
        swing_ratio: 1.0 - stance,
        stride_length_m: mean(&sl),
        speed_mps: mean(&col(|s| s.speed_mps)),
        stride_length_cv: cv(&sl),
        stride_time_cv: cv(&st),
        sta_per_s: f64::NAN,
        sta_per_stride: f64::NAN,
        sta_status: "not computed".into(),
        wqk_deg: mean(&col(|s| s.wqk_deg)),
        pbi_deg: mean(&col(|s| s.pbi_deg)),
        bdk_deg: mean(&col(|s| s.bdk_deg)),
        withheld: Default::default(),
    };
    withhold_side_length(&mut out, &valid, sl.len());
    out
}

/// Fewest valid strides with a length for the side's stride length, speed and SV (half of
/// them, rounded up, when the side has fewer than 6 valid strides).
pub const MIN_LENGTH_STRIDES: usize = 3;

/// Smallest share of the valid strides that must have a length for the side's stride length,
/// speed and SV. When most strides of a leg fail the per-stride integration checks, the few
/// that pass are survivors of the same faulty integration (their drift happened to be small),
/// not a sample of the leg's walking, so their mean is not vouched for. A rule of evidence,
/// not a fitted value: with HuGaDB 06_00 (right leg: 4 of 127 strides passing) it withheld a
/// mean 10 % off the other leg's.
pub const MIN_LENGTH_SHARE: f64 = 0.5;

/// Whether `with_length` strides with a length among `valid` valid strides vouch for the leg's
/// stride length ([`MIN_LENGTH_STRIDES`], [`MIN_LENGTH_SHARE`]).
fn lengths_vouched(valid: usize, with_length: usize) -> bool {
    with_length >= MIN_LENGTH_STRIDES.min(valid.div_ceil(2)).max(1)
        && with_length as f64 >= MIN_LENGTH_SHARE * valid as f64
}

/// The end of the reason [`withhold_unvouched_lengths`] gives a survivor, by which
/// [`withhold_side_length`] still counts it as having passed its own checks.
const SURVIVOR: &str = "valid strides pass the integration checks";

/// Withholds the per-stride lengths (and speeds) of a leg whose lengths are not vouched for
/// ([`lengths_vouched`]): the few strides that passed their own checks are survivors of the
/// same faulty integration (on simulator family A the ACC-only model's 2 survivors of 616 were
/// 99 % short), so strides.csv does not report them either. Call on the final strides, before
/// [`side_parameters`].
pub fn withhold_unvouched_lengths(strides: &mut [Stride]) {
    let valid = strides.iter().filter(|s| s.valid).count();
    let with_length = strides
        .iter()
        .filter(|s| s.valid && s.stride_length_m.is_finite())
        .count();
    if valid == 0 || with_length == 0 || lengths_vouched(valid, with_length) {
        return;
    }
    for s in strides.iter_mut().filter(|s| s.stride_length_m.is_finite()) {
        s.stride_length_m = f64::NAN;
        s.speed_mps = f64::NAN;
        append_reason(
            s,
            format!("stride length withheld: only {with_length} of the leg's {valid} {SURVIVOR}"),
        );
    }
}

/// Withhold the side's stride length, speed and SV unless at least [`MIN_LENGTH_STRIDES`] (or
/// half, when fewer) and at least [`MIN_LENGTH_SHARE`] of the valid strides have a length: say
/// why (the most common per-stride reason).
fn withhold_side_length(out: &mut SideParameters, valid: &[&Stride], with_length: usize) {
    if valid.is_empty() || lengths_vouched(valid.len(), with_length) {
        return;
    }
    // Survivors withheld by `withhold_unvouched_lengths` passed their own checks.
    let survivors = valid.iter().filter(|s| s.reason.contains(SURVIVOR)).count();
    let passed = with_length + survivors;
    let mut why: std::collections::BTreeMap<String, usize> = Default::default();
    for s in valid
        .iter()
        .filter(|s| !s.stride_length_m.is_finite() && !s.reason.contains(SURVIVOR))
    {
        let r = &s.reason;
        let key = [
            (
                "ACC-only",
                "the ACC-only attitude cannot separate gravity from motion",
            ),
            ("clipped", "accelerometer clipped"),
            ("drift", "velocity drift"),
            ("floor", "ankle off the floor level"),
            ("pendulum", "disagrees with the shank-pendulum estimate"),
            ("median", "far from its bout's median"),
        ]
        .iter()
        .find(|(k, _)| r.contains(k))
        .map_or("not integrable", |(_, v)| v)
        .to_string();
        *why.entry(key).or_default() += 1;
    }
    let top = why
        .iter()
        .max_by_key(|(_, n)| **n)
        .map(|(r, _)| r.clone())
        .unwrap_or_default();
    let reason = format!(
        "stride length vouched for on {passed} of {} valid strides ({top})",
        valid.len()
    );
    out.stride_length_m = f64::NAN;
    out.speed_mps = f64::NAN;
    out.stride_length_cv = f64::NAN;
    for c in ["stride_length_m", "speed_mps", "stride_length_cv"] {
        out.withheld.insert(c.to_string(), reason.clone());
    }
}

#[cfg(test)]
mod tests;
