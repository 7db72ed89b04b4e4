//! Pearson correlation with its exact p-value (scipy.stats.pearsonr).
//! statrs has no correlation test; its beta function is used for the p-value.

use serde::{Deserialize, Serialize};

use super::dist::beta_cdf;
use super::ttest::is_constant;
use super::{check_finite, Alternative, StatsError};

/// Result of [`pearsonr`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PearsonRResult {
    /// Pearson's r, in [−1, 1].
    pub statistic: f64,
    /// p-value for H0: ρ = 0.
    pub pvalue: f64,
    /// Number of pairs.
    pub n: usize,
    /// The alternative the p-value and the confidence interval are for.
    #[serde(default)]
    pub alternative: Alternative,
}

impl PearsonRResult {
    /// Confidence interval of ρ at `confidence_level` by the Fisher transformation (scipy's
    /// `PearsonRResult.confidence_interval(confidence_level=0.95)`): `tanh(atanh(r) ± z·se)`
    /// with `se = 1/√(n − 3)`; one-sided for `Less` (−1, ·) and `Greater` (·, 1).
    ///
    /// Errors: `confidence_level` outside (0, 1); n ≤ 3 (scipy returns NaN there).
    pub fn confidence_interval(&self, confidence_level: f64) -> Result<(f64, f64), StatsError> {
        let q = super::dist::confidence_quantile(confidence_level, self.alternative)?;
        if self.n <= 3 {
            return Err(StatsError::TooFewObservations {
                test: "pearsonr confidence_interval",
                needed: 4,
                got: self.n,
                what: " pairs",
            });
        }
        let z = self.statistic.atanh();
        let half = super::dist::norm_ppf(q) / ((self.n - 3) as f64).sqrt();
        Ok(match self.alternative {
            Alternative::TwoSided => ((z - half).tanh(), (z + half).tanh()),
            Alternative::Less => (-1.0, (z + half).tanh()),
            Alternative::Greater => ((z - half).tanh(), 1.0),
        })
    }
}

/// Pearson correlation coefficient and p-value, equal to
/// `scipy.stats.pearsonr(x, y, alternative=...)`.
///
/// Under H0 (independent normal x, y), r follows a beta distribution on
/// [−1, 1] with a = b = n/2 − 1; the p-value is exact: `Less` = P(R ≤ r),
/// `Greater` = P(R ≥ r), `TwoSided` = 2·P(R ≥ |r|). For n = 2, r = ±1 and
/// p = 1 (as scipy).
///
/// Errors: different lengths ([`StatsError::LengthMismatch`]); n < 2
/// ([`StatsError::TooFewObservations`]); NaN / ±inf; a constant input
/// ([`StatsError::ConstantInput`]; scipy warns and returns NaN).
pub fn pearsonr(
    x: &[f64],
    y: &[f64],
    alternative: Alternative,
) -> Result<PearsonRResult, StatsError> {
    const T: &str = "pearsonr";
    if x.len() != y.len() {
        return Err(StatsError::LengthMismatch {
            test: T,
            x_len: x.len(),
            y_len: y.len(),
        });
    }
    let n = x.len();
    if n < 2 {
        return Err(StatsError::TooFewObservations {
            test: T,
            needed: 2,
            got: n,
            what: "",
        });
    }
    check_finite(T, "x", x)?;
    check_finite(T, "y", y)?;
    for (name, s) in [("x", x), ("y", y)] {
        if is_constant(s) {
            return Err(StatsError::ConstantInput {
                test: T,
                detail: format!("all {n} values of {name} equal {:?}", s[0]),
            });
        }
    }
    // scipy: centre, scale each vector by its max |.| before the norm, then
    // r = <xm/|xm|, ym/|ym|>
    let unit = |v: &[f64]| -> Vec<f64> {
        let m = v.iter().sum::<f64>() / n as f64;
        let c: Vec<f64> = v.iter().map(|a| a - m).collect();
        let mx = c.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let norm = mx * c.iter().map(|a| (a / mx) * (a / mx)).sum::<f64>().sqrt();
        c.into_iter().map(|a| a / norm).collect()
    };
    let (ux, uy) = (unit(x), unit(y));
    let mut r: f64 = ux.iter().zip(&uy).map(|(a, b)| a * b).sum();
    r = r.clamp(-1.0, 1.0);
    if n == 2 {
        return Ok(PearsonRResult {
            statistic: r.round(),
            pvalue: 1.0,
            n,
            alternative,
        });
    }
    let ab = n as f64 / 2.0 - 1.0;
    // R = 2B − 1 with B ~ Beta(ab, ab); by symmetry P(R ≥ r) = I_{(1−r)/2}(ab, ab)
    let cdf = |r_: f64| beta_cdf((r_ + 1.0) / 2.0, ab, ab);
    let sf = |r_: f64| beta_cdf(1.0 - (r_ + 1.0) / 2.0, ab, ab);
    let p = match alternative {
        Alternative::Less => cdf(r),
        Alternative::Greater => sf(r),
        Alternative::TwoSided => 2.0 * sf(r.abs()),
    };
    Ok(PearsonRResult {
        statistic: r,
        pvalue: p.clamp(0.0, 1.0),
        n,
        alternative,
    })
}
