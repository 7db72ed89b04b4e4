//! The family A sensor's error model ([`SensorModel`]): range, noise, bias, quantisation and
//! mounting misalignment of the two shank IMUs (paper §2.2 for the ranges).

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};

/// The sensor's error model. Defaults: a 16-bit IMU at ±8 g and ±1000 deg/s (the paper's
/// ranges, §2.2) with consumer-grade noise and bias.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SensorModel {
    /// Add noise, bias and quantisation (false: clean signals, still clipped at the range). Default true.
    pub noise: bool,
    /// White noise SD of the accelerometer, g. Default 0.004.
    pub acc_noise_g: f64,
    /// White noise SD of the gyroscope, deg/s. Default 0.25.
    pub gyro_noise_dps: f64,
    /// SD of the constant accelerometer bias per axis, g. Default 0.01.
    pub acc_bias_g_sd: f64,
    /// SD of the constant gyroscope bias per axis, deg/s. Default 1.0.
    pub gyro_bias_dps_sd: f64,
    /// Accelerometer range (±), g. Default 8.
    pub acc_range_g: f64,
    /// Gyroscope range (±), deg/s. Default 1000.
    pub gyro_range_dps: f64,
    /// ADC bits (quantisation step = range / 2^(bits−1)). Default 16.
    pub bits: u32,
    /// Largest rotation of the device about the shank axis (uniform in ±), deg. Default 20.
    pub axial_misalignment_deg_max: f64,
    /// SD of the small tilts of the device, deg. Default 2.
    pub tilt_misalignment_deg_sd: f64,
    /// The right device is mounted mirrored (rotated 180° about the shank axis, as identical
    /// devices on both lateral sides are). Default true.
    pub mirrored_right: bool,
}

impl Default for SensorModel {
    fn default() -> Self {
        SensorModel {
            noise: true,
            acc_noise_g: 0.004,
            gyro_noise_dps: 0.25,
            acc_bias_g_sd: 0.01,
            gyro_bias_dps_sd: 1.0,
            acc_range_g: 8.0,
            gyro_range_dps: 1000.0,
            bits: 16,
            axial_misalignment_deg_max: 20.0,
            tilt_misalignment_deg_sd: 2.0,
            mirrored_right: true,
        }
    }
}

impl SensorModel {
    /// An ideal sensor: no noise, bias, quantisation or misalignment, not mirrored.
    pub fn ideal() -> Self {
        SensorModel {
            noise: false,
            axial_misalignment_deg_max: 0.0,
            tilt_misalignment_deg_sd: 0.0,
            mirrored_right: false,
            ..SensorModel::default()
        }
    }
    /// Set the accelerometer range, g.
    pub fn acc_range_g(mut self, v: f64) -> Self {
        self.acc_range_g = v;
        self
    }
    /// Set the gyroscope range, deg/s.
    pub fn gyro_range_dps(mut self, v: f64) -> Self {
        self.gyro_range_dps = v;
        self
    }
    /// Set the largest axial misalignment, deg.
    pub fn axial_misalignment_deg_max(mut self, v: f64) -> Self {
        self.axial_misalignment_deg_max = v;
        self
    }
    /// Check ranges.
    pub fn validate(&self) -> Result<()> {
        let pos = |name: &'static str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(LdhError::param(name, v, "must be > 0"))
            }
        };
        let nonneg = |name: &'static str, v: f64| {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(LdhError::param(name, v, "must be ≥ 0"))
            }
        };
        pos("acc_range_g", self.acc_range_g)?;
        pos("gyro_range_dps", self.gyro_range_dps)?;
        nonneg("acc_noise_g", self.acc_noise_g)?;
        nonneg("gyro_noise_dps", self.gyro_noise_dps)?;
        nonneg("acc_bias_g_sd", self.acc_bias_g_sd)?;
        nonneg("gyro_bias_dps_sd", self.gyro_bias_dps_sd)?;
        nonneg("tilt_misalignment_deg_sd", self.tilt_misalignment_deg_sd)?;
        if !(0.0..=180.0).contains(&self.axial_misalignment_deg_max) {
            return Err(LdhError::param(
                "axial_misalignment_deg_max",
                self.axial_misalignment_deg_max,
                "must be in 0–180",
            ));
        }
        if !(8..=32).contains(&self.bits) {
            return Err(LdhError::param("bits", self.bits, "must be 8–32"));
        }
        Ok(())
    }
}
