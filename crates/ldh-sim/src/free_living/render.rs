//! The signals of each planned [`Motion`], in the shank frame F (e1 anterior, e2 left, e3 up
//! along the shank; [`crate::model`]): specific force in g and angular velocity in deg/s,
//! before the device's mounting, bias and noise ([`super::stream`]).
//!
//! - Worn rest: the posture's gravity direction with a slow postural sway of the shank about
//!   e2 (0.3° at 0.05 Hz plus 0.15° at 0.21 Hz), so a worn still sensor is never perfectly still.
//! - Non-wear: the gravity direction fixed in the device frame, no motion at all.
//! - Cycling: the ankle on a crank circle of 0.17 m turning at the cadence (≈ 1 Hz; centripetal
//!   acceleration ω²r), the shank pitch oscillating with it, the legs half a turn apart; no
//!   impacts.
//! - Fidgeting: a Hann-windowed sum of three sinusoids (0.8–5 Hz, 1–8°) of shank pitch about
//!   the knee (radius 0.35 m: tangential and centripetal acceleration).
//! - Gait: the family A model with an ideal sensor; running adds a heel impact along the shank
//!   at each heel strike (peak 4–7 g, 12 ms rise: tibial shock of running, Lafortune et al.,
//!   J Biomech 1996).

use rand_chacha::ChaCha8Rng;

use super::plan::Motion;
use crate::{simulate_subject, SensorModel};
use ldh_core::error::Result;

const G_MPS2: f64 = 9.80665;
const CRANK_M: f64 = 0.17;
const KNEE_TO_SENSOR_M: f64 = 0.35;

/// Samples of one leg in F: specific force (g) and angular velocity (deg/s), per axis.
#[derive(Debug, Clone, Default)]
pub(super) struct LegSignal {
    pub acc_g: [Vec<f64>; 3],
    pub gyro_dps: [Vec<f64>; 3],
}

impl LegSignal {
    pub fn len(&self) -> usize {
        self.acc_g[0].len()
    }
    pub fn clear(&mut self) {
        for k in 0..3 {
            self.acc_g[k].clear();
            self.gyro_dps[k].clear();
        }
    }
    fn push(&mut self, a: [f64; 3], w: [f64; 3]) {
        for k in 0..3 {
            self.acc_g[k].push(a[k]);
            self.gyro_dps[k].push(w[k]);
        }
    }
    /// Samples `from..to` of `other` appended (the last sample repeated past its end).
    pub fn extend_from(&mut self, other: &LegSignal, from: usize, to: usize) {
        let n = other.len();
        for i in from..to {
            let j = i.min(n.saturating_sub(1));
            for k in 0..3 {
                self.acc_g[k].push(other.acc_g[k][j]);
                self.gyro_dps[k].push(other.gyro_dps[k][j]);
            }
        }
    }
}

/// `u` (a vector in F) seen from F rotated by `a` rad about e2.
fn rot_e2(u: [f64; 3], a: f64) -> [f64; 3] {
    let (s, c) = a.sin_cos();
    [c * u[0] - s * u[2], u[1], s * u[0] + c * u[2]]
}

/// Render `n` samples of an analytic motion from `t0_s` s into its segment of `dur_s` s,
/// appending to `out` (left, right). `mounts` are the device axes in F (columns) per leg.
pub(super) fn render_analytic(
    motion: &Motion,
    t0_s: f64,
    dur_s: f64,
    n: usize,
    fs_hz: f64,
    mounts: &[[[f64; 3]; 3]; 2],
    out: &mut [LegSignal; 2],
) {
    for (leg, sig) in out.iter_mut().enumerate() {
        for i in 0..n {
            let t = t0_s + i as f64 / fs_hz;
            let (a, w) = sample(motion, leg, t, dur_s, &mounts[leg]);
            sig.push(a, w);
        }
    }
}

/// One sample of leg `leg` (0 left, 1 right) at `t` s into the segment.
fn sample(
    motion: &Motion,
    leg: usize,
    t: f64,
    dur_s: f64,
    mount: &[[f64; 3]; 3],
) -> ([f64; 3], [f64; 3]) {
    use std::f64::consts::TAU;
    match motion {
        Motion::Rest { up_f } => {
            let ph = leg as f64 * 1.3;
            let (w1, w2) = (TAU * 0.05, TAU * 0.21);
            let a = (0.3 * (w1 * t + ph).sin() + 0.15 * (w2 * t + ph).sin()).to_radians();
            let da = 0.3 * w1 * (w1 * t + ph).cos() + 0.15 * w2 * (w2 * t + ph).cos();
            (rot_e2(up_f[leg], a), [0.0, da, 0.0])
        }
        Motion::Table { up_device } => {
            let v = up_device[leg];
            let f: [f64; 3] = std::array::from_fn(|r| (0..3).map(|c| mount[r][c] * v[c]).sum());
            (f, [0.0; 3])
        }
        Motion::Cycling {
            cadence_hz,
            mean_pitch_deg,
            amp_pitch_deg,
        } => {
            let om = TAU * cadence_hz;
            let ph = om * t + leg as f64 * std::f64::consts::PI;
            let th = (mean_pitch_deg + amp_pitch_deg * ph.sin()).to_radians();
            let dth = amp_pitch_deg * om * ph.cos();
            let acc = om * om * CRANK_M / G_MPS2;
            let fw = [-acc * ph.cos(), 0.0, 1.0 - acc * ph.sin()];
            let (s, c) = th.sin_cos();
            (
                [c * fw[0] - s * fw[2], 0.0, s * fw[0] + c * fw[2]],
                [0.0, dth, 0.0],
            )
        }
        Motion::Fidget {
            up_f,
            moving,
            freq_hz,
            amp_deg,
            phase,
        } => {
            if !moving[leg] {
                return sample(&Motion::Rest { up_f: *up_f }, leg, t, dur_s, mount);
            }
            let alpha = |t: f64| {
                let w = 0.5 * (1.0 - (TAU * t / dur_s).cos());
                let s: f64 = (0..3)
                    .map(|j| amp_deg[j] * (TAU * freq_hz[j] * t + phase[j]).sin())
                    .sum();
                (w * s).to_radians()
            };
            let h = 1e-3;
            let (a0, am, ap) = (alpha(t), alpha(t - h), alpha(t + h));
            let da = (ap - am) / (2.0 * h);
            let dda = (ap - 2.0 * a0 + am) / (h * h);
            let f = rot_e2(up_f[leg], a0);
            let lin = [
                -KNEE_TO_SENSOR_M * dda / G_MPS2,
                0.0,
                KNEE_TO_SENSOR_M * da * da / G_MPS2,
            ];
            (
                [f[0] + lin[0], f[1], f[2] + lin[2]],
                [0.0, da.to_degrees(), 0.0],
            )
        }
        Motion::Gait { .. } => unreachable!("gait bouts are simulated whole"),
    }
}

/// A simulated gait bout: both legs' signals in F and their heel strikes (s from the
/// segment's start).
pub(super) struct GaitBout {
    pub legs: [LegSignal; 2],
    pub hs_s: [Vec<f64>; 2],
}

/// Simulate a gait segment with the family A model (ideal sensor, unclipped) and convert its
/// device axes (x = e3, y = e1, z = e2 for both legs) to F; add heel impacts when
/// `impact_g` > 0.
pub(super) fn render_gait(
    params: &crate::SubjectParams,
    impact_g: f64,
    rng: &mut ChaCha8Rng,
) -> Result<GaitBout> {
    let sensor = SensorModel::ideal()
        .acc_range_g(1000.0)
        .gyro_range_dps(100_000.0);
    let s = simulate_subject(params, &sensor, rng)?;
    let fs = params.fs_hz;
    let mut legs: [LegSignal; 2] = Default::default();
    let mut hs_s: [Vec<f64>; 2] = Default::default();
    for (k, leg) in [&s.left, &s.right].into_iter().enumerate() {
        let r = &leg.recording;
        let mut sig = LegSignal::default();
        for (f, d) in [(0, 1), (1, 2), (2, 0)] {
            sig.acc_g[f] = r.acc_g[d].clone();
            sig.gyro_dps[f] = r.gyro_dps[d].clone();
        }
        if impact_g > 0.0 {
            add_impacts(&mut sig, &leg.truth.hs_times_s, impact_g, fs);
        }
        legs[k] = sig;
        hs_s[k] = leg.truth.hs_times_s.clone();
    }
    Ok(GaitBout { legs, hs_s })
}

/// A heel impact along the shank (e3) at each heel strike: `peak_g`·(τ/τ₀)·e^(1 − τ/τ₀),
/// τ₀ = 12 ms, over 120 ms; half of it backwards along e1.
fn add_impacts(sig: &mut LegSignal, hs_s: &[f64], peak_g: f64, fs: f64) {
    let tau0 = 0.012;
    let n = sig.len();
    for &h in hs_s {
        let i0 = (h * fs).ceil() as usize;
        let i1 = (((h + 0.12) * fs).ceil() as usize).min(n);
        for i in i0..i1 {
            let tau = i as f64 / fs - h;
            let p = peak_g * (tau / tau0) * (1.0 - tau / tau0).exp();
            sig.acc_g[2][i] += p;
            sig.acc_g[0][i] -= 0.5 * p;
        }
    }
}
