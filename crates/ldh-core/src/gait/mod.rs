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

mod code;
mod double_support;
mod height;
mod length;
mod params;
mod segment;
mod side;
mod steady;
mod times;

use serde::{Deserialize, Serialize};

use crate::domain::{block, Measured, Parameter, PerParameter, Reason, Side, Withheld};

/// NaN: the value of a field absent from what was read back (issue 49's double support).
fn nan() -> f64 {
    f64::NAN
}
pub use code::{
    FindingEffect, LengthCheck, StrideCode, StrideCodes, StrideFinding, UnknownStrideCode,
};
pub use double_support::double_support;
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
    TurnTest, ACC_ONLY_LENGTH, LOCAL_LENGTH_STRIDES,
};
pub use side::{side_parameters, withhold_unvouched_lengths, MIN_LENGTH_SHARE, MIN_LENGTH_STRIDES};
pub use steady::{
    exclude_unsteady, exclude_unsteady_walk, walk_window, SteadyParams, SteadySpan,
    ValidSteadyParams, WalkWindow, STEADY_REASON, TOO_LITTLE_STEADY,
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
    /// Double support (initial + terminal) / stride time, from the other leg's toe off and heel
    /// strike inside the stride ([`double_support`]; issue 49); NaN without them.
    #[serde(default = "nan")]
    pub double_support_ratio: f64,
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
    /// reasons joined by "; ", "" when valid with every value reported. The text of
    /// [`Stride::findings`], for people: no code decides on it.
    pub reason: String,
    /// The same reasons as typed findings, in the same order (what the pipeline decides on);
    /// serialised as their codes, `reason_codes` (the column of strides.csv), and not read back.
    #[serde(
        rename = "reason_codes",
        serialize_with = "serialize_codes",
        skip_deserializing
    )]
    pub findings: Vec<StrideFinding>,
    /// The ankle's vertical displacement between the stride's two foot-flat instants, m
    /// (positive up; ≈ 0 on level ground, ≈ ±0.3 on stairs; `length::LengthEstimate::vertical_m`),
    /// NaN when not integrated or when the integration is not consistent (its drift, tilt or
    /// clipping checks withheld the length). Read by the monitor's stair rule (`monitor::stairs`); not
    /// serialised.
    #[serde(skip, default = "nan")]
    pub vertical_m: f64,
}

/// A stride's findings written as their codes (`StrideCodes`' text), as strides.csv has them.
fn serialize_codes<S: serde::Serializer>(f: &[StrideFinding], s: S) -> Result<S::Ok, S::Error> {
    serde::Serialize::serialize(&StrideCodes(f.iter().map(|f| f.code).collect()), s)
}

impl Stride {
    /// The stride's value of `p` (NaN when not measured), for the parameters with a
    /// per-stride value (`Definition::per_stride`: a column of strides.csv); `None` for the
    /// others (they are a leg's, not a stride's). One arm per parameter: a new parameter with
    /// a per-stride value adds its arm here (its computation may be the arm itself).
    pub fn value(&self, p: Parameter) -> Option<f64> {
        use Parameter::*;
        match p {
            StrideTime => Some(self.stride_time_s),
            StanceRatio => Some(self.stance_ratio),
            DoubleSupport => Some(self.double_support_ratio),
            StrideLength => Some(self.stride_length_m),
            Speed => Some(self.speed_mps),
            Wqk => Some(self.wqk_deg),
            Pbi => Some(self.pbi_deg),
            Bdk => Some(self.bdk_deg),
            StepFrequency | StepTime | SwingRatio | StrideLengthCv | StrideTimeCv | Sta => None,
            #[cfg(feature = "dummy-parameter")]
            Dummy => Some(2.0 * self.stride_time_s),
        }
    }

    /// The codes of the stride's findings, in the order of `reason`'s reasons (the
    /// `reason_codes` column).
    pub fn codes(&self) -> StrideCodes {
        StrideCodes(self.findings.iter().map(|f| f.code).collect())
    }

    /// Whether a finding of `code` is among the stride's.
    pub fn has(&self, code: &StrideCode) -> bool {
        self.findings.iter().any(|f| &f.code == code)
    }

    /// Add a finding (its text to `reason`, after "; ").
    pub fn push(&mut self, f: StrideFinding) {
        self.findings.push(f);
        self.write_reason();
    }

    /// Add a finding unless the same one is there already (checks applied again).
    pub fn push_once(&mut self, f: StrideFinding) {
        if !self.findings.contains(&f) {
            self.push(f);
        }
    }

    /// Replace every finding by `f`.
    pub fn replace_findings(&mut self, f: StrideFinding) {
        self.findings = vec![f];
        self.write_reason();
    }

    /// Drop the findings of `code`.
    pub fn remove(&mut self, code: &StrideCode) {
        self.findings.retain(|f| &f.code != code);
        self.write_reason();
    }

    fn write_reason(&mut self) {
        self.reason = self
            .findings
            .iter()
            .map(|f| f.message.as_str())
            .collect::<Vec<_>>()
            .join("; ");
    }
}

/// Per-side parameters (SPEC §3.6): means over valid strides, one value per [`Parameter`]
/// (NaN when not measured). Written (a leg's `parameters` in Python) as `strides_total`,
/// `strides_valid`, then every parameter under its column in the order of the per-recording
/// table ([`crate::domain::block`]; SF under its historic key `step_frequency_hz`), then
/// `withheld` when not empty.
#[derive(Debug, Clone, PartialEq)]
pub struct SideParameters {
    /// Strides found.
    pub strides_total: usize,
    /// Valid strides used.
    pub strides_valid: usize,
    /// Every parameter's value (NaN when not measured): its computation is in
    /// [`side_parameters`] (STT: the other leg's last heel strike before each; SF: 1 / mean
    /// STT, or 2 / mean ST with one leg; SWP: 1 − STP; SV, STV: SD / mean; STA from
    /// [`crate::nonlinear::gait_sta`]; the rest the means of the valid strides).
    pub values: PerParameter<f64>,
    /// STA per stride (λ · mean stride time).
    pub sta_per_stride: f64,
    /// Why STA is missing ("" when present).
    pub sta_status: String,
    /// Parameters withheld by a quality check, with the typed reason (written as column →
    /// reason, as in recordings.csv). A withheld parameter's value is NaN and must be shown as
    /// "not measured: <reason>", never as a number. Empty when every parameter is vouched for.
    pub withheld: Withheld,
}

/// The key of `p` in a leg's written parameters: its column, but SF's historic
/// `step_frequency_hz` (the same steps/s; the Python dict has always used it).
fn leg_key(p: Parameter) -> &'static str {
    match p {
        Parameter::StepFrequency => "step_frequency_hz",
        _ => p.column(),
    }
}

impl Serialize for SideParameters {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let with = usize::from(!self.withheld.is_empty());
        let mut st = s.serialize_struct("SideParameters", 2 + block::BLOCK_FIELDS + with)?;
        st.serialize_field("strides_total", &self.strides_total)?;
        st.serialize_field("strides_valid", &self.strides_valid)?;
        block::serialize_parameters(
            &mut st,
            &self.values,
            leg_key,
            &self.sta_per_stride,
            &self.sta_status,
        )?;
        if with == 1 {
            st.serialize_field("withheld", &self.withheld)?;
        } else {
            st.skip_field("withheld")?;
        }
        st.end()
    }
}

impl<'de> Deserialize<'de> for SideParameters {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let m = serde_json::Map::<String, serde_json::Value>::deserialize(d)?;
        let count = |k: &str| -> Result<usize, D::Error> {
            m.get(k)
                .and_then(|v| v.as_u64())
                .map(|n| n as usize)
                .ok_or_else(|| D::Error::custom(format!("{k}: expected a count")))
        };
        let b = block::ParameterBlock::from_map::<D::Error>(&m, leg_key)?;
        let withheld = match m.get("withheld") {
            None => Withheld::default(),
            Some(v) => Withheld::deserialize(v).map_err(D::Error::custom)?,
        };
        Ok(SideParameters {
            strides_total: count("strides_total")?,
            strides_valid: count("strides_valid")?,
            values: PerParameter::from_fn(|p| b.values[p].unwrap_or(f64::NAN)),
            sta_per_stride: b.sta_per_stride.unwrap_or(f64::NAN),
            sta_status: b.sta_status,
            withheld,
        })
    }
}

impl std::ops::Index<Parameter> for SideParameters {
    type Output = f64;
    fn index(&self, p: Parameter) -> &f64 {
        &self.values[p]
    }
}

impl std::ops::IndexMut<Parameter> for SideParameters {
    fn index_mut(&mut self, p: Parameter) -> &mut f64 {
        &mut self.values[p]
    }
}

impl SideParameters {
    /// The value of `p` (NaN when not measured).
    pub fn value(&self, p: Parameter) -> f64 {
        self.values[p]
    }

    /// The value of `p`, or why it is withheld (`None`: neither measured nor withheld, e.g. the
    /// step time of one leg).
    pub fn measured(&self, p: Parameter) -> Option<Measured> {
        match self.withheld.get(p) {
            Some(r) => Some(Measured::Withheld(r.clone())),
            None => Some(self.value(p))
                .filter(|v| v.is_finite())
                .map(Measured::Value),
        }
    }

    /// Withhold `p` for `reason`: its value (for STA, both per second and per stride) becomes
    /// NaN; `replace` says whether the reason replaces an earlier one (a fault's does).
    pub fn withhold(&mut self, p: Parameter, reason: Reason, replace: bool) {
        self.values[p] = f64::NAN;
        if p == Parameter::Sta {
            self.sta_per_stride = f64::NAN;
        }
        if replace {
            self.withheld.insert(p, reason);
        } else {
            self.withheld.insert_first(p, || reason);
        }
    }
}

/// Anatomical roll (positive: knee lateral to the ankle) from the ZYX roll of frame F.
pub fn anatomical_roll_deg(roll_zyx_deg: f64, side: Side) -> f64 {
    match side {
        Side::Left => -roll_zyx_deg,
        Side::Right => roll_zyx_deg,
    }
}

#[cfg(test)]
mod tests;
