//! Strides and gait parameters (paper §3.2 and Table 2; SPEC §3.5–3.6).
//!
//! **Strides** run from a heel strike to the next heel strike of the same leg, with the toe off
//! between them. A stride is kept in the table but flagged invalid, with the reason, when its
//! toe off is missing, its time is outside [`StrideParams::min_stride_s`, `max_stride_s`], it is
//! part of a turn (heading change over the stride above `turn_deg`; with both legs, the other
//! leg must turn too — [`crate::pipeline::Analysis::pair`] — and on a treadmill nothing is a
//! turn), or it is the first or last
//! stride of a walking bout (bouts are separated by pauses longer than a stride and by turns).
//!
//! **Stride length** (the paper: "estimated by fusing three-axis acceleration"): the
//! acceleration is rotated to the world with the fused attitude, gravity removed, and integrated
//! twice between consecutive mid-stances (the foot-flat instant, [`ZeroVelocity`]), with the
//! stride's tilt error removed (the velocity at the next mid-stance observes it) and linear
//! de-drifting of the velocity; samples where the accelerometer clipped are reconstructed
//! first ([`crate::preprocess::declip`]). The sensor is not at rest at mid-stance: the shank pivots about
//! the ankle, which is at rest. The sensor's velocity there is ω × r (r the sensor's position from
//! the ankle, `sensor_height_m` along the shank), used as the boundary velocity, and the change
//! of r over the stride is removed from the displacement, so the result is the ankle's horizontal
//! displacement: the stride length. When the height is not given, how much the leg's length
//! depends on it is measured ([`height_sensitivity`]) and the length withheld when the leg's
//! median moves by more than 15 % over the heights a shank sensor can sit at.
//!
//! **Parameters** per stride: stride time, stance ratio, stride length, speed, WQK (max pitch),
//! PBI (−min pitch), BDK (range of anatomical roll from TO to the next HS); per side, the means
//! over valid strides and SV, STV (SD / mean), SF, STT (needs both legs) and STA
//! ([`crate::nonlinear::gait_sta`]).

mod height;
mod length;
mod params;
mod segment;
mod side;
mod steady;
mod times;

use serde::{Deserialize, Serialize};

use crate::recording::Side;
pub use height::{
    height_sensitivity, height_sensitivity_measured, heights_to_measure, HeightSensitivity,
    MAX_HEIGHT_SPREAD_SHARE, SENSOR_HEIGHT_RANGE_M,
};
pub use length::{
    pendulum_length_m, stride_length, stride_lengths, zero_velocity_sample, LengthEstimate,
    ZeroVelocity, MAX_CLIP_STEP_SHARE, MAX_DRIFT_MPS, MAX_TILT_DEG, MAX_VERTICAL_M,
    MAX_VERTICAL_SHARE, PENDULUM_GAIN, SHANK_LENGTH_M,
};
pub use params::{check_stride_range, StrideParams, ValidStrideParams, DEFAULT_SENSOR_HEIGHT_M};
pub use segment::{
    lengths_at_heights, strides, strides_at_heights, strides_with_turns, LengthsAtHeights,
    TurnTest, ACC_ONLY_LENGTH,
};
pub use side::{side_parameters, withhold_unvouched_lengths, MIN_LENGTH_SHARE, MIN_LENGTH_STRIDES};
pub use steady::{
    exclude_unsteady, steady_window, SteadyParams, SteadySpan, SteadyWindow, ValidSteadyParams,
    STEADY_REASON, TOO_LITTLE_STEADY,
};

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

/// Anatomical roll (positive: knee lateral to the ankle) from the ZYX roll of frame F.
pub fn anatomical_roll_deg(roll_zyx_deg: f64, side: Side) -> f64 {
    match side {
        Side::Left => -roll_zyx_deg,
        Side::Right => roll_zyx_deg,
    }
}

/// Append `r` to a stride's reasons ("; " between reasons).
pub(crate) fn append_reason(s: &mut Stride, r: String) {
    s.reason = if s.reason.is_empty() {
        r
    } else {
        format!("{}; {r}", s.reason)
    };
}

#[cfg(test)]
mod tests;
