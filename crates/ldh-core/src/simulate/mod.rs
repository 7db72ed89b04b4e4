//! The deterministic two-shank gait simulator (SPEC §8): demo data and ground truth.
//!
//! The paper's data are private, so ldh ships a physically derived model of two shank IMUs
//! ([`model`] explains the kinematics and frames): sagittal segment kinematics from published
//! normal-gait curves, feet that roll over heel and forefoot without slipping, the sensor on the
//! lateral shank above the ankle, acceleration from the exact second derivative of its position
//! plus gravity rotated into the sensor frame, angular velocity from the segment's body rate;
//! then sensor noise, bias, mounting misalignment (mirrored on the right leg), quantisation and
//! saturation. Subjects stand quietly at start and end and have stride-to-stride variability.
//! LDH subjects get an affected side with less swing knee flexion, a longer stance, slower and
//! more variable gait, and circumduction (SPEC §2, issue 2).
//!
//! Over a straight walk both feet travel the same distance, so the two sides' mean stride
//! lengths are equal; asymmetry is in step length, stance and angles.
//!
//! Everything is drawn from a ChaCha8 stream seeded by the cohort seed with one stream per
//! subject, so a cohort is byte-identical for a seed whatever the thread count.

pub mod curves;
pub mod family_b;
pub mod jet;
pub mod model;
mod write;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use std::path::Path;

use crate::error::{LdhError, Result};
use crate::io::{write_atomic, FormatSpec, WriteOptions};
use crate::recording::Side;
use model::normal_clamped;
pub use model::{
    simulate_subject, DenseTruth, LegTruth, SensorTruth, SimLeg, SimSubject, StrideTruth,
};
pub use write::{write_cohort, Cohort};

/// Version tag of the ground-truth JSON.
pub const TRUTH_SCHEMA: &str = "ldh-sim-truth/1";

/// The most samples one simulated leg may have (`duration_s × fs_hz`): 1 000 000, e.g. 2.7 h
/// at 100 Hz or 500 s at 2000 Hz. The simulator holds about 0.8 kB per output sample of a
/// subject (the 10× oversampled integration grid of both legs), so this bounds one subject in
/// flight to about 0.8 GB; longer recordings are made by concatenating simulated ones
/// (tests/tests/bad_inputs.rs `two_hour`).
pub const MAX_SAMPLES_PER_LEG: u64 = 1_000_000;

/// The most subjects one simulated cohort may have (`healthy + ldh`): 100 000.
pub const MAX_SUBJECTS: u64 = 100_000;

/// The declared size limits of a simulation, checked with exact arithmetic before any work:
/// `healthy + ldh` (which must not overflow) at most [`MAX_SUBJECTS`], `duration_s × fs_hz`
/// at most [`MAX_SAMPLES_PER_LEG`]. The error says which limit and what to do.
pub fn check_size(healthy: usize, ldh: usize, duration_s: f64, fs_hz: f64) -> Result<()> {
    let n = (healthy as u64).checked_add(ldh as u64);
    if n.is_none_or(|n| n > MAX_SUBJECTS) {
        return Err(LdhError::param(
            "healthy + ldh",
            format!("{healthy} + {ldh}"),
            format!("a simulated cohort holds at most {MAX_SUBJECTS} subjects"),
        ));
    }
    check_samples(duration_s, fs_hz)
}

/// `duration_s × fs_hz` at most [`MAX_SAMPLES_PER_LEG`] (both finite and positive; the range of
/// each is checked by the caller).
pub fn check_samples(duration_s: f64, fs_hz: f64) -> Result<()> {
    let samples = duration_s * fs_hz;
    if duration_s.is_finite() && fs_hz.is_finite() && samples <= MAX_SAMPLES_PER_LEG as f64 {
        return Ok(());
    }
    let longest_s = MAX_SAMPLES_PER_LEG as f64 / fs_hz.max(1.0);
    let longest = if longest_s >= 3600.0 {
        format!("{:.1} h", longest_s / 3600.0)
    } else {
        format!("{longest_s:.0} s")
    };
    Err(LdhError::param(
        "duration_s × fs_hz",
        format!("{duration_s:?} s × {fs_hz:?} Hz"),
        format!(
            "a simulated leg holds at most {MAX_SAMPLES_PER_LEG} samples ({longest} at {fs_hz:?} Hz); \
             simulate shorter recordings (or a lower rate) and concatenate them"
        ),
    ))
}

/// Subject group.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Group {
    /// Healthy control.
    Healthy,
    /// Lumbar disc herniation, one affected side.
    Ldh,
}

impl Group {
    /// `"healthy"` or `"ldh"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Group::Healthy => "healthy",
            Group::Ldh => "ldh",
        }
    }
}

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

/// Per-leg parameters of a subject.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LegParams {
    /// Mean stance ratio (stance time / stride time). Normal 0.60.
    pub stance_ratio: f64,
    /// Fraction of the swing knee flexion removed (0 = normal, 0.2 = peak 60° → 48°).
    pub knee_reduction: f64,
    /// Scale of the hip flexion excursion about its mean (1 = normal).
    pub hip_scale: f64,
    /// Lateral excursion of the ankle in swing (circumduction), m.
    pub circumduction_m: f64,
    /// Anatomical roll change at mid-swing, deg (negative: knee medial to the ankle as the foot
    /// swings out).
    pub roll_swing_deg: f64,
    /// Anatomical roll in stance, deg (positive: knee lateral to the ankle).
    pub roll_stance_deg: f64,
    /// Height of the sensor above the ankle joint along the shank, m.
    pub sensor_height_m: f64,
    /// Distance of the sensor from the shank axis on the lateral side, m.
    pub sensor_lateral_m: f64,
    /// Extra ankle height at mid-swing, m.
    pub swing_clearance_m: f64,
}

impl Default for LegParams {
    fn default() -> Self {
        LegParams {
            stance_ratio: 0.60,
            knee_reduction: 0.0,
            hip_scale: 1.0,
            circumduction_m: 0.01,
            roll_swing_deg: -1.5,
            roll_stance_deg: 2.0,
            sensor_height_m: 0.10,
            sensor_lateral_m: 0.04,
            swing_clearance_m: 0.04,
        }
    }
}

/// One subject's gait and recording parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubjectParams {
    /// Identifier (folder name).
    pub subject_id: String,
    /// Group.
    pub group: Group,
    /// Affected side of an LDH subject.
    pub affected_side: Option<Side>,
    /// Sampling rate of both sensors, Hz.
    pub fs_hz: f64,
    /// Recording length, s.
    pub duration_s: f64,
    /// Quiet standing at start and at end, s.
    pub standing_s: f64,
    /// Mean stride time, s.
    pub stride_time_s: f64,
    /// Mean stride length, m.
    pub stride_length_m: f64,
    /// Coefficient of variation of stride time.
    pub stride_time_cv: f64,
    /// Coefficient of variation of stride length.
    pub stride_length_cv: f64,
    /// SD of the stance ratio from stride to stride.
    pub stance_ratio_sd: f64,
    /// Right heel strike at left phase 0.5 + this (step-time asymmetry, fraction of a stride).
    pub step_timing_asymmetry: f64,
    /// Right step = (1 + a) · L/2, left step = (1 − a) · L/2.
    pub step_length_asymmetry: f64,
    /// Foot angle to the ground at heel strike, deg.
    pub heel_strike_foot_angle_deg: f64,
    /// Foot angle to the ground at toe off, deg.
    pub toe_off_foot_angle_deg: f64,
    /// Walk there and back with a 180° turn in the middle (when there are ≥ 8 strides).
    pub turn: bool,
    /// Left leg.
    pub left: LegParams,
    /// Right leg.
    pub right: LegParams,
}

impl SubjectParams {
    /// A typical healthy adult at 1.3 m/s, 100 Hz, 25 s with a turn.
    pub fn healthy(subject_id: impl Into<String>) -> Self {
        SubjectParams {
            subject_id: subject_id.into(),
            group: Group::Healthy,
            affected_side: None,
            fs_hz: 100.0,
            duration_s: 25.0,
            standing_s: 3.0,
            stride_time_s: 1.05,
            stride_length_m: 1.36,
            stride_time_cv: 0.02,
            stride_length_cv: 0.02,
            stance_ratio_sd: 0.008,
            step_timing_asymmetry: 0.0,
            step_length_asymmetry: 0.0,
            heel_strike_foot_angle_deg: 15.0,
            toe_off_foot_angle_deg: 55.0,
            turn: true,
            left: LegParams::default(),
            right: LegParams::default(),
        }
    }

    /// The parameters of one leg.
    pub fn leg(&self, side: Side) -> &LegParams {
        match side {
            Side::Left => &self.left,
            Side::Right => &self.right,
        }
    }

    /// Mutable parameters of one leg.
    pub fn leg_mut(&mut self, side: Side) -> &mut LegParams {
        match side {
            Side::Left => &mut self.left,
            Side::Right => &mut self.right,
        }
    }

    /// Draw a subject of `group` (LDH: affected side drawn too). Population values: healthy
    /// 1.30 ± 0.10 m/s, stride time 1.05 ± 0.05 s, CV 2 %; LDH slower (0.98 ± 0.10 m/s), longer
    /// strides in time (1.18 ± 0.06 s), CV 4 %, affected side stance 0.65, swing knee flexion
    /// −18 %, circumduction 3.5 cm.
    pub fn draw(
        subject_id: impl Into<String>,
        group: Group,
        fs_hz: f64,
        duration_s: f64,
        rng: &mut ChaCha8Rng,
    ) -> Self {
        use rand::Rng;
        let mut p = SubjectParams::healthy(subject_id);
        p.group = group;
        p.fs_hz = fs_hz;
        p.duration_s = duration_s;
        let h = normal_clamped(rng, 0.10, 0.015, 0.06, 0.16);
        for side in [Side::Left, Side::Right] {
            let l = p.leg_mut(side);
            l.sensor_height_m =
                (h + normal_clamped(rng, 0.0, 0.005, -0.015, 0.015)).clamp(0.06, 0.16);
            l.roll_stance_deg = normal_clamped(rng, 2.0, 1.0, -1.0, 5.0);
        }
        match group {
            Group::Healthy => {
                p.stride_time_s = normal_clamped(rng, 1.05, 0.05, 0.92, 1.2);
                let speed = normal_clamped(rng, 1.30, 0.10, 1.05, 1.6);
                p.stride_length_m = speed * p.stride_time_s;
                p.stride_time_cv = normal_clamped(rng, 0.02, 0.004, 0.01, 0.03);
                p.stride_length_cv = normal_clamped(rng, 0.02, 0.004, 0.01, 0.03);
                p.step_timing_asymmetry = normal_clamped(rng, 0.0, 0.005, -0.015, 0.015);
                p.step_length_asymmetry = normal_clamped(rng, 0.0, 0.01, -0.03, 0.03);
                for side in [Side::Left, Side::Right] {
                    let l = p.leg_mut(side);
                    l.stance_ratio = normal_clamped(rng, 0.60, 0.008, 0.58, 0.62);
                    l.knee_reduction = normal_clamped(rng, 0.0, 0.02, -0.04, 0.04);
                    l.circumduction_m = normal_clamped(rng, 0.01, 0.003, 0.0, 0.02);
                    l.roll_swing_deg = normal_clamped(rng, -1.5, 0.5, -3.0, 0.0);
                }
            }
            Group::Ldh => {
                let affected = if rng.gen_bool(0.5) {
                    Side::Left
                } else {
                    Side::Right
                };
                p.affected_side = Some(affected);
                p.stride_time_s = normal_clamped(rng, 1.18, 0.06, 1.02, 1.35);
                let speed = normal_clamped(rng, 0.98, 0.10, 0.75, 1.25);
                p.stride_length_m = speed * p.stride_time_s;
                p.stride_time_cv = normal_clamped(rng, 0.04, 0.008, 0.025, 0.06);
                p.stride_length_cv = normal_clamped(rng, 0.04, 0.008, 0.025, 0.06);
                p.stance_ratio_sd = 0.012;
                // The affected leg's step (its heel strike after the other's) comes late and short.
                let sign = if affected == Side::Right { 1.0 } else { -1.0 };
                p.step_timing_asymmetry = sign * normal_clamped(rng, 0.02, 0.008, 0.0, 0.04);
                p.step_length_asymmetry = -sign * normal_clamped(rng, 0.04, 0.015, 0.0, 0.08);
                for side in [Side::Left, Side::Right] {
                    let aff = side == affected;
                    let l = p.leg_mut(side);
                    if aff {
                        l.stance_ratio = normal_clamped(rng, 0.65, 0.01, 0.62, 0.68);
                        l.knee_reduction = normal_clamped(rng, 0.18, 0.04, 0.08, 0.28);
                        l.circumduction_m = normal_clamped(rng, 0.035, 0.008, 0.02, 0.055);
                        l.roll_swing_deg = normal_clamped(rng, -5.0, 1.0, -8.0, -3.0);
                    } else {
                        l.stance_ratio = normal_clamped(rng, 0.615, 0.01, 0.59, 0.64);
                        l.knee_reduction = normal_clamped(rng, 0.05, 0.03, -0.02, 0.12);
                        l.circumduction_m = normal_clamped(rng, 0.012, 0.004, 0.0, 0.025);
                        l.roll_swing_deg = normal_clamped(rng, -2.0, 0.6, -3.5, -0.5);
                    }
                }
            }
        }
        let hip_scale = (p.stride_length_m / 1.36).clamp(0.75, 1.15);
        p.left.hip_scale = hip_scale;
        p.right.hip_scale = hip_scale;
        p
    }

    /// This (LDH) subject's gait moved towards `healthy`: every gait parameter becomes
    /// healthy + severity · (self − healthy). Group, affected side and sensor placement stay.
    pub fn blend_towards(&self, healthy: &SubjectParams, severity: f64) -> SubjectParams {
        let b = |l: f64, h: f64| h + severity * (l - h);
        let mut p = self.clone();
        p.stride_time_s = b(self.stride_time_s, healthy.stride_time_s);
        p.stride_length_m = b(self.stride_length_m, healthy.stride_length_m);
        p.stride_time_cv = b(self.stride_time_cv, healthy.stride_time_cv);
        p.stride_length_cv = b(self.stride_length_cv, healthy.stride_length_cv);
        p.stance_ratio_sd = b(self.stance_ratio_sd, healthy.stance_ratio_sd);
        p.step_timing_asymmetry = b(self.step_timing_asymmetry, healthy.step_timing_asymmetry);
        p.step_length_asymmetry = b(self.step_length_asymmetry, healthy.step_length_asymmetry);
        for side in [Side::Left, Side::Right] {
            let (l, h) = (self.leg(side).clone(), healthy.leg(side).clone());
            let t = p.leg_mut(side);
            t.stance_ratio = b(l.stance_ratio, h.stance_ratio);
            t.knee_reduction = b(l.knee_reduction, h.knee_reduction);
            t.hip_scale = b(l.hip_scale, h.hip_scale);
            t.circumduction_m = b(l.circumduction_m, h.circumduction_m);
            t.roll_swing_deg = b(l.roll_swing_deg, h.roll_swing_deg);
        }
        p
    }

    /// Check the parameters are physically sensible.
    pub fn validate(&self) -> Result<()> {
        let range = |name: &'static str, v: f64, lo: f64, hi: f64| {
            if v.is_finite() && (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(LdhError::param(
                    name,
                    v,
                    format!("must lie in [{lo}, {hi}]"),
                ))
            }
        };
        range("fs_hz", self.fs_hz, 20.0, 2000.0)?;
        range("duration_s", self.duration_s, 5.0, 24.0 * 3600.0)?;
        check_samples(self.duration_s, self.fs_hz)?;
        range("standing_s", self.standing_s, 0.0, 60.0)?;
        range("stride_time_s", self.stride_time_s, 0.7, 2.0)?;
        range("stride_length_m", self.stride_length_m, 0.3, 2.2)?;
        range("stride_time_cv", self.stride_time_cv, 0.0, 0.1)?;
        range("stride_length_cv", self.stride_length_cv, 0.0, 0.1)?;
        range("stance_ratio_sd", self.stance_ratio_sd, 0.0, 0.03)?;
        range(
            "step_timing_asymmetry",
            self.step_timing_asymmetry,
            -0.045,
            0.045,
        )?;
        range(
            "step_length_asymmetry",
            self.step_length_asymmetry,
            -0.3,
            0.3,
        )?;
        range(
            "heel_strike_foot_angle_deg",
            self.heel_strike_foot_angle_deg,
            0.0,
            35.0,
        )?;
        range(
            "toe_off_foot_angle_deg",
            self.toe_off_foot_angle_deg,
            10.0,
            80.0,
        )?;
        for l in [&self.left, &self.right] {
            range("stance_ratio", l.stance_ratio, 0.55, 0.70)?;
            range("knee_reduction", l.knee_reduction, -0.3, 0.6)?;
            range("hip_scale", l.hip_scale, 0.5, 1.5)?;
            range("circumduction_m", l.circumduction_m, 0.0, 0.15)?;
            range("roll_swing_deg", l.roll_swing_deg, -20.0, 20.0)?;
            range("roll_stance_deg", l.roll_stance_deg, -15.0, 15.0)?;
            range("sensor_height_m", l.sensor_height_m, 0.0, 0.4)?;
            range("sensor_lateral_m", l.sensor_lateral_m, 0.0, 0.1)?;
            range("swing_clearance_m", l.swing_clearance_m, 0.0, 0.2)?;
        }
        if self.group == Group::Ldh && self.affected_side.is_none() {
            return Err(LdhError::param(
                "affected_side",
                "none",
                "an LDH subject needs an affected side",
            ));
        }
        Ok(())
    }
}

/// Parameters of a simulated cohort (`ldh simulate`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CohortParams {
    /// Number of healthy subjects. Default 2.
    pub healthy: usize,
    /// Number of LDH subjects. Default 2.
    pub ldh: usize,
    /// Recording length per subject, s. Default 25.
    pub duration_s: f64,
    /// Sampling rate, Hz. Default 100.
    pub fs_hz: f64,
    /// Seed. Default 1.
    pub seed: u64,
    /// Walk there and back with a turn. Default true.
    pub turn: bool,
    /// Lowest LDH severity: each LDH subject's severity is drawn uniformly in [this, 1] and
    /// scales every LDH effect from a healthy gait (0) to the full LDH gait (1). Default 1 (all
    /// subjects fully affected; nothing extra is drawn, so seeds keep their output).
    pub ldh_severity_min: f64,
    /// Sensor model.
    pub sensor: SensorModel,
}

impl Default for CohortParams {
    fn default() -> Self {
        CohortParams {
            healthy: 2,
            ldh: 2,
            duration_s: 25.0,
            fs_hz: 100.0,
            seed: 1,
            turn: true,
            ldh_severity_min: 1.0,
            sensor: SensorModel::default(),
        }
    }
}

impl CohortParams {
    /// Total number of subjects (saturating: [`CohortParams::validate`] refuses a sum that
    /// overflows).
    pub fn len(&self) -> usize {
        self.healthy.saturating_add(self.ldh)
    }
    /// No subjects.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Identifier of subject `i` (healthy first: H01…, then L01…).
    pub fn subject_id(&self, i: usize) -> String {
        let width = (self.len().max(1) as f64).log10().floor() as usize + 1;
        let width = width.max(2);
        if i < self.healthy {
            format!("H{:0width$}", i + 1)
        } else {
            format!("L{:0width$}", i - self.healthy + 1)
        }
    }
    /// Check the cohort parameters.
    pub fn validate(&self) -> Result<()> {
        if self.is_empty() {
            return Err(LdhError::param(
                "healthy + ldh",
                0,
                "at least one subject is needed",
            ));
        }
        check_size(self.healthy, self.ldh, self.duration_s, self.fs_hz)?;
        if !(0.0..=1.0).contains(&self.ldh_severity_min) {
            return Err(LdhError::param(
                "ldh_severity_min",
                self.ldh_severity_min,
                "must lie in [0, 1]",
            ));
        }
        self.sensor.validate()?;
        // 3 s of standing at each end and four strides of the slowest drawn gait (1.35 s each,
        // plus the ramps in and out).
        if !(self.duration_s >= 14.0) {
            return Err(LdhError::param(
                "duration_s",
                self.duration_s,
                "a simulated cohort needs at least 14 s per subject (3 s standing at each end and four strides of slow gait)",
            ));
        }
        SubjectParams {
            fs_hz: self.fs_hz,
            duration_s: self.duration_s,
            ..SubjectParams::healthy("check")
        }
        .validate()
    }
    /// The random stream of subject `i`: independent of the other subjects and of threads.
    pub fn rng(&self, i: usize) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(i as u64 + 1);
        rng
    }
    /// Draw and simulate subject `i`.
    pub fn simulate(&self, i: usize) -> Result<SimSubject> {
        let mut rng = self.rng(i);
        let group = if i < self.healthy {
            Group::Healthy
        } else {
            Group::Ldh
        };
        let mut p = SubjectParams::draw(
            self.subject_id(i),
            group,
            self.fs_hz,
            self.duration_s,
            &mut rng,
        );
        if group == Group::Ldh && self.ldh_severity_min < 1.0 {
            use rand::Rng;
            let severity = rng.gen_range(self.ldh_severity_min..=1.0);
            let h = SubjectParams::draw(
                self.subject_id(i),
                Group::Healthy,
                self.fs_hz,
                self.duration_s,
                &mut rng,
            );
            p = p.blend_towards(&h, severity);
        }
        p.turn = self.turn;
        simulate_subject(&p, &self.sensor, &mut rng)
    }
}

/// The ground-truth file of one subject (`truth.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubjectTruth {
    /// [`TRUTH_SCHEMA`].
    pub schema: String,
    /// Subject.
    pub subject_id: String,
    /// Group.
    pub group: Group,
    /// Affected side (LDH).
    pub affected_side: Option<Side>,
    /// Sampling rate, Hz.
    pub fs_hz: f64,
    /// The parameters the subject was simulated with.
    pub params: SubjectParams,
    /// Left leg truth.
    pub left: LegTruth,
    /// Right leg truth.
    pub right: LegTruth,
    /// Family B subjects: the full parameters (`params` is then a family A-shaped summary).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub family_b: Option<family_b::SubjectParamsB>,
}

fn round_to(v: &mut [f64], decimals: i32) {
    let k = 10f64.powi(decimals);
    for x in v {
        *x = (*x * k).round() / k;
    }
}

impl SimSubject {
    /// The truth file's content (angles rounded to 0.001°).
    pub fn truth(&self) -> SubjectTruth {
        let mut left = self.left.truth.clone();
        let mut right = self.right.truth.clone();
        for t in [&mut left, &mut right] {
            round_to(&mut t.pitch_deg, 3);
            round_to(&mut t.roll_deg, 3);
            round_to(&mut t.yaw_deg, 3);
        }
        SubjectTruth {
            schema: TRUTH_SCHEMA.to_string(),
            subject_id: self.params.subject_id.clone(),
            group: self.params.group,
            affected_side: self.params.affected_side,
            fs_hz: self.params.fs_hz,
            params: self.params.clone(),
            left,
            right,
            family_b: self.family_b.clone(),
        }
    }

    /// Write `left.csv`, `right.csv` (in `format`) and `truth.json` into `dir`.
    /// Formats without timestamps (a sample counter or no time) are written with the simulated
    /// rate as their stated rate.
    pub fn write(&self, dir: &Path, format: &FormatSpec) -> Result<()> {
        let opts = WriteOptions::default();
        let format = &match format.time.unit {
            crate::io::format::TimeUnit::Counter | crate::io::format::TimeUnit::None => {
                format.clone().with_rate_hz(self.params.fs_hz)
            }
            _ => format.clone(),
        };
        for leg in [&self.left, &self.right] {
            let side = leg.truth.side.as_str();
            crate::io::write_recording(
                dir.join(format!("{side}.csv")),
                &leg.recording,
                format,
                &opts,
            )?;
        }
        let json = serde_json::to_string(&self.truth()).map_err(|e| LdhError::Write {
            path: dir.join("truth.json"),
            reason: e.to_string(),
        })?;
        write_atomic(dir.join("truth.json"), json.as_bytes())
    }
}

/// Read a `truth.json`.
pub fn read_truth(path: impl AsRef<Path>) -> Result<SubjectTruth> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| LdhError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|e| LdhError::Format {
        name: path.display().to_string(),
        reason: format!("not a ground-truth file: {e}"),
    })
}

/// A cohort manifest row (SPEC §2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ManifestRow {
    /// Subject.
    pub subject_id: String,
    /// `healthy` or `ldh`.
    pub group: Group,
    /// `left`, `right` or `none`.
    pub affected_side: String,
    /// Left recording, relative to the manifest.
    pub left: String,
    /// Right recording, relative to the manifest.
    pub right: String,
    /// Sensor height above the ankle, m (optional column).
    pub sensor_height_m: Option<f64>,
    /// Overground or treadmill (optional column `setting`; written for family B only).
    #[serde(default)]
    pub setting: Option<crate::recording::Setting>,
}

impl ManifestRow {
    /// The row of a simulated subject stored in `<subject_id>/`.
    pub fn of(s: &SimSubject) -> ManifestRow {
        let id = &s.params.subject_id;
        ManifestRow {
            subject_id: id.clone(),
            group: s.params.group,
            affected_side: s
                .params
                .affected_side
                .map(|x| x.as_str().to_string())
                .unwrap_or_else(|| "none".into()),
            left: format!("{id}/left.csv"),
            right: format!("{id}/right.csv"),
            sensor_height_m: Some(
                ((s.left.truth.sensor_height_m + s.right.truth.sensor_height_m) / 2.0 * 1000.0)
                    .round()
                    / 1000.0,
            ),
            setting: s.family_b.as_ref().map(|p| p.setting),
        }
    }
}

/// Render manifest rows as CSV text.
/// The `setting` column is written only when a row has a setting (family B), so family A
/// manifests keep their columns.
pub fn manifest_csv(rows: &[ManifestRow]) -> String {
    let with_setting = rows.iter().any(|r| r.setting.is_some());
    let mut out = String::from("subject_id,group,affected_side,left,right,sensor_height_m");
    out.push_str(if with_setting { ",setting\n" } else { "\n" });
    for r in rows {
        out.push_str(&format!(
            "{},{},{},{},{},{}",
            r.subject_id,
            r.group.as_str(),
            r.affected_side,
            r.left,
            r.right,
            r.sensor_height_m.map(|h| h.to_string()).unwrap_or_default()
        ));
        if with_setting {
            out.push(',');
            out.push_str(r.setting.map(|s| s.as_str()).unwrap_or(""));
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests;
