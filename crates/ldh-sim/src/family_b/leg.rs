//! One leg of a family B subject: phase, angles, ankle path, sensor kinematics.

use nalgebra::{Matrix3, Rotation3, Vector3};

use super::kin::{
    bump3, diff2, hs_transient, r_wf, rolling_ankle, s5, FootRoll, Fourier, Hermite5, Phase,
    CANON_TO,
};
use super::LegParamsB;
use ldh_core::recording::STANDARD_GRAVITY_MPS2;

/// Half the step width: lateral distance of each ankle from the line of progression, m.
pub const HALF_STEP_WIDTH_M: f64 = 0.08;
const H_POS: f64 = 1e-3;
const H_ROT: f64 = 1e-4;

/// Heading and belt shared by both legs.
#[derive(Debug, Clone, Copy)]
pub struct Walk {
    /// Turn of π between these times.
    pub turn: Option<(f64, f64)>,
    /// Treadmill belt: (speed m/s, ramp start, ramp end, stride time for the ramp and ripple,
    /// ripple fraction).
    pub belt: Option<(f64, f64, f64, f64, f64)>,
}

impl Walk {
    /// Heading ψ, rad.
    pub fn psi(&self, t: f64) -> f64 {
        match self.turn {
            Some((a, b)) => std::f64::consts::PI * s5((t - a) / (b - a)),
            None => 0.0,
        }
    }
    /// Belt speed, m/s (0 overground).
    pub fn belt(&self, t: f64) -> f64 {
        match self.belt {
            Some((v, a, b, d, ripple)) => {
                let ramp = s5((t - a) / d) * s5((b - t) / d);
                v * ramp * (1.0 + ripple * (std::f64::consts::TAU * 2.0 * (t - a) / d).sin())
            }
            None => 0.0,
        }
    }
}

/// The evaluable model of one leg.
#[derive(Debug, Clone)]
pub struct LegModelB {
    /// +1 left, −1 right.
    pub lat: f64,
    /// Leg phase (k at heel strike k, k from −1).
    pub phase: Phase,
    /// Last heel strike index n.
    pub n: i64,
    /// Stance fraction per stride k (index k + 1).
    pub stance: Vec<f64>,
    /// Flat-foot ankle position along progression per stride k (index k + 1), m.
    pub place: Vec<f64>,
    /// Swing k (index k + 1): x and z Hermites, toe off and heel strike times.
    pub swing: Vec<Option<(Hermite5, Hermite5, f64, f64)>>,
    /// Parameters.
    pub p: LegParamsB,
    /// Foot roll.
    pub foot: FootRoll,
    /// Shank curve.
    pub curve: Fourier,
    /// Heel strike times k = 0..=n.
    pub hs: Vec<f64>,
    /// Device axes in F (columns).
    pub mount: Matrix3<f64>,
}

impl LegModelB {
    fn idx(&self, k: i64) -> usize {
        (k.clamp(-1, self.n + 1) + 1) as usize
    }
    /// Stance fraction of stride k.
    pub fn s(&self, k: i64) -> f64 {
        self.stance[self.idx(k)]
    }
    /// Gait envelope: 0 standing, 1 walking, C² ramps over the first and last stance.
    pub fn alpha(&self, phi: f64) -> f64 {
        s5((phi + 1.0) / self.s(-1)) * s5((self.n as f64 + self.s(self.n) - phi) / self.s(self.n))
    }
    /// Canonical cycle fraction from the leg phase (toe off mapped to [`CANON_TO`]).
    pub fn canon(&self, phi: f64) -> f64 {
        let k = phi.floor();
        let u = phi - k;
        let s = self.s(k as i64);
        let ms = 0.5 * (CANON_TO / s + (1.0 - CANON_TO) / (1.0 - s));
        let herm = |x: f64, h: f64, y0: f64, y1: f64, m0: f64, m1: f64| {
            let w = x / h;
            let (h00, h10) = (
                2.0 * w.powi(3) - 3.0 * w * w + 1.0,
                w.powi(3) - 2.0 * w * w + w,
            );
            let (h01, h11) = (-2.0 * w.powi(3) + 3.0 * w * w, w.powi(3) - w * w);
            h00 * y0 + h10 * h * m0 + h01 * y1 + h11 * h * m1
        };
        if u < s {
            herm(u, s, 0.0, CANON_TO, 1.0, ms)
        } else {
            herm(u - s, 1.0 - s, CANON_TO, 1.0, ms, 1.0)
        }
    }
    /// Shank pitch θ and anatomical roll ρ, rad.
    pub fn angles(&self, t: f64) -> (f64, f64) {
        let phi = self.phase.eval(t);
        let a = self.alpha(phi);
        let c = self.canon(phi);
        let mean = self.curve.mean();
        let peak = self.curve.eval(0.67) - mean;
        let gait = mean + self.p.amplitude * (self.curve.eval(c) - mean)
            - self.p.amplitude * self.p.stiff_knee * peak * bump3((c - 0.55) / 0.26);
        let theta = (1.0 - a) * self.p.standing_pitch_deg + a * gait;
        let rho = self.p.roll_stance_deg
            + a * self.p.roll_swing_deg * bump3((c - CANON_TO) / (1.0 - CANON_TO));
        (theta.to_radians(), rho.to_radians())
    }
    /// Ankle in the progression frame during (or extrapolating) the stance of stride k.
    pub fn stance_ankle(&self, k: i64, t: f64) -> [f64; 3] {
        let phi = self.phase.eval(t);
        let v = (phi - k as f64) / self.s(k);
        let g = self.alpha(phi) * self.foot.angle(v);
        let [x, z] = rolling_ankle(self.place[self.idx(k)], g);
        [x, self.lat * HALF_STEP_WIDTH_M, z]
    }
    /// Ankle in the progression frame at time t.
    pub fn ankle(&self, t: f64) -> [f64; 3] {
        let phi = self.phase.eval(t);
        let k = (phi.floor() as i64).clamp(-1, self.n);
        if let Some((hx, hz, t_to, t_hs)) = self.swing[self.idx(k)] {
            if t > t_to && t < t_hs {
                let s = (t - t_to) / (t_hs - t_to);
                let b = bump3(s);
                return [
                    hx.eval(t),
                    self.lat * (HALF_STEP_WIDTH_M + self.p.circumduction_m * b),
                    hz.eval(t) + self.p.swing_clearance_m * b,
                ];
            }
        }
        self.stance_ankle(k, t)
    }
    /// Build the swing of stride k from its toe off to heel strike k + 1.
    pub fn build_swing(&mut self, k: i64) -> (f64, f64) {
        let t_to = self.phase.time_of(k as f64 + self.s(k));
        let t_hs = self.phase.time_of((k + 1) as f64);
        let a = diff2(|t| self.stance_ankle(k, t), t_to, 1e-4);
        let b = diff2(|t| self.stance_ankle(k + 1, t), t_hs, 1e-4);
        let hx = Hermite5::new(
            t_to,
            t_hs,
            [a[0][0], a[1][0], a[2][0]],
            [b[0][0], b[1][0], b[2][0]],
        );
        let hz = Hermite5::new(
            t_to,
            t_hs,
            [a[0][2], a[1][2], a[2][2]],
            [b[0][2], b[1][2], b[2][2]],
        );
        let i = self.idx(k);
        self.swing[i] = Some((hx, hz, t_to, t_hs));
        (t_to, t_hs)
    }
    /// Ankle velocity in the world (heading-rotated progression velocity minus the belt).
    pub fn ankle_vel_world(&self, walk: &Walk, t: f64) -> Vector3<f64> {
        let (a, b) = (self.ankle(t - H_POS), self.ankle(t + H_POS));
        let v = Vector3::new(
            (b[0] - a[0]) / (2.0 * H_POS),
            (b[1] - a[1]) / (2.0 * H_POS),
            (b[2] - a[2]) / (2.0 * H_POS),
        );
        let r = Rotation3::from_axis_angle(&Vector3::z_axis(), walk.psi(t));
        r * v - Vector3::new(walk.belt(t), 0.0, 0.0)
    }
    /// Soft-tissue displacement of the sensor (in F, m) and its rotation about e2 (rad).
    fn transient(&self, t: f64) -> (Vector3<f64>, f64) {
        let i = self.hs.partition_point(|&h| h <= t);
        if i == 0 {
            return (Vector3::zeros(), 0.0);
        }
        let w = hs_transient(t - self.hs[i - 1], self.p.hs_transient_hz, 0.03);
        let a = self.p.hs_transient_mm * 1e-3 * w;
        (
            Vector3::new(0.8 * a, 0.0, 0.6 * a),
            self.p.hs_transient_rot_deg.to_radians() * w,
        )
    }
    /// Shank frame at t.
    pub fn r_wf(&self, walk: &Walk, t: f64) -> Matrix3<f64> {
        let (theta, rho) = self.angles(t);
        r_wf(walk.psi(t), theta, -self.lat * rho)
    }
    /// World ← device at t (soft-tissue rotation included).
    pub fn r_wd(&self, walk: &Walk, t: f64) -> Matrix3<f64> {
        let eps = self.transient(t).1;
        self.r_wf(walk, t)
            * Rotation3::from_axis_angle(&Vector3::y_axis(), eps).into_inner()
            * self.mount
    }
    /// Sensor from the ankle in the world, m.
    pub fn lever(&self, walk: &Walk, t: f64) -> Vector3<f64> {
        let r_f = Vector3::new(
            self.p.sensor_anterior_m,
            self.lat * self.p.sensor_lateral_m,
            self.p.sensor_height_m,
        ) + self.transient(t).0;
        self.r_wf(walk, t) * r_f
    }
    /// Clean specific force (g) and angular velocity (deg/s) in the device frame, and R_wD.
    pub fn measure(&self, walk: &Walk, t: f64) -> ([f64; 3], [f64; 3], Matrix3<f64>) {
        let a_ankle = (self.ankle_vel_world(walk, t + H_POS)
            - self.ankle_vel_world(walk, t - H_POS))
            / (2.0 * H_POS);
        let a_lever = (self.lever(walk, t + H_POS) - 2.0 * self.lever(walk, t)
            + self.lever(walk, t - H_POS))
            / (H_POS * H_POS);
        let f_w = a_ankle + a_lever + Vector3::new(0.0, 0.0, STANDARD_GRAVITY_MPS2);
        let r = self.r_wd(walk, t);
        let f_d = r.transpose() * f_w / STANDARD_GRAVITY_MPS2;
        let w_d = super::kin::body_rate(|x| self.r_wd(walk, x), t, H_ROT);
        (
            [f_d[0], f_d[1], f_d[2]],
            [
                w_d[0].to_degrees(),
                w_d[1].to_degrees(),
                w_d[2].to_degrees(),
            ],
            r,
        )
    }
}
