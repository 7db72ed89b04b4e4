//! The Rauch–Tung–Striebel smoother of the filter bank (Rauch, Tung & Striebel, AIAA J
//! 1965;3:1445), run per filter and fused with the forward weights, in bounded memory: the
//! forward pass keeps checkpoints and the current segment only ([`SEGMENT`]).

use super::{predict, weighted, wrap, Angles, Bank, Model, SinCos, Vector3, M5, V5};

/// Samples per segment of the smoother's storage. The forward pass keeps a checkpoint of the
/// bank (a few hundred bytes per filter) at the start of every segment and the filtered states
/// and covariances of the current segment only; the backward pass re-runs the forward pass of
/// each earlier segment from its checkpoint (the same deterministic steps, so the same numbers)
/// before smoothing it. A leg of up to `SEGMENT` samples (82 s at 100 Hz) is filtered once;
/// a longer one costs one more forward pass but keeps the attitude's memory at the output
/// (24 bytes per sample) plus ~8 MB, instead of ~1 kB per sample (issue 19: a 2-hour leg used
/// ~0.9 GB here).
pub(super) const SEGMENT: usize = 1 << 13;

/// Filtered states (with the sines and cosines of their tilt) and covariances of one segment,
/// filter-major within a sample, and the bank's weights; preallocated once and reused for
/// every segment.
pub(super) struct SegmentStore {
    nf: usize,
    steps: Vec<Filtered>,
    ws: Vec<f64>,
}

/// One filter's filtered state at one sample, kept together: the backward pass reads them in
/// one descending stream (separate arrays of states and covariances stalled it on memory).
struct Filtered {
    x: V5,
    sc: SinCos,
    p: M5,
}

impl SegmentStore {
    pub(super) fn new(nf: usize, len: usize) -> SegmentStore {
        SegmentStore {
            nf,
            steps: Vec::with_capacity(nf * len),
            ws: Vec::with_capacity(nf * len),
        }
    }

    pub(super) fn clear(&mut self) {
        self.steps.clear();
        self.ws.clear();
    }

    pub(super) fn push(&mut self, bank: &Bank) {
        for f in &bank.filters {
            self.steps.push(Filtered {
                x: f.x,
                sc: f.sc,
                p: f.p,
            });
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
                next.extend(store.steps[j..j + nf].iter().map(|s| s.x));
            } else {
                let wm = m.w_mid(k + 1);
                for (xs, f) in next.iter_mut().zip(&store.steps[j..j + nf]) {
                    *xs = rts_step(&f.x, &f.sc, &f.p, xs, &wm, m);
                }
            }
            out.set(k, &weighted(&next, &store.ws[j..j + nf]));
        }
    }
}

/// One RTS step: the smoothed state at k from the filtered state and covariance at k and the
/// smoothed state at k + 1 (the filtered state when the predicted covariance is singular).
///
/// Only C (x̂ₛ − x̂ₚ) is needed, C = P Fᵀ P_pred⁻¹, so P_pred y = x̂ₛ − x̂ₚ is solved by
/// Cholesky ([`spd_solve`]) and the correction is P Fᵀ y, instead of forming P_pred⁻¹ and the
/// 5 × 5 gain (a quarter of the attitude's time, issue 17). Accuracy, against a solve refined in
/// double-double (`rts_accuracy.rs`, all 36 HuGaDB shank legs): on every leg whose angles the
/// pipeline reports (condition number of P_pred ≤ 5e5) both this solve and the explicit
/// inverse give the smoothed angles to ≤ 1e-9°; on the legs with a faulty gyroscope, whose
/// angles are withheld (`gyro_scale_fault`), P_pred reaches condition numbers of 1e15-1e24
/// and neither way is determined beyond rounding (they differ from the refined solve and from
/// each other by 0.01-300°). The explicit inverse remains the fallback when P_pred is not
/// numerically positive definite.
pub(super) fn rts_step(
    xf: &V5,
    sc: &SinCos,
    pf: &M5,
    xs_next: &V5,
    wm: &Vector3<f64>,
    m: &Model,
) -> V5 {
    let (xp, pp, fj) = predict(xf, sc, pf, wm, m.dt, &m.q);
    let mut diff = xs_next - xp;
    diff[2] = wrap(diff[2]);
    match spd_solve(&pp, &diff) {
        Some(y) => xf + pf * fj.tr_mul(&y),
        None => match super::products::lu_inverse(&pp) {
            Some(inv) => xf + (super::products::times_ft(pf, &fj) * inv) * diff,
            None => *xf,
        },
    }
}

/// x with A x = b for a symmetric positive definite A (its lower triangle is read), by
/// Cholesky A = L Lᵀ and two triangular solves; `None` when A is not numerically positive
/// definite. Written out for the fixed 5 × 5 size: nalgebra's generic `cholesky().solve()`
/// took three times as long here.
pub(super) fn spd_solve(a: &M5, b: &V5) -> Option<V5> {
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

#[cfg(test)]
mod tests {
    use super::{spd_solve, M5, V5};

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
