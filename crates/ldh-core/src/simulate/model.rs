//! The kinematic model of one subject's two shanks and the sensors on them.
//!
//! Frames. World: X forward (initial walking direction), Y left, Z up. The shank's anatomical
//! frame F (the same for both legs): e1 anterior, e2 left, e3 along the shank upwards. Its
//! orientation is `R_wF = Rz(ψ) · Ry(θ) · Rx(φ)` (ZYX Euler angles): θ is the sagittal
//! inclination from vertical, positive when the knee is anterior to the ankle (SPEC §3.3), φ the
//! frontal inclination and ψ the heading. The anatomical roll reported as truth is ρ, positive
//! when the knee is lateral to the ankle (φ = −ρ on the left leg, +ρ on the right).
//!
//! Sensor (device) frame, paper §2.2: x along the shank (up), y anterior-posterior, z
//! medio-lateral. A device worn on the lateral side of the left shank has (x, y, z) = (e3, e1,
//! e2); the same device on the right shank faces the other way: (e3, −e1, −e2) — the mirrored
//! mounting of real recordings. On top comes a mounting misalignment: a rotation about the
//! shank axis (tens of degrees on real recordings) and small tilts.
//!
//! Motion. A continuous gait phase p(t) (a C² quintic through the heel-strike times, stride
//! durations drawn with the subject's variability) is warped to a canonical phase q in which
//! toe off is always at 0.60, so each leg's stance ratio is set by the warp. Hip and knee
//! flexion follow the normal curves ([`super::curves`]), modified per leg (less swing knee
//! flexion, smaller hip excursion on the affected side of an LDH subject); the shank
//! inclination is knee − hip flexion. The foot rolls over the heel (foot angle down to 0 at
//! 10 % of the cycle), stays flat (ankle fixed), then rolls over the forefoot until toe off;
//! the ankle therefore moves on circles about the heel and toe contact points and never slips.
//! In swing the ankle follows a quintic matching position, velocity and acceleration at toe off
//! and at the next heel strike, plus a clearance bump and a lateral (circumduction) bump. At
//! start and end the subject stands still; gait is ramped in and out over one stride. A 180°
//! turn (heading ψ ramped over two strides, shorter strides) can split the walk into two bouts;
//! during a turn the ankle's world velocity is the heading-rotated progression velocity (the
//! foot pivots about the ankle's vertical axis).
//!
//! Every quantity is a [`Jet`] of time: acceleration is the exact second derivative of the
//! sensor's position, angular velocity the exact body rate of `R_wF`.

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use serde::{Deserialize, Serialize};

use super::curves::{self, PeriodicSpline, FOOT_FLAT, HEEL_OFF, TOE_OFF};
use super::jet::{
    body_rate, bump, mat_mul, mat_vec, rot_x, rot_y, rot_z, smoothstep5, Jet, JetVec3, Quintic,
};
use super::{LegParams, SensorModel, SubjectParams};
use crate::error::{LdhError, Result};
use crate::recording::{Recording, Side, STANDARD_GRAVITY_MPS2};

const TAU: f64 = std::f64::consts::TAU;
/// Heel contact point to ankle joint, foot frame (forward, up), m.
const HEEL_TO_ANKLE: (f64, f64) = (0.05, 0.08);
/// Forefoot (MTP) contact point to ankle joint, foot frame, m.
const TOE_TO_ANKLE: (f64, f64) = (-0.15, 0.08);
/// Half the step width: lateral distance of each ankle from the line of progression, m.
const HALF_STEP_WIDTH_M: f64 = 0.09;
/// Oversampling of the internal grid used to integrate world positions.
const OVERSAMPLE: usize = 10;

/// A C² gait phase p(t) through knots (t, p, ṗ, p̈).
#[derive(Debug, Clone)]
struct PhaseCurve {
    t: Vec<f64>,
    p: Vec<f64>,
    segs: Vec<Quintic>,
}

impl PhaseCurve {
    fn new(knots: &[(f64, f64, f64, f64)]) -> PhaseCurve {
        let segs = knots
            .windows(2)
            .map(|w| {
                let (t0, p0, v0, a0) = w[0];
                let (t1, p1, v1, a1) = w[1];
                Quintic::new(t0, t1, Jet::new(p0, v0, a0), Jet::new(p1, v1, a1))
            })
            .collect();
        PhaseCurve {
            t: knots.iter().map(|k| k.0).collect(),
            p: knots.iter().map(|k| k.1).collect(),
            segs,
        }
    }
    fn eval(&self, t: f64) -> Jet {
        if t <= self.t[0] {
            return Jet::cst(self.p[0]);
        }
        if t >= *self.t.last().unwrap() {
            return Jet::cst(*self.p.last().unwrap());
        }
        let i = self.t.partition_point(|&x| x <= t) - 1;
        self.segs[i].eval(t)
    }
    /// The time at which the phase equals `p` (bisection; p(t) is monotone).
    fn time_of(&self, p: f64) -> Option<f64> {
        if p < self.p[0] || p > *self.p.last().unwrap() {
            return None;
        }
        let i = self.p.partition_point(|&x| x < p).max(1) - 1;
        let seg = &self.segs[i.min(self.segs.len() - 1)];
        let (mut lo, mut hi) = (seg.t0, seg.t1);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if seg.eval(mid).v < p {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(0.5 * (lo + hi))
    }
    fn is_monotone(&self) -> bool {
        self.segs.iter().all(|s| {
            (0..=200).all(|k| {
                let t = s.t0 + (s.t1 - s.t0) * k as f64 / 200.0;
                s.eval(t).d >= -1e-12
            })
        })
    }
}

/// One swing: ankle x and z in the progression frame between toe off and the next heel strike.
#[derive(Debug, Clone)]
struct Swing {
    x: Quintic,
    z: Quintic,
}

/// Everything needed to evaluate one leg at any time.
#[derive(Debug, Clone)]
struct LegModel {
    side: Side,
    /// +1 on the left (lateral = +Y), −1 on the right.
    lat: f64,
    /// Leg phase = left phase + offset.
    offset: f64,
    /// Warp coefficient per stride index.
    c: Vec<f64>,
    /// Heel contact position (progression frame) per stride index.
    x_heel: Vec<f64>,
    ramp_up_start: f64,
    ramp_down_end: f64,
    p: LegParams,
    phi_hs: f64,
    phi_to: f64,
    swing: Vec<Option<Swing>>,
    /// Columns: device axes in F (nominal mounting × misalignment).
    mount: [[f64; 3]; 3],
    axial_deg: f64,
    tilt_deg: [f64; 2],
    mirrored: bool,
}

struct Shared<'a> {
    phase: &'a PhaseCurve,
    knee: &'a PeriodicSpline,
    hip: &'a PeriodicSpline,
}

/// Heading ψ(t): 0, then a C² ramp to π over the turn.
#[derive(Debug, Clone, Copy)]
struct Heading {
    turn: Option<(f64, f64)>,
}

impl Heading {
    fn eval(&self, t: f64) -> Jet {
        match self.turn {
            None => Jet::cst(0.0),
            Some((t0, t1)) => {
                let x = Jet::time(t).scale(1.0 / (t1 - t0)) - t0 / (t1 - t0);
                let (f, f1, f2) = smoothstep5(x.v);
                x.compose(f, f1, f2).scale(std::f64::consts::PI)
            }
        }
    }
}

fn spline_jet(s: &PeriodicSpline, q: Jet) -> Jet {
    let (f, f1, f2) = s.eval(q.v);
    q.compose(f, f1, f2)
}

impl LegModel {
    fn leg_phase(&self, sh: &Shared, t: f64) -> Jet {
        sh.phase.eval(t) + self.offset
    }

    fn c_at(&self, j: i64) -> f64 {
        let j = j.clamp(0, self.c.len() as i64 - 1) as usize;
        self.c[j]
    }

    /// Canonical phase q from leg phase P.
    fn warp(&self, pj: Jet) -> Jet {
        let j = pj.v.floor();
        let f = pj - j;
        let (s, s1, s2) = smoothstep5(f.v);
        let sj = f.compose(s, s1, s2);
        let c0 = self.c_at(j as i64);
        let c1 = self.c_at(j as i64 + 1);
        let c = sj.scale(c1 - c0) + c0;
        let sterm = (pj * TAU).sin().scale(1.0 / TAU);
        pj + c * sterm
    }

    /// Leg phase at which the canonical phase equals `q` (within the stride floor(q)).
    fn phase_of_q(&self, q: f64) -> f64 {
        let j = q.floor();
        let (mut lo, mut hi) = (j, j + 1.0);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if self.warp(Jet::cst(mid)).v < q {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    fn alpha(&self, pj: Jet) -> Jet {
        let up = smoothstep5(pj.v - self.ramp_up_start);
        let down = smoothstep5(self.ramp_down_end - pj.v);
        let a = pj.compose(up.0, up.1, up.2);
        let b = pj.compose(down.0, -down.1, down.2);
        a * b
    }

    /// Shank pitch θ (rad) and ZYX roll φ (rad) from the canonical phase.
    fn angles(&self, sh: &Shared, q: Jet, alpha: Jet) -> (Jet, Jet, Jet) {
        let qf = q - q.v.floor();
        let knee = spline_jet(sh.knee, q);
        let (b, b1, b2) = bump(qf.v, 0.72, 0.2);
        let knee_w = Jet::cst(1.0) - qf.compose(b, b1, b2).scale(self.p.knee_reduction);
        let knee = knee * knee_w;
        let hip = (spline_jet(sh.hip, q) - curves::HIP_MEAN_DEG).scale(self.p.hip_scale)
            + curves::HIP_MEAN_DEG;
        let theta = ((knee - hip) * alpha).scale(std::f64::consts::PI / 180.0);
        let (r, r1, r2) = bump(qf.v, 0.8, 0.2);
        let rho_deg =
            (qf.compose(r, r1, r2).scale(self.p.roll_swing_deg) + self.p.roll_stance_deg) * alpha;
        let rho = rho_deg.scale(std::f64::consts::PI / 180.0);
        let phi = rho.scale(-self.lat);
        (theta, phi, rho)
    }

    /// Ankle position in the progression frame during stance of stride `j`.
    fn stance_ankle(&self, q: Jet, j: usize, alpha: Jet) -> JetVec3 {
        let qf = q - j as f64;
        let xh = self.x_heel[j];
        if qf.v < FOOT_FLAT {
            let u = qf.v / FOOT_FLAT;
            let a = 1.0 - u;
            let f = self.phi_hs * a * a * a;
            let f1 = -3.0 * self.phi_hs * a * a / FOOT_FLAT;
            let f2 = 6.0 * self.phi_hs * a / (FOOT_FLAT * FOOT_FLAT);
            let phi = qf.compose(f, f1, f2) * alpha;
            let (c, s) = (phi.cos(), phi.sin());
            let (dx, dz) = HEEL_TO_ANKLE;
            [
                c.scale(dx) - s.scale(dz) + xh,
                Jet::cst(0.0),
                s.scale(dx) + c.scale(dz),
            ]
        } else if qf.v <= HEEL_OFF {
            [
                Jet::cst(xh + HEEL_TO_ANKLE.0),
                Jet::cst(0.0),
                Jet::cst(HEEL_TO_ANKLE.1),
            ]
        } else {
            let span = TOE_OFF - HEEL_OFF;
            let w = ((qf.v - HEEL_OFF) / span).min(1.0);
            let f = -self.phi_to * (2.5 * w.powi(3) - 1.5 * w.powi(4));
            let f1 = -self.phi_to * (7.5 * w * w - 6.0 * w.powi(3)) / span;
            let f2 = -self.phi_to * (15.0 * w - 18.0 * w * w) / (span * span);
            let phi = qf.compose(f, f1, f2) * alpha;
            let (c, s) = (phi.cos(), phi.sin());
            let (dx, dz) = TOE_TO_ANKLE;
            let toe = xh + HEEL_TO_ANKLE.0 - TOE_TO_ANKLE.0;
            [
                c.scale(dx) - s.scale(dz) + toe,
                Jet::cst(0.0),
                s.scale(dx) + c.scale(dz),
            ]
        }
    }

    /// State at time t: canonical phase, θ, φ, ρ and the ankle in the progression frame.
    fn state(&self, sh: &Shared, t: f64) -> LegState {
        let pj = self.leg_phase(sh, t);
        let q = self.warp(pj);
        let alpha = self.alpha(pj);
        let (theta, phi, rho) = self.angles(sh, q, alpha);
        let j = q.v.floor().max(0.0) as usize;
        let qf = q.v - q.v.floor();
        let ankle = if qf < TOE_OFF || j >= self.swing.len() || self.swing[j].is_none() {
            self.stance_ankle(q, j.min(self.x_heel.len() - 1), alpha)
        } else {
            let sw = self.swing[j].as_ref().expect("checked");
            let s = Jet::time(t).scale(1.0 / (sw.x.t1 - sw.x.t0)) - sw.x.t0 / (sw.x.t1 - sw.x.t0);
            let (b, b1, b2) = bump(s.v, 0.5, 0.5);
            let bj = s.compose(b, b1, b2);
            [
                sw.x.eval(t),
                bj.scale(self.lat * self.p.circumduction_m),
                sw.z.eval(t) + bj.scale(self.p.swing_clearance_m),
            ]
        };
        LegState {
            q: q.v,
            theta,
            phi,
            rho,
            ankle,
        }
    }
}

struct LegState {
    q: f64,
    theta: Jet,
    phi: Jet,
    rho: Jet,
    ankle: JetVec3,
}

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
    pub family_b: Option<super::family_b::SubjectParamsB>,
}

/// Simulate one subject. `rng` draws stride-to-stride variability and the sensor errors.
pub fn simulate_subject(
    params: &SubjectParams,
    sensor: &SensorModel,
    rng: &mut ChaCha8Rng,
) -> Result<SimSubject> {
    params.validate()?;
    sensor.validate()?;
    let std_normal = Normal::new(0.0, 1.0).expect("valid");
    let mut z = || -> f64 { std_normal.sample(rng) };

    // Timeline of the left leg's phase.
    let t0 = params.standing_s;
    let big_t = params.stride_time_s;
    let walk_s = params.duration_s - 2.0 * params.standing_s - 1.8 * big_t;
    let n = (walk_s / big_t).floor() as usize + 1; // heel strikes of the left leg
    if n < 4 {
        return Err(LdhError::param(
            "duration_s",
            params.duration_s,
            format!(
                "too short for 4 strides after {} s of standing at each end",
                params.standing_s
            ),
        ));
    }
    let turn_strides = if params.turn && n >= 8 {
        Some(n / 2 - 1)
    } else {
        None
    };
    let mut durations = Vec::with_capacity(n);
    for k in 1..n {
        let mut d = big_t * (1.0 + params.stride_time_cv * z());
        if let Some(kt) = turn_strides {
            if k >= kt && k < kt + 2 {
                d *= 1.1;
            }
        }
        durations.push(d.clamp(0.6 * big_t, 1.6 * big_t));
    }
    let mut knots = vec![(t0, 0.55, 0.0, 0.0)];
    let mut t = t0 + 0.9 * big_t;
    for k in 1..=n {
        let prev = if k == 1 {
            durations[0]
        } else {
            durations[k - 2]
        };
        let next = if k == n {
            durations[n - 2]
        } else {
            durations[k - 1]
        };
        let v = 2.0 / (prev + next);
        knots.push((t, k as f64, v, 0.0));
        if k < n {
            t += durations[k - 1];
        }
    }
    let t_end = t + 0.9 * big_t;
    knots.push((t_end, n as f64 + 0.55, 0.0, 0.0));
    let phase = PhaseCurve::new(&knots);
    if !phase.is_monotone() {
        return Err(LdhError::param(
            "stride_time_cv",
            params.stride_time_cv,
            "gives a non-monotone gait phase",
        ));
    }
    let heading = Heading {
        turn: turn_strides.map(|kt| {
            (
                phase.time_of(kt as f64).unwrap(),
                phase.time_of(kt as f64 + 2.0).unwrap(),
            )
        }),
    };
    let (knee, hip) = (curves::knee_flexion(), curves::hip_flexion());
    let sh = Shared {
        phase: &phase,
        knee: &knee,
        hip: &hip,
    };

    // Legs: left offset 0, right offset 0.5 + δ.
    let delta = params.step_timing_asymmetry;
    let offsets = [0.0, 0.5 + delta];
    let sides = [Side::Left, Side::Right];
    let n_idx = n + 3;
    let mut legs: Vec<LegModel> = Vec::with_capacity(2);
    for (li, side) in sides.iter().enumerate() {
        let lp = params.leg(*side).clone();
        let c: Vec<f64> = (0..n_idx)
            .map(|_| {
                let s = (lp.stance_ratio + params.stance_ratio_sd * z()).clamp(0.52, 0.72);
                (TOE_OFF - s) * TAU / (TAU * s).sin()
            })
            .collect();
        let off = offsets[li];
        legs.push(LegModel {
            side: *side,
            lat: if *side == Side::Left { 1.0 } else { -1.0 },
            offset: off,
            c,
            x_heel: vec![f64::NAN; n_idx],
            ramp_up_start: 0.55 + off,
            ramp_down_end: n as f64 + 0.55 + off,
            p: lp,
            phi_hs: params.heel_strike_foot_angle_deg.to_radians(),
            phi_to: params.toe_off_foot_angle_deg.to_radians(),
            swing: vec![None; n_idx],
            mount: [[0.0; 3]; 3],
            axial_deg: 0.0,
            tilt_deg: [0.0; 2],
            mirrored: false,
        });
    }

    // Heel placements in time order: L0, R1, L1, R2, …, LN, R(N+1).
    {
        let alpha_at = |leg: &LegModel, p: f64| leg.alpha(Jet::cst(p)).v;
        legs[0].x_heel[0] = 0.0;
        legs[1].x_heel[1] = 0.0;
        let mut x = 0.0;
        for k in 1..=n {
            let factor = |k: usize| -> f64 {
                match turn_strides {
                    Some(kt) if k >= kt && k < kt + 2 => 0.6,
                    _ => 1.0,
                }
            };
            let l = params.stride_length_m * (1.0 + params.stride_length_cv * z()) * factor(k);
            // Left heel strike k (left phase k).
            let step_l =
                0.5 * l * (1.0 - params.step_length_asymmetry) * alpha_at(&legs[0], k as f64);
            x = legs[1].x_heel[k] + step_l;
            legs[0].x_heel[k] = x;
            // Right heel strike k + 1 (right phase k + 1).
            if k < n {
                let step_r = 0.5
                    * l
                    * (1.0 + params.step_length_asymmetry)
                    * alpha_at(&legs[1], (k + 1) as f64);
                legs[1].x_heel[k + 1] = x + step_r;
            } else {
                legs[1].x_heel[k + 1] = x;
            }
        }
        let _ = x;
    }

    // Events and swings.
    let mut events: Vec<(Vec<f64>, Vec<f64>)> = Vec::new();
    for leg in legs.iter_mut() {
        let (j_first, j_last) = if leg.side == Side::Left {
            (0usize, n)
        } else {
            (1usize, n + 1)
        };
        let mut hs = Vec::new();
        let mut to = Vec::new();
        for j in j_first..=j_last {
            if let Some(t) = phase.time_of(j as f64 - leg.offset) {
                if j > j_first {
                    hs.push((j, t));
                }
            }
            if j < j_last {
                let pq = leg.phase_of_q(j as f64 + TOE_OFF);
                if let Some(t) = phase.time_of(pq - leg.offset) {
                    to.push((j, t));
                }
            }
        }
        // Swing quintics from TO_j to HS_{j+1}.
        for &(j, t_to) in &to {
            let Some(&(_, t_hs)) = hs.iter().find(|(jj, _)| *jj == j + 1) else {
                continue;
            };
            let at = |t: f64, jj: usize, leg: &LegModel| -> JetVec3 {
                let pj = leg.leg_phase(&sh, t);
                let q = leg.warp(pj);
                let alpha = leg.alpha(pj);
                leg.stance_ankle(q, jj, alpha)
            };
            let a = at(t_to, j, leg);
            let b = at(t_hs, j + 1, leg);
            leg.swing[j] = Some(Swing {
                x: Quintic::new(t_to, t_hs, a[0], b[0]),
                z: Quintic::new(t_to, t_hs, a[2], b[2]),
            });
        }
        events.push((
            hs.iter().map(|e| e.1).collect(),
            to.iter().map(|e| e.1).collect(),
        ));
        // Mounting.
        let mirrored = sensor.mirrored_right && leg.side == Side::Right;
        let nominal: [[f64; 3]; 3] = if mirrored {
            // columns x_d = e3, y_d = −e1, z_d = −e2
            [[0.0, -1.0, 0.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]]
        } else {
            // columns x_d = e3, y_d = e1, z_d = e2
            [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]
        };
        let axial = rng.gen_range(-1.0..=1.0) * sensor.axial_misalignment_deg_max;
        let tilt = [
            sensor.tilt_misalignment_deg_sd * std_normal.sample(rng),
            sensor.tilt_misalignment_deg_sd * std_normal.sample(rng),
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
        leg.mount = mount;
        leg.axial_deg = axial;
        leg.tilt_deg = tilt;
        leg.mirrored = mirrored;
    }

    // Evaluate on the internal grid.
    let fs = params.fs_hz;
    let n_out = (params.duration_s * fs).round() as usize + 1;
    let h = 1.0 / (fs * OVERSAMPLE as f64);
    let n_int = (n_out - 1) * OVERSAMPLE + 1;
    let mut sim_legs = Vec::with_capacity(2);
    for (li, leg) in legs.iter().enumerate() {
        let (hs_times, to_times) = events[li].clone();
        let mut acc_clean: [Vec<f64>; 3] = Default::default();
        let mut gyro_clean: [Vec<f64>; 3] = Default::default();
        let mut pos: [Vec<f64>; 3] = Default::default();
        let mut vel: [Vec<f64>; 3] = Default::default();
        let mut rwd = Vec::with_capacity(n_out);
        let mut euler: [Vec<f64>; 3] = Default::default();
        let mut pitch = Vec::with_capacity(n_out);
        let mut roll = Vec::with_capacity(n_out);
        let mut yaw = Vec::with_capacity(n_out);
        // Dense per-internal-step pitch / roll and flat-phase ankle positions for stride truth.
        let mut fine_t = Vec::with_capacity(n_int);
        let mut fine_theta = Vec::with_capacity(n_int);
        let mut fine_rho = Vec::with_capacity(n_int);
        let mut heel_pos: Vec<Option<[f64; 2]>> = vec![None; n_idx];
        let lateral0 = leg.lat * HALF_STEP_WIDTH_M;
        let mut world = [0.0f64; 3];
        let mut prev_v = [0.0f64; 3];
        let mut prev_a = [0.0f64; 3];
        let r_f = [
            Jet::cst(0.0),
            Jet::cst(leg.lat * leg.p.sensor_lateral_m),
            Jet::cst(leg.p.sensor_height_m),
        ];
        for i in 0..n_int {
            let t = i as f64 * h;
            let st = leg.state(&sh, t);
            let psi = heading.eval(t);
            let (cp, sp) = (psi.v.cos(), psi.v.sin());
            let rot = |v: [f64; 3]| [cp * v[0] - sp * v[1], sp * v[0] + cp * v[1], v[2]];
            let rot_d = |v: [f64; 3]| [-sp * v[0] - cp * v[1], cp * v[0] - sp * v[1], 0.0];
            let vp = [st.ankle[0].d, st.ankle[1].d, st.ankle[2].d];
            let ap = [st.ankle[0].dd, st.ankle[1].dd, st.ankle[2].dd];
            let v_w = rot(vp);
            let rd = rot_d(vp);
            let a_w: [f64; 3] = std::array::from_fn(|k| rot(ap)[k] + psi.d * rd[k]);
            if i == 0 {
                let p0 = [st.ankle[0].v, st.ankle[1].v + lateral0, st.ankle[2].v];
                world = rot(p0);
            } else {
                for k in 0..3 {
                    world[k] +=
                        0.5 * h * (prev_v[k] + v_w[k]) + h * h / 12.0 * (prev_a[k] - a_w[k]);
                }
            }
            prev_v = v_w;
            prev_a = a_w;
            fine_t.push(t);
            fine_theta.push(st.theta.v.to_degrees());
            fine_rho.push(st.rho.v.to_degrees());
            // Heel contact point of stride j in the world, at its first stance sample:
            // ankle − R(ψ)·(ankle − heel) in the progression frame.
            let qf = st.q - st.q.floor();
            let j = st.q.floor().max(0.0) as usize;
            if qf < TOE_OFF && j < n_idx && heel_pos[j].is_none() && leg.x_heel[j].is_finite() {
                let rel = rot([st.ankle[0].v - leg.x_heel[j], st.ankle[1].v, 0.0]);
                heel_pos[j] = Some([world[0] - rel[0], world[1] - rel[1]]);
            }
            if i % OVERSAMPLE != 0 {
                continue;
            }
            // Sensor kinematics at an output sample.
            let r_wf = mat_mul(&rot_z(psi), &mat_mul(&rot_y(st.theta), &rot_x(st.phi)));
            let off = mat_vec(&r_wf, &r_f);
            let acc_w: [f64; 3] = std::array::from_fn(|k| a_w[k] + off[k].dd);
            let f_w = [acc_w[0], acc_w[1], acc_w[2] + STANDARD_GRAVITY_MPS2];
            let r_fv: [[f64; 3]; 3] =
                std::array::from_fn(|a| std::array::from_fn(|b| r_wf[a][b].v));
            // F coordinates, then device coordinates.
            let f_f: [f64; 3] = std::array::from_fn(|k| (0..3).map(|m| r_fv[m][k] * f_w[m]).sum());
            let f_d: [f64; 3] =
                std::array::from_fn(|k| (0..3).map(|m| leg.mount[m][k] * f_f[m]).sum());
            let w_f = body_rate(&r_wf);
            let w_d: [f64; 3] =
                std::array::from_fn(|k| (0..3).map(|m| leg.mount[m][k] * w_f[m]).sum());
            for k in 0..3 {
                acc_clean[k].push(f_d[k] / STANDARD_GRAVITY_MPS2);
                gyro_clean[k].push(w_d[k].to_degrees());
                pos[k].push(world[k] + off[k].v);
                vel[k].push(v_w[k] + off[k].d);
            }
            let r_wd: [[f64; 3]; 3] = std::array::from_fn(|a| {
                std::array::from_fn(|b| (0..3).map(|m| r_fv[a][m] * leg.mount[m][b]).sum())
            });
            rwd.push(r_wd);
            euler[0].push(st.phi.v);
            euler[1].push(st.theta.v);
            euler[2].push(psi.v);
            pitch.push(st.theta.v.to_degrees());
            roll.push(st.rho.v.to_degrees());
            yaw.push(psi.v.to_degrees());
        }

        // Stride truth.
        let (j_first, _) = if leg.side == Side::Left {
            (0usize, n)
        } else {
            (1usize, n + 1)
        };
        let mut strides = Vec::new();
        for (si, w) in hs_times.windows(2).enumerate() {
            let j = j_first + 1 + si;
            let (t_hs, t_next) = (w[0], w[1]);
            let Some(&t_to) = to_times.iter().find(|&&x| x > t_hs && x < t_next) else {
                continue;
            };
            let (mut mx, mut mn) = (f64::MIN, f64::MAX);
            let (mut rmx, mut rmn) = (f64::MIN, f64::MAX);
            // `fine_t` increases: the stride's samples are one index range (found by bisection,
            // so the truth is linear in the recording's length, not quadratic).
            let at = |t: f64| fine_t.partition_point(|&ft| ft < t);
            for k in at(t_hs)..at(t_next) {
                mx = mx.max(fine_theta[k]);
                mn = mn.min(fine_theta[k]);
            }
            for k in at(t_to)..at(t_next) {
                rmx = rmx.max(fine_rho[k]);
                rmn = rmn.min(fine_rho[k]);
            }
            let length = match (
                heel_pos.get(j).copied().flatten(),
                heel_pos.get(j + 1).copied().flatten(),
            ) {
                (Some(a), Some(b)) => ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt(),
                _ => f64::NAN,
            };
            let turning = heading
                .turn
                .map(|(a, b)| t_next > a && t_hs < b)
                .unwrap_or(false);
            let bout_edge = si == 0 || si + 2 == hs_times.len();
            strides.push(StrideTruth {
                index: j,
                hs_time_s: t_hs,
                to_time_s: t_to,
                next_hs_time_s: t_next,
                stride_time_s: t_next - t_hs,
                stance_ratio: (t_to - t_hs) / (t_next - t_hs),
                stride_length_m: length,
                max_pitch_deg: mx,
                min_pitch_deg: mn,
                roll_swing_excursion_deg: rmx - rmn,
                turning,
                bout_edge,
            });
        }

        // Sensor errors.
        let gyro_bias: [f64; 3] =
            std::array::from_fn(|_| sensor.gyro_bias_dps_sd * std_normal.sample(rng));
        let acc_bias: [f64; 3] =
            std::array::from_fn(|_| sensor.acc_bias_g_sd * std_normal.sample(rng));
        let acc_lsb = sensor.acc_range_g / 2f64.powi(sensor.bits as i32 - 1);
        let gyro_lsb = sensor.gyro_range_dps / 2f64.powi(sensor.bits as i32 - 1);
        let mut saturated = vec![false; n_out];
        let mut measure = |clean: &[Vec<f64>; 3],
                           bias: [f64; 3],
                           noise_sd: f64,
                           lsb: f64,
                           range: f64,
                           sat: &mut Vec<bool>| {
            let mut out: [Vec<f64>; 3] = Default::default();
            for k in 0..3 {
                out[k] = clean[k]
                    .iter()
                    .enumerate()
                    .map(|(i, &v)| {
                        let noisy = if sensor.noise {
                            v + bias[k] + noise_sd * std_normal.sample(rng)
                        } else {
                            v
                        };
                        let qv = if sensor.noise {
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
        };
        let acc_meas = measure(
            &acc_clean,
            acc_bias,
            sensor.acc_noise_g,
            acc_lsb,
            sensor.acc_range_g,
            &mut saturated,
        );
        let gyro_meas = measure(
            &gyro_clean,
            gyro_bias,
            sensor.gyro_noise_dps,
            gyro_lsb,
            sensor.gyro_range_dps,
            &mut saturated,
        );
        let sat_count = saturated.iter().filter(|&&s| s).count();
        let recording = Recording::new(fs, acc_meas, gyro_meas, saturated)?.with_side(leg.side);
        let truth = LegTruth {
            side: leg.side,
            sensor_height_m: leg.p.sensor_height_m,
            sensor: SensorTruth {
                axial_misalignment_deg: leg.axial_deg,
                tilt_misalignment_deg: leg.tilt_deg,
                mirrored: leg.mirrored,
                device_axes_in_f: leg.mount,
                gyro_bias_dps: if sensor.noise { gyro_bias } else { [0.0; 3] },
                acc_bias_g: if sensor.noise { acc_bias } else { [0.0; 3] },
                saturated_samples: sat_count,
            },
            hs_times_s: hs_times,
            to_times_s: to_times,
            strides,
            pitch_deg: pitch,
            roll_deg: roll,
            yaw_deg: yaw,
        };
        sim_legs.push(SimLeg {
            recording,
            truth,
            dense: DenseTruth {
                acc_clean_g: acc_clean,
                gyro_clean_dps: gyro_clean,
                sensor_pos_m: pos,
                sensor_vel_mps: vel,
                r_world_device: rwd,
                euler_rad: euler,
            },
        });
    }
    let right = sim_legs.pop().expect("two legs");
    let left = sim_legs.pop().expect("two legs");
    Ok(SimSubject {
        params: params.clone(),
        left,
        right,
        family_b: None,
    })
}

/// Draw a value from N(mean, sd) clamped to [lo, hi].
pub(crate) fn normal_clamped(rng: &mut ChaCha8Rng, mean: f64, sd: f64, lo: f64, hi: f64) -> f64 {
    let v = Normal::new(mean, sd.max(1e-12)).expect("valid").sample(rng);
    v.clamp(lo, hi)
}
