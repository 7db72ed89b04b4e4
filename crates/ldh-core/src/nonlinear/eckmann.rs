//! Eckmann, Kamphorst, Ruelle & Ciliberto (1986): the Lyapunov spectrum from
//! local Jacobians fitted in neighbourhoods, with the exact semantics of
//! `nolds.lyap_e` (nolds 0.6.2).

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::embed::delay_embed_flat;
use super::linalg::{lstsq_min_norm, matmul, qr_positive};
use super::neighbours::chebyshev_neighbourhoods;
use super::{check_series, invalid, NonlinearError};

/// Parameters of [`lyap_e`], mirroring `nolds.lyap_e` one to one. Lengths in
/// samples.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct EckmannParams {
    /// Embedding dimension (lag 1) for the neighbour search (default 10).
    /// `emb_dim − 1` must be divisible by `matrix_dim − 1`.
    pub emb_dim: usize,
    /// Size of the local Jacobians = number of exponents returned (default 4).
    pub matrix_dim: usize,
    /// Minimal number of neighbours; `None` (default): nolds' rule
    /// `min(2·matrix_dim, matrix_dim + 4)`.
    pub min_nb: Option<usize>,
    /// Theiler window in samples: neighbours satisfy `|i − j| > min_tsep`
    /// (default 0: only the point itself is excluded).
    pub min_tsep: usize,
    /// Sampling interval in seconds (default 1.0); exponents are divided by it.
    pub tau: f64,
}

impl Default for EckmannParams {
    fn default() -> Self {
        Self {
            emb_dim: 10,
            matrix_dim: 4,
            min_nb: None,
            min_tsep: 0,
            tau: 1.0,
        }
    }
}

impl EckmannParams {
    /// Sets the embedding dimension.
    pub fn emb_dim(mut self, emb_dim: usize) -> Self {
        self.emb_dim = emb_dim;
        self
    }
    /// Sets the Jacobian size.
    pub fn matrix_dim(mut self, matrix_dim: usize) -> Self {
        self.matrix_dim = matrix_dim;
        self
    }
    /// Sets the minimal number of neighbours (`None`: nolds' rule).
    pub fn min_nb(mut self, min_nb: Option<usize>) -> Self {
        self.min_nb = min_nb;
        self
    }
    /// Sets the Theiler window in samples.
    pub fn min_tsep(mut self, min_tsep: usize) -> Self {
        self.min_tsep = min_tsep;
        self
    }
    /// Sets the sampling interval in seconds.
    pub fn tau(mut self, tau_s: f64) -> Self {
        self.tau = tau_s;
        self
    }

    /// Validates (`matrix_dim ≥ 2`, `emb_dim − 1` a positive multiple of
    /// `matrix_dim − 1`, finite `tau > 0`, `min_nb ≥ 1`) and resolves the
    /// `min_nb` default into the type [`lyap_e`] accepts.
    pub fn check(&self) -> Result<ValidEckmannParams, NonlinearError> {
        if self.matrix_dim < 2 {
            return Err(invalid("matrix_dim", self.matrix_dim, "must be at least 2"));
        }
        if self.emb_dim < self.matrix_dim || !(self.emb_dim - 1).is_multiple_of(self.matrix_dim - 1)
        {
            return Err(invalid(
                "emb_dim",
                self.emb_dim,
                format!(
                    "emb_dim - 1 must be a positive multiple of matrix_dim - 1 = {}",
                    self.matrix_dim - 1
                ),
            ));
        }
        if !(self.tau.is_finite() && self.tau > 0.0) {
            return Err(invalid(
                "tau",
                self.tau,
                "must be a finite, positive sampling interval in seconds",
            ));
        }
        let min_nb = self
            .min_nb
            .unwrap_or((2 * self.matrix_dim).min(self.matrix_dim + 4));
        if min_nb == 0 {
            return Err(invalid("min_nb", min_nb, "must be at least 1"));
        }
        Ok(ValidEckmannParams {
            params: self.clone(),
            step: (self.emb_dim - 1) / (self.matrix_dim - 1),
            min_nb,
        })
    }
}

/// [`EckmannParams`] validated by [`EckmannParams::check`], with `min_nb`
/// resolved: the type [`lyap_e`] accepts. Dereferences to the parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct ValidEckmannParams {
    params: EckmannParams,
    step: usize,
    min_nb: usize,
}

impl std::ops::Deref for ValidEckmannParams {
    type Target = EckmannParams;
    fn deref(&self) -> &EckmannParams {
        &self.params
    }
}

/// Result of [`lyap_e`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EckmannResult {
    /// The `matrix_dim` Lyapunov exponents, largest first as nolds orders them
    /// (1/s if `tau` is in s). `+inf` where no R diagonal was positive (nolds).
    pub exponents: Vec<f64>,
    /// Embedding dimension used.
    pub emb_dim: usize,
    /// Jacobian size used.
    pub matrix_dim: usize,
    /// Minimal number of neighbours used.
    pub min_nb: usize,
    /// Theiler window used in samples.
    pub min_tsep: usize,
    /// Step `m = (emb_dim − 1)/(matrix_dim − 1)` between Jacobian coordinates,
    /// in samples.
    pub step: usize,
    /// Sampling interval in seconds.
    pub tau: f64,
}

/// Minimum series length for [`lyap_e`] (nolds `lyap_e_len`):
/// `emb_dim + m + 2·min_tsep + min_nb` with `m = (emb_dim − 1)/(matrix_dim − 1)`.
pub fn lyap_e_len(emb_dim: usize, matrix_dim: usize, min_nb: usize, min_tsep: usize) -> usize {
    let m = emb_dim.saturating_sub(1) / matrix_dim.saturating_sub(1).max(1);
    emb_dim
        .saturating_add(m)
        .saturating_add(min_tsep.saturating_mul(2))
        .saturating_add(min_nb)
}

/// Lyapunov spectrum by Eckmann's method, equal to
/// `nolds.lyap_e(x, emb_dim, matrix_dim, min_nb, min_tsep, tau)`.
///
/// Steps: orbit = lag-1 embedding of `x[..n−m]`; for each orbit vector the
/// radius `r_i` is its `min_nb`-th smallest Chebyshev distance to vectors
/// with `|i − j| > min_tsep` (`j ≠ i`), and all such vectors within `r_i` are
/// its neighbours; the last row of the local Jacobian `T_i` is the
/// minimum-norm least-squares solution of `(x_{j+k·m} − x_{i+k·m})_k · a =
/// x_{j+matrix_dim·m} − x_{i+matrix_dim·m}` (the other rows shift);
/// `T_i Q_{i−1} = Q_i R_i` with `diag(R_i) ≥ 0`; exponents are the means of
/// `ln R_i[k,k]` over the positive diagonals, divided by `tau·m`.
///
/// Errors: empty, non-finite or constant input; series shorter than
/// [`lyap_e_len`]. Parameters are validated by [`EckmannParams::check`].
pub fn lyap_e(x: &[f64], params: &ValidEckmannParams) -> Result<EckmannResult, NonlinearError> {
    check_series(x)?;
    let (m, min_nb) = (params.step, params.min_nb);
    let n = x.len();
    let (emb_dim, md) = (params.emb_dim, params.matrix_dim);
    let needed = lyap_e_len(emb_dim, md, min_nb, params.min_tsep);
    if n < needed {
        return Err(NonlinearError::TooShortEckmann {
            len: n,
            emb_dim,
            matrix_dim: md,
            min_nb,
            min_tsep: params.min_tsep,
            needed,
        });
    }
    let orbit = delay_embed_flat(&x[..n - m], emb_dim, 1)?;
    let hoods = chebyshev_neighbourhoods(&orbit, emb_dim, params.min_tsep, min_nb);
    // local Jacobians (last rows) in parallel; the QR chain below is sequential
    let rows: Vec<Option<Vec<f64>>> = hoods
        .par_iter()
        .enumerate()
        .map(|(i, hood)| {
            let hood = hood.as_ref()?;
            let p = hood.len();
            let mut a = Vec::with_capacity(p * md);
            let mut b = Vec::with_capacity(p);
            for &j in hood {
                for k in 0..md {
                    a.push(x[j + k * m] - x[i + k * m]);
                }
                b.push(x[j + md * m] - x[i + md * m]);
            }
            Some(lstsq_min_norm(&a, p, md, &b))
        })
        .collect();
    let mut q = vec![0.0; md * md];
    for k in 0..md {
        q[k * md + k] = 1.0;
    }
    let mut lexp = vec![0.0; md];
    let mut counts = vec![0usize; md];
    let mut t = vec![0.0; md * md];
    for row in rows.iter() {
        let Some(a) = row else {
            // a row without min_nb valid neighbours: nolds raises here
            return Err(NonlinearError::TooShortEckmann {
                len: n,
                emb_dim,
                matrix_dim: md,
                min_nb,
                min_tsep: params.min_tsep,
                // unreachable once n ≥ lyap_e_len (every row then has at
                // least min_nb candidates); kept as an error, not a panic
                needed: needed.max(n + 1),
            });
        };
        t.iter_mut().for_each(|v| *v = 0.0);
        for r in 0..md - 1 {
            t[r * md + r + 1] = 1.0;
        }
        t[(md - 1) * md..].copy_from_slice(a);
        let (qn, rn) = qr_positive(&matmul(&t, &q, md), md);
        q = qn;
        for k in 0..md {
            let dk = rn[k * md + k];
            if dk > 0.0 {
                lexp[k] += dk.ln();
                counts[k] += 1;
            }
        }
    }
    let exponents = lexp
        .iter()
        .zip(&counts)
        .map(|(&s, &c)| {
            let v = if c > 0 { s / c as f64 } else { f64::INFINITY };
            v / params.tau / m as f64
        })
        .collect();
    Ok(EckmannResult {
        exponents,
        emb_dim,
        matrix_dim: md,
        min_nb,
        min_tsep: params.min_tsep,
        step: m,
        tau: params.tau,
    })
}
