//! Tail probabilities from `statrs`, always evaluated on the side that keeps
//! small p-values accurate (no `1 - cdf` cancellation), and the upper quantiles of the F and
//! Student t distributions to full double precision for the agreement statistics' intervals
//! ([`f_isf`], [`t_isf`]).
//!
//! statrs' `inv_beta_reg` gives a start good to about 1e-10; a few safeguarded Newton steps on
//! the regularised incomplete beta function (statrs' `beta_reg`, accurate to ~1e-15) take it
//! to the last bits, so the intervals agree with scipy's `f.ppf` / `t.ppf` (Boost's `ibeta_inv`)
//! to ~1e-14 relative, well inside the goldens' 1e-9.

use statrs::distribution::{ContinuousCDF, Normal, StudentsT};
use statrs::function::beta::{beta_reg, inv_beta_reg, ln_beta};
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

/// x in (0, 1) with I_x(a, b) = p, for 0 < p < 1.
fn inv_beta(a: f64, b: f64, p: f64) -> f64 {
    let mut x = inv_beta_reg(a, b, p);
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    if !(x > 0.0 && x < 1.0) {
        x = 0.5;
    }
    let lb = ln_beta(a, b);
    for _ in 0..100 {
        let g = beta_reg(a, b, x) - p;
        if g == 0.0 {
            break;
        }
        if g > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let dens = ((a - 1.0) * x.ln() + (b - 1.0) * (-x).ln_1p() - lb).exp();
        let mut next = x - g / dens;
        if !(next > lo && next < hi && next.is_finite()) {
            next = 0.5 * (lo + hi);
        }
        if (next - x).abs() <= 4.0 * f64::EPSILON * x.abs() {
            x = next;
            break;
        }
        x = next;
    }
    x
}

/// Upper quantile of F(d1, d2): the f with P(F > f) = `alpha` (scipy `f.ppf(1 − alpha, d1, d2)`,
/// `f.isf(alpha, d1, d2)`). `0 < alpha < 1`, `d1, d2 > 0` (non-integer allowed).
pub(crate) fn f_isf(alpha: f64, d1: f64, d2: f64) -> f64 {
    // P(F > f) = I_y(d2/2, d1/2) with y = d2 / (d2 + d1 f)
    let y = inv_beta(d2 / 2.0, d1 / 2.0, alpha);
    d2 * (1.0 - y) / (d1 * y)
}

/// Upper quantile of Student's t with `df` degrees of freedom: the t with P(T > t) = `alpha`
/// (scipy `t.ppf(1 − alpha, df)`), `0 < alpha < 0.5`.
pub(crate) fn t_isf(alpha: f64, df: f64) -> f64 {
    // P(|T| > t) = 2 alpha = I_y(df/2, 1/2) with y = df / (df + t²)
    let y = inv_beta(df / 2.0, 0.5, 2.0 * alpha);
    (df * (1.0 - y) / y).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) {
        assert!((a - b).abs() <= 1e-13 * b.abs(), "{a} vs {b}");
    }

    #[test]
    fn quantiles_match_scipy() {
        // scipy 1.17.1: stats.f.ppf(0.975, d1, d2), stats.t.ppf(0.975, df)
        close(f_isf(0.025, 9.0, 18.0), 2.929112493123264);
        close(f_isf(0.025, 18.0, 9.0), 3.7014809046166);
        close(f_isf(0.025, 4.0, 2.7315), 18.129866025074865);
        close(t_isf(0.025, 9.0), 2.262157162798205);
        close(t_isf(0.025, 2.0), 4.302652729749462);
        close(t_isf(0.025, 199.0), 1.9719565442517533);
    }

    #[test]
    fn the_survival_function_inverts_the_quantile() {
        for (d1, d2) in [(1.0, 1.0), (4.0, 40.0), (29.0, 58.0), (2.5, 0.8)] {
            let f = f_isf(0.025, d1, d2);
            assert!((f_sf(f, d1, d2) - 0.025).abs() < 1e-15, "{d1} {d2}");
        }
    }
}
