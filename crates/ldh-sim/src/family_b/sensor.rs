//! Family B sensor error model: per-axis scale faults, bias with linear drift and random walk,
//! white noise, quantisation and clipping at a range drawn per subject (±2 g … ±16 g,
//! ±500 … ±2000 deg/s).

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use serde::{Deserialize, Serialize};

use ldh_core::error::{LdhError, Result};

/// Sensor errors of family B (defaults: a consumer MEMS IMU worn on the shank).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SensorModelB {
    /// Add errors at all (false: clean signals, still clipped). Default true.
    pub noise: bool,
    /// White noise SD, g. Default 0.006.
    pub acc_noise_g: f64,
    /// White noise SD, deg/s. Default 0.4.
    pub gyro_noise_dps: f64,
    /// SD of the initial gyroscope bias per axis, deg/s. Default 1.5.
    pub gyro_bias_dps_sd: f64,
    /// SD of the linear gyroscope bias drift per axis, deg/s per minute. Default 1.0.
    pub gyro_drift_dps_per_min_sd: f64,
    /// Gyroscope bias random walk, deg/s/√s. Default 0.02.
    pub gyro_random_walk: f64,
    /// SD of the constant accelerometer bias per axis, g. Default 0.015.
    pub acc_bias_g_sd: f64,
    /// Largest gyroscope scale-factor error per axis (uniform in ±), fraction. Default 0.04.
    pub gyro_scale_fault: f64,
    /// Largest accelerometer scale-factor error per axis, fraction. Default 0.03.
    pub acc_scale_fault: f64,
    /// Accelerometer ranges drawn from (±, g). Default [2, 4, 8, 16].
    pub acc_ranges_g: Vec<f64>,
    /// Gyroscope ranges drawn from (±, deg/s). Default [500, 1000, 2000].
    pub gyro_ranges_dps: Vec<f64>,
    /// ADC bits. Default 16.
    pub bits: u32,
    /// SD of the device's tilt off the shank axis (two angles), deg. Default 3.
    pub tilt_deg_sd: f64,
}

impl Default for SensorModelB {
    fn default() -> Self {
        SensorModelB {
            noise: true,
            acc_noise_g: 0.006,
            gyro_noise_dps: 0.4,
            gyro_bias_dps_sd: 1.5,
            gyro_drift_dps_per_min_sd: 1.0,
            gyro_random_walk: 0.02,
            acc_bias_g_sd: 0.015,
            gyro_scale_fault: 0.04,
            acc_scale_fault: 0.03,
            acc_ranges_g: vec![2.0, 4.0, 8.0, 16.0],
            gyro_ranges_dps: vec![500.0, 1000.0, 2000.0],
            bits: 16,
            tilt_deg_sd: 3.0,
        }
    }
}

impl SensorModelB {
    /// Clean signals at the widest ranges (no scale, bias, noise, tilt).
    pub fn ideal() -> Self {
        SensorModelB {
            noise: false,
            acc_ranges_g: vec![16.0],
            gyro_ranges_dps: vec![2000.0],
            tilt_deg_sd: 0.0,
            ..SensorModelB::default()
        }
    }
    /// Check values.
    pub fn validate(&self) -> Result<()> {
        for (n, v) in [
            ("acc_noise_g", self.acc_noise_g),
            ("gyro_noise_dps", self.gyro_noise_dps),
            ("gyro_bias_dps_sd", self.gyro_bias_dps_sd),
            ("gyro_drift_dps_per_min_sd", self.gyro_drift_dps_per_min_sd),
            ("gyro_random_walk", self.gyro_random_walk),
            ("acc_bias_g_sd", self.acc_bias_g_sd),
            ("tilt_deg_sd", self.tilt_deg_sd),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(LdhError::param(n, v, "must be ≥ 0"));
            }
        }
        for (n, v) in [
            ("gyro_scale_fault", self.gyro_scale_fault),
            ("acc_scale_fault", self.acc_scale_fault),
        ] {
            if !(0.0..0.5).contains(&v) {
                return Err(LdhError::param(n, v, "must lie in [0, 0.5)"));
            }
        }
        for (n, r) in [
            ("acc_ranges_g", &self.acc_ranges_g),
            ("gyro_ranges_dps", &self.gyro_ranges_dps),
        ] {
            if r.is_empty() || r.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
                return Err(LdhError::param(n, format!("{r:?}"), "needs ranges > 0"));
            }
        }
        if !(8..=32).contains(&self.bits) {
            return Err(LdhError::param("bits", self.bits, "must be 8–32"));
        }
        Ok(())
    }
}

/// What was drawn for one channel triple.
#[derive(Debug, Clone, PartialEq)]
pub struct Errors {
    /// Scale factor per axis.
    pub scale: [f64; 3],
    /// Bias at t = 0 per axis.
    pub bias0: [f64; 3],
}

/// Measure clean signals (`clean[k][i]`, unit of the range): scale, bias (+ drift and random
/// walk for the gyroscope), noise, quantisation, clipping. Marks clipped samples in `sat`.
#[allow(clippy::too_many_arguments)]
pub fn measure(
    clean: &[Vec<f64>; 3],
    fs_hz: f64,
    m: &SensorModelB,
    gyro: bool,
    range: f64,
    rng: &mut ChaCha8Rng,
    sat: &mut [bool],
) -> ([Vec<f64>; 3], Errors) {
    let z = Normal::new(0.0, 1.0).expect("valid");
    let (scale_fault, bias_sd, noise_sd) = if gyro {
        (m.gyro_scale_fault, m.gyro_bias_dps_sd, m.gyro_noise_dps)
    } else {
        (m.acc_scale_fault, m.acc_bias_g_sd, m.acc_noise_g)
    };
    let lsb = range / 2f64.powi(m.bits as i32 - 1);
    let mut out: [Vec<f64>; 3] = Default::default();
    let mut errs = Errors {
        scale: [1.0; 3],
        bias0: [0.0; 3],
    };
    for k in 0..3 {
        let scale = if m.noise && scale_fault > 0.0 {
            1.0 + rng.gen_range(-scale_fault..=scale_fault)
        } else {
            1.0
        };
        let bias0 = if m.noise {
            bias_sd * z.sample(rng)
        } else {
            0.0
        };
        let drift_per_s = if m.noise && gyro {
            m.gyro_drift_dps_per_min_sd * z.sample(rng) / 60.0
        } else {
            0.0
        };
        errs.scale[k] = scale;
        errs.bias0[k] = bias0;
        let mut walk = 0.0;
        let step = m.gyro_random_walk / fs_hz.sqrt();
        out[k] = clean[k]
            .iter()
            .enumerate()
            .map(|(i, &v)| {
                let mut x = v * scale;
                if m.noise {
                    if gyro {
                        walk += step * z.sample(rng);
                    }
                    x += bias0 + drift_per_s * i as f64 / fs_hz + walk + noise_sd * z.sample(rng);
                    x = (x / lsb).round() * lsb;
                }
                if x.abs() >= range {
                    sat[i] = true;
                    range * x.signum()
                } else {
                    x
                }
            })
            .collect();
    }
    (out, errs)
}
