//! Bland–Altman limits of agreement with their confidence intervals, and the test for
//! proportional bias (regression of the difference on the mean).
//!
//! Method: Bland, J. M. & Altman, D. G. (1986), "Statistical methods for assessing agreement
//! between two methods of clinical measurement", *The Lancet* 327(8476), 307–310; and (1999),
//! "Measuring agreement in method comparison studies", *Statistical Methods in Medical Research*
//! 8(2), 135–160. The limits are bias ± z·SD of the differences (z = 1.96 by default, pingouin's
//! `agreement=1.96`, not the t quantile). Their confidence intervals use the **approximate**
//! standard error of 1986 / 1999 §4.2, SE(limit) = √(3·s²/n), with the t quantile on n − 1
//! degrees of freedom — not the exact interval from the non-central t (Carkeet 2015). That is
//! what `pingouin.plot_blandaltman(x, y, agreement=1.96, confidence=0.95)` draws (its `axhspan`
//! bands), and the bias interval is `scipy.stats.t.interval(conf, n − 1, bias, s/√n)`.
//!
//! Proportional bias: the ordinary least-squares line of the difference (ldh − reference) on
//! the mean of the two, equal to `scipy.stats.linregress(mean, diff)` (slope, intercept, r,
//! two-sided p-value of the slope, the standard errors).

use serde::{Deserialize, Serialize};

use super::AgreementError;
use crate::stats::dist::{t_isf, t_pvalue};
use crate::stats::{mean, std_dev, Alternative};

/// Spread, relative to the largest |value|, below which values count as equal: rounding, not
/// data (scipy tests exact equality and returns meaningless numbers for 1e-16 spreads).
pub(crate) const ROUNDING: f64 = 1e-12;

/// Limits of agreement of paired differences, with confidence intervals.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LimitsOfAgreement {
    /// Mean difference (ldh − reference), the bias.
    pub bias: f64,
    /// Sample standard deviation of the differences (ddof = 1).
    pub sd_diff: f64,
    /// Lower limit, bias − z·SD.
    pub lower: f64,
    /// Upper limit, bias + z·SD.
    pub upper: f64,
    /// Confidence interval of the bias, bias ± t·SD/√n.
    pub bias_ci: (f64, f64),
    /// Confidence interval of the lower limit, lower ± t·√(3·SD²/n).
    pub lower_ci: (f64, f64),
    /// Confidence interval of the upper limit, upper ± t·√(3·SD²/n).
    pub upper_ci: (f64, f64),
}

/// Ordinary least-squares line of y on x, as `scipy.stats.linregress(x, y)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LinearFit {
    /// Slope (for proportional bias: change of the difference per unit of the mean).
    pub slope: f64,
    /// Intercept.
    pub intercept: f64,
    /// Pearson's r of x and y.
    pub rvalue: f64,
    /// Two-sided p-value of H0: slope = 0 (t test, n − 2 degrees of freedom).
    pub pvalue: f64,
    /// Standard error of the slope.
    pub stderr: f64,
    /// Standard error of the intercept.
    pub intercept_stderr: f64,
}

/// Limits of agreement of the differences `diff` (finite, n ≥ 2) at `z`·SD, with intervals at
/// `confidence_level` (pingouin `plot_blandaltman(agreement=z, confidence=...)`).
///
/// Errors: n < 2; all differences equal up to rounding (SD ≤ 1e-12·max |difference|: the limits collapse onto the bias and their
/// intervals are empty).
pub fn limits_of_agreement(
    diff: &[f64],
    z: f64,
    confidence_level: f64,
) -> Result<LimitsOfAgreement, AgreementError> {
    const W: &str = "limits of agreement";
    let n = diff.len();
    if n < 2 {
        return Err(AgreementError::TooFewPairs {
            what: W,
            needed: 2,
            got: n,
            dropped: 0,
            unit: "pairs",
        });
    }
    let bias = mean(diff)?;
    let sd = std_dev(diff)?;
    let scale = diff.iter().fold(0.0f64, |m, d| m.max(d.abs()));
    if sd <= ROUNDING * scale {
        return Err(AgreementError::ConstantData {
            what: W,
            detail: format!("all {n} differences equal {:?} (up to rounding)", diff[0]),
        });
    }
    let nf = n as f64;
    let t = t_isf((1.0 - confidence_level) / 2.0, nf - 1.0);
    let se_bias = (sd * sd / nf).sqrt();
    let se_limit = (3.0 * sd * sd / nf).sqrt();
    let (lower, upper) = (bias - z * sd, bias + z * sd);
    // scipy's t.interval(conf, df, loc, scale) = (loc + scale·t.ppf(a), loc + scale·t.ppf(1 − a))
    let around = |loc: f64, se: f64| (loc + se * -t, loc + se * t);
    Ok(LimitsOfAgreement {
        bias,
        sd_diff: sd,
        lower,
        upper,
        bias_ci: around(bias, se_bias),
        lower_ci: around(lower, se_limit),
        upper_ci: around(upper, se_limit),
    })
}

/// `scipy.stats.linregress(x, y)` (two-sided), for n ≥ 3 finite pairs.
///
/// Errors: n < 3 (scipy gives a p-value of 0 or 1 and zero standard errors for n = 2); all x
/// equal (scipy raises), or equal up to rounding (SD ≤ 1e-12·max |x|).
pub fn linregress(x: &[f64], y: &[f64]) -> Result<LinearFit, AgreementError> {
    const W: &str = "proportional bias (linregress)";
    let n = x.len();
    if n != y.len() {
        return Err(AgreementError::LengthMismatch {
            what: W,
            ldh_len: n,
            reference_len: y.len(),
        });
    }
    if n < 3 {
        return Err(AgreementError::TooFewPairs {
            what: W,
            needed: 3,
            got: n,
            dropped: 0,
            unit: "pairs",
        });
    }
    let (xm, ym) = (mean(x)?, mean(y)?);
    let nf = n as f64;
    // np.cov(x, y, bias=1)
    let ssxm = x.iter().map(|a| (a - xm) * (a - xm)).sum::<f64>() / nf;
    let ssym = y.iter().map(|b| (b - ym) * (b - ym)).sum::<f64>() / nf;
    let ssxym = x
        .iter()
        .zip(y)
        .map(|(a, b)| (a - xm) * (b - ym))
        .sum::<f64>()
        / nf;
    let scale = x.iter().fold(0.0f64, |m, a| m.max(a.abs()));
    if ssxm.sqrt() <= ROUNDING * scale {
        return Err(AgreementError::ConstantData {
            what: W,
            detail: format!("all {n} means equal {:?} (up to rounding): no slope", x[0]),
        });
    }
    let r = if ssym == 0.0 {
        0.0
    } else {
        (ssxym / (ssxm * ssym).sqrt()).clamp(-1.0, 1.0)
    };
    let slope = ssxym / ssxm;
    let intercept = ym - slope * xm;
    let df = nf - 2.0;
    const TINY: f64 = 1.0e-20;
    let t = r * (df / ((1.0 - r + TINY) * (1.0 + r + TINY))).sqrt();
    let pvalue = t_pvalue(t, df, Alternative::TwoSided);
    let stderr = ((1.0 - r * r) * ssym / ssxm / df).sqrt();
    Ok(LinearFit {
        slope,
        intercept,
        rvalue: r,
        pvalue,
        stderr,
        intercept_stderr: stderr * (ssxm + xm * xm).sqrt(),
    })
}
