//! Dense linear algebra for Eckmann's method on nalgebra: minimum-norm least squares through
//! an SVD and a QR decomposition normalised to a positive diagonal. Matrices are at most
//! `matrix_dim × matrix_dim` (typically 4) or `n_neighbours × matrix_dim`, row-major slices as
//! the rest of `nonlinear` keeps them.

use nalgebra::{DMatrix, DVector};

/// Minimum-norm least-squares solution of `A x ≈ b`, `A` row-major `p × d`,
/// singular values `≤ eps · σ_max` treated as zero — the semantics of
/// `np.linalg.lstsq(A, b, rcond=-1)` (LAPACK `dgelsd` with machine precision
/// as `rcond`).
pub(crate) fn lstsq_min_norm(a: &[f64], p: usize, d: usize, b: &[f64]) -> Vec<f64> {
    let svd = DMatrix::from_row_slice(p, d, a).svd(true, true);
    let smax = svd.singular_values.iter().copied().fold(0.0, f64::max);
    let x = svd
        .solve(&DVector::from_column_slice(b), f64::EPSILON * smax)
        .expect("U and V were computed");
    x.iter().copied().collect()
}

/// QR decomposition of a square row-major `d × d` matrix (Householder, nalgebra),
/// normalised so that `diag(R) ≥ 0` (nolds flips the signs of `np.linalg.qr`'s output the same
/// way; zero diagonal entries keep sign +1). With a positive diagonal the factorisation of a
/// non-singular matrix is unique, so the result does not depend on the QR algorithm.
/// Returns `(Q, R)` row-major.
pub(crate) fn qr_positive(a: &[f64], d: usize) -> (Vec<f64>, Vec<f64>) {
    let qr = DMatrix::from_row_slice(d, d, a).qr();
    let (mut q, mut r) = (qr.q(), qr.r());
    for k in 0..d {
        if r[(k, k)] < 0.0 {
            r.row_mut(k).neg_mut();
            q.column_mut(k).neg_mut();
        }
    }
    let row_major = |m: &DMatrix<f64>| m.transpose().as_slice().to_vec();
    (row_major(&q), row_major(&r))
}

/// Row-major `d × d` product.
pub(crate) fn matmul(a: &[f64], b: &[f64], d: usize) -> Vec<f64> {
    let mut c = vec![0.0; d * d];
    for i in 0..d {
        for k in 0..d {
            let aik = a[i * d + k];
            for j in 0..d {
                c[i * d + j] += aik * b[k * d + j];
            }
        }
    }
    c
}

/// Ordinary least-squares line `y ≈ slope·x + intercept` (same solution as
/// `np.polyfit(x, y, 1)`; centred formulation for accuracy).
pub(crate) fn line_fit(x: &[f64], y: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let xm = x.iter().sum::<f64>() / n;
    let ym = y.iter().sum::<f64>() / n;
    let mut sxy = 0.0;
    let mut sxx = 0.0;
    for (a, b) in x.iter().zip(y) {
        sxy += (a - xm) * (b - ym);
        sxx += (a - xm) * (a - xm);
    }
    let slope = sxy / sxx;
    (slope, ym - slope * xm)
}
