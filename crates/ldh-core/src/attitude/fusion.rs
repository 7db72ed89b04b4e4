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

use nalgebra::{Matrix2, Matrix3, SMatrix, SVector, Vector2, Vector3};

use super::anchor::quasi_static_windows;
use super::{acc_tilt, wrap, Attitude, AttitudeModel, AttitudeParams};
use crate::align::Aligned;
use crate::error::{LdhError, Result};

type V5 = SVector<f64, 5>;
type M5 = SMatrix<f64, 5, 5>;
type M2x5 = SMatrix<f64, 2, 5>;
type M5x2 = SMatrix<f64, 5, 2>;

/// Euler-angle rates (eq. 7) and their Jacobian with respect to (φ, θ, ψ).
pub(super) fn euler_rates(x: &Vector3<f64>, w: &Vector3<f64>) -> (Vector3<f64>, Matrix3<f64>) {
    let (sp, cp) = x[0].sin_cos();
    let (st, ct) = x[1].sin_cos();
    let ct = if ct.abs() < 1e-6 {
        1e-6f64.copysign(ct)
    } else {
        ct
    };
    let tt = st / ct;
    let a = sp * w[1] + cp * w[2];
    let b = cp * w[1] - sp * w[2];
    let rates = Vector3::new(w[0] + a * tt, b, a / ct);
    let j = Matrix3::new(
        b * tt,
        a / (ct * ct),
        0.0,
        -a,
        0.0,
        0.0,
        b / ct,
        a * st / (ct * ct),
        0.0,
    );
    (rates, j)
}

/// One prediction step: the state, its covariance and the transition Jacobian.
fn predict(x: &V5, p: &M5, w_mid: &Vector3<f64>, dt: f64, q: &M5) -> (V5, M5, M5) {
    let wc = w_mid - Vector3::new(x[3], x[4], 0.0);
    let ang = Vector3::new(x[0], x[1], x[2]);
    let (rates, j) = euler_rates(&ang, &wc);
    let mut f = M5::identity();
    let mut fa = f.fixed_view_mut::<3, 3>(0, 0);
    fa += j * dt;
    // ∂rates/∂b = −(columns x and y of the Euler-rate matrix).
    let (sp, cp) = x[0].sin_cos();
    let (st, ct) = x[1].sin_cos();
    let ct = if ct.abs() < 1e-6 {
        1e-6f64.copysign(ct)
    } else {
        ct
    };
    f[(0, 3)] = -dt;
    f[(0, 4)] = -sp * st / ct * dt;
    f[(1, 4)] = -cp * dt;
    f[(2, 4)] = -sp / ct * dt;
    let mut xp = *x;
    for i in 0..3 {
        xp[i] += rates[i] * dt;
    }
    xp[2] = wrap(xp[2]);
    (xp, f * p * f.transpose() + q, f)
}

struct Filter {
    x: V5,
    p: M5,
    r: Matrix2<f64>,
    gate2: f64,
    logw: f64,
    rejected: usize,
    // For the smoother (the predictions are recomputed in the backward pass).
    xs: Vec<V5>,
    ps: Vec<M5>,
}

pub(super) fn fusion(al: &Aligned, p: &AttitudeParams) -> Result<Attitude> {
    let n = al.acc_g[0].len();
    if n < 2 {
        return Err(LdhError::signal("attitude", "fewer than 2 samples"));
    }
    let dt = 1.0 / al.fs_hz;
    let mut h = M2x5::zeros();
    h[(0, 0)] = 1.0;
    h[(1, 1)] = 1.0;
    let f_at = |i: usize| [al.acc_g[0][i], al.acc_g[1][i], al.acc_g[2][i]];
    let w_at = |i: usize| {
        Vector3::new(al.gyro_dps[0][i], al.gyro_dps[1][i], al.gyro_dps[2][i])
            * (std::f64::consts::PI / 180.0)
    };
    let w_mid = |k: usize| {
        if k == 0 {
            w_at(0)
        } else {
            (w_at(k - 1) + w_at(k)) * 0.5
        }
    };
    let mut q = M5::zeros();
    let qa = (p.gyro_noise_dps.to_radians() * dt).powi(2);
    let qb = p.gyro_bias_walk_dps.to_radians().powi(2) * dt;
    for i in 0..5 {
        q[(i, i)] = if i < 3 { qa } else { qb };
    }
    let r0 = p.acc_tilt_noise_deg.to_radians().powi(2);
    let (rlo, rhi) = (
        p.acc_tilt_noise_bounds_deg[0].to_radians().powi(2),
        p.acc_tilt_noise_bounds_deg[1].to_radians().powi(2),
    );
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
    let r_anchor = p.anchor_tilt_noise_deg.to_radians().powi(2) * anchor_len as f64;
    let (phi0, th0) = acc_tilt(f_at(0));
    let x0 = V5::from_column_slice(&[phi0, th0, 0.0, 0.0, 0.0]);
    let b0 = p.gyro_bias_sd_dps.to_radians().powi(2);
    let p0 = M5::from_diagonal(&V5::from_column_slice(&[r0, r0, 1e-6, b0, b0]));
    let keep = p.smoother;
    let mut bank: Vec<Filter> = p
        .gates_sigma
        .iter()
        .map(|g| Filter {
            x: x0,
            p: p0,
            r: Matrix2::from_diagonal_element(r0),
            gate2: g * g,
            logw: 0.0,
            rejected: 0,
            xs: Vec::with_capacity(if keep { n } else { 0 }),
            ps: Vec::with_capacity(if keep { n } else { 0 }),
        })
        .collect();
    let mut weights_t: Vec<Vec<f64>> = Vec::with_capacity(n);
    let mut fused: Vec<V5> = Vec::with_capacity(n);
    let b = p.forgetting;
    let mut bpow = 1.0;
    for k in 0..n {
        let f = f_at(k);
        let norm = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
        let dyn_dev = (norm - 1.0).abs();
        let w_norm_dps =
            (al.gyro_dps[0][k].powi(2) + al.gyro_dps[1][k].powi(2) + al.gyro_dps[2][k].powi(2))
                .sqrt();
        let infl = 1.0
            + (dyn_dev / p.dynamic_scale_g).powi(2)
            + (w_norm_dps / p.rotation_scale_dps).powi(2);
        let (zphi, zth) = acc_tilt(f);
        let z = Vector2::new(zphi, zth);
        let wm = w_mid(k);
        bpow *= b;
        let d_k = (1.0 - b) / (1.0 - bpow);
        for flt in bank.iter_mut() {
            let (xp, pp) = if k == 0 {
                (flt.x, flt.p)
            } else {
                let (xp, pp, _) = predict(&flt.x, &flt.p, &wm, dt, &q);
                (xp, pp)
            };
            let mut nu = z - h * xp;
            nu[0] = wrap(nu[0]);
            nu[1] = wrap(nu[1]);
            let hph = h * pp * h.transpose();
            let mut rk = flt.r * infl;
            if anchor[k] {
                // Gravity re-acquisition: the tilt is trusted to σ_anchor per window.
                for i in 0..2 {
                    rk[(i, i)] = rk[(i, i)].min(r_anchor);
                }
            }
            let s = hph + rk;
            let s_inv = s
                .try_inverse()
                .unwrap_or_else(|| Matrix2::from_diagonal_element(1.0 / r0));
            let d2 = (nu.transpose() * s_inv * nu)[0];
            let det = s.determinant().max(1e-300);
            flt.logw += -0.5 * d2 - 0.5 * (det * (std::f64::consts::TAU).powi(2)).ln();
            let reacquire = flt.rejected as f64 * dt >= p.reacquire_s;
            let (xu, pu) = if d2 <= flt.gate2 || reacquire || anchor[k] {
                flt.rejected = 0;
                let kg: M5x2 = pp * h.transpose() * s_inv;
                let ikh = M5::identity() - kg * h;
                let xu = xp + kg * nu;
                let pu = ikh * pp * ikh.transpose() + kg * rk * kg.transpose();
                // Sage–Husa adaptation of R from quasi-static innovations.
                if dyn_dev < 2.0 * p.dynamic_scale_g {
                    for i in 0..2 {
                        let est = nu[i] * nu[i] - hph[(i, i)];
                        let v = ((1.0 - d_k) * flt.r[(i, i)] + d_k * est).clamp(rlo, rhi);
                        flt.r[(i, i)] = v;
                    }
                }
                (xu, pu)
            } else {
                flt.rejected += 1;
                (xp, pp)
            };
            flt.x = xu;
            flt.x[2] = wrap(flt.x[2]);
            flt.p = pu;
            if keep {
                flt.xs.push(flt.x);
                flt.ps.push(flt.p);
            }
        }
        let w = bank_weights(&mut bank, p.min_weight);
        fused.push(weighted(&bank.iter().map(|f| f.x).collect::<Vec<_>>(), &w));
        weights_t.push(w);
    }
    let final_bias = fused
        .last()
        .map_or([0.0; 2], |x| [x[3].to_degrees(), x[4].to_degrees()]);
    if keep {
        smooth(&bank, &mut fused, &weights_t, &w_mid, dt, &q);
    }
    Ok(Attitude {
        model: AttitudeModel::Fusion,
        fs_hz: al.fs_hz,
        roll_deg: fused.iter().map(|x| x[0].to_degrees()).collect(),
        pitch_deg: fused.iter().map(|x| x[1].to_degrees()).collect(),
        yaw_deg: fused.iter().map(|x| x[2].to_degrees()).collect(),
        final_weights: weights_t.last().cloned().unwrap_or_default(),
        final_tilt_noise_deg: bank
            .iter()
            .map(|f| ((f.r[(0, 0)] + f.r[(1, 1)]) / 2.0).sqrt().to_degrees())
            .collect(),
        gyro_bias_dps: final_bias,
        gravity_windows: count_runs(&anchor),
    })
}

/// Normalised likelihood weights with a floor (eq. 15); the filters' log-weights are reset to
/// them.
fn bank_weights(bank: &mut [Filter], floor: f64) -> Vec<f64> {
    let mx = bank.iter().map(|f| f.logw).fold(f64::MIN, f64::max);
    let mut w: Vec<f64> = bank.iter().map(|f| (f.logw - mx).exp()).collect();
    let sum: f64 = w.iter().sum();
    w.iter_mut().for_each(|x| *x /= sum);
    w.iter_mut().for_each(|x| *x = x.max(floor));
    let sum: f64 = w.iter().sum();
    w.iter_mut().for_each(|x| *x /= sum);
    for (f, wi) in bank.iter_mut().zip(&w) {
        f.logw = wi.ln();
    }
    w
}

/// Rauch–Tung–Striebel backward pass per filter, fused with the forward weights. The
/// predictions are recomputed from the filtered states (the same deterministic step as the
/// forward pass), so only the filtered states and covariances are stored.
fn smooth(
    bank: &[Filter],
    fused: &mut [V5],
    weights_t: &[Vec<f64>],
    w_mid: &dyn Fn(usize) -> Vector3<f64>,
    dt: f64,
    q: &M5,
) {
    let n = fused.len();
    let smoothed: Vec<Vec<V5>> = bank
        .iter()
        .map(|flt| {
            let mut xs = flt.xs.clone();
            for k in (0..n - 1).rev() {
                let (xp, pp, fj) = predict(&flt.xs[k], &flt.ps[k], &w_mid(k + 1), dt, q);
                let Some(inv) = pp.try_inverse() else {
                    continue;
                };
                let c = flt.ps[k] * fj.transpose() * inv;
                let mut diff = xs[k + 1] - xp;
                diff[2] = wrap(diff[2]);
                xs[k] = flt.xs[k] + c * diff;
            }
            xs
        })
        .collect();
    for (k, fk) in fused.iter_mut().enumerate() {
        let xs: Vec<V5> = smoothed.iter().map(|s| s[k]).collect();
        *fk = weighted(&xs, &weights_t[k]);
    }
}

fn count_runs(mask: &[bool]) -> usize {
    mask.windows(2).filter(|w| w[1] && !w[0]).count() + usize::from(mask.first() == Some(&true))
}

/// Weighted mean of states, angles averaged as offsets from the first (no wrap artefacts).
fn weighted(xs: &[V5], w: &[f64]) -> V5 {
    let base = xs[0];
    let mut acc = V5::zeros();
    for (x, wi) in xs.iter().zip(w) {
        let mut d = x - base;
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
    use super::super::{estimate, AttitudeParams};
    use crate::align::{align, AlignParams, Aligned};
    use crate::preprocess::{preprocess, PreprocessParams};
    use crate::simulate::CohortParams;

    /// A simulated 70 s walk (family A) and its true pitch, the signals aligned as the pipeline
    /// aligns them.
    fn walk() -> (Aligned, Vec<f64>) {
        let c = CohortParams {
            healthy: 1,
            ldh: 0,
            seed: 11,
            duration_s: 70.0,
            ..CohortParams::default()
        };
        let s = c.simulate(0).unwrap();
        let rec = &s.left.recording;
        let pre = preprocess(rec, &PreprocessParams::default().check(rec.fs_hz).unwrap()).unwrap();
        let al = align(&pre, &AlignParams::default().check().unwrap()).unwrap();
        (al, s.left.truth.pitch_deg.clone())
    }

    fn rmse(a: &[f64], b: &[f64]) -> f64 {
        let n = a.len().min(b.len());
        ((0..n).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>() / n as f64).sqrt()
    }

    fn worst(a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn a_gyroscope_bias_of_several_deg_per_s_does_not_drift_the_pitch() {
        let (mut al, truth) = walk();
        // 6 deg/s on the sagittal axis and 4 on the anterior one, left after alignment (as when
        // a recording has no quiet standing to measure it).
        al.gyro_dps[0].iter_mut().for_each(|w| *w += 4.0);
        al.gyro_dps[1].iter_mut().for_each(|w| *w += 6.0);
        let p = AttitudeParams::default().check().unwrap();
        let att = estimate(&al, &p).unwrap();
        // Over the whole minute (plain integration: 6 deg/s x 70 s = 420 deg).
        let (e, w) = (rmse(&att.pitch_deg, &truth), worst(&att.pitch_deg, &truth));
        assert!(e < 1.5 && w < 6.0, "pitch RMSE {e:.2}, worst {w:.2} deg");
        let b = att.gyro_bias_dps;
        assert!(
            (b[1] - 6.0).abs() < 1.0,
            "sagittal bias estimated {:.2} deg/s",
            b[1]
        );
        assert!(
            att.gravity_windows > 50,
            "{} gravity windows",
            att.gravity_windows
        );
        // The same filter without bias states and gravity re-acquisition is worse.
        let mut off = AttitudeParams::default();
        off.reacquire_gravity = false;
        off.gyro_bias_sd_dps = 1e-6;
        off.gyro_bias_walk_dps = 1e-9;
        let plain = estimate(&al, &off.check().unwrap()).unwrap();
        let e0 = rmse(&plain.pitch_deg, &truth);
        assert!(
            e0 > 1.5 * e,
            "without the additions: pitch RMSE {e0:.2} vs {e:.2} deg"
        );
    }

    #[test]
    fn an_unbiased_walk_keeps_its_accuracy() {
        let (al, truth) = walk();
        let att = estimate(&al, &AttitudeParams::default().check().unwrap()).unwrap();
        let e = rmse(&att.pitch_deg, &truth);
        assert!(e < 1.0, "pitch RMSE {e:.2} deg");
        assert!(
            att.gyro_bias_dps.iter().all(|b| b.abs() < 1.0),
            "{:?}",
            att.gyro_bias_dps
        );
    }
}
