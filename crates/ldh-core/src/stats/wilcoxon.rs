//! Wilcoxon signed-rank test (scipy.stats.wilcoxon with its defaults
//! `zero_method="wilcox"`, `correction=False`, `method="auto"`).
//!
//! statrs has no signed-rank test, so it is written here, including the
//! exact null distribution (subset-sum counting) and the exact permutation
//! distribution scipy uses for small samples with ties or zeros.

use serde::{Deserialize, Serialize};

use super::dist::z_pvalue;
use super::rank::{rank_average, tie_term};
use super::{check_finite, clip01, Alternative, PValueMethod, StatsError};

/// Result of [`wilcoxon`] / [`wilcoxon_paired`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WilcoxonResult {
    /// As scipy reports it: min(R+, R−) for `TwoSided`, R+ (sum of the ranks
    /// of the positive differences) for `Less` / `Greater`.
    pub statistic: f64,
    /// p-value.
    pub pvalue: f64,
    /// Exact, exact-permutation or asymptotic p-value.
    pub method: PValueMethod,
}

/// Wilcoxon signed-rank test of paired samples, on `x[i] - y[i]`; equal to
/// `scipy.stats.wilcoxon(x, y, alternative=...)`. See [`wilcoxon`].
///
/// Errors as [`wilcoxon`], plus [`StatsError::LengthMismatch`].
pub fn wilcoxon_paired(
    x: &[f64],
    y: &[f64],
    alternative: Alternative,
) -> Result<WilcoxonResult, StatsError> {
    if x.len() != y.len() {
        return Err(StatsError::LengthMismatch {
            test: "wilcoxon",
            x_len: x.len(),
            y_len: y.len(),
        });
    }
    check_finite("wilcoxon", "x", x)?;
    check_finite("wilcoxon", "y", y)?;
    let d: Vec<f64> = x.iter().zip(y).map(|(a, b)| a - b).collect();
    wilcoxon(&d, alternative)
}

/// Wilcoxon signed-rank test of the differences `d` (one-sample form),
/// equal to `scipy.stats.wilcoxon(d, alternative=...)` with the defaults
/// `zero_method="wilcox"` (zero differences are dropped before ranking),
/// `correction=False` and `method="auto"`, which in scipy 1.17 means, with
/// n = len(d) counting zeros:
///
/// * n > 50: normal approximation, z = (R+ − m(m+1)/4) / σ with m the number
///   of non-zero differences and σ² = (m(m+1)(2m+1) − Σ(t³−t)/2)/24;
/// * n ≤ 50, no ties and no zeros: exact null distribution of R+;
/// * n ≤ 13 with ties or zeros: exact permutation test over all 2^n sign
///   flips (scipy `PermutationMethod()`, deterministic for n ≤ 13);
/// * 14 ≤ n ≤ 50 with ties or zeros: the normal approximation.
///
/// `Less` / `Greater`: the differences are stochastically less / greater
/// than zero. Exact two-sided p = 2·min(P(R+ ≤ r), P(R+ ≥ r)), clipped to 1.
///
/// Errors: empty input ([`StatsError::TooFewObservations`]); NaN / ±inf
/// ([`StatsError::NonFinite`]); all differences zero
/// ([`StatsError::ConstantInput`]; scipy returns p = 1 for n ≤ 13 and NaN
/// for larger n, warning in both cases).
pub fn wilcoxon(d: &[f64], alternative: Alternative) -> Result<WilcoxonResult, StatsError> {
    const T: &str = "wilcoxon";
    let n = d.len();
    if n == 0 {
        return Err(StatsError::TooFewObservations {
            test: T,
            needed: 1,
            got: 0,
            what: "",
        });
    }
    check_finite(T, "d", d)?;
    let nonzero: Vec<f64> = d.iter().copied().filter(|v| *v != 0.0).collect();
    let n_zero = n - nonzero.len();
    let m = nonzero.len();
    if m == 0 {
        return Err(StatsError::ConstantInput {
            test: T,
            detail: format!("all {n} differences are zero"),
        });
    }
    let abs: Vec<f64> = nonzero.iter().map(|v| v.abs()).collect();
    let (ranks, ties) = rank_average(&abs);
    let r_plus: f64 = nonzero
        .iter()
        .zip(&ranks)
        .filter(|(v, _)| **v > 0.0)
        .map(|(_, r)| r)
        .sum();
    let r_minus: f64 = nonzero
        .iter()
        .zip(&ranks)
        .filter(|(v, _)| **v < 0.0)
        .map(|(_, r)| r)
        .sum();
    let has_ties = ties.iter().any(|&t| t > 1);

    let method = if n > 50 {
        PValueMethod::Asymptotic
    } else if !has_ties && n_zero == 0 {
        PValueMethod::Exact
    } else if n <= 13 {
        PValueMethod::ExactPermutation
    } else {
        PValueMethod::Asymptotic
    };

    let pvalue = match method {
        PValueMethod::Asymptotic => {
            let mf = m as f64;
            let mn = mf * (mf + 1.0) * 0.25;
            let se = mf * (mf + 1.0) * (2.0 * mf + 1.0);
            let se = ((se - tie_term(&ties) / 2.0) / 24.0).sqrt();
            z_pvalue((r_plus - mn) / se, alternative)
        }
        _ => {
            // Both exact cases: the distribution of 2·R+ over all 2^m sign
            // patterns of the (doubled, hence integral) ranks. Without ties
            // these are 2, 4, ..., 2m: the classical exact distribution.
            let doubled: Vec<usize> = ranks.iter().map(|r| (2.0 * r).round() as usize).collect();
            let counts = signed_rank_counts(&doubled);
            let obs = (2.0 * r_plus).round() as usize;
            let total = 2f64.powi(m as i32);
            let le: u64 = counts[..=obs].iter().sum();
            let ge: u64 = counts[obs..].iter().sum();
            let (cdf, sf) = (le as f64 / total, ge as f64 / total);
            match alternative {
                Alternative::Less => cdf,
                Alternative::Greater => sf,
                Alternative::TwoSided => clip01(2.0 * cdf.min(sf)),
            }
        }
    };
    let statistic = match alternative {
        Alternative::TwoSided => r_plus.min(r_minus),
        _ => r_plus,
    };
    Ok(WilcoxonResult {
        statistic,
        pvalue,
        method,
    })
}

/// counts[s] = number of subsets of `weights` with sum s (subset-sum DP).
/// With at most 50 weights the total 2^50 fits u64 exactly.
fn signed_rank_counts(weights: &[usize]) -> Vec<u64> {
    let max: usize = weights.iter().sum();
    let mut c = vec![0u64; max + 1];
    c[0] = 1;
    let mut reach = 0;
    for &w in weights {
        reach += w;
        for s in (w..=reach).rev() {
            c[s] += c[s - w];
        }
    }
    c
}
