//! The family A sensor: its error model ([`SensorModel`]: range, noise, bias, quantisation and
//! mounting misalignment of the two shank IMUs, paper §2.2 for the ranges), the draw of a
//! device's mounting on a leg ([`Mounting`]) and the measurement of the clean signals
//! ([`measure`]). Frames as in [`super::model`].

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::draw::std_normal;
use super::jet::{mat_mul, rot_x, rot_y, rot_z, Jet};
use ldh_core::error::{LdhError, Result};
use ldh_core::recording::Side;

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

/// The device on one leg: the nominal mounting (device x along the shank, y anterior, z
/// lateral-left; the right device mirrored when [`SensorModel::mirrored_right`]) times a drawn
/// misalignment.
#[derive(Debug, Clone, Default)]
pub(crate) struct Mounting {
    /// Columns: device axes in the anatomical frame F (nominal mounting × misalignment).
    pub(crate) mount: [[f64; 3]; 3],
    /// Rotation about the shank axis, deg.
    pub(crate) axial_deg: f64,
    /// Small tilts about the device's y and z axes, deg.
    pub(crate) tilt_deg: [f64; 2],
    /// Mounted mirrored (rotated 180° about the shank axis).
    pub(crate) mirrored: bool,
}

impl Mounting {
    /// Draw the device's mounting on the `side` leg: the axial rotation uniform in
    /// ±`axial_misalignment_deg_max`, then two tilts N(0, `tilt_misalignment_deg_sd`), from
    /// `rng` in that order.
    pub(crate) fn draw(sensor: &SensorModel, side: Side, rng: &mut ChaCha8Rng) -> Mounting {
        let mirrored = sensor.mirrored_right && side == Side::Right;
        let nominal: [[f64; 3]; 3] = if mirrored {
            // columns x_d = e3, y_d = −e1, z_d = −e2
            [[0.0, -1.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]]
        } else {
            // columns x_d = e3, y_d = e1, z_d = e2
            [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]
        };
        let axial = rng.gen_range(-1.0..=1.0) * sensor.axial_misalignment_deg_max;
        let tilt = [
            sensor.tilt_misalignment_deg_sd * std_normal(rng),
            sensor.tilt_misalignment_deg_sd * std_normal(rng),
        ];
        let rm = mat_mul(
            &rot_x(Jet::cst(axial.to_radians())),
            &mat_mul(
                &rot_y(Jet::cst(tilt[0].to_radians())),
                &rot_z(Jet::cst(tilt[1].to_radians())),
            ),
        );
        let mut mount = [[0.0; 3]; 3];
        for (i, row) in mount.iter_mut().enumerate() {
            for (j, cell) in row.iter_mut().enumerate() {
                *cell = (0..3).map(|k| nominal[i][k] * rm[k][j].v).sum();
            }
        }
        Mounting {
            mount,
            axial_deg: axial,
            tilt_deg: tilt,
            mirrored,
        }
    }
}

/// What one device delivers: the measured signals and the biases drawn for them.
#[derive(Debug, Clone)]
pub(crate) struct Measured {
    /// Specific force, g, device axes.
    pub(crate) acc_g: [Vec<f64>; 3],
    /// Angular velocity, deg/s, device axes.
    pub(crate) gyro_dps: [Vec<f64>; 3],
    /// Samples where any axis was clipped at the range.
    pub(crate) saturated: Vec<bool>,
    /// Samples where an accelerometer axis was clipped.
    pub(crate) acc_saturated: Vec<bool>,
    /// Samples where a gyroscope axis was clipped.
    pub(crate) gyro_saturated: Vec<bool>,
    /// Gyroscope bias drawn, deg/s (drawn even when `noise` is off, then not applied).
    pub(crate) gyro_bias_dps: [f64; 3],
    /// Accelerometer bias drawn, g (as above).
    pub(crate) acc_bias_g: [f64; 3],
}

/// Measure clean device-frame signals (`acc_clean` g, `gyro_clean` deg/s, one value per output
/// sample): constant biases (gyroscope then accelerometer, 3 draws each), then with
/// [`SensorModel::noise`] white noise per sample (accelerometer axes x, y, z, then gyroscope
/// axes) and quantisation to the ADC step, and in every case clipping at the range.
pub(crate) fn measure(
    sensor: &SensorModel,
    acc_clean: &[Vec<f64>; 3],
    gyro_clean: &[Vec<f64>; 3],
    rng: &mut ChaCha8Rng,
) -> Measured {
    let gyro_bias: [f64; 3] = std::array::from_fn(|_| sensor.gyro_bias_dps_sd * std_normal(rng));
    let acc_bias: [f64; 3] = std::array::from_fn(|_| sensor.acc_bias_g_sd * std_normal(rng));
    let acc_lsb = sensor.acc_range_g / 2f64.powi(sensor.bits as i32 - 1);
    let gyro_lsb = sensor.gyro_range_dps / 2f64.powi(sensor.bits as i32 - 1);
    // One mask per sensor (as the reader gives): preprocessing replaces a clipped sample only
    // on the sensor that clipped.
    let mut acc_saturated = vec![false; acc_clean[0].len()];
    let mut gyro_saturated = vec![false; acc_clean[0].len()];
    let acc = Channel {
        bias: acc_bias,
        noise_sd: sensor.acc_noise_g,
        lsb: acc_lsb,
        range: sensor.acc_range_g,
    };
    let acc_g = acc.measure(sensor.noise, acc_clean, &mut acc_saturated, rng);
    let gyro = Channel {
        bias: gyro_bias,
        noise_sd: sensor.gyro_noise_dps,
        lsb: gyro_lsb,
        range: sensor.gyro_range_dps,
    };
    let gyro_dps = gyro.measure(sensor.noise, gyro_clean, &mut gyro_saturated, rng);
    let saturated = acc_saturated
        .iter()
        .zip(&gyro_saturated)
        .map(|(a, g)| *a || *g)
        .collect();
    Measured {
        acc_g,
        gyro_dps,
        saturated,
        acc_saturated,
        gyro_saturated,
        gyro_bias_dps: gyro_bias,
        acc_bias_g: acc_bias,
    }
}

/// The error model of one three-axis channel (accelerometer or gyroscope), in its unit.
struct Channel {
    bias: [f64; 3],
    noise_sd: f64,
    lsb: f64,
    range: f64,
}

impl Channel {
    /// Bias, noise and quantisation (when `noise`), then clipping at ±range (marking the
    /// sample in `sat`), axis by axis.
    fn measure(
        &self,
        noise: bool,
        clean: &[Vec<f64>; 3],
        sat: &mut [bool],
        rng: &mut ChaCha8Rng,
    ) -> [Vec<f64>; 3] {
        let (bias, noise_sd, lsb, range) = (self.bias, self.noise_sd, self.lsb, self.range);
        let mut out: [Vec<f64>; 3] = Default::default();
        for k in 0..3 {
            out[k] = clean[k]
                .iter()
                .enumerate()
                .map(|(i, &v)| {
                    let noisy = if noise {
                        v + bias[k] + noise_sd * std_normal(rng)
                    } else {
                        v
                    };
                    let qv = if noise {
                        (noisy / lsb).round() * lsb
                    } else {
                        noisy
                    };
                    if qv.abs() >= range {
                        sat[i] = true;
                        range * qv.signum()
                    } else {
                        qv
                    }
                })
                .collect();
        }
        out
    }
}
