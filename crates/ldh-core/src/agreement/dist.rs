//! Upper quantiles of the F and Student t distributions to full double precision, for the
//! confidence intervals of the ICC (F) and of the limits of agreement (t).
//!
//! statrs' `inv_beta_reg` gives a start good to about 1e-10; a few safeguarded Newton steps on
//! the regularised incomplete beta function (statrs' `beta_reg`, accurate to ~1e-15) take it
//! to the last bits, so the intervals agree with scipy's `f.ppf` / `t.ppf` (Boost's `ibeta_inv`)
//! to ~1e-14 relative, well inside the goldens' 1e-9.

use statrs::function::beta::{beta_reg, inv_beta_reg, ln_beta};

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

/// Two-sided p-value of a t statistic, P(|T| > |t|) (scipy `2·t.sf(|t|, df)`), clipped to
/// [0, 1].
pub(crate) fn t_pvalue_two_sided(t: f64, df: f64) -> f64 {
    if t == 0.0 {
        return 1.0;
    }
    beta_reg(df / 2.0, 0.5, df / (df + t * t)).clamp(0.0, 1.0)
}

/// P(F > f) for F(d1, d2) (scipy `f.sf`).
pub(crate) fn f_sf(f: f64, d1: f64, d2: f64) -> f64 {
    if f <= 0.0 {
        return 1.0;
    }
    beta_reg(d2 / 2.0, d1 / 2.0, d2 / (d2 + d1 * f))
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
