//! Tiny dense linear algebra for Eckmann's method: minimum-norm least squares
//! through an SVD (one-sided Jacobi) and a QR decomposition with a positive
//! diagonal (Householder). Matrices are at most `matrix_dim × matrix_dim`
//! (typically 4) or `n_neighbours × matrix_dim`, so hand-written kernels are
//! simpler than pulling a LAPACK binding (`ndarray-linalg` needs system BLAS,
//! which the host workspace avoids).

/// Minimum-norm least-squares solution of `A x ≈ b`, `A` row-major `p × d`,
/// singular values `≤ eps · σ_max` treated as zero — the semantics of
/// `np.linalg.lstsq(A, b, rcond=-1)` (LAPACK `dgelsd` with machine precision
/// as `rcond`).
pub(crate) fn lstsq_min_norm(a: &[f64], p: usize, d: usize, b: &[f64]) -> Vec<f64> {
    // column-major copy: columns get rotated by one-sided Jacobi
    let mut u: Vec<Vec<f64>> = (0..d)
        .map(|j| (0..p).map(|i| a[i * d + j]).collect())
        .collect();
    let mut v: Vec<Vec<f64>> = (0..d)
        .map(|j| (0..d).map(|i| if i == j { 1.0 } else { 0.0 }).collect())
        .collect();
    let eps = f64::EPSILON;
    for _sweep in 0..60 {
        let mut rotated = false;
        for j in 0..d {
            for k in j + 1..d {
                let alpha: f64 = u[j].iter().map(|x| x * x).sum();
                let beta: f64 = u[k].iter().map(|x| x * x).sum();
                let gamma: f64 = u[j].iter().zip(&u[k]).map(|(x, y)| x * y).sum();
                if gamma == 0.0 || gamma.abs() <= eps * (alpha * beta).sqrt() {
                    continue;
                }
                rotated = true;
                let zeta = (beta - alpha) / (2.0 * gamma);
                let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
                let c = 1.0 / (1.0 + t * t).sqrt();
                let s = c * t;
                rotate(&mut u, j, k, c, s);
                rotate(&mut v, j, k, c, s);
            }
        }
        if !rotated {
            break;
        }
    }
    let sigma: Vec<f64> = u
        .iter()
        .map(|col| col.iter().map(|x| x * x).sum::<f64>().sqrt())
        .collect();
    let smax = sigma.iter().copied().fold(0.0, f64::max);
    let mut x = vec![0.0; d];
    for j in 0..d {
        if sigma[j] > eps * smax && sigma[j] > 0.0 {
            let coef: f64 =
                u[j].iter().zip(b).map(|(ui, bi)| ui * bi).sum::<f64>() / (sigma[j] * sigma[j]);
            for i in 0..d {
                x[i] += coef * v[j][i];
            }
        }
    }
    x
}

/// Plane rotation of columns `j < k`: `(x, y) ← (c·x − s·y, s·x + c·y)`.
fn rotate(cols: &mut [Vec<f64>], j: usize, k: usize, c: f64, s: f64) {
    let (lo, hi) = cols.split_at_mut(k);
    for (x, y) in lo[j].iter_mut().zip(hi[0].iter_mut()) {
        let (a, b) = (*x, *y);
        *x = c * a - s * b;
        *y = s * a + c * b;
    }
}

/// QR decomposition of a square row-major `d × d` matrix by Householder
/// reflections, normalised so that `diag(R) ≥ 0` (nolds flips the signs of
/// `np.linalg.qr`'s output the same way; zero diagonal entries keep sign +1).
/// With a positive diagonal the factorisation of a non-singular matrix is
/// unique, so the result does not depend on the QR algorithm.
pub(crate) fn qr_positive(a: &[f64], d: usize) -> (Vec<f64>, Vec<f64>) {
    let mut r = a.to_vec();
    let mut q = vec![0.0; d * d];
    for i in 0..d {
        q[i * d + i] = 1.0;
    }
    for k in 0..d.saturating_sub(1) {
        let norm: f64 = (k..d)
            .map(|i| r[i * d + k] * r[i * d + k])
            .sum::<f64>()
            .sqrt();
        if norm == 0.0 {
            continue;
        }
        let alpha = if r[k * d + k] > 0.0 { -norm } else { norm };
        let mut vk: Vec<f64> = (k..d).map(|i| r[i * d + k]).collect();
        vk[0] -= alpha;
        let vnorm2: f64 = vk.iter().map(|x| x * x).sum();
        if vnorm2 == 0.0 {
            continue;
        }
        // R ← H R
        for j in 0..d {
            let dot: f64 = (k..d).map(|i| vk[i - k] * r[i * d + j]).sum();
            let f = 2.0 * dot / vnorm2;
            for i in k..d {
                r[i * d + j] -= f * vk[i - k];
            }
        }
        // Q ← Q H
        for i in 0..d {
            let dot: f64 = (k..d).map(|j| q[i * d + j] * vk[j - k]).sum();
            let f = 2.0 * dot / vnorm2;
            for j in k..d {
                q[i * d + j] -= f * vk[j - k];
            }
        }
    }
    for i in 1..d {
        for j in 0..i {
            r[i * d + j] = 0.0;
        }
    }
    for k in 0..d {
        if r[k * d + k] < 0.0 {
            for j in 0..d {
                r[k * d + j] = -r[k * d + j];
                q[j * d + k] = -q[j * d + k];
            }
        }
    }
    (q, r)
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
