//! The Rauch–Tung–Striebel smoother of the filter bank (Rauch, Tung & Striebel, AIAA J
//! 1965;3:1445), run per filter and fused with the forward weights, in bounded memory: the
//! forward pass keeps checkpoints and the current segment only ([`SEGMENT`]).

use super::bank::{Bank, Filtered};
use super::lanes::{array, Num, L4, LANES};
use super::products::{lu_inverse, matrix, rows, times_ft, Jacobian, Mat};
use super::{predict, predict_n, weighted, wrap, Angles, Model, SinCos, M5, V5};

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
/// group-major within a sample, and the bank's weights; preallocated once and reused for
/// every segment.
pub(super) struct SegmentStore {
    nf: usize,
    groups: usize,
    steps: Vec<Filtered>,
    ws: Vec<f64>,
}

impl SegmentStore {
    pub(super) fn new(bank: &Bank, len: usize) -> SegmentStore {
        let groups = bank.groups.len();
        SegmentStore {
            nf: bank.len(),
            groups,
            steps: Vec::with_capacity(groups * len),
            ws: Vec::with_capacity(bank.len() * len),
        }
    }

    pub(super) fn clear(&mut self) {
        self.steps.clear();
        self.ws.clear();
    }

    pub(super) fn push(&mut self, bank: &Bank) {
        self.steps.extend(bank.groups.iter().map(|g| g.f));
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
    let (nf, ng) = (store.nf, store.groups);
    // The smoothed states of each group at the sample after the current one.
    let mut next: Vec<[L4; 5]> = Vec::with_capacity(ng);
    let mut mid: Vec<[L4; 5]> = Vec::with_capacity(ng);
    for (s, checkpoint) in checkpoints.iter().enumerate().rev() {
        let k0 = s * seg_len;
        let k1 = (k0 + seg_len).min(n);
        if k1 < n {
            store.refill(m, checkpoint, k0, k1);
        }
        let steps = |k: usize| &store.steps[(k - k0) * ng..][..ng];
        let ws = |k: usize| &store.ws[(k - k0) * nf..][..nf];
        let set = |out: &mut Angles, k: usize, xs: &[[L4; 5]]| {
            let state = |i: usize| V5::from_fn(|r, _| xs[i / LANES][r].0[i % LANES]);
            out.set(k, &weighted(nf, state, ws(k)));
        };
        // samples k1 − 1 down to k0, two at a time where two are left in the segment
        let mut k = k1;
        while k > k0 {
            k -= 1;
            if k == n - 1 {
                next.extend(steps(k).iter().map(|s| s.x));
                set(out, k, &next);
            } else if k > k0 {
                rts_pairs(&mut next, &mut mid, [steps(k), steps(k - 1)], k, m);
                set(out, k, &mid);
                k -= 1;
                set(out, k, &next);
            } else {
                rts_groups(&mut next, steps(k), &m.w_mid(k + 1), m);
                set(out, k, &next);
            }
        }
    }
}

/// Two steps of [`rts_groups`], samples `k` and `k − 1` (`steps` their filtered states):
/// `mid` receives the smoothed states at k, `next` those at k − 1. The predictions and
/// Cholesky factors of the two samples do not depend on the smoothed states, so they are
/// computed together, their columns interleaved: a factor is a chain of five square roots and
/// divisions, each waiting on the last, and two independent chains side by side fill the time
/// one alone spends waiting (≈ a third of the smoother's time was that wait, issue 17). The
/// same operations on the same values, so the same numbers.
#[multiversion::multiversion(targets("x86_64+avx2"))]
fn rts_pairs(
    next: &mut [[L4; 5]],
    mid: &mut Vec<[L4; 5]>,
    steps: [&[Filtered]; 2],
    k: usize,
    m: &Model,
) {
    mid.clear();
    let (wa, wb) = (m.w_mid(k + 1), m.w_mid(k));
    for ((xs, fa), fb) in next.iter_mut().zip(steps[0]).zip(steps[1]) {
        let (xpa, ppa, fja) = predict_n(&fa.x, &fa.sc, &fa.p, &wa, m.dt, &m.q);
        let (xpb, ppb, fjb) = predict_n(&fb.x, &fb.sc, &fb.p, &wb, m.dt, &m.q);
        let (mut oka, mut okb) = ([true; LANES], [true; LANES]);
        let (cha, chb) =
            Cholesky::pair(&ppa, &ppb, &mut positive(&mut oka), &mut positive(&mut okb));
        let xa = finish(fa, &xpa, &fja, &cha, &oka, xs, &wa, m);
        *xs = finish(fb, &xpb, &fjb, &chb, &okb, &xa, &wb, m);
        mid.push(xa);
    }
}

/// [`rts_step_lanes`] of every group, in an AVX2 clone where the CPU has it (as the forward
/// step, `bank::step_groups`).
#[multiversion::multiversion(targets("x86_64+avx2"))]
fn rts_groups(next: &mut [[L4; 5]], steps: &[Filtered], wm: &[f64; 3], m: &Model) {
    for (xs, f) in next.iter_mut().zip(steps) {
        *xs = rts_step_lanes(f, xs, wm, m);
    }
}

/// [`rts_step`] of a group of four filters: the lanes whose predicted covariance is not
/// numerically positive definite go through the scalar fallback.
#[inline(always)]
fn rts_step_lanes(f: &Filtered, xs_next: &[L4; 5], wm: &[f64; 3], m: &Model) -> [L4; 5] {
    let (xp, pp, fj) = predict_n(&f.x, &f.sc, &f.p, wm, m.dt, &m.q);
    let mut ok = [true; LANES];
    let ch = Cholesky::of(&pp, &mut positive(&mut ok));
    finish(f, &xp, &fj, &ch, &ok, xs_next, wm, m)
}

/// The pivot test of a group's Cholesky factor: `ok[l]` stays true while lane l's pivots are
/// > 0.
#[inline(always)]
fn positive(ok: &mut [bool; LANES]) -> impl FnMut(L4) + '_ {
    move |d: L4| {
        for l in 0..LANES {
            ok[l] &= d.0[l] > 0.0;
        }
    }
}

/// The rest of [`rts_step_lanes`] from the prediction (`xp`, `fj`) and the factor of its
/// covariance: the smoothed states of the group at its sample, the lanes not `ok` by the
/// scalar fallback.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn finish(
    f: &Filtered,
    xp: &[L4; 5],
    fj: &Jacobian<L4>,
    ch: &Cholesky<L4>,
    ok: &[bool; LANES],
    xs_next: &[L4; 5],
    wm: &[f64; 3],
    m: &Model,
) -> [L4; 5] {
    let mut diff: [L4; 5] = array(|i| xs_next[i] - xp[i]);
    diff[2] = diff[2].wrap();
    let y = ch.solve(&diff);
    let mut xs = correct(&f.x, &f.p, fj, &y);
    for l in (0..LANES).filter(|l| !ok[*l]) {
        let lane = |v: &[L4; 5]| V5::from_fn(|r, _| v[r].0[l]);
        let pf = M5::from_fn(|r, c| f.p[r][c].0[l]);
        let x = rts_step(&lane(&f.x), &f.sc.lane(l), &pf, &lane(xs_next), wm, m);
        for r in 0..5 {
            xs[r].0[l] = x[r];
        }
    }
    xs
}

/// x̂ + P (Fᵀ y), with nalgebra's operations: `tr_mul` sums each column's dot product from
/// +0 in ascending order, the matrix-vector product each row from its first term.
#[inline(always)]
fn correct<T: Num>(xf: &[T; 5], pf: &Mat<T>, fj: &Jacobian<T>, y: &[T; 5]) -> [T; 5] {
    let f = dense(fj);
    let v: [T; 5] = array(|i| {
        let mut s = T::splat(0.0);
        for (row, yk) in f.iter().zip(y) {
            s = s + row[i] * *yk;
        }
        s
    });
    array(|i| {
        let mut s = pf[i][0] * v[0];
        for k in 1..5 {
            s = s + pf[i][k] * v[k];
        }
        xf[i] + s
    })
}

/// The dense F of [`super::predict_n`]: the identity's 0 and 1 where F is structural.
#[inline(always)]
fn dense<T: Num>(fj: &Jacobian<T>) -> Mat<T> {
    let (z, o) = (T::splat(0.0), T::splat(1.0));
    let a = &fj.a;
    [
        [a[0][0], a[0][1], z, fj.b03, fj.b4[0]],
        [a[1][0], o, z, z, fj.b4[1]],
        [a[2][0], a[2][1], o, z, fj.b4[2]],
        [z, z, z, o, z],
        [z, z, z, z, o],
    ]
}

/// One RTS step of one filter: the smoothed state at k from the filtered state and covariance
/// at k and the smoothed state at k + 1 (the filtered state when the predicted covariance is
/// singular).
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
    wm: &[f64; 3],
    m: &Model,
) -> V5 {
    let (xp, pp, fj) = predict(xf, sc, pf, wm, m.dt, &m.q);
    let mut diff = xs_next - xp;
    diff[2] = wrap(diff[2]);
    match spd_solve(&pp, &diff) {
        Some(y) => xf + pf * fj.tr_mul(&y),
        None => match lu_inverse(&pp) {
            Some(inv) => xf + (times_ft_dense(pf, &fj) * inv) * diff,
            None => *xf,
        },
    }
}

/// P Fᵀ for a dense F of [`predict`].
pub(super) fn times_ft_dense(pf: &M5, f: &M5) -> M5 {
    let jac = Jacobian {
        a: std::array::from_fn(|i| std::array::from_fn(|j| f[(i, j)])),
        b03: f[(0, 3)],
        b4: std::array::from_fn(|i| f[(i, 4)]),
    };
    matrix(&times_ft(&rows(pf), &jac))
}

/// x with A x = b for a symmetric positive definite A (its lower triangle is read), by
/// Cholesky A = L Lᵀ and two triangular solves; `None` when A is not numerically positive
/// definite. Written out for the fixed 5 × 5 size: nalgebra's generic `cholesky().solve()`
/// took three times as long here.
pub(super) fn spd_solve(a: &M5, b: &V5) -> Option<V5> {
    let mut ok = true;
    let bb: [f64; 5] = std::array::from_fn(|i| b[i]);
    let y = spd_solve_n(&rows(a), &bb, |d: f64| ok &= d > 0.0);
    ok.then(|| V5::from(y))
}

/// [`spd_solve`] of one system or four; `pivot` is shown every pivot before its square root,
/// which must be > 0 (the result is meaningless otherwise).
#[inline(always)]
fn spd_solve_n<T: Num>(a: &Mat<T>, b: &[T; 5], mut pivot: impl FnMut(T)) -> [T; 5] {
    let f = Cholesky::of(a, &mut pivot);
    f.solve(b)
}

/// The Cholesky factor L of a 5 × 5 matrix (its lower triangle read) and the reciprocals of
/// its diagonal, of one matrix or four.
struct Cholesky<T> {
    /// L below the diagonal (the diagonal and above are unused).
    l: Mat<T>,
    /// 1 / L[j][j].
    inv_d: [T; 5],
}

impl<T: Num> Cholesky<T> {
    /// The factor column by column, each column written out for its index (`column::<J>`: the
    /// loops have fixed bounds and unroll, so L stays in registers; as one loop over j it was
    /// zeroed in memory by a `memset` per step and its entries went through the stack).
    /// Every entry is the same sequence of IEEE operations as the loop ([`spd_solve_loops`],
    /// the reference of the test), so the same bits.
    #[inline(always)]
    fn of(a: &Mat<T>, pivot: &mut impl FnMut(T)) -> Cholesky<T> {
        let z = T::splat(0.0);
        let mut f = Cholesky {
            l: [[z; 5]; 5],
            inv_d: [z; 5],
        };
        f.column::<0>(a, pivot);
        f.column::<1>(a, pivot);
        f.column::<2>(a, pivot);
        f.column::<3>(a, pivot);
        f.column::<4>(a, pivot);
        f
    }

    /// [`Cholesky::of`] of two matrices, their columns interleaved (two independent chains of
    /// square roots and divisions side by side).
    #[inline(always)]
    fn pair(
        a: &Mat<T>,
        b: &Mat<T>,
        pa: &mut impl FnMut(T),
        pb: &mut impl FnMut(T),
    ) -> (Cholesky<T>, Cholesky<T>) {
        let z = T::splat(0.0);
        let new = || Cholesky {
            l: [[z; 5]; 5],
            inv_d: [z; 5],
        };
        let (mut fa, mut fb) = (new(), new());
        fa.column::<0>(a, pa);
        fb.column::<0>(b, pb);
        fa.column::<1>(a, pa);
        fb.column::<1>(b, pb);
        fa.column::<2>(a, pa);
        fb.column::<2>(b, pb);
        fa.column::<3>(a, pa);
        fb.column::<3>(b, pb);
        fa.column::<4>(a, pa);
        fb.column::<4>(b, pb);
        (fa, fb)
    }

    #[inline(always)]
    fn column<const J: usize>(&mut self, a: &Mat<T>, pivot: &mut impl FnMut(T)) {
        let l = &mut self.l;
        let mut d = a[J][J];
        for k in 0..J {
            d = d - l[J][k] * l[J][k];
        }
        pivot(d);
        let ljj = d.sqrt();
        self.inv_d[J] = T::splat(1.0) / ljj;
        for i in J + 1..5 {
            let mut s = a[i][J];
            for k in 0..J {
                s = s - l[i][k] * l[J][k];
            }
            l[i][J] = s * self.inv_d[J];
        }
    }

    /// x with L Lᵀ x = b: the two triangular solves.
    #[inline(always)]
    fn solve(&self, b: &[T; 5]) -> [T; 5] {
        let (l, inv_d) = (&self.l, &self.inv_d);
        let mut zv = [T::splat(0.0); 5];
        for i in 0..5 {
            let mut s = b[i];
            for k in 0..i {
                s = s - l[i][k] * zv[k];
            }
            zv[i] = s * inv_d[i];
        }
        let mut y = [T::splat(0.0); 5];
        for i in (0..5).rev() {
            let mut s = zv[i];
            for k in i + 1..5 {
                s = s - l[k][i] * y[k];
            }
            y[i] = s * inv_d[i];
        }
        y
    }
}

/// [`spd_solve_n`] with the factor as it was computed before [`Cholesky::of`] (one loop over
/// the columns): the reference its bits are tested against (the triangular solves are the
/// same code, moved into [`Cholesky::solve`]).
#[cfg(test)]
fn spd_solve_loops<T: Num>(a: &Mat<T>, b: &[T; 5], mut pivot: impl FnMut(T)) -> [T; 5] {
    let z = T::splat(0.0);
    let mut f = Cholesky {
        l: [[z; 5]; 5],
        inv_d: [z; 5],
    };
    let (l, inv_d) = (&mut f.l, &mut f.inv_d);
    for j in 0..5 {
        let mut d = a[j][j];
        for k in 0..j {
            d = d - l[j][k] * l[j][k];
        }
        pivot(d);
        let ljj = d.sqrt();
        inv_d[j] = T::splat(1.0) / ljj;
        for i in j + 1..5 {
            let mut s = a[i][j];
            for k in 0..j {
                s = s - l[i][k] * l[j][k];
            }
            l[i][j] = s * inv_d[j];
        }
    }
    f.solve(b)
}

#[cfg(test)]
mod tests {
    use super::super::lanes::L4;
    use super::{spd_solve, spd_solve_loops, spd_solve_n, M5, V5};

    /// The unrolled factor and solves give the loop's bits, pivots included, on one matrix and
    /// on four (random SPD matrices of condition numbers up to ~1e12, indefinite and singular
    /// ones, and the ±0 / NaN that a non-positive pivot produces).
    #[test]
    fn the_unrolled_solve_is_the_loop_bit_for_bit() {
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        for case in 0..20_000 {
            let mut g = M5::zeros();
            for v in g.iter_mut() {
                *v = next() * 10f64.powi((case % 7) as i32 - 3);
            }
            let mut a = g * g.transpose();
            if case % 5 == 1 {
                a[(case % 5, case % 5)] = -a[(case % 5, case % 5)];
            }
            if case % 11 == 2 {
                a = M5::zeros();
            }
            let rows = super::rows(&a);
            let b: [f64; 5] = std::array::from_fn(|_| next());
            let (mut p1, mut p2) = (Vec::new(), Vec::new());
            let y1 = spd_solve_n(&rows, &b, |d: f64| p1.push(d));
            let y2 = spd_solve_loops(&rows, &b, |d: f64| p2.push(d));
            assert_eq!(bits(&y1), bits(&y2), "case {case}");
            assert_eq!(bits(&p1), bits(&p2), "case {case}");
            // four lanes: this matrix and three scaled copies
            let scale = [1.0, 3.0, 1e-6, -1.0];
            let lanes = rows.map(|r| r.map(|v| L4(scale.map(|s| v * s))));
            let bl = b.map(|v| L4([v, -v, 2.0 * v, v]));
            let (mut q1, mut q2) = (Vec::new(), Vec::new());
            let z1 = spd_solve_n(&lanes, &bl, |d: L4| q1.extend(d.0));
            let z2 = spd_solve_loops(&lanes, &bl, |d: L4| q2.extend(d.0));
            let flat = |y: [L4; 5]| y.iter().flat_map(|l| l.0).collect::<Vec<_>>();
            assert_eq!(bits(&flat(z1)), bits(&flat(z2)), "case {case}, lanes");
            assert_eq!(bits(&q1), bits(&q2), "case {case}, lanes");
        }
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
