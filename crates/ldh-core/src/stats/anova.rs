//! One-way ANOVA (scipy.stats.f_oneway) and Kruskal-Wallis H
//! (scipy.stats.kruskal).
//!
//! `f_oneway` is hand-written rather than `statrs::stats_tests::f_oneway`
//! because statrs rejects any input in which one group is constant
//! (scipy computes F normally in that case) and uses the uncentred
//! sum-of-squares formula, which loses precision for data with a large
//! offset. statrs has no Kruskal-Wallis test.

use serde::{Deserialize, Serialize};

use super::dist::{chi2_sf, f_sf};
use super::rank::{rank_average, tie_term};
use super::ttest::is_constant;
use super::{check_finite, StatsError};

/// Result of [`f_oneway`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FOnewayResult {
    /// The F statistic.
    pub statistic: f64,
    /// p-value, P(F(df_between, df_within) > statistic).
    pub pvalue: f64,
    /// Between-groups degrees of freedom, k − 1.
    pub df_between: f64,
    /// Within-groups degrees of freedom, N − k.
    pub df_within: f64,
}

/// Result of [`kruskal`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct KruskalResult {
    /// The tie-corrected H statistic.
    pub statistic: f64,
    /// p-value from the chi-squared distribution with k − 1 df.
    pub pvalue: f64,
    /// Degrees of freedom, k − 1.
    pub df: f64,
}

fn validate_groups(test: &'static str, groups: &[&[f64]]) -> Result<(), StatsError> {
    if groups.len() < 2 {
        return Err(StatsError::TooFewGroups {
            test,
            got: groups.len(),
        });
    }
    for (i, g) in groups.iter().enumerate() {
        if g.is_empty() {
            return Err(StatsError::EmptyGroup { test, index: i });
        }
        check_finite(test, &format!("group {i}"), g)?;
    }
    Ok(())
}

/// One-way ANOVA F-test, equal to `scipy.stats.f_oneway(*groups)` (default
/// `equal_var=True`): F = (SS_between/(k−1)) / (SS_within/(N−k)), computed
/// on data centred at the grand mean as scipy does, p = P(F > f).
/// Single constant groups are fine (as in scipy).
///
/// Errors: fewer than 2 groups ([`StatsError::TooFewGroups`]; scipy raises
/// TypeError); an empty group ([`StatsError::EmptyGroup`]; scipy NaN); every
/// group of length 1 ([`StatsError::TooFewObservations`]; scipy NaN); NaN /
/// ±inf; every group constant, so the within-group variance is zero
/// ([`StatsError::ConstantInput`]; scipy returns F = inf, p = 0, or NaN if
/// all values are equal).
pub fn f_oneway(groups: &[&[f64]]) -> Result<FOnewayResult, StatsError> {
    const T: &str = "f_oneway";
    validate_groups(T, groups)?;
    let k = groups.len();
    let big_n: usize = groups.iter().map(|g| g.len()).sum();
    if big_n <= k {
        return Err(StatsError::TooFewObservations {
            test: T,
            needed: k + 1,
            got: big_n,
            what: " in total (at least one group needs 2)",
        });
    }
    if groups.iter().all(|g| is_constant(g)) {
        let all: Vec<f64> = groups.iter().flat_map(|g| g.iter().copied()).collect();
        let detail = if is_constant(&all) {
            format!("all {big_n} values equal {:?}", all[0])
        } else {
            "every group is constant, so the within-group variance is zero".to_string()
        };
        return Err(StatsError::ConstantInput { test: T, detail });
    }
    let nf = big_n as f64;
    let offset = groups.iter().flat_map(|g| g.iter()).sum::<f64>() / nf;
    let centred_sum: f64 = groups
        .iter()
        .flat_map(|g| g.iter())
        .map(|v| v - offset)
        .sum();
    let normalized_ss = centred_sum * centred_sum / nf;
    let sstot = groups
        .iter()
        .flat_map(|g| g.iter())
        .map(|v| (v - offset) * (v - offset))
        .sum::<f64>()
        - normalized_ss;
    let mut ssbn = 0.0;
    for g in groups {
        let s: f64 = g.iter().map(|v| v - offset).sum();
        ssbn += s * s / g.len() as f64;
    }
    ssbn -= normalized_ss;
    let sswn = sstot - ssbn;
    let dfbn = (k - 1) as f64;
    let dfwn = (big_n - k) as f64;
    let f = (ssbn / dfbn) / (sswn / dfwn);
    Ok(FOnewayResult {
        statistic: f,
        pvalue: f_sf(f, dfbn, dfwn),
        df_between: dfbn,
        df_within: dfwn,
    })
}

/// Kruskal-Wallis H-test, equal to `scipy.stats.kruskal(*groups)`:
/// H = [12/(N(N+1)) Σ R_i²/n_i − 3(N+1)] / [1 − Σ(t³−t)/(N³−N)] on mid-ranks,
/// p = P(χ²_{k−1} > H). Groups of one observation are allowed.
///
/// Errors: fewer than 2 groups ([`StatsError::TooFewGroups`]); an empty
/// group ([`StatsError::EmptyGroup`]); NaN / ±inf; all values equal
/// ([`StatsError::ConstantInput`]; scipy returns NaN).
pub fn kruskal(groups: &[&[f64]]) -> Result<KruskalResult, StatsError> {
    const T: &str = "kruskal";
    validate_groups(T, groups)?;
    let all: Vec<f64> = groups.iter().flat_map(|g| g.iter().copied()).collect();
    let big_n = all.len();
    let nf = big_n as f64;
    let (ranks, ties) = rank_average(&all);
    let tie_corr = 1.0 - tie_term(&ties) / (nf * nf * nf - nf);
    if tie_corr <= 0.0 {
        return Err(StatsError::ConstantInput {
            test: T,
            detail: format!("all {big_n} values equal {:?}", all[0]),
        });
    }
    let mut start = 0;
    let mut ssbn = 0.0;
    for g in groups {
        let s: f64 = ranks[start..start + g.len()].iter().sum();
        ssbn += s * s / g.len() as f64;
        start += g.len();
    }
    let h = (12.0 / (nf * (nf + 1.0)) * ssbn - 3.0 * (nf + 1.0)) / tie_corr;
    let df = (groups.len() - 1) as f64;
    Ok(KruskalResult {
        statistic: h,
        pvalue: chi2_sf(h, df),
        df,
    })
}
