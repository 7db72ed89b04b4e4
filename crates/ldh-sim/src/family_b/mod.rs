//! Simulator family B: a second, independently written two-shank gait simulator (issue 20).
//!
//! Built without the pipeline's assumptions or family A's kinematic model, so the pipeline can be
//! tuned on one family and scored on the other (docs/simulator.md, docs/accuracy.md):
//!
//! - **Segment angles, not joint angles**: the shank's sagittal inclination follows a segment
//!   curve ([`kin::SHANK_KEYPOINTS_DEG`]; Winter 2009 appendix A "leg" angle, Tong & Granat
//!   1999, Aminian et al. 2002), fitted as an 8-harmonic Fourier series, stretched so toe off lands
//!   at each stride's stance fraction; the amplitude scales with speed, the paretic leg loses part
//!   of its early-swing peak (stiff knee).
//! - **A rigid foot that rolls** (no slip) over a heel arc (r = 3.5 cm) from heel strike to foot
//!   flat, stays flat, then rolls over a forefoot arc (r = 1.5 cm) to toe off; the swing ankle
//!   path is a quintic matching position, velocity and acceleration at toe off and heel strike,
//!   plus clearance and circumduction bumps.
//! - **Gait**: healthy 0.9–1.6 m/s; slow hemiparetic gait 0.2–0.7 m/s with strides of 1.6–2.3 s,
//!   a longer stance on the non-paretic side, flat-foot contact and a stiff knee on the paretic
//!   side; stride-to-stride variability; a 180° turn over two strides overground, none on a
//!   treadmill (belt speed with a 1.5 % ripple, the foot moves with the belt in stance; stride
//!   length is measured on the belt).
//! - **Sensor**: 5–25 cm above the ankle, any rotation about the shank axis (0–360°), tilt, a
//!   heel-strike soft-tissue transient (damped 14–22 Hz wobble, translation and rotation), a
//!   shank that is not exactly vertical when standing, then [`sensor`] errors: scale faults,
//!   bias, bias drift and random walk, noise, 16-bit quantisation, clipping at ±2 … ±16 g and
//!   ±500 … ±2000 deg/s.
//!
//! Derivatives are central differences of closed-form functions of time (acceleration of the
//! sensor's world position, body rate of its orientation), not analytic jets as in family A.
//! Output: the same [`SimSubject`] (recordings + [`LegTruth`]) as family A, so `ldh evaluate` scores
//! both the same way.

pub mod kin;
pub mod leg;
pub mod sensor;
mod subject;
#[cfg(test)]
mod tests;

use rand::Rng;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::draw::normal_clamped;
use super::Group;
use ldh_core::error::{LdhError, Result};
use ldh_core::recording::{Setting, Side};
pub use sensor::SensorModelB;
pub use subject::simulate_subject_b;

#[allow(unused_imports)]
use super::{LegTruth, SimSubject};

/// Per-leg parameters of a family B subject.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LegParamsB {
    /// Mean stance fraction.
    pub stance_ratio: f64,
    /// Scale of the shank excursion about its mean (1 = normal adult at ≈ 1.2 m/s).
    pub amplitude: f64,
    /// Fraction of the early-swing pitch peak removed (stiff knee; 0 normal).
    pub stiff_knee: f64,
    /// Foot angle at heel strike (toes up), deg; 0 = flat-foot contact.
    pub foot_hs_deg: f64,
    /// Foot angle at toe off (plantar), deg.
    pub foot_to_deg: f64,
    /// Foot flat from this fraction of stance.
    pub foot_flat: f64,
    /// Heel off at this fraction of stance.
    pub heel_off: f64,
    /// Lateral swing excursion of the ankle, m.
    pub circumduction_m: f64,
    /// Extra ankle height at mid-swing, m.
    pub swing_clearance_m: f64,
    /// Anatomical roll in stance, deg.
    pub roll_stance_deg: f64,
    /// Roll change in swing, deg.
    pub roll_swing_deg: f64,
    /// Shank inclination while standing, deg.
    pub standing_pitch_deg: f64,
    /// Sensor height above the ankle, m.
    pub sensor_height_m: f64,
    /// Sensor distance lateral of the shank axis, m.
    pub sensor_lateral_m: f64,
    /// Sensor offset anterior of the shank axis, m.
    pub sensor_anterior_m: f64,
    /// Device rotation about the shank axis, deg (any value).
    pub axial_deg: f64,
    /// Device tilts about its y and z axes, deg.
    pub tilt_deg: [f64; 2],
    /// Heel-strike soft-tissue transient amplitude, mm.
    pub hs_transient_mm: f64,
    /// Its rotation amplitude, deg.
    pub hs_transient_rot_deg: f64,
    /// Its frequency, Hz.
    pub hs_transient_hz: f64,
}

/// One family B subject.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubjectParamsB {
    /// Identifier.
    pub subject_id: String,
    /// Group (`ldh`: slow hemiparetic-like gait with an affected side).
    pub group: Group,
    /// Affected (paretic) side.
    pub affected_side: Option<Side>,
    /// Sampling rate, Hz.
    pub fs_hz: f64,
    /// Recording length, s.
    pub duration_s: f64,
    /// Quiet standing at each end, s.
    pub standing_s: f64,
    /// Overground or treadmill.
    pub setting: Setting,
    /// Walk there and back (overground, ≥ 8 strides).
    pub turn: bool,
    /// Mean walking speed, m/s.
    pub speed_mps: f64,
    /// Mean stride time, s.
    pub stride_time_s: f64,
    /// Stride time CV.
    pub stride_time_cv: f64,
    /// Stride length CV.
    pub stride_length_cv: f64,
    /// Stance fraction SD from stride to stride.
    pub stance_ratio_sd: f64,
    /// Right step = (1 + a)·L/2.
    pub step_length_asymmetry: f64,
    /// Right heel strike at left phase 0.5 + this.
    pub step_timing_asymmetry: f64,
    /// Treadmill belt speed ripple (fraction).
    pub belt_ripple: f64,
    /// Accelerometer range of both sensors, ±g.
    pub acc_range_g: f64,
    /// Gyroscope range, ±deg/s.
    pub gyro_range_dps: f64,
    /// Left leg.
    pub left: LegParamsB,
    /// Right leg.
    pub right: LegParamsB,
    /// Start-up, s from the first step (a treadmill belt accelerating, gait initiation): a
    /// stride that begins `e` s into it is `1 + RAMP_STRIDE_EXTRA · (1 − e / ramp_s)` times
    /// longer ([`crate::RAMP_STRIDE_EXTRA`], 25 %), in time and in length (the walker keeps the
    /// belt's pace). Default 0 (then not serialised, so earlier subjects keep their bytes).
    #[serde(default, skip_serializing_if = "crate::params::is_zero_s")]
    pub ramp_s: f64,
    /// Slowing down, s before the last step (the belt slowing to a stop): the mirror of
    /// `ramp_s`, measured back from the end of the walk. Default 0 (then not serialised).
    #[serde(default, skip_serializing_if = "crate::params::is_zero_s")]
    pub slowdown_s: f64,
    /// A trend over the whole walk: the last stride is `1 + trend_share` times the first in
    /// time and length, linearly in between (−0.25: a walker who speeds up throughout).
    /// Default 0 (then not serialised).
    #[serde(default, skip_serializing_if = "crate::params::is_zero_s")]
    pub trend_share: f64,
}

/// What one family B leg's draw depends on besides the random stream.
struct LegDraw {
    /// The affected (paretic) leg of a patient.
    paretic: bool,
    /// The other leg of a patient.
    other: bool,
    /// The subject's walking speed, m/s.
    speed_mps: f64,
    /// The subject's stance ratio before the per-leg changes.
    base_stance: f64,
    /// The subject's mean sensor height above the ankle, m.
    sensor_height_m: f64,
}

impl LegParamsB {
    /// Draw one leg of [`SubjectParamsB::draw`]: the amplitude first, then the fields in the
    /// order written here (the order of the draws from `rng` fixes every simulated number). A
    /// paretic leg gets a stiff knee, a flat foot and circumduction; the other leg of a patient
    /// a longer stance.
    fn draw(c: &LegDraw, sensor: &SensorModelB, rng: &mut ChaCha8Rng) -> LegParamsB {
        let nc = normal_clamped;
        let (paretic, other, v, base_stance, h) = (
            c.paretic,
            c.other,
            c.speed_mps,
            c.base_stance,
            c.sensor_height_m,
        );
        let amp = (0.4 + 0.5 * v).clamp(0.45, 1.2) * nc(rng, 1.0, 0.05, 0.9, 1.1);
        LegParamsB {
            stance_ratio: (base_stance
                + if other { 0.06 } else { 0.0 }
                + if paretic { -0.01 } else { 0.0 }
                + nc(rng, 0.0, 0.01, -0.02, 0.02))
            .clamp(0.55, 0.78),
            amplitude: if paretic { amp * 0.85 } else { amp },
            stiff_knee: if paretic {
                rng.gen_range(0.15..0.45)
            } else {
                nc(rng, 0.0, 0.03, -0.05, 0.05)
            },
            foot_hs_deg: if paretic {
                rng.gen_range(0.0..8.0)
            } else {
                (amp * nc(rng, 18.0, 3.0, 10.0, 25.0)).max(2.0)
            },
            foot_to_deg: if paretic {
                rng.gen_range(25.0..40.0)
            } else {
                amp * nc(rng, 58.0, 5.0, 45.0, 70.0)
            },
            foot_flat: nc(rng, 0.17, 0.03, 0.1, 0.25),
            heel_off: if paretic || v < 0.8 {
                nc(rng, 0.68, 0.04, 0.6, 0.78)
            } else {
                nc(rng, 0.5, 0.04, 0.42, 0.6)
            },
            circumduction_m: if paretic {
                rng.gen_range(0.03..0.06)
            } else {
                nc(rng, 0.01, 0.004, 0.0, 0.02)
            },
            swing_clearance_m: if paretic { 0.012 } else { 0.03 * amp },
            roll_stance_deg: nc(rng, 1.5, 1.5, -2.0, 5.0),
            roll_swing_deg: if paretic {
                rng.gen_range(-8.0..-4.0)
            } else {
                nc(rng, -2.0, 0.7, -4.0, 0.0)
            },
            standing_pitch_deg: nc(rng, 0.0, 1.0, -2.0, 2.0),
            sensor_height_m: (h + nc(rng, 0.0, 0.006, -0.012, 0.012)).clamp(0.05, 0.25),
            sensor_lateral_m: rng.gen_range(0.03..0.055),
            sensor_anterior_m: rng.gen_range(-0.01..0.02),
            axial_deg: rng.gen_range(0.0..360.0),
            tilt_deg: [
                sensor.tilt_deg_sd * nc(rng, 0.0, 1.0, -3.0, 3.0),
                sensor.tilt_deg_sd * nc(rng, 0.0, 1.0, -3.0, 3.0),
            ],
            hs_transient_mm: (v / 1.2) * rng.gen_range(0.4..1.5),
            hs_transient_rot_deg: (v / 1.2) * rng.gen_range(0.2..0.8),
            hs_transient_hz: rng.gen_range(14.0..22.0),
        }
    }
}

impl SubjectParamsB {
    /// Mean stride length, m.
    pub fn stride_length_m(&self) -> f64 {
        self.speed_mps * self.stride_time_s
    }
    /// Leg parameters.
    pub fn leg(&self, side: Side) -> &LegParamsB {
        match side {
            Side::Left => &self.left,
            Side::Right => &self.right,
        }
    }

    /// Draw a subject. `speed` forces the mean speed (m/s); `setting` forces the setting.
    #[allow(clippy::too_many_arguments)]
    pub fn draw(
        subject_id: impl Into<String>,
        group: Group,
        fs_hz: f64,
        duration_s: f64,
        speed: Option<f64>,
        setting: Setting,
        sensor: &SensorModelB,
        rng: &mut ChaCha8Rng,
    ) -> SubjectParamsB {
        let nc = normal_clamped;
        let patient = group == Group::Ldh;
        let affected = patient.then(|| {
            if rng.gen_bool(0.5) {
                Side::Left
            } else {
                Side::Right
            }
        });
        let v = speed.unwrap_or_else(|| {
            if patient {
                rng.gen_range(0.2..0.7)
            } else {
                rng.gen_range(0.9..1.6)
            }
        });
        let stride_time_s =
            (1.05 + 1.06 * (1.2 - v) + nc(rng, 0.0, 0.08, -0.15, 0.15)).clamp(0.85, 2.35);
        let base_stance = 0.60 + 0.06 * ((1.2 - v) / 0.9).clamp(-0.3, 1.0);
        let h = rng.gen_range(0.05..0.25);
        let pick = |r: &mut ChaCha8Rng, v: &[f64]| v[r.gen_range(0..v.len())];
        let acc_range_g = pick(rng, &sensor.acc_ranges_g);
        let gyro_range_dps = pick(rng, &sensor.gyro_ranges_dps);
        let mut legs = Vec::with_capacity(2);
        for side in [Side::Left, Side::Right] {
            let paretic = affected == Some(side);
            let other = patient && !paretic;
            let leg = LegDraw {
                paretic,
                other,
                speed_mps: v,
                base_stance,
                sensor_height_m: h,
            };
            legs.push(LegParamsB::draw(&leg, sensor, rng));
        }
        let right = legs.pop().expect("two");
        let left = legs.pop().expect("two");
        let sign = if affected == Some(Side::Right) {
            1.0
        } else {
            -1.0
        };
        SubjectParamsB {
            subject_id: subject_id.into(),
            group,
            affected_side: affected,
            fs_hz,
            duration_s,
            standing_s: rng.gen_range(3.0..5.0),
            setting,
            turn: setting == Setting::Overground,
            speed_mps: v,
            stride_time_s,
            stride_time_cv: if patient {
                rng.gen_range(0.03..0.06)
            } else {
                rng.gen_range(0.01..0.03)
            },
            stride_length_cv: if patient {
                rng.gen_range(0.03..0.06)
            } else {
                rng.gen_range(0.01..0.03)
            },
            stance_ratio_sd: if patient { 0.012 } else { 0.007 },
            step_length_asymmetry: if patient {
                sign * rng.gen_range(0.0..0.15)
            } else {
                nc(rng, 0.0, 0.01, -0.03, 0.03)
            },
            step_timing_asymmetry: if patient {
                sign * rng.gen_range(0.0..0.04)
            } else {
                nc(rng, 0.0, 0.005, -0.015, 0.015)
            },
            belt_ripple: if setting == Setting::Treadmill {
                0.015
            } else {
                0.0
            },
            acc_range_g,
            gyro_range_dps,
            left,
            right,
            ramp_s: 0.0,
            slowdown_s: 0.0,
            trend_share: 0.0,
        }
    }
}

/// A family B cohort (`ldh simulate --family b`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CohortParamsB {
    /// Subjects with normal gait. Default 2.
    pub healthy: usize,
    /// Subjects with slow hemiparetic-like gait (group `ldh`). Default 2.
    pub patients: usize,
    /// Recording length per subject, s. Default 40.
    pub duration_s: f64,
    /// Sampling rate, Hz. Default 100.
    pub fs_hz: f64,
    /// Seed. Default 1.
    pub seed: u64,
    /// Force every subject's mean speed, m/s. Default none (drawn).
    pub speed_mps: Option<f64>,
    /// Force the setting. Default none: each subject is on a treadmill with
    /// `treadmill_fraction`.
    pub setting: Option<Setting>,
    /// Share of subjects on a treadmill when `setting` is none. Default 0.3.
    pub treadmill_fraction: f64,
    /// Sensor errors.
    pub sensor: SensorModelB,
}

impl Default for CohortParamsB {
    fn default() -> Self {
        CohortParamsB {
            healthy: 2,
            patients: 2,
            duration_s: 40.0,
            fs_hz: 100.0,
            seed: 1,
            speed_mps: None,
            setting: None,
            treadmill_fraction: 0.3,
            sensor: SensorModelB::default(),
        }
    }
}

impl CohortParamsB {
    /// Number of subjects (saturating: [`CohortParamsB::validate`] refuses a sum that
    /// overflows).
    pub fn len(&self) -> usize {
        self.healthy.saturating_add(self.patients)
    }
    /// No subjects.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Identifier of subject i (`BH01…`, then `BP01…`).
    pub fn subject_id(&self, i: usize) -> String {
        let width = ((self.len().max(1) as f64).log10().floor() as usize + 1).max(2);
        if i < self.healthy {
            format!("BH{:0width$}", i + 1)
        } else {
            format!("BP{:0width$}", i - self.healthy + 1)
        }
    }
    /// Check the parameters.
    pub fn validate(&self) -> Result<()> {
        if self.is_empty() {
            return Err(LdhError::param(
                "healthy + ldh",
                0,
                "at least one subject is needed",
            ));
        }
        if !(self.fs_hz.is_finite() && (20.0..=2000.0).contains(&self.fs_hz)) {
            return Err(LdhError::param(
                "fs_hz",
                self.fs_hz,
                "must lie in [20, 2000]",
            ));
        }
        if !(self.duration_s.is_finite() && (25.0..=3600.0).contains(&self.duration_s)) {
            return Err(LdhError::param(
                "duration_s",
                self.duration_s,
                "family B needs 25–3600 s per subject (up to 5 s standing at each end and four strides of 2.3 s)",
            ));
        }
        super::check_size(self.healthy, self.patients, self.duration_s, self.fs_hz)?;
        if let Some(v) = self.speed_mps {
            if !(v.is_finite() && (0.15..=2.0).contains(&v)) {
                return Err(LdhError::param("speed_mps", v, "must lie in [0.15, 2]"));
            }
        }
        if !(0.0..=1.0).contains(&self.treadmill_fraction) {
            return Err(LdhError::param(
                "treadmill_fraction",
                self.treadmill_fraction,
                "must lie in [0, 1]",
            ));
        }
        self.sensor.validate()
    }
    /// Draw and simulate subject i (its own ChaCha8 stream: independent of threads).
    pub fn simulate(&self, i: usize) -> Result<SimSubject> {
        let (p, mut rng) = self.draw(i);
        simulate_subject_b(&p, &self.sensor, &mut rng)
    }
    /// Draw subject i's parameters, and its stream in the state the simulation continues from
    /// (change the parameters, then [`simulate_subject_b`] with the stream).
    pub fn draw(&self, i: usize) -> (SubjectParamsB, ChaCha8Rng) {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed ^ 0xBFA4_117B);
        rng.set_stream(i as u64 + 1);
        let group = if i < self.healthy {
            Group::Healthy
        } else {
            Group::Ldh
        };
        let setting = self.setting.unwrap_or_else(|| {
            if rng.gen_bool(self.treadmill_fraction) {
                Setting::Treadmill
            } else {
                Setting::Overground
            }
        });
        let p = SubjectParamsB::draw(
            self.subject_id(i),
            group,
            self.fs_hz,
            self.duration_s,
            self.speed_mps,
            setting,
            &self.sensor,
            &mut rng,
        );
        (p, rng)
    }
}

/// Which simulator family (`ldh simulate --family`).
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Family {
    /// The original simulator ([`crate::model`]). Default.
    #[default]
    A,
    /// The independent family B (this module).
    B,
}

impl std::fmt::Display for Family {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Family::A => "a",
            Family::B => "b",
        })
    }
}

impl std::str::FromStr for Family {
    type Err = LdhError;
    fn from_str(s: &str) -> Result<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "a" => Ok(Family::A),
            "b" => Ok(Family::B),
            other => Err(LdhError::param("family", other, "expected 'a' or 'b'")),
        }
    }
}
