//! Mann-Whitney U test (scipy.stats.mannwhitneyu).
//!
//! Hand-written instead of `statrs::stats_tests::mannwhitneyu` because
//! statrs (0.19.1): (a) returns wrong exact p-values (checked against the
//! golden set: p = 1.0 where scipy gives 0.0303 for n = 5 vs 7, and 1.0 vs
//! 1.6e-4 for 8 vs 8); (b) enumerates all C(n1+n2, min(n1,n2)) rank subsets
//! for the exact p-value (4.8 s for n = 8 vs 30, unusable for 8 vs 200,
//! which scipy's `method="auto"` also treats exactly); (c) computes the
//! asymptotic p-value as `1 - cdf(z)`, which returns 0 where scipy gives
//! 1.6e-19. The exact null distribution here is the Gaussian binomial
//! coefficient [n1+n2 choose n1]_q, tabulated with exact integer arithmetic.

use serde::{Deserialize, Serialize};

use super::dist::norm_sf;
use super::rank::{rank_average, tie_term};
use super::{check_finite, clip01, Alternative, PValueMethod, StatsError};

/// How [`mannwhitneyu_with`] computes the p-value (scipy's `method=`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MwuMethod {
    /// scipy `method="auto"` (default): exact when either sample has at most
    /// 8 observations and there are no ties, otherwise asymptotic.
    #[default]
    Auto,
    /// scipy `method="exact"` (no ties allowed here).
    Exact,
    /// scipy `method="asymptotic"`: normal approximation with tie correction.
    Asymptotic,
}

/// Result of [`mannwhitneyu`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MannWhitneyUResult {
    /// U statistic of the first sample `x` (scipy's `statistic`), i.e.
    /// R1 − n1(n1+1)/2 with R1 the sum of x's mid-ranks in the pooled data.
    pub statistic: f64,
    /// p-value.
    pub pvalue: f64,
    /// Whether the p-value is exact or asymptotic.
    pub method: PValueMethod,
}

/// Mann-Whitney U rank test on two independent samples, equal to
/// `scipy.stats.mannwhitneyu(x, y, alternative=...)` (defaults
/// `use_continuity=True`, `method="auto"`).
///
/// `Less` / `Greater`: the distribution underlying `x` is stochastically
/// less / greater than that underlying `y`. See [`mannwhitneyu_with`].
pub fn mannwhitneyu(
    x: &[f64],
    y: &[f64],
    alternative: Alternative,
) -> Result<MannWhitneyUResult, StatsError> {
    mannwhitneyu_with(x, y, alternative, MwuMethod::Auto, true)
}

/// Mann-Whitney U test with scipy's `method` and `use_continuity` options,
/// equal to `scipy.stats.mannwhitneyu(x, y, use_continuity, alternative, method=...)`.
///
/// * `Auto`: exact if `min(n1, n2) <= 8` and there are no ties (scipy's
///   rule: asymptotic when both n1 > 8 and n2 > 8, or when there are ties).
/// * Exact: P(U ≥ u) from the exact null distribution; two-sided is
///   2·P(U ≥ max(U1, U2)), clipped to 1.
/// * Asymptotic: z = (U − n1 n2/2 − 0.5·continuity) / σ with the tie-corrected
///   σ² = n1 n2/12 · ((n+1) − Σ(t³−t)/(n(n−1))), p = P(Z ≥ z) (two-sided ×2).
///
/// If every pooled value is tied (σ = 0) scipy's formula gives p = 1 with
/// the continuity correction; that is returned. Without it (0/0) this is
/// [`StatsError::ConstantInput`].
///
/// Errors: an empty sample ([`StatsError::TooFewObservations`]); NaN / ±inf
/// ([`StatsError::NonFinite`]); `Exact` with ties
/// ([`StatsError::InvalidArgument`]; scipy silently truncates U);
/// an exact distribution with more than 2^128 configurations
/// ([`StatsError::TooLarge`], min(n1, n2) = 8 and max > ~2·10^5).
pub fn mannwhitneyu_with(
    x: &[f64],
    y: &[f64],
    alternative: Alternative,
    method: MwuMethod,
    use_continuity: bool,
) -> Result<MannWhitneyUResult, StatsError> {
    const T: &str = "mannwhitneyu";
    for s in [x, y] {
        if s.is_empty() {
            return Err(StatsError::TooFewObservations {
                test: T,
                needed: 1,
                got: 0,
                what: " in each sample",
            });
        }
    }
    check_finite(T, "x", x)?;
    check_finite(T, "y", y)?;
    let (n1, n2) = (x.len(), y.len());
    let pooled: Vec<f64> = x.iter().chain(y.iter()).copied().collect();
    let (ranks, ties) = rank_average(&pooled);
    let r1: f64 = ranks[..n1].iter().sum();
    let u1 = r1 - (n1 * (n1 + 1)) as f64 / 2.0;
    let u2 = (n1 * n2) as f64 - u1;
    let (u, factor) = match alternative {
        Alternative::Greater => (u1, 1.0),
        Alternative::Less => (u2, 1.0),
        Alternative::TwoSided => (u1.max(u2), 2.0),
    };
    let has_ties = ties.iter().any(|&t| t > 1);
    let method = match method {
        MwuMethod::Auto => {
            if (n1 > 8 && n2 > 8) || has_ties {
                MwuMethod::Asymptotic
            } else {
                MwuMethod::Exact
            }
        }
        MwuMethod::Exact if has_ties => {
            return Err(StatsError::InvalidArgument {
                test: T,
                detail: "method Exact is not valid with tied values".to_string(),
            })
        }
        m => m,
    };
    let (p, used) = match method {
        MwuMethod::Exact => (exact_sf(u, n1, n2)?, PValueMethod::Exact),
        _ => {
            let n = (n1 + n2) as f64;
            let (f1, f2) = (n1 as f64, n2 as f64);
            let mu = f1 * f2 / 2.0;
            let s = (f1 * f2 / 12.0 * ((n + 1.0) - tie_term(&ties) / (n * (n - 1.0)))).sqrt();
            let mut num = u - mu;
            if use_continuity {
                num -= 0.5;
            }
            if s == 0.0 && num == 0.0 {
                return Err(StatsError::ConstantInput {
                    test: T,
                    detail: format!(
                        "all {} pooled values equal {:?} and use_continuity is false",
                        n1 + n2,
                        x[0]
                    ),
                });
            }
            // s == 0 with num < 0 gives z = -inf and p = 1, as scipy
            (norm_sf(num / s), PValueMethod::Asymptotic)
        }
    };
    Ok(MannWhitneyUResult {
        statistic: u1,
        pvalue: clip01(p * factor),
        method: used,
    })
}

/// Exact P(U ≥ u) under H0 for sample sizes n1, n2 (no ties, integral u).
fn exact_sf(u: f64, n1: usize, n2: usize) -> Result<f64, StatsError> {
    let counts = u_distribution(n1, n2)?;
    let total: u128 = counts.iter().fold(0u128, |a, &c| a.wrapping_add(c));
    let k = u.round().max(0.0) as usize;
    let upper: u128 = counts.iter().skip(k).fold(0u128, |a, &c| a.wrapping_add(c));
    Ok(upper as f64 / total as f64)
}

/// Number of rank configurations giving U = 0..=n1·n2: the coefficients of
/// the Gaussian binomial [n1+n2 choose m]_q (m = min(n1, n2)), built with
/// [N choose k]_q = [N−1 choose k−1]_q (1 − q^N)/(1 − q^k). Arithmetic is
/// wrapping u128: the final coefficients are exact when their total
/// C(n1+n2, m) < 2^128, which is checked first.
fn u_distribution(n1: usize, n2: usize) -> Result<Vec<u128>, StatsError> {
    let m = n1.min(n2);
    let n = n1.max(n2);
    // total = C(n+m, m), checked
    let mut total: u128 = 1;
    for i in 1..=m {
        total = total
            .checked_mul((n + i) as u128)
            .map(|t| t / i as u128)
            .ok_or_else(|| StatsError::TooLarge {
                test: "mannwhitneyu",
                detail: format!(
                    "the exact null distribution for sample sizes {n1} and {n2} exceeds 2^128 \
                     configurations; use MwuMethod::Asymptotic"
                ),
            })?;
    }
    let len = m * n + 1;
    let mut c = vec![0u128; len + n + m + 1];
    c[0] = 1;
    let mut deg = 0usize; // degree of [n+i-1 choose i-1]_q = (i-1)·n
    for i in 1..=m {
        let a = n + i;
        // multiply by (1 - q^a)
        for k in (a..=deg + a).rev() {
            c[k] = c[k].wrapping_sub(c[k - a]);
        }
        // divide by (1 - q^i): running sum with stride i
        for k in i..=deg + a {
            c[k] = c[k].wrapping_add(c[k - i]);
        }
        deg += n;
        for v in c.iter_mut().skip(deg + 1).take(a) {
            *v = 0;
        }
    }
    c.truncate(len);
    Ok(c)
}

#[cfg(test)]
mod unit {
    use super::*;

    #[test]
    fn u_distribution_small() {
        // n1 = 2, n2 = 2: U in 0..=4 with counts 1,1,2,1,1
        assert_eq!(u_distribution(2, 2).unwrap(), vec![1, 1, 2, 1, 1]);
        // n1 = 3, n2 = 3: 1,1,2,3,3,3,3,2,1,1 (sum 20)
        assert_eq!(
            u_distribution(3, 3).unwrap(),
            vec![1, 1, 2, 3, 3, 3, 3, 2, 1, 1]
        );
        let c = u_distribution(8, 1000).unwrap();
        let total: u128 = c.iter().sum();
        // C(1008, 8)
        let mut expect: u128 = 1;
        for i in 1..=8u128 {
            expect = expect * (1000 + i) / i;
        }
        assert_eq!(total, expect);
        assert_eq!(c.first(), c.last());
    }
}
