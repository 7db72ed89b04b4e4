//! Student, Welch, paired and one-sample t-tests (scipy.stats.ttest_*).
//!
//! Hand-written rather than `statrs::stats_tests::ttest_onesample`, which
//! computes two-sided p-values as `2 * (1 - cdf(|t|))` and so loses the
//! relative precision of small p-values (it returns 0 where scipy gives
//! 1.3e-20 in the golden set), and has no two-sample forms. The t distribution itself is statrs' (incomplete beta).

use serde::{Deserialize, Serialize};

use super::descriptive::{mean_unchecked, var_unchecked};
use super::dist::t_pvalue;
use super::{check_finite, Alternative, StatsError};

/// Result of the t-tests.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TTestResult {
    /// The t statistic.
    pub statistic: f64,
    /// p-value.
    pub pvalue: f64,
    /// Degrees of freedom (Welch–Satterthwaite df for Welch's test).
    pub df: f64,
    /// The estimated quantity the confidence interval is about: the difference of the means
    /// (`ttest_ind`), the mean difference (`ttest_rel`) or the mean (`ttest_1samp`).
    pub estimate: f64,
    /// Standard error of `estimate` (the t statistic's denominator).
    pub standard_error: f64,
    /// The alternative the p-value and the confidence interval are for.
    pub alternative: Alternative,
}

impl TTestResult {
    /// Confidence interval of [`TTestResult::estimate`] at `confidence_level` (scipy's
    /// `TtestResult.confidence_interval(confidence_level=0.95)`): two-sided
    /// `estimate ± t(1 − (1 − level)/2, df)·se`; for `Less` `(−∞, estimate + t(level, df)·se)`,
    /// for `Greater` `(estimate − t(level, df)·se, ∞)`.
    ///
    /// Errors: `confidence_level` outside (0, 1) ([`StatsError::InvalidArgument`]).
    pub fn confidence_interval(&self, confidence_level: f64) -> Result<(f64, f64), StatsError> {
        let q = super::dist::confidence_quantile(confidence_level, self.alternative)?;
        let half = super::dist::t_ppf(q, self.df) * self.standard_error;
        Ok(match self.alternative {
            Alternative::TwoSided => (self.estimate - half, self.estimate + half),
            Alternative::Less => (f64::NEG_INFINITY, self.estimate + half),
            Alternative::Greater => (self.estimate - half, f64::INFINITY),
        })
    }
}

/// All values equal (a single value counts as constant).
pub(crate) fn is_constant(x: &[f64]) -> bool {
    x.iter().all(|v| *v == x[0])
}

fn constant_err(test: &'static str, detail: String) -> StatsError {
    StatsError::ConstantInput { test, detail }
}

/// Two independent samples t-test, equal to
/// `scipy.stats.ttest_ind(x, y, equal_var=equal_var, alternative=...)`.
///
/// * `equal_var = true` (scipy's default): Student's t with pooled variance,
///   df = n1 + n2 − 2. Needs n1, n2 ≥ 1 and n1 + n2 ≥ 3.
/// * `equal_var = false`: Welch's t, Welch–Satterthwaite df. Needs n1, n2 ≥ 2.
///
/// `Less` / `Greater`: mean of `x` less / greater than mean of `y`.
///
/// Errors: too few observations ([`StatsError::TooFewObservations`]; scipy
/// returns NaN); NaN / ±inf ([`StatsError::NonFinite`]); zero standard
/// error, i.e. both samples constant ([`StatsError::ConstantInput`]; scipy
/// returns t = ±inf, p = 0 if the means differ, NaN otherwise).
pub fn ttest_ind(
    x: &[f64],
    y: &[f64],
    equal_var: bool,
    alternative: Alternative,
) -> Result<TTestResult, StatsError> {
    const T: &str = "ttest_ind";
    let (n1, n2) = (x.len(), y.len());
    if equal_var {
        if n1 == 0 || n2 == 0 || n1 + n2 < 3 {
            let got = if n1 == 0 || n2 == 0 {
                n1.min(n2)
            } else {
                n1 + n2
            };
            let (needed, what) = if n1 == 0 || n2 == 0 {
                (1, " in each sample")
            } else {
                (3, " in total")
            };
            return Err(StatsError::TooFewObservations {
                test: T,
                needed,
                got,
                what,
            });
        }
    } else if n1 < 2 || n2 < 2 {
        return Err(StatsError::TooFewObservations {
            test: "ttest_ind(equal_var=false)",
            needed: 2,
            got: n1.min(n2),
            what: " in each sample",
        });
    }
    check_finite(T, "x", x)?;
    check_finite(T, "y", y)?;
    let (f1, f2) = (n1 as f64, n2 as f64);
    let v1 = if n1 > 1 { var_unchecked(x, 1.0) } else { 0.0 };
    let v2 = if n2 > 1 { var_unchecked(y, 1.0) } else { 0.0 };
    let d = mean_unchecked(x) - mean_unchecked(y);
    let (denom, df) = if equal_var {
        let df = f1 + f2 - 2.0;
        let svar = ((f1 - 1.0) * v1 + (f2 - 1.0) * v2) / df;
        ((svar * (1.0 / f1 + 1.0 / f2)).sqrt(), df)
    } else {
        let (vn1, vn2) = (v1 / f1, v2 / f2);
        let df = (vn1 + vn2).powi(2) / (vn1 * vn1 / (f1 - 1.0) + vn2 * vn2 / (f2 - 1.0));
        ((vn1 + vn2).sqrt(), df)
    };
    if (is_constant(x) && is_constant(y)) || denom == 0.0 || !df.is_finite() {
        return Err(constant_err(
            T,
            format!("both samples are constant (x = {:?}, y = {:?})", x[0], y[0]),
        ));
    }
    let t = d / denom;
    Ok(TTestResult {
        statistic: t,
        pvalue: t_pvalue(t, df, alternative),
        df,
        estimate: d,
        standard_error: denom,
        alternative,
    })
}

/// Paired-samples t-test, equal to `scipy.stats.ttest_rel(x, y, alternative=...)`:
/// the one-sample t-test of the differences `x[i] - y[i]` against 0,
/// df = n − 1.
///
/// Errors: different lengths ([`StatsError::LengthMismatch`]); n < 2
/// ([`StatsError::TooFewObservations`]); NaN / ±inf; all differences equal
/// ([`StatsError::ConstantInput`]; scipy returns ±inf / NaN).
pub fn ttest_rel(
    x: &[f64],
    y: &[f64],
    alternative: Alternative,
) -> Result<TTestResult, StatsError> {
    const T: &str = "ttest_rel";
    if x.len() != y.len() {
        return Err(StatsError::LengthMismatch {
            test: T,
            x_len: x.len(),
            y_len: y.len(),
        });
    }
    check_finite(T, "x", x)?;
    check_finite(T, "y", y)?;
    let d: Vec<f64> = x.iter().zip(y).map(|(a, b)| a - b).collect();
    one_sample(T, "differences", &d, 0.0, alternative)
}

/// One-sample t-test, equal to
/// `scipy.stats.ttest_1samp(x, popmean, alternative=...)`:
/// t = (mean − popmean) / (s/√n), df = n − 1.
///
/// Errors: n < 2 ([`StatsError::TooFewObservations`]); NaN / ±inf (also in
/// `popmean`); a constant sample ([`StatsError::ConstantInput`]; scipy
/// returns ±inf or NaN).
pub fn ttest_1samp(
    x: &[f64],
    popmean: f64,
    alternative: Alternative,
) -> Result<TTestResult, StatsError> {
    const T: &str = "ttest_1samp";
    check_finite(T, "x", x)?;
    check_finite(T, "popmean", &[popmean])?;
    one_sample(T, "values", x, popmean, alternative)
}

fn one_sample(
    test: &'static str,
    what: &str,
    x: &[f64],
    popmean: f64,
    alternative: Alternative,
) -> Result<TTestResult, StatsError> {
    let n = x.len();
    if n < 2 {
        return Err(StatsError::TooFewObservations {
            test,
            needed: 2,
            got: n,
            what: "",
        });
    }
    if is_constant(x) {
        return Err(constant_err(
            test,
            format!("all {n} {what} equal {:?}", x[0]),
        ));
    }
    let v = var_unchecked(x, 1.0);
    let df = (n - 1) as f64;
    let (mean, se) = (mean_unchecked(x), (v / n as f64).sqrt());
    let t = (mean - popmean) / se;
    // scipy's interval is of the mean itself (ttest_1samp) or of the mean difference (ttest_rel,
    // popmean 0), not of mean − popmean.
    Ok(TTestResult {
        statistic: t,
        pvalue: t_pvalue(t, df, alternative),
        df,
        estimate: mean,
        standard_error: se,
        alternative,
    })
}
