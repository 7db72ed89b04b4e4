//! The covariance products of the filter step without the multiplications by the structural
//! zeros and ones of the transition matrix F, the gain matrix I − KH and the diagonal R (issue
//! 17: they were two thirds of the attitude's time as dense 5 × 5 products).
//!
//! Every entry is summed over the same terms in the same order as nalgebra's dense product
//! (k ascending, `c = a₀b₀ + a₁b₁ + …`), leaving out only terms whose factor is an exact 0
//! (adding ±0 changes at most the sign of a zero) and writing `1·x` as `x`, so the results are
//! those of the dense products bit for bit (tested below against nalgebra).

use super::{M5x2, M5};
use nalgebra::Matrix2;

/// F P Fᵀ for the transition matrix of [`super::predict`]: F = I except `F[0..3, 0..2]`
/// (the Euler-rate Jacobian; its third column is zero and `F[1][1]` = 1), `F[0][3]` and
/// `F[0..3][4]` (the bias columns).
pub(super) fn propagate(f: &M5, p: &M5) -> M5 {
    let mut a = M5::zeros();
    for j in 0..5 {
        a[(0, j)] = ((f[(0, 0)] * p[(0, j)] + f[(0, 1)] * p[(1, j)]) + f[(0, 3)] * p[(3, j)])
            + f[(0, 4)] * p[(4, j)];
        a[(1, j)] = (f[(1, 0)] * p[(0, j)] + p[(1, j)]) + f[(1, 4)] * p[(4, j)];
        a[(2, j)] =
            ((f[(2, 0)] * p[(0, j)] + f[(2, 1)] * p[(1, j)]) + p[(2, j)]) + f[(2, 4)] * p[(4, j)];
        a[(3, j)] = p[(3, j)];
        a[(4, j)] = p[(4, j)];
    }
    times_ft(&a, f)
}

/// A Fᵀ for F as in [`propagate`].
pub(super) fn times_ft(a: &M5, f: &M5) -> M5 {
    let mut b = M5::zeros();
    for i in 0..5 {
        b[(i, 0)] = ((a[(i, 0)] * f[(0, 0)] + a[(i, 1)] * f[(0, 1)]) + a[(i, 3)] * f[(0, 3)])
            + a[(i, 4)] * f[(0, 4)];
        b[(i, 1)] = (a[(i, 0)] * f[(1, 0)] + a[(i, 1)]) + a[(i, 4)] * f[(1, 4)];
        b[(i, 2)] =
            ((a[(i, 0)] * f[(2, 0)] + a[(i, 1)] * f[(2, 1)]) + a[(i, 2)]) + a[(i, 4)] * f[(2, 4)];
        b[(i, 3)] = a[(i, 3)];
        b[(i, 4)] = a[(i, 4)];
    }
    b
}

/// The Kalman gain K = P Hᵀ S⁻¹ for H selecting the first two states.
pub(super) fn gain(pp: &M5, s_inv: &Matrix2<f64>) -> M5x2 {
    let mut k = M5x2::zeros();
    for j in 0..2 {
        for i in 0..5 {
            k[(i, j)] = pp[(i, 0)] * s_inv[(0, j)] + pp[(i, 1)] * s_inv[(1, j)];
        }
    }
    k
}

/// The Joseph-form update (I − KH) P (I − KH)ᵀ + K R Kᵀ for H selecting the first two states
/// and a diagonal R.
pub(super) fn joseph(pp: &M5, kg: &M5x2, rk: &Matrix2<f64>) -> M5 {
    // I − KH: columns 0 and 1 are e_j − K_j, the others those of I
    let ikh = |i: usize, j: usize| f64::from(u8::from(i == j)) - kg[(i, j)];
    let mut a = M5::zeros();
    for j in 0..5 {
        for i in 0..5 {
            let t = ikh(i, 0) * pp[(0, j)] + ikh(i, 1) * pp[(1, j)];
            a[(i, j)] = if i >= 2 { t + pp[(i, j)] } else { t };
        }
    }
    let mut out = M5::zeros();
    for j in 0..5 {
        for i in 0..5 {
            let t = a[(i, 0)] * ikh(j, 0) + a[(i, 1)] * ikh(j, 1);
            let b = if j >= 2 { t + a[(i, j)] } else { t };
            // K R Kᵀ with R diagonal
            let c0 = kg[(i, 0)] * rk[(0, 0)];
            let c1 = kg[(i, 1)] * rk[(1, 1)];
            out[(i, j)] = b + (c0 * kg[(j, 0)] + c1 * kg[(j, 1)]);
        }
    }
    out
}

/// `m.try_inverse()` bit for bit, for a 5 × 5 matrix: nalgebra's LU with partial pivoting
/// (`linalg::lu::try_invert_to`, 0.35: pivot = first largest |entry|, the column scaled by the
/// reciprocal of the pivot, rank-one updates column by column as `y += (−p)·c`, then the unit
/// lower and the upper triangular solves on the identity, column by column) written out for
/// the fixed size. nalgebra's generic views and strides made its inverse the largest single
/// cost of the smoother (≈ 19 % of a `leg_cpu` profile); the numbers are the same (tested
/// below against `try_inverse` on random, pivoting-heavy and singular matrices). `None` when a
/// pivot is exactly zero, as nalgebra.
pub(super) fn lu_inverse(m: &M5) -> Option<M5> {
    let mut a = [[0.0f64; 5]; 5]; // a[row][col]
    for (r, row) in a.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = m[(r, c)];
        }
    }
    let mut out = [[0.0f64; 5]; 5];
    for (i, row) in out.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    for i in 0..5 {
        let mut piv = i;
        let mut best = a[i][i].abs();
        for (r, row) in a.iter().enumerate().skip(i + 1) {
            if row[i].abs() > best {
                best = row[i].abs();
                piv = r;
            }
        }
        let diag = a[piv][i];
        if diag == 0.0 {
            return None;
        }
        if piv != i {
            out.swap(i, piv);
            for c in 0..i {
                let t = a[i][c];
                a[i][c] = a[piv][c];
                a[piv][c] = t;
            }
            let t = a[i][i];
            a[i][i] = a[piv][i];
            a[piv][i] = t;
        }
        let inv_diag = 1.0 / diag;
        for row in a.iter_mut().skip(i + 1) {
            row[i] *= inv_diag;
        }
        for c in i + 1..5 {
            if piv != i {
                let t = a[i][c];
                a[i][c] = a[piv][c];
                a[piv][c] = t;
            }
            let p = -a[i][c];
            for r in i + 1..5 {
                a[r][c] += p * a[r][i];
            }
        }
    }
    // columns of the result: L y = e_k (unit diagonal), then U x = y
    for k in 0..5 {
        for i in 0..4 {
            let coeff = -(out[i][k] / 1.0);
            for r in i + 1..5 {
                out[r][k] += coeff * a[r][i];
            }
        }
        for i in (0..5).rev() {
            let coeff = out[i][k] / a[i][i];
            out[i][k] = coeff;
            for r in 0..i {
                out[r][k] += -coeff * a[r][i];
            }
        }
    }
    let mut inv = M5::zeros();
    for (r, row) in out.iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            inv[(r, c)] = *v;
        }
    }
    Some(inv)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn bits(m: &[f64]) -> Vec<u64> {
        // the sign of a zero may differ (see the module docs)
        m.iter()
            .map(|v| if *v == 0.0 { 0 } else { v.to_bits() })
            .collect()
    }

    /// `lu_inverse` equals nalgebra's `try_inverse` bit for bit (zeros included, since no
    /// sign of a zero is special-cased there), and refuses the same singular matrices.
    #[test]
    fn lu_inverse_equals_nalgebras_try_inverse_bit_for_bit() {
        let exact = |m: &M5| -> Vec<u64> { m.iter().map(|v| v.to_bits()).collect() };
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for t in 0..20_000 {
            let mut m = M5::zeros();
            // scales from 1e-12 to 1e6 in one matrix: covariances of angles and biases
            m.iter_mut()
                .for_each(|v| *v = rng.gen_range(-1.0..1.0) * 10f64.powi(rng.gen_range(-12..6)));
            if t % 3 == 0 {
                // symmetric positive definite, like P_pred
                m = m * m.transpose() + M5::identity() * 1e-14;
            }
            if t % 7 == 0 {
                // exact zeros and repeated magnitudes: pivot ties
                m[(1, 0)] = 0.0;
                m[(3, 0)] = -m[(0, 0)];
                m[(2, 2)] = 0.0;
            }
            let want = m.try_inverse();
            let got = lu_inverse(&m);
            assert_eq!(want.is_some(), got.is_some(), "{m}");
            if let (Some(w), Some(g)) = (want, got) {
                assert_eq!(exact(&g), exact(&w), "{m}");
            }
        }
        // singular: a zero column, and two equal rows (an exactly zero pivot after one step)
        let mut z = M5::identity();
        z.column_mut(2).fill(0.0);
        assert!(lu_inverse(&z).is_none() && z.try_inverse().is_none());
        let mut e = M5::identity();
        let r0 = e.row(0).clone_owned();
        e.row_mut(1).copy_from(&r0);
        assert_eq!(lu_inverse(&e).is_none(), e.try_inverse().is_none());
    }

    #[test]
    fn structured_products_equal_nalgebras_bit_for_bit() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut r = |s: f64| rng.gen_range(-s..s);
        let mut h = nalgebra::SMatrix::<f64, 2, 5>::zeros();
        h[(0, 0)] = 1.0;
        h[(1, 1)] = 1.0;
        for _ in 0..2000 {
            let mut p = M5::zeros();
            p.iter_mut().for_each(|v| *v = r(1.0));
            let mut f = M5::identity();
            let dt = 0.01;
            for (i, j) in [(0, 0), (0, 1), (1, 0), (2, 0), (2, 1)] {
                f[(i, j)] += r(50.0) * dt;
            }
            for (i, j) in [(0, 3), (0, 4), (1, 4), (2, 4)] {
                f[(i, j)] = r(2.0) * dt;
            }
            assert_eq!(
                bits(propagate(&f, &p).as_slice()),
                bits((f * p * f.transpose()).as_slice())
            );
            assert_eq!(
                bits(times_ft(&p, &f).as_slice()),
                bits((p * f.transpose()).as_slice())
            );
            let mut s_inv = Matrix2::zeros();
            s_inv.iter_mut().for_each(|v| *v = r(100.0));
            let kg = gain(&p, &s_inv);
            assert_eq!(
                bits(kg.as_slice()),
                bits((p * h.transpose() * s_inv).as_slice())
            );
            let rk = Matrix2::new(r(1.0).abs(), 0.0, 0.0, r(1.0).abs());
            let ikh = M5::identity() - kg * h;
            let dense = ikh * p * ikh.transpose() + kg * rk * kg.transpose();
            assert_eq!(
                bits(joseph(&p, &kg, &rk).as_slice()),
                bits(dense.as_slice())
            );
        }
    }
}
