//! What a simulation delivers ([`SimSubject`]: per leg the recording, the ground truth and the
//! noise-free dense kinematics) and the ground-truth file `truth.json` ([`SubjectTruth`],
//! [`read_truth`]).

use serde::{Deserialize, Serialize};
use std::path::Path;

use super::{family_b, Group, SubjectParams};
use ldh_core::error::{LdhError, Result};
use ldh_core::recording::{Recording, Side};

/// Ground truth of one stride of one leg.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StrideTruth {
    /// Stride number within the leg (its heel strike's index).
    pub index: usize,
    /// Heel strike, s from the first sample.
    pub hs_time_s: f64,
    /// Toe off, s.
    pub to_time_s: f64,
    /// Next heel strike, s.
    pub next_hs_time_s: f64,
    /// Stride time, s.
    pub stride_time_s: f64,
    /// Stance ratio (TO − HS) / stride time.
    pub stance_ratio: f64,
    /// Horizontal displacement of the foot over the stride, m.
    pub stride_length_m: f64,
    /// Maximum shank pitch θ in the stride, deg (WQK).
    pub max_pitch_deg: f64,
    /// Minimum shank pitch θ in the stride, deg (−PBI).
    pub min_pitch_deg: f64,
    /// Range of anatomical roll from toe off to the next heel strike, deg (BDK).
    pub roll_swing_excursion_deg: f64,
    /// The stride overlaps the turn.
    pub turning: bool,
    /// First or last stride of a walking bout (gait ramping in or out).
    pub bout_edge: bool,
    /// Begins during the treadmill belt's start-up ([`super::SubjectParams::ramp_s`]; not
    /// written when false, so truths without a ramp keep their bytes).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub accelerating: bool,
    /// Ends while the walker slows down before the end ([`super::SubjectParams::slowdown_s`];
    /// not written when false).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub decelerating: bool,
}

/// What was drawn for one sensor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SensorTruth {
    /// Rotation of the device about the shank axis relative to nominal, deg.
    pub axial_misalignment_deg: f64,
    /// Small tilts about the device's y and z axes, deg.
    pub tilt_misalignment_deg: [f64; 2],
    /// The device is mounted mirrored (rotated 180° about the shank axis: right leg).
    pub mirrored: bool,
    /// Device axes (columns x, y, z) in the anatomical frame F (e1 anterior, e2 left, e3 up).
    pub device_axes_in_f: [[f64; 3]; 3],
    /// Gyroscope bias, deg/s, device axes.
    pub gyro_bias_dps: [f64; 3],
    /// Accelerometer bias, g, device axes.
    pub acc_bias_g: [f64; 3],
    /// Samples clipped at the sensor's range.
    pub saturated_samples: usize,
}

/// Ground truth of one leg.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LegTruth {
    /// The leg.
    pub side: Side,
    /// Sensor height above the ankle joint, m.
    pub sensor_height_m: f64,
    /// The sensor's draw.
    pub sensor: SensorTruth,
    /// All heel strikes, s.
    pub hs_times_s: Vec<f64>,
    /// All toe offs, s.
    pub to_times_s: Vec<f64>,
    /// Strides with both heel strikes.
    pub strides: Vec<StrideTruth>,
    /// Shank pitch θ at each sample, deg.
    pub pitch_deg: Vec<f64>,
    /// Anatomical roll ρ at each sample, deg (positive: knee lateral to ankle).
    pub roll_deg: Vec<f64>,
    /// Heading ψ at each sample, deg.
    pub yaw_deg: Vec<f64>,
}

/// Noise-free signals and world kinematics at each sample (for physics tests; not written).
#[derive(Debug, Clone, PartialEq)]
pub struct DenseTruth {
    /// Specific force in the device frame without noise, bias, quantisation or clipping, g.
    pub acc_clean_g: [Vec<f64>; 3],
    /// Angular velocity in the device frame, noise-free, deg/s.
    pub gyro_clean_dps: [Vec<f64>; 3],
    /// Sensor position in the world, m.
    pub sensor_pos_m: [Vec<f64>; 3],
    /// Sensor velocity in the world, m/s.
    pub sensor_vel_mps: [Vec<f64>; 3],
    /// Rotation world ← device at each sample (row-major).
    pub r_world_device: Vec<[[f64; 3]; 3]>,
    /// ZYX Euler angles (φ, θ, ψ) of the anatomical frame, rad.
    pub euler_rad: [Vec<f64>; 3],
}

/// One simulated leg: the sensor's recording and the truth.
#[derive(Debug, Clone)]
pub struct SimLeg {
    /// The recording as the sensor delivers it (noise, bias, quantisation, clipping).
    pub recording: Recording,
    /// Events, strides, angles.
    pub truth: LegTruth,
    /// Noise-free dense kinematics.
    pub dense: DenseTruth,
}

/// One simulated subject.
#[derive(Debug, Clone)]
pub struct SimSubject {
    /// The parameters drawn or given.
    pub params: SubjectParams,
    /// Left shank.
    pub left: SimLeg,
    /// Right shank.
    pub right: SimLeg,
    /// The full parameters of a family B subject (`params` then holds a summary).
    pub family_b: Option<family_b::SubjectParamsB>,
}

/// Version tag of the ground-truth JSON.
pub const TRUTH_SCHEMA: &str = "ldh-sim-truth/1";
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
            group: self.params.group.clone(),
            affected_side: self.params.affected_side,
            fs_hz: self.params.fs_hz,
            params: self.params.clone(),
            left,
            right,
            family_b: self.family_b.clone(),
        }
    }
}

/// Read a `truth.json`.
pub fn read_truth(path: impl AsRef<Path>) -> Result<SubjectTruth> {
    let path = path.as_ref();
    let text =
        ldh_core::io::read_text_limited(path, ldh_core::io::MAX_TABLE_MB, "a ground-truth file")?;
    serde_json::from_str(&text).map_err(|e| LdhError::Format {
        name: path.display().to_string(),
        reason: format!("not a ground-truth file: {e}"),
    })
}
