//! The covariance products of the filter step without the multiplications by the structural
//! zeros and ones of the transition matrix F, the gain matrix I − KH and the diagonal R (issue
//! 17: they were two thirds of the attitude's time as dense 5 × 5 products).
//!
//! Every entry is summed over the same terms in the same order as nalgebra's dense product
//! (k ascending, `c = a₀b₀ + a₁b₁ + …`), leaving out only terms whose factor is an exact 0
//! (adding ±0 changes at most the sign of a zero) and writing `1·x` as `x`, so the results are
//! those of the dense products bit for bit (tested below against nalgebra). They are generic
//! over [`Num`]: on `f64` one filter, on [`super::lanes::L4`] four filters lane by lane with
//! the same operations.

use super::lanes::{array, Num};
use super::M5;

/// A 5 × 5 matrix as rows, `m[i][j]`, of any [`Num`] (one filter or four).
pub(super) type Mat<T> = [[T; 5]; 5];

/// The entries of F that are not structural: `f[(0..3, 0..2)]`, `f[(0, 3)]`, `f[(0..3, 4)]`.
#[derive(Clone, Copy)]
pub(super) struct Jacobian<T> {
    /// `F[0..3][0..2]`.
    pub(super) a: [[T; 2]; 3],
    /// `F[0][3]`.
    pub(super) b03: T,
    /// `F[0..3][4]`.
    pub(super) b4: [T; 3],
}

impl Jacobian<f64> {
    /// The dense F (for nalgebra's products and the scalar fallbacks).
    pub(super) fn dense(&self) -> M5 {
        let mut f = M5::identity();
        for i in 0..3 {
            for j in 0..2 {
                f[(i, j)] = self.a[i][j];
            }
            f[(i, 4)] = self.b4[i];
        }
        f[(0, 3)] = self.b03;
        // F[0][2] and F[1][2] are 0 + 0·dt, F[1][1] and F[2][2] 1 + 0·dt: as the identity
        f
    }
}

/// A nalgebra matrix as rows.
pub(super) fn rows(m: &M5) -> Mat<f64> {
    std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
}

/// Rows as a nalgebra matrix.
pub(super) fn matrix(a: &Mat<f64>) -> M5 {
    M5::from_fn(|i, j| a[i][j])
}

/// F P Fᵀ for the transition matrix of [`super::predict`]: F = I except `F[0..3, 0..2]`
/// (the Euler-rate Jacobian; its third column is zero and `F[1][1]` = 1), `F[0][3]` and
/// `F[0..3][4]` (the bias columns).
#[inline(always)]
pub(super) fn propagate<T: Num>(f: &Jacobian<T>, p: &Mat<T>) -> Mat<T> {
    let (a, b03, b4) = (&f.a, f.b03, &f.b4);
    let mut fp = *p;
    for j in 0..5 {
        fp[0][j] = ((a[0][0] * p[0][j] + a[0][1] * p[1][j]) + b03 * p[3][j]) + b4[0] * p[4][j];
        fp[1][j] = (a[1][0] * p[0][j] + p[1][j]) + b4[1] * p[4][j];
        fp[2][j] = ((a[2][0] * p[0][j] + a[2][1] * p[1][j]) + p[2][j]) + b4[2] * p[4][j];
    }
    times_ft(&fp, f)
}

/// A Fᵀ for F as in [`propagate`].
#[inline(always)]
pub(super) fn times_ft<T: Num>(m: &Mat<T>, f: &Jacobian<T>) -> Mat<T> {
    let (a, b03, b4) = (&f.a, f.b03, &f.b4);
    let mut b = *m;
    for row in b.iter_mut() {
        let r = *row;
        row[0] = ((r[0] * a[0][0] + r[1] * a[0][1]) + r[3] * b03) + r[4] * b4[0];
        row[1] = (r[0] * a[1][0] + r[1]) + r[4] * b4[1];
        row[2] = ((r[0] * a[2][0] + r[1] * a[2][1]) + r[2]) + r[4] * b4[2];
    }
    b
}

/// The Kalman gain K = P Hᵀ S⁻¹ for H selecting the first two states.
#[inline(always)]
pub(super) fn gain<T: Num>(pp: &Mat<T>, s_inv: &[[T; 2]; 2]) -> [[T; 2]; 5] {
    array(|i| array(|j| pp[i][0] * s_inv[0][j] + pp[i][1] * s_inv[1][j]))
}

/// The Joseph-form update (I − KH) P (I − KH)ᵀ + K R Kᵀ for H selecting the first two states
/// and R = diag(`rk`).
#[inline(always)]
#[cfg(test)]
pub(super) fn joseph<T: Num>(pp: &Mat<T>, kg: &[[T; 2]; 5], rk: [T; 2]) -> Mat<T> {
    let mut out = *pp;
    joseph_into(pp, kg, rk, &mut out);
    out
}

/// [`joseph`] written into `out` (the filter's covariance itself: no copy of the result).
#[inline(always)]
pub(super) fn joseph_into<T: Num>(pp: &Mat<T>, kg: &[[T; 2]; 5], rk: [T; 2], out: &mut Mat<T>) {
    // I − KH: columns 0 and 1 are e_j − K_j, the others those of I
    let ikh: [[T; 2]; 5] = array(|i| array(|j| T::splat(f64::from(u8::from(i == j))) - kg[i][j]));
    let mut a = *pp;
    for i in 0..5 {
        for j in 0..5 {
            let t = ikh[i][0] * pp[0][j] + ikh[i][1] * pp[1][j];
            a[i][j] = if i >= 2 { t + pp[i][j] } else { t };
        }
    }
    for i in 0..5 {
        // K R Kᵀ with R diagonal
        let c0 = kg[i][0] * rk[0];
        let c1 = kg[i][1] * rk[1];
        for j in 0..5 {
            let t = a[i][0] * ikh[j][0] + a[i][1] * ikh[j][1];
            let b = if j >= 2 { t + a[i][j] } else { t };
            out[i][j] = b + (c0 * kg[j][0] + c1 * kg[j][1]);
        }
    }
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
    use nalgebra::Matrix2;
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
        let flat = |m: &Mat<f64>| bits(matrix(m).as_slice());
        for _ in 0..2000 {
            let mut p = M5::zeros();
            p.iter_mut().for_each(|v| *v = r(1.0));
            let dt = 0.01;
            let jac = Jacobian {
                a: std::array::from_fn(|i| {
                    std::array::from_fn(|j| f64::from(u8::from(i == j)) + r(50.0) * dt)
                }),
                b03: r(2.0) * dt,
                b4: std::array::from_fn(|_| r(2.0) * dt),
            };
            let mut jac = jac;
            jac.a[1][1] = 1.0;
            let f = jac.dense();
            let pr = rows(&p);
            assert_eq!(
                flat(&propagate(&jac, &pr)),
                bits((f * p * f.transpose()).as_slice())
            );
            assert_eq!(
                flat(&times_ft(&pr, &jac)),
                bits((p * f.transpose()).as_slice())
            );
            let mut s_inv = Matrix2::zeros();
            s_inv.iter_mut().for_each(|v| *v = r(100.0));
            let si = [
                [s_inv[(0, 0)], s_inv[(0, 1)]],
                [s_inv[(1, 0)], s_inv[(1, 1)]],
            ];
            let kg = gain(&pr, &si);
            let kn = p * h.transpose() * s_inv;
            let kgm = nalgebra::SMatrix::<f64, 5, 2>::from_fn(|i, j| kg[i][j]);
            assert_eq!(bits(kgm.as_slice()), bits(kn.as_slice()));
            let rk = Matrix2::new(r(1.0).abs(), 0.0, 0.0, r(1.0).abs());
            let ikh = M5::identity() - kn * h;
            let dense = ikh * p * ikh.transpose() + kn * rk * kn.transpose();
            assert_eq!(
                flat(&joseph(&pr, &kg, [rk[(0, 0)], rk[(1, 1)]])),
                bits(dense.as_slice())
            );
        }
    }
}
