//! The Rauch–Tung–Striebel smoother of the filter bank (Rauch, Tung & Striebel, AIAA J
//! 1965;3:1445), run per filter and fused with the forward weights, in bounded memory: the
//! forward pass keeps checkpoints and the current segment only ([`SEGMENT`]).

use super::{predict, weighted, wrap, Angles, Bank, Model, Vector3, M5, V5};

/// Samples per segment of the smoother's storage. The forward pass keeps a checkpoint of the
/// bank (a few hundred bytes per filter) at the start of every segment and the filtered states
/// and covariances of the current segment only; the backward pass re-runs the forward pass of
/// each earlier segment from its checkpoint (the same deterministic steps, so the same numbers)
/// before smoothing it. A leg of up to `SEGMENT` samples (82 s at 100 Hz) is filtered once;
/// a longer one costs one more forward pass but keeps the attitude's memory at the output
/// (24 bytes per sample) plus ~8 MB, instead of ~1 kB per sample (issue 19: a 2-hour leg used
/// ~0.9 GB here).
pub(super) const SEGMENT: usize = 1 << 13;

/// Filtered states and covariances of one segment, filter-major within a sample, and the
/// bank's weights; preallocated once and reused for every segment.
pub(super) struct SegmentStore {
    nf: usize,
    xs: Vec<V5>,
    ps: Vec<M5>,
    ws: Vec<f64>,
}

impl SegmentStore {
    pub(super) fn new(nf: usize, len: usize) -> SegmentStore {
        SegmentStore {
            nf,
            xs: Vec::with_capacity(nf * len),
            ps: Vec::with_capacity(nf * len),
            ws: Vec::with_capacity(nf * len),
        }
    }

    pub(super) fn clear(&mut self) {
        self.xs.clear();
        self.ps.clear();
        self.ws.clear();
    }

    pub(super) fn push(&mut self, bank: &Bank) {
        for f in &bank.filters {
            self.xs.push(f.x);
            self.ps.push(f.p);
        }
        self.ws.extend_from_slice(&bank.weights);
    }

    /// Re-run the forward pass over samples `k0..k1` from `checkpoint`, storing every step.
    fn refill(&mut self, m: &Model, checkpoint: &Bank, k0: usize, k1: usize) {
        self.clear();
        let mut bank = checkpoint.clone();
        for k in k0..k1 {
            bank.step(m, k);
            self.push(&bank);
        }
    }
}

/// Rauch–Tung–Striebel backward pass per filter, fused with the forward weights, into `out`.
/// The predictions are recomputed from the filtered states (the same deterministic step as the
/// forward pass), so only the filtered states and covariances are stored; `store` holds the
/// last segment's on entry, and each earlier segment is re-filtered from its checkpoint.
pub(super) fn smooth(
    m: &Model,
    checkpoints: &[Bank],
    store: &mut SegmentStore,
    seg_len: usize,
    out: &mut Angles,
) {
    let n = out.roll.len();
    let nf = store.nf;
    // The smoothed state of each filter at the sample after the current one.
    let mut next: Vec<V5> = Vec::with_capacity(nf);
    for (s, checkpoint) in checkpoints.iter().enumerate().rev() {
        let k0 = s * seg_len;
        let k1 = (k0 + seg_len).min(n);
        if k1 < n {
            store.refill(m, checkpoint, k0, k1);
        }
        for k in (k0..k1).rev() {
            let j = (k - k0) * nf;
            if k == n - 1 {
                next.extend_from_slice(&store.xs[j..j + nf]);
            } else {
                let wm = m.w_mid(k + 1);
                for (i, xs) in next.iter_mut().enumerate() {
                    *xs = rts_step(&store.xs[j + i], &store.ps[j + i], xs, &wm, m);
                }
            }
            out.set(k, &weighted(&next, &store.ws[j..j + nf]));
        }
    }
}

/// One RTS step: the smoothed state at k from the filtered state and covariance at k and the
/// smoothed state at k + 1.
///
/// The gain C = P Fᵀ P_pred⁻¹ is never formed: only C (x̂ₛ − x̂ₚ) is needed, so P_pred (SPD:
/// F P Fᵀ plus a positive diagonal Q) is factored by Cholesky and solved for the one vector,
/// then multiplied by P Fᵀ (issue 17: the 5 × 5 LU inverse and the 5 × 5 × 5 product were a
/// third of the attitude's time). The result equals the explicit gain's to rounding (tested
/// below to 1e-9 relative on a walk). When P_pred is not numerically positive definite, the
/// explicit inverse is used as before, and the filtered state when that too is singular.
fn rts_step(xf: &V5, pf: &M5, xs_next: &V5, wm: &Vector3<f64>, m: &Model) -> V5 {
    let (xp, pp, fj) = predict(xf, pf, wm, m.dt, &m.q);
    let mut diff = xs_next - xp;
    diff[2] = wrap(diff[2]);
    match spd_solve(&pp, &diff) {
        Some(y) => xf + pf * fj.tr_mul(&y),
        None => rts_step_inverse(xf, pf, &pp, &fj, &diff),
    }
}

/// x with A x = b for a symmetric positive definite A (its lower triangle is read), by
/// Cholesky A = L Lᵀ and two triangular solves; `None` when A is not numerically positive
/// definite. Written out for the fixed 5 × 5 size: nalgebra's generic `cholesky().solve()`
/// took three times as long here.
fn spd_solve(a: &M5, b: &V5) -> Option<V5> {
    let mut l = [[0.0f64; 5]; 5];
    let mut inv_d = [0.0f64; 5];
    for j in 0..5 {
        let mut d = a[(j, j)];
        for k in 0..j {
            d -= l[j][k] * l[j][k];
        }
        if !(d > 0.0) {
            return None;
        }
        let ljj = d.sqrt();
        inv_d[j] = 1.0 / ljj;
        for i in j + 1..5 {
            let mut s = a[(i, j)];
            for k in 0..j {
                s -= l[i][k] * l[j][k];
            }
            l[i][j] = s * inv_d[j];
        }
    }
    let mut z = [0.0f64; 5];
    for i in 0..5 {
        let mut s = b[i];
        for k in 0..i {
            s -= l[i][k] * z[k];
        }
        z[i] = s * inv_d[i];
    }
    let mut y = V5::zeros();
    for i in (0..5).rev() {
        let mut s = z[i];
        for k in i + 1..5 {
            s -= l[k][i] * y[k];
        }
        y[i] = s * inv_d[i];
    }
    Some(y)
}

/// The RTS correction with the explicit gain C = P Fᵀ P_pred⁻¹ (the filtered state when P_pred
/// is singular).
fn rts_step_inverse(xf: &V5, pf: &M5, pp: &M5, fj: &M5, diff: &V5) -> V5 {
    let Some(inv) = pp.try_inverse() else {
        return *xf;
    };
    let c = super::products::times_ft(pf, fj) * inv;
    xf + c * diff
}

#[cfg(test)]
mod tests {
    use super::super::tests::walk;
    use super::super::{Bank, Model};
    use super::{predict, rts_step, rts_step_inverse, spd_solve, wrap, M5, V5};
    use crate::attitude::AttitudeParams;

    /// The Cholesky solve gives the explicit gain's smoothed state to rounding: every step of
    /// a 70 s walk, every filter, with the smoothed state at k + 1 a perturbed prediction.
    #[test]
    fn the_solved_rts_step_equals_the_explicit_gain_to_1e_9() {
        let (mut al, _) = walk();
        al.gyro_dps[1].iter_mut().for_each(|w| *w += 3.0);
        let p = AttitudeParams::default().check().unwrap().params().clone();
        let m = Model::new(&al, &p);
        let mut bank = Bank::new(&m);
        let n = al.acc_g[0].len();
        let mut worst = 0.0f64;
        for k in 0..n - 1 {
            bank.step(&m, k);
            let wm = m.w_mid(k + 1);
            for (i, f) in bank.filters.iter().enumerate() {
                let (xp, pp, fj) = predict(&f.x, &f.p, &wm, m.dt, &m.q);
                // a smoothed state a few σ of the prediction away
                let mut xs_next = xp;
                for (j, v) in xs_next.iter_mut().enumerate() {
                    let s = if (k + i + j) % 2 == 0 { 3.0 } else { -2.0 };
                    *v += s * pp[(j, j)].sqrt();
                }
                let mut diff = xs_next - xp;
                diff[2] = wrap(diff[2]);
                let a = rts_step(&f.x, &f.p, &xs_next, &wm, &m);
                let b = rts_step_inverse(&f.x, &f.p, &pp, &fj, &diff);
                let d: V5 = a - b;
                for j in 0..5 {
                    let scale = b[j].abs().max((b[j] - f.x[j]).abs()).max(1e-300);
                    worst = worst.max(d[j].abs() / scale);
                }
            }
        }
        assert!(worst < 1e-9, "largest relative difference {worst:e}");
    }

    #[test]
    fn spd_solve_solves_and_refuses_what_is_not_positive_definite() {
        let mut g = M5::zeros();
        for i in 0..5 {
            for j in 0..5 {
                g[(i, j)] = ((i * 7 + j * 3) % 11) as f64 - 5.0;
            }
        }
        let a = g * g.transpose() + M5::identity() * 1e-3;
        let b = V5::from_column_slice(&[1.0, -2.0, 0.5, 3.0, -1.0]);
        let x = spd_solve(&a, &b).unwrap();
        let want = a.cholesky().unwrap().solve(&b);
        assert!((x - want).norm() <= 1e-9 * want.norm(), "{x} vs {want}");
        assert!((a * x - b).norm() <= 1e-9 * b.norm());
        let mut indefinite = M5::identity();
        indefinite[(3, 3)] = -1.0;
        assert!(spd_solve(&indefinite, &b).is_none());
        assert!(spd_solve(&M5::zeros(), &b).is_none());
    }
}
