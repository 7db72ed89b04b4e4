//! Tail probabilities from `statrs`, always evaluated on the side that keeps
//! small p-values accurate (no `1 - cdf` cancellation).

use statrs::distribution::{ContinuousCDF, Normal, StudentsT};
use statrs::function::beta::beta_reg;
use statrs::function::gamma::gamma_ur;

use super::{Alternative, StatsError};

/// Standard normal survival function P(Z > z) (scipy `special.ndtr(-z)`).
pub(crate) fn norm_sf(z: f64) -> f64 {
    if z == f64::INFINITY {
        return 0.0;
    }
    if z == f64::NEG_INFINITY {
        return 1.0;
    }
    Normal::standard().sf(z)
}

/// Standard normal cdf P(Z ≤ z).
pub(crate) fn norm_cdf(z: f64) -> f64 {
    norm_sf(-z)
}

/// Student t survival function P(T > t) with `df` degrees of freedom
/// (`df > 0`, finite `t`), via the regularized incomplete beta function.
pub(crate) fn t_sf(t: f64, df: f64) -> f64 {
    if t == 0.0 {
        return 0.5;
    }
    // P(|T| > |t|) / 2 = I_{df/(df+t^2)}(df/2, 1/2) / 2
    let tail = 0.5 * beta_reg(df / 2.0, 0.5, df / (df + t * t));
    if t > 0.0 {
        tail
    } else {
        1.0 - tail
    }
}

/// p-value of a t statistic for the given alternative (scipy
/// `_get_pvalue(t, t_dist, alternative)`: two-sided = 2·sf(|t|)).
pub(crate) fn t_pvalue(t: f64, df: f64, alternative: Alternative) -> f64 {
    let p = match alternative {
        Alternative::Less => t_sf(-t, df),
        Alternative::Greater => t_sf(t, df),
        Alternative::TwoSided => 2.0 * t_sf(t.abs(), df),
    };
    super::clip01(p)
}

/// p-value of a z statistic for the given alternative.
pub(crate) fn z_pvalue(z: f64, alternative: Alternative) -> f64 {
    let p = match alternative {
        Alternative::Less => norm_cdf(z),
        Alternative::Greater => norm_sf(z),
        Alternative::TwoSided => 2.0 * norm_sf(z.abs()),
    };
    super::clip01(p)
}

/// F distribution survival function P(F > f) (scipy `special.fdtrc`).
pub(crate) fn f_sf(f: f64, dfn: f64, dfd: f64) -> f64 {
    if f <= 0.0 {
        return 1.0;
    }
    // P(F > f) = I_{dfd/(dfd + dfn f)}(dfd/2, dfn/2)
    beta_reg(dfd / 2.0, dfn / 2.0, dfd / (dfd + dfn * f))
}

/// Chi-squared survival function P(X > x) with `k` degrees of freedom.
pub(crate) fn chi2_sf(x: f64, k: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    gamma_ur(k / 2.0, x / 2.0)
}

/// Regularized incomplete beta I_x(a, b) for x in [0, 1].
pub(crate) fn beta_cdf(x: f64, a: f64, b: f64) -> f64 {
    if x <= 0.0 {
        0.0
    } else if x >= 1.0 {
        1.0
    } else {
        beta_reg(a, b, x)
    }
}

/// The quantile a confidence interval at `level` needs: `1 − (1 − level)/2` two-sided, `level`
/// one-sided. Errors when `level` is not in (0, 1).
pub(crate) fn confidence_quantile(level: f64, alternative: Alternative) -> Result<f64, StatsError> {
    if !(level > 0.0 && level < 1.0) {
        return Err(StatsError::InvalidArgument {
            test: "confidence_interval",
            detail: format!("confidence_level must be in (0, 1), got {level}"),
        });
    }
    Ok(match alternative {
        Alternative::TwoSided => 1.0 - (1.0 - level) / 2.0,
        _ => level,
    })
}

/// Quantile of Student's t with `df` degrees of freedom (scipy `stats.t.ppf`).
pub(crate) fn t_ppf(q: f64, df: f64) -> f64 {
    StudentsT::new(0.0, 1.0, df)
        .map(|t| t.inverse_cdf(q))
        .unwrap_or(f64::NAN)
}

/// Quantile of the standard normal distribution (scipy `stats.norm.ppf`).
pub(crate) fn norm_ppf(q: f64) -> f64 {
    Normal::standard().inverse_cdf(q)
}
