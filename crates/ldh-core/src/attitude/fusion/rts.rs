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
/// The gain C = P Fᵀ P_pred⁻¹ is formed with nalgebra's LU inverse (written out for 5 × 5,
/// bit for bit: [`super::products::lu_inverse`]) on purpose: a Cholesky solve of P_pred for the
/// one vector C needs is 25 % faster, but on real recordings (HuGaDB) P_pred is ill-conditioned
/// enough that the smoothed roll and yaw then move by up to 0.1° (issue 17, session of
/// 2026-11-25 03:50), which is not a change of the last bits.
fn rts_step(xf: &V5, sc: &SinCos, pf: &M5, xs_next: &V5, wm: &Vector3<f64>, m: &Model) -> V5 {
    let (xp, pp, fj) = predict(xf, sc, pf, wm, m.dt, &m.q);
    let Some(inv) = super::products::lu_inverse(&pp) else {
        return *xf;
    };
    let c = super::products::times_ft(pf, &fj) * inv;
    let mut diff = xs_next - xp;
    diff[2] = wrap(diff[2]);
    xf + c * diff
}
