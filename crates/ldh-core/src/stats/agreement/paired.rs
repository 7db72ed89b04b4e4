//! Agreement of one parameter between ldh and the reference system from paired values: bias
//! and limits of agreement ([`super::bland_altman`]), proportional bias, MAE and relative MAE,
//! ICC(2,1) and ICC(3,1) of the n × 2 table ([`super::icc`]), Pearson's r
//! ([`crate::stats::pearsonr`]).
//!
//! A pair with a NaN on either side is dropped and counted ([`ParameterAgreement::n_dropped`]);
//! ±inf is an error.

use serde::{Deserialize, Serialize};

use super::bland_altman::{limits_of_agreement, linregress, LimitsOfAgreement, LinearFit};
use super::icc::{icc, IccResult};
use super::{AgreementError, ValidAgreementParams};
use crate::stats::{pearsonr, Alternative};

/// Fewest complete pairs [`agreement`] accepts: the regression for proportional bias has
/// n − 2 degrees of freedom.
pub const MIN_PAIRS: usize = 3;

/// Agreement of one parameter, ldh against the reference. Differences are ldh − reference
/// (pingouin's x − y with x = ldh), in the parameter's unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParameterAgreement {
    /// Pairs used (both values present).
    pub n_pairs: usize,
    /// Pairs dropped because one or both values were NaN.
    pub n_dropped: usize,
    /// Mean of the ldh values of the pairs used.
    pub mean_ldh: f64,
    /// Mean of the reference values of the pairs used.
    pub mean_reference: f64,
    /// Bias, SD of the differences, limits of agreement and their confidence intervals.
    pub limits: LimitsOfAgreement,
    /// Proportional bias: regression of the difference on the mean of the two
    /// (`scipy.stats.linregress(mean, diff)`); `slope` and its `pvalue` are the test.
    pub proportional_bias: LinearFit,
    /// Mean absolute difference, mean |ldh − reference|.
    pub mae: f64,
    /// MAE / mean |reference| (a fraction, not %).
    pub relative_mae: f64,
    /// ICC(1,1), ICC(2,1) and ICC(3,1) of the n × 2 table (ldh and reference as the two
    /// raters), with their confidence intervals.
    pub icc: IccResult,
    /// Pearson's r of ldh and reference (`scipy.stats.pearsonr`).
    pub pearson_r: f64,
    /// Two-sided p-value of Pearson's r.
    pub pearson_pvalue: f64,
}

/// The complete pairs of `ldh` and `reference` and how many were dropped for a NaN.
pub(crate) fn complete_pairs(
    what: &'static str,
    ldh: &[f64],
    reference: &[f64],
) -> Result<(Vec<f64>, Vec<f64>, usize), AgreementError> {
    if ldh.len() != reference.len() {
        return Err(AgreementError::LengthMismatch {
            what,
            ldh_len: ldh.len(),
            reference_len: reference.len(),
        });
    }
    for (input, v) in [("ldh", ldh), ("reference", reference)] {
        if let Some(index) = v.iter().position(|x| x.is_infinite()) {
            return Err(AgreementError::NonFinite {
                what,
                input: input.into(),
                index,
                value: v[index],
            });
        }
    }
    let (mut x, mut y) = (Vec::with_capacity(ldh.len()), Vec::with_capacity(ldh.len()));
    for (&a, &b) in ldh.iter().zip(reference) {
        if !a.is_nan() && !b.is_nan() {
            x.push(a);
            y.push(b);
        }
    }
    let dropped = ldh.len() - x.len();
    Ok((x, y, dropped))
}

/// Agreement of paired values of one parameter: `ldh[i]` and `reference[i]` measure the same
/// thing (one subject, trial, side). See `docs/agreement.md` for every formula.
///
/// Errors: different lengths; ±inf; fewer than [`MIN_PAIRS`] complete pairs; all ldh or all
/// reference values equal (Pearson's r undefined); all differences equal; all means equal.
pub fn agreement(
    ldh: &[f64],
    reference: &[f64],
    params: &ValidAgreementParams,
) -> Result<ParameterAgreement, AgreementError> {
    const W: &str = "agreement";
    let p = params.params();
    let (x, y, n_dropped) = complete_pairs(W, ldh, reference)?;
    let n = x.len();
    if n < MIN_PAIRS {
        return Err(AgreementError::TooFewPairs {
            what: W,
            needed: MIN_PAIRS,
            got: n,
            dropped: n_dropped,
            unit: "pairs",
        });
    }
    for (name, v) in [("ldh", &x), ("reference", &y)] {
        if v.iter().all(|a| *a == v[0]) {
            return Err(AgreementError::ConstantData {
                what: W,
                detail: format!("all {n} {name} values equal {:?}", v[0]),
            });
        }
    }
    let diff: Vec<f64> = x.iter().zip(&y).map(|(a, b)| a - b).collect();
    let means: Vec<f64> = x.iter().zip(&y).map(|(a, b)| (a + b) / 2.0).collect();
    let limits = limits_of_agreement(&diff, p.loa_sd_multiplier, p.confidence_level)?;
    let proportional_bias = linregress(&means, &diff)?;
    let nf = n as f64;
    let mae = diff.iter().map(|d| d.abs()).sum::<f64>() / nf;
    let mean_abs_ref = y.iter().map(|b| b.abs()).sum::<f64>() / nf;
    let table: Vec<f64> = x.iter().zip(&y).flat_map(|(a, b)| [*a, *b]).collect();
    let icc = icc(&table, 2, p.confidence_level)?;
    let r = pearsonr(&x, &y, Alternative::TwoSided)?;
    Ok(ParameterAgreement {
        n_pairs: n,
        n_dropped,
        mean_ldh: crate::stats::mean(&x)?,
        mean_reference: crate::stats::mean(&y)?,
        limits,
        proportional_bias,
        mae,
        relative_mae: mae / mean_abs_ref,
        icc,
        pearson_r: r.statistic,
        pearson_pvalue: r.pvalue,
    })
}
