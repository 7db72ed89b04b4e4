//! One leg of family A: the per-stride stance warp, heel placements and the leg's state (shank
//! angles and ankle position) at any time (the "Motion" paragraph of [`super`]).

use rand_chacha::ChaCha8Rng;

use super::super::curves::{self, PeriodicSpline, FOOT_FLAT, HEEL_OFF, TOE_OFF};
use super::super::jet::{bump, smoothstep5, Jet, JetVec3, Quintic};
use super::super::sensor::Mounting;
use super::super::{LegParams, SubjectParams};
use super::phase::{PhaseCurve, Timeline};
use super::{std_normal, HEEL_TO_ANKLE, TAU, TOE_TO_ANKLE};
use ldh_core::recording::Side;

/// One swing: ankle x and z in the progression frame between toe off and the next heel strike.
#[derive(Debug, Clone)]
pub(super) struct Swing {
    pub(super) x: Quintic,
    pub(super) z: Quintic,
}

/// Everything needed to evaluate one leg at any time.
#[derive(Debug, Clone)]
pub(super) struct LegModel {
    pub(super) side: Side,
    /// +1 on the left (lateral = +Y), −1 on the right.
    pub(super) lat: f64,
    /// Leg phase = left phase + offset.
    pub(super) offset: f64,
    /// Warp coefficient per stride index.
    c: Vec<f64>,
    /// Heel contact position (progression frame) per stride index.
    pub(super) x_heel: Vec<f64>,
    /// Height of the floor under each stride index's heel contact, m (0 on level ground;
    /// the stair the foot stands on, [`SubjectParams::stair_rise_m`]).
    pub(super) z_heel: Vec<f64>,
    /// [`SubjectParams::stair_rise_m`], m.
    stair_rise_m: f64,
    ramp_up_start: f64,
    ramp_down_end: f64,
    pub(super) p: LegParams,
    phi_hs: f64,
    phi_to: f64,
    /// The swing after each stride's toe off (filled by [`super::events::leg_events`]).
    pub(super) swing: Vec<Option<Swing>>,
    /// The device on this leg (drawn by [`Mounting::draw`]).
    pub(super) mounting: Mounting,
}

/// The curves both legs share: the left gait phase and the normal joint angles.
pub(super) struct Shared<'a> {
    pub(super) phase: &'a PhaseCurve,
    pub(super) knee: &'a PeriodicSpline,
    pub(super) hip: &'a PeriodicSpline,
}

/// A leg at one instant.
pub(super) struct LegState {
    /// Canonical phase q (toe off at stride + 0.60).
    pub(super) q: f64,
    /// Shank pitch θ, rad.
    pub(super) theta: Jet,
    /// ZYX roll φ, rad.
    pub(super) phi: Jet,
    /// Anatomical roll ρ, rad (positive: knee lateral to ankle).
    pub(super) rho: Jet,
    /// Ankle in the progression frame, m.
    pub(super) ankle: JetVec3,
}

fn spline_jet(s: &PeriodicSpline, q: Jet) -> Jet {
    let (f, f1, f2) = s.eval(q.v);
    q.compose(f, f1, f2)
}

/// The two legs (left offset 0, right offset 0.5 + step-timing asymmetry) with their
/// stride-to-stride stance ratios drawn: `n_idx` standard normals per leg, left first, each
/// stance ratio `stance_ratio + stance_ratio_sd · z` clamped to 0.52–0.72. Heel positions,
/// swings and mountings are filled in later.
pub(super) fn build_legs(
    params: &SubjectParams,
    timeline: &Timeline,
    rng: &mut ChaCha8Rng,
) -> Vec<LegModel> {
    let (n, n_idx) = (timeline.n, timeline.n_idx());
    let delta = params.step_timing_asymmetry;
    let offsets = [0.0, 0.5 + delta];
    let sides = [Side::Left, Side::Right];
    let mut legs: Vec<LegModel> = Vec::with_capacity(2);
    for (li, side) in sides.iter().enumerate() {
        let lp = params.leg(*side).clone();
        let c: Vec<f64> = (0..n_idx)
            .map(|_| {
                let s =
                    (lp.stance_ratio + params.stance_ratio_sd * std_normal(rng)).clamp(0.52, 0.72);
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
            z_heel: vec![0.0; n_idx],
            stair_rise_m: params.stair_rise_m,
            ramp_up_start: 0.55 + off,
            ramp_down_end: n as f64 + 0.55 + off,
            p: lp,
            phi_hs: params.heel_strike_foot_angle_deg.to_radians(),
            phi_to: params.toe_off_foot_angle_deg.to_radians(),
            swing: vec![None; n_idx],
            mounting: Mounting::default(),
        });
    }
    legs
}

/// Heel placements in time order: L0, R1, L1, R2, …, LN, R(N+1), in the progression frame, m.
/// Each stride length is `stride_length_m · (1 + stride_length_cv · z)` (× 0.6 over the two
/// turning strides), split into steps by the step-length asymmetry and scaled by the gait ramp.
/// On stairs each heel contact lands one riser (`stair_rise_m`) above (ascent) or below
/// (descent) the other foot's, step over step: the left heel k on riser 2k − 1, the right heel
/// k + 1 on riser 2k, the last step bringing the feet together on one riser. Draws `n`
/// standard normals from `rng`.
pub(super) fn place_heels(
    legs: &mut [LegModel],
    params: &SubjectParams,
    timeline: &Timeline,
    rng: &mut ChaCha8Rng,
) {
    let (n, turn_strides) = (timeline.n, timeline.turn_strides);
    let alpha_at = |leg: &LegModel, p: f64| leg.alpha(Jet::cst(p)).v;
    legs[0].x_heel[0] = 0.0;
    legs[1].x_heel[1] = 0.0;
    for k in 1..=n {
        let factor = |k: usize| -> f64 {
            match turn_strides {
                Some(kt) if k >= kt && k < kt + 2 => 0.6,
                _ => 1.0,
            }
        };
        let l =
            params.stride_length_m * (1.0 + params.stride_length_cv * std_normal(rng)) * factor(k);
        // Left heel strike k (left phase k).
        let step_l = 0.5 * l * (1.0 - params.step_length_asymmetry) * alpha_at(&legs[0], k as f64);
        let x = legs[1].x_heel[k] + step_l;
        legs[0].x_heel[k] = x;
        let rise = params.stair_rise_m;
        legs[0].z_heel[k] = (2 * k - 1) as f64 * rise;
        legs[1].z_heel[k + 1] = (if k < n { 2 * k } else { 2 * k - 1 }) as f64 * rise;
        // Right heel strike k + 1 (right phase k + 1).
        if k < n {
            let step_r =
                0.5 * l * (1.0 + params.step_length_asymmetry) * alpha_at(&legs[1], (k + 1) as f64);
            legs[1].x_heel[k + 1] = x + step_r;
        } else {
            legs[1].x_heel[k + 1] = x;
        }
    }
}

impl LegModel {
    /// The first stride index whose heel strike this leg's events count from: 0 on the left, 1
    /// on the right (the right leg's phase runs half a stride ahead).
    pub(super) fn first_stride(&self) -> usize {
        if self.side == Side::Left {
            0
        } else {
            1
        }
    }

    /// Leg phase P at time `t`, s.
    pub(super) fn leg_phase(&self, sh: &Shared, t: f64) -> Jet {
        sh.phase.eval(t) + self.offset
    }

    fn c_at(&self, j: i64) -> f64 {
        let j = j.clamp(0, self.c.len() as i64 - 1) as usize;
        self.c[j]
    }

    /// Canonical phase q from leg phase P.
    pub(super) fn warp(&self, pj: Jet) -> Jet {
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
    pub(super) fn phase_of_q(&self, q: f64) -> f64 {
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

    /// Gait ramp α(P) in 0–1: up over the first stride, down over the last.
    pub(super) fn alpha(&self, pj: Jet) -> Jet {
        let up = smoothstep5(pj.v - self.ramp_up_start);
        let down = smoothstep5(self.ramp_down_end - pj.v);
        let a = pj.compose(up.0, up.1, up.2);
        let b = pj.compose(down.0, -down.1, down.2);
        a * b
    }

    /// What stairs add to the shank pitch, deg, at the phase `qf` within the stride (0 on
    /// level ground). Ascent: the foot lands on the next stair with hip and knee both flexed
    /// ≈ 60°, the shank near vertical at contact (level walking: ≈ 20° backwards), so up to
    /// 14° forwards around heel strike. Descent: the stance knee flexes to ≈ 85° lowering the
    /// body onto the next stair while the hip stays near 20°, so the shank tilts up to 18° further
    /// forwards in mid to late stance. Riener, Rabuffetti & Frigo, "Stair ascent and descent at
    /// different inclinations", Gait & Posture 15:32–44 (2002); McFadyen & Winter, J Biomech
    /// 21:733–744 (1988).
    fn stair_pitch_deg(&self, qf: Jet) -> Jet {
        if self.stair_rise_m > 0.0 {
            let x = qf - (qf.v + 0.5).floor() + 0.5;
            let (b, b1, b2) = bump(x.v, 0.5, 0.25);
            x.compose(b, b1, b2).scale(14.0)
        } else if self.stair_rise_m < 0.0 {
            let (b, b1, b2) = bump(qf.v, 0.4, 0.25);
            qf.compose(b, b1, b2).scale(18.0)
        } else {
            Jet::cst(0.0)
        }
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
        let theta =
            ((knee - hip + self.stair_pitch_deg(qf)) * alpha).scale(std::f64::consts::PI / 180.0);
        let (r, r1, r2) = bump(qf.v, 0.8, 0.2);
        let rho_deg =
            (qf.compose(r, r1, r2).scale(self.p.roll_swing_deg) + self.p.roll_stance_deg) * alpha;
        let rho = rho_deg.scale(std::f64::consts::PI / 180.0);
        let phi = rho.scale(-self.lat);
        (theta, phi, rho)
    }

    /// Ankle position in the progression frame during stance of stride `j`.
    pub(super) fn stance_ankle(&self, q: Jet, j: usize, alpha: Jet) -> JetVec3 {
        let qf = q - j as f64;
        let xh = self.x_heel[j];
        let zh = self.z_heel[j];
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
                s.scale(dx) + c.scale(dz) + zh,
            ]
        } else if qf.v <= HEEL_OFF {
            [
                Jet::cst(xh + HEEL_TO_ANKLE.0),
                Jet::cst(0.0),
                Jet::cst(HEEL_TO_ANKLE.1 + zh),
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
                s.scale(dx) + c.scale(dz) + zh,
            ]
        }
    }

    /// State at time t: canonical phase, θ, φ, ρ and the ankle in the progression frame.
    pub(super) fn state(&self, sh: &Shared, t: f64) -> LegState {
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
