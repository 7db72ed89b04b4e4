//! Stride segmentation and stride-length parameters ([`StrideParams`]) and their check into
//! [`ValidStrideParams`] (SPEC §3.5; the physiological stride-time range is shared with the
//! event detector through [`check_stride_range`]).

use serde::{Deserialize, Serialize};

use super::ZeroVelocity;
use crate::error::{LdhError, Result};

/// Sensor height above the ankle joint assumed when none is given, m (SPEC: "just above the
/// ankle"). A stride length computed with it is checked for its dependence on the height
/// ([`super::height_sensitivity`]).
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
    /// Height of the sensor above the ankle joint along the shank, m. Default `None`: not
    /// given, [`DEFAULT_SENSOR_HEIGHT_M`] (0.10 m) is assumed and each leg's stride length is
    /// checked for how much it depends on the height ([`super::height_sensitivity`]); a
    /// manifest's `sensor_height_m` gives it per subject. Serialised as `null` when not given,
    /// so parameters written out and read back stay "not given".
    pub sensor_height_m: Option<f64>,
    /// Flag the first and last stride of every bout. Default true.
    pub drop_bout_edges: bool,
    /// How the zero-velocity instant of each stance is found. Default foot-flat.
    pub zero_velocity: ZeroVelocity,
    /// A stride whose length differs from the median of the strides around it in its bout
    /// (10 valid strides on each side, `gait::LOCAL_LENGTH_STRIDES`) by more than this fraction is
    /// invalid (stride length withheld). Default 0.25.
    pub max_length_deviation: f64,
}

impl Default for StrideParams {
    fn default() -> Self {
        StrideParams {
            min_stride_s: 0.7,
            max_stride_s: 2.5,
            turn_deg: 20.0,
            sensor_height_m: None,
            drop_bout_edges: true,
            zero_velocity: ZeroVelocity::default(),
            max_length_deviation: 0.25,
        }
    }
}

impl StrideParams {
    /// Set the sensor height, m (given).
    pub fn sensor_height_m(mut self, h: f64) -> Self {
        self.sensor_height_m = Some(h);
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
        if let Some(h) = self.sensor_height_m {
            if !(h.is_finite() && (0.0..=0.5).contains(&h)) {
                return Err(LdhError::param(
                    "sensor_height_m",
                    h,
                    "must lie in [0, 0.5] m",
                ));
            }
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

/// Check a physiological stride-time range: 0.2 ≤ min < max ≤ 10 s (shared by events and
/// strides): no human stride is shorter than 0.2 s (sprinting: ≈ 0.45 s), and a 10 s stride is
/// standing, not walking (the slowest pathological gait: ≈ 2.5–3 s).
pub fn check_stride_range(min_stride_s: f64, max_stride_s: f64) -> Result<()> {
    if min_stride_s >= 0.2 && max_stride_s > min_stride_s && max_stride_s <= 10.0 {
        Ok(())
    } else {
        Err(LdhError::param(
            "min_stride_s/max_stride_s",
            format!("{min_stride_s}/{max_stride_s}"),
            "need 0.2 <= min < max <= 10 s",
        ))
    }
}

/// Checked stride parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ValidStrideParams(pub(super) StrideParams);

impl ValidStrideParams {
    /// The parameters.
    pub fn params(&self) -> &StrideParams {
        &self.0
    }

    /// The sensor height the stride length uses, m: the one given, else
    /// [`DEFAULT_SENSOR_HEIGHT_M`].
    pub fn sensor_height_m(&self) -> f64 {
        self.0.sensor_height_m.unwrap_or(DEFAULT_SENSOR_HEIGHT_M)
    }

    /// Whether the sensor height was given (by the manifest, an option or the parameters)
    /// rather than assumed.
    pub fn sensor_height_given(&self) -> bool {
        self.0.sensor_height_m.is_some()
    }

    /// These parameters with a subject's sensor height, m (the height belongs to the subject:
    /// checked here, with the same rule and message as [`StrideParams::check`]).
    pub fn with_sensor_height_m(&self, sensor_height_m: f64) -> Result<ValidStrideParams> {
        self.0.clone().sensor_height_m(sensor_height_m).check()
    }

    /// These parameters with no stride a turn (`turn_deg` = 180, a treadmill).
    pub fn without_turns(&self) -> ValidStrideParams {
        let mut p = self.0.clone();
        p.turn_deg = 180.0;
        ValidStrideParams(p)
    }
}
