//! The adaptive Kalman fusion (paper §3.2, eq. 4–15), with two additions that keep it anchored
//! to gravity on real sensors (issue 20):
//!
//! - **Gyroscope bias states.** The state is (φ, θ, ψ, b_x, b_y): the Euler angles and the
//!   bias of the two angular-rate axes that tilt the shank (anterior x: frontal; medio-lateral
//!   y: sagittal), a random walk of `gyro_bias_walk_dps` per √s from a prior of
//!   `gyro_bias_sd_dps`. The accelerometer's tilt observes them through the attitude they make
//!   drift (the classic bias-augmented attitude filter: Foxlin, VRAIS 1996; Sabatini, IEEE TBME
//!   2006;53:1346). The bias about the shank axis only moves the heading, which no
//!   accelerometer observes, and is not estimated. A recording without quiet standing keeps
//!   its full bias otherwise (`align` removes it only from standing): 1–3 deg/s on consumer
//!   MEMS gyroscopes, 60–180° of pitch per minute of plain integration.
//! - **Gravity re-acquisition.** During quasi-static windows ([`super::anchor`]: |a| ≈ 1 g,
//!   slow rotation, ≥ `anchor_window_s`; the foot-flat phases of walking) the tilt update is
//!   never gated out and its noise is capped at `anchor_tilt_noise_deg` per window, however
//!   large the adapted R has grown: without the cap, innovations caused by drift inflate the
//!   Sage–Husa R, which lets the attitude drift further (on real recordings the filter then
//!   integrates the gyroscope alone for minutes). With the RTS smoother the correction at each
//!   foot flat is spread back over the swing before it, so drift cannot accumulate across
//!   strides.

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

mod bank;
mod lanes;
mod products;
mod rts;
#[cfg(test)]
mod rts_accuracy;

use super::anchor::quasi_static_windows;
use super::{acc_tilt, wrap, Attitude, AttitudeModel, AttitudeParams};
use crate::align::Aligned;
use crate::error::{LdhError, Result};
use bank::Bank;
use lanes::{Num, L4, LANES};
use products::{Jacobian, Mat};
use rts::{smooth, SegmentStore, SEGMENT};

type V5 = SVector<f64, 5>;
type M5 = SMatrix<f64, 5, 5>;

/// Euler-angle rates (eq. 7) and their Jacobian with respect to (φ, θ, ψ).
pub(super) fn euler_rates(x: &Vector3<f64>, w: &Vector3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
    let (r, j) = euler_rates_of(&SinCos::of(x[0], x[1]), &[w[0], w[1], w[2]]);
    (Vector3::from(r), Matrix3::from_fn(|a, b| j[a][b]))
}

/// sin φ, cos φ, sin θ and cos θ (kept away from 0) of the tilt angles, of one filter (`f64`)
/// or of four ([`L4`]).
#[derive(Clone, Copy)]
struct SinCos<T = f64> {
    sp: T,
    cp: T,
    st: T,
    ct: T,
}

impl SinCos {
    fn of(phi: f64, theta: f64) -> SinCos {
        let (sp, cp) = phi.sin_cos();
        let (st, ct) = theta.sin_cos();
        let ct = if ct.abs() < 1e-6 {
            1e-6f64.copysign(ct)
        } else {
            ct
        };
        SinCos { sp, cp, st, ct }
    }
}

impl SinCos<L4> {
    /// [`SinCos::of`] lane by lane.
    fn of_lanes(phi: L4, theta: L4) -> SinCos<L4> {
        let mut out = SinCos::<L4> {
            sp: L4::default(),
            cp: L4::default(),
            st: L4::default(),
            ct: L4::default(),
        };
        for l in 0..LANES {
            let s = SinCos::of(phi.0[l], theta.0[l]);
            (out.sp.0[l], out.cp.0[l], out.st.0[l], out.ct.0[l]) = (s.sp, s.cp, s.st, s.ct);
        }
        out
    }

    /// Lane `l`.
    fn lane(&self, l: usize) -> SinCos {
        SinCos {
            sp: self.sp.0[l],
            cp: self.cp.0[l],
            st: self.st.0[l],
            ct: self.ct.0[l],
        }
    }
}

/// [`euler_rates`] from the sines and cosines of the tilt: the rates and the Jacobian as rows.
#[inline(always)]
fn euler_rates_of<T: Num>(sc: &SinCos<T>, w: &[T; 3]) -> ([T; 3], [[T; 3]; 3]) {
    let SinCos { sp, cp, st, ct } = *sc;
    let tt = st / ct;
    let a = sp * w[1] + cp * w[2];
    let b = cp * w[1] - sp * w[2];
    let rates = [w[0] + a * tt, b, a / ct];
    let z = T::splat(0.0);
    let j = [
        [b * tt, a / (ct * ct), z],
        [-a, z, z],
        [b / ct, a * st / (ct * ct), z],
    ];
    (rates, j)
}

/// One prediction step of one filter or four: the state, its covariance and the transition
/// Jacobian. `sc` is [`SinCos::of`] the tilt of `x` (each filter keeps its own: the smoother's
/// prediction from a stored state then needs no trigonometry); `q` the diagonal of Q. Every
/// operation is nalgebra's on the dense F = I + [J·dt | bias columns] (see [`products`]).
#[inline(always)]
fn predict_n<T: Num>(
    x: &[T; 5],
    sc: &SinCos<T>,
    p: &Mat<T>,
    w_mid: &[f64; 3],
    dt: f64,
    q: &[f64; 5],
) -> ([T; 5], Mat<T>, Jacobian<T>) {
    // w − (b_x, b_y, 0): the third component minus 0 is itself
    let wc = [
        T::splat(w_mid[0]) - x[3],
        T::splat(w_mid[1]) - x[4],
        T::splat(w_mid[2]),
    ];
    let (rates, j) = euler_rates_of(sc, &wc);
    let (zero, one, d) = (T::splat(0.0), T::splat(1.0), T::splat(dt));
    // F = I with J·dt added to its upper 3 × 3 (F[1][1] = 1 + 0·dt = 1) and the bias columns:
    // ∂rates/∂b = −(columns x and y of the Euler-rate matrix).
    let SinCos { sp, cp, st, ct } = *sc;
    let f = Jacobian {
        a: [
            [one + j[0][0] * d, zero + j[0][1] * d],
            [zero + j[1][0] * d, one],
            [zero + j[2][0] * d, zero + j[2][1] * d],
        ],
        b03: T::splat(-dt),
        b4: [-sp * st / ct * d, -cp * d, -sp / ct * d],
    };
    let xp = [
        x[0] + rates[0] * d,
        x[1] + rates[1] * d,
        (x[2] + rates[2] * d).wrap(),
        x[3],
        x[4],
    ];
    let mut pp = products::propagate(&f, p);
    for (i, row) in pp.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = *v + T::splat(if i == j { q[i] } else { 0.0 });
        }
    }
    (xp, pp, f)
}

/// [`predict_n`] of one filter on nalgebra values (the smoother's fallback and its tests).
fn predict(x: &V5, sc: &SinCos, p: &M5, w_mid: &[f64; 3], dt: f64, q: &[f64; 5]) -> (V5, M5, M5) {
    let xa: [f64; 5] = std::array::from_fn(|i| x[i]);
    let (xp, pp, f) = predict_n(&xa, sc, &products::rows(p), w_mid, dt, q);
    (V5::from(xp), products::matrix(&pp), f.dense())
}

/// The fixed quantities of one run: inputs, model matrices and parameters.
struct Model<'a> {
    al: &'a Aligned,
    p: &'a AttitudeParams,
    dt: f64,
    /// The diagonal of Q.
    q: [f64; 5],
    r0: f64,
    rlo: f64,
    rhi: f64,
    anchor: Vec<bool>,
    r_anchor: f64,
}

/// What the update of sample k needs from the inputs.
struct Sample {
    z: [f64; 2],
    wm: [f64; 3],
    infl: f64,
    dyn_dev: f64,
    anchor: bool,
}

impl<'a> Model<'a> {
    fn new(al: &'a Aligned, p: &'a AttitudeParams) -> Model<'a> {
        let n = al.acc_g[0].len();
        let dt = 1.0 / al.fs_hz;
        let qa = (p.gyro_noise_dps.to_radians() * dt).powi(2);
        let qb = p.gyro_bias_walk_dps.to_radians().powi(2) * dt;
        let q = [qa, qa, qa, qb, qb];
        let (anchor, anchor_len) = if p.reacquire_gravity {
            quasi_static_windows(
                &al.acc_g,
                &al.gyro_dps,
                al.fs_hz,
                p.anchor_acc_g,
                p.anchor_gyro_dps,
                p.anchor_window_s,
            )
        } else {
            (vec![false; n], 1)
        };
        Model {
            al,
            p,
            dt,
            q,
            r0: p.acc_tilt_noise_deg.to_radians().powi(2),
            rlo: p.acc_tilt_noise_bounds_deg[0].to_radians().powi(2),
            rhi: p.acc_tilt_noise_bounds_deg[1].to_radians().powi(2),
            anchor,
            r_anchor: p.anchor_tilt_noise_deg.to_radians().powi(2) * anchor_len as f64,
        }
    }

    fn f_at(&self, i: usize) -> [f64; 3] {
        let a = &self.al.acc_g;
        [a[0][i], a[1][i], a[2][i]]
    }

    fn w_at(&self, i: usize) -> [f64; 3] {
        let g = &self.al.gyro_dps;
        [g[0][i], g[1][i], g[2][i]].map(|v| v * (std::f64::consts::PI / 180.0))
    }

    /// Angular velocity between samples k − 1 and k, rad/s.
    fn w_mid(&self, k: usize) -> [f64; 3] {
        if k == 0 {
            self.w_at(0)
        } else {
            let (a, b) = (self.w_at(k - 1), self.w_at(k));
            std::array::from_fn(|i| (a[i] + b[i]) * 0.5)
        }
    }

    fn sample(&self, k: usize) -> Sample {
        let (p, g) = (self.p, &self.al.gyro_dps);
        let f = self.f_at(k);
        let norm = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        let dyn_dev = (norm - 1.0).abs();
        let w_norm_dps = (g[0][k].powi(2) + g[1][k].powi(2) + g[2][k].powi(2)).sqrt();
        let infl = 1.0
            + (dyn_dev / p.dynamic_scale_g).powi(2)
            + (w_norm_dps / p.rotation_scale_dps).powi(2);
        let (zphi, zth) = acc_tilt(f);
        Sample {
            z: [zphi, zth],
            wm: self.w_mid(k),
            infl,
            dyn_dev,
            anchor: self.anchor[k],
        }
    }
}

/// Roll, pitch and yaw in degrees, filled one sample at a time.
struct Angles {
    roll: Vec<f64>,
    pitch: Vec<f64>,
    yaw: Vec<f64>,
}

impl Angles {
    fn new(n: usize) -> Angles {
        Angles {
            roll: vec![0.0; n],
            pitch: vec![0.0; n],
            yaw: vec![0.0; n],
        }
    }

    fn set(&mut self, k: usize, x: &V5) {
        self.roll[k] = x[0].to_degrees();
        self.pitch[k] = x[1].to_degrees();
        self.yaw[k] = x[2].to_degrees();
    }
}

/// The fused (and, with `p.smoother`, smoothed) attitude of one aligned recording.
pub(super) fn fusion(al: &Aligned, p: &AttitudeParams) -> Result<Attitude> {
    fusion_segmented(al, p, SEGMENT)
}

/// [`fusion`] with the smoother's storage in segments of `seg_len` samples (the numbers do not
/// depend on it).
fn fusion_segmented(al: &Aligned, p: &AttitudeParams, seg_len: usize) -> Result<Attitude> {
    let n = al.acc_g[0].len();
    if n < 2 {
        return Err(LdhError::signal("attitude", "fewer than 2 samples"));
    }
    let m = Model::new(al, p);
    let mut bank = Bank::new(&m);
    let keep = p.smoother;
    let mut out = Angles::new(n);
    let mut store = SegmentStore::new(&bank, if keep { seg_len.min(n) } else { 0 });
    let mut checkpoints: Vec<Bank> = Vec::new();
    for k in 0..n {
        if keep && k % seg_len == 0 {
            checkpoints.push(bank.clone());
            store.clear();
        }
        bank.step(&m, k);
        if keep {
            store.push(&bank);
        } else {
            out.set(k, &weighted(bank.len(), |i| bank.state(i), &bank.weights));
        }
    }
    let last = weighted(bank.len(), |i| bank.state(i), &bank.weights);
    if keep {
        smooth(&m, &checkpoints, &mut store, seg_len, &mut out);
    }
    Ok(Attitude {
        model: AttitudeModel::Fusion,
        fs_hz: al.fs_hz,
        roll_deg: out.roll,
        pitch_deg: out.pitch,
        yaw_deg: out.yaw,
        final_weights: bank.weights.clone(),
        final_tilt_noise_deg: (0..bank.len())
            .map(|i| {
                let r = bank.tilt_noise(i);
                ((r[0] + r[1]) / 2.0).sqrt().to_degrees()
            })
            .collect(),
        gyro_bias_dps: [last[3].to_degrees(), last[4].to_degrees()],
        gravity_windows: count_runs(&m.anchor),
    })
}

fn count_runs(mask: &[bool]) -> usize {
    mask.windows(2).filter(|w| w[1] && !w[0]).count() + usize::from(mask.first() == Some(&true))
}

/// Weighted mean of the states `x(0..nf)`, angles averaged as offsets from the first (no wrap
/// artefacts).
fn weighted(nf: usize, x: impl Fn(usize) -> V5, w: &[f64]) -> V5 {
    let base = x(0);
    let mut acc = V5::zeros();
    for (i, wi) in w.iter().enumerate().take(nf) {
        let mut d = x(i) - base;
        for i in 0..3 {
            d[i] = wrap(d[i]);
        }
        acc += d * *wi;
    }
    let mut out = base + acc;
    out[2] = wrap(out[2]);
    out
}

#[cfg(test)]
mod tests {
    use super::super::{Attitude, AttitudeParams};
    use super::{fusion_segmented, SEGMENT};
    use crate::align::{align, AlignParams, Aligned};
    use crate::preprocess::{preprocess, PreprocessParams};

    /// The demo cohort's first leg (35 s at 100 Hz), aligned as the pipeline aligns it. (The
    /// accuracy against the true pitch is tested in `ldh-sim`, tests/analysis/fusion.rs.)
    fn demo_walk() -> Aligned {
        let rec = crate::demo::recording("H01/left.csv").unwrap();
        let pre = preprocess(&rec, &PreprocessParams::default().check(rec.fs_hz).unwrap()).unwrap();
        align(&pre, &AlignParams::default().check().unwrap()).unwrap()
    }

    /// The smoother's segments only trade memory for time: any segment length gives the same
    /// attitude bit for bit (the refiltered segments repeat the forward pass exactly).
    #[test]
    fn the_smoothed_attitude_does_not_depend_on_the_segment_length() {
        let mut al = demo_walk();
        al.gyro_dps[1].iter_mut().for_each(|w| *w += 3.0);
        let p = AttitudeParams::default().check().unwrap().params().clone();
        let bits = |a: &Attitude| -> Vec<u64> {
            a.roll_deg
                .iter()
                .chain(&a.pitch_deg)
                .chain(&a.yaw_deg)
                .chain(&a.final_weights)
                .chain(&a.final_tilt_noise_deg)
                .chain(&a.gyro_bias_dps)
                .map(|v| v.to_bits())
                .collect()
        };
        let whole = fusion_segmented(&al, &p, usize::MAX).unwrap();
        // 2 501 samples: one segment by default, 1–2 501 here
        for seg in [1, 7, 1000, 4001, SEGMENT] {
            let a = fusion_segmented(&al, &p, seg).unwrap();
            assert!(bits(&a) == bits(&whole), "segments of {seg} samples");
            assert_eq!(a.gravity_windows, whole.gravity_windows);
        }
    }
}
