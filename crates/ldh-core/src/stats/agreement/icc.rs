//! Intraclass correlation coefficients from the two-way ANOVA of a complete n × k table
//! (n subjects or targets, k raters or trials), with their F tests and confidence intervals.
//!
//! Definitions: Shrout, P. E. & Fleiss, J. L. (1979), "Intraclass correlations: uses in
//! assessing rater reliability", *Psychological Bulletin* 86(2), 420–428 (ICC(1,1), ICC(2,1),
//! ICC(3,1)); McGraw, K. O. & Wong, S. P. (1996), "Forming inferences about some intraclass
//! correlation coefficients", *Psychological Methods* 1(1), 30–46 (the same coefficients as
//! ICC(1), ICC(A,1) and ICC(C,1), and the confidence interval of ICC(A,1) with its
//! Satterthwaite-type degrees of freedom v).
//!
//! Numbers are those of `pingouin.intraclass_corr` (0.7.0) rows `ICC(1,1)`, `ICC(A,1)` (= ICC2,
//! Shrout–Fleiss ICC(2,1): two-way random, absolute agreement) and `ICC(C,1)` (= ICC3,
//! ICC(3,1): two-way mixed, consistency): columns `ICC`, `F`, `df1`, `df2`, `pval`, `CI95`
//! (pingouin rounds `CI95` to 2 decimals by default; the goldens take it unrounded).
//! pingouin has the confidence level fixed at 95 %; here it is a parameter.

use serde::{Deserialize, Serialize};

use super::AgreementError;
use crate::stats::dist::{f_isf, f_sf};

/// One intraclass correlation coefficient with its F test and confidence interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Icc {
    /// The coefficient (may be negative when the between-subject mean square is below the
    /// error mean square).
    pub value: f64,
    /// F statistic of H0: ICC = 0 (pingouin `F`).
    pub f: f64,
    /// Numerator degrees of freedom, n − 1.
    pub df1: f64,
    /// Denominator degrees of freedom: n(k − 1) for ICC(1,1), (n − 1)(k − 1) for the others.
    pub df2: f64,
    /// One-sided p-value P(F(df1, df2) > f) (pingouin `pval`).
    pub pvalue: f64,
    /// Lower confidence limit (pingouin `CI95[0]` at 95 %).
    pub ci_low: f64,
    /// Upper confidence limit (pingouin `CI95[1]` at 95 %).
    pub ci_high: f64,
}

/// The mean squares of the two-way ANOVA without replication and the ICCs built from them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct IccResult {
    /// Number of subjects (rows), n.
    pub n_subjects: usize,
    /// Number of raters or trials (columns), k.
    pub k: usize,
    /// Between-subject mean square, MSB = k·Σ(row mean − grand mean)² / (n − 1).
    pub ms_subjects: f64,
    /// Between-rater (trial) mean square, MSJ = n·Σ(column mean − grand mean)² / (k − 1).
    pub ms_raters: f64,
    /// Residual (error) mean square, MSE = Σ(x − row mean − column mean + grand mean)² /
    /// ((n − 1)(k − 1)).
    pub ms_error: f64,
    /// Within-subject mean square of the one-way model, MSW = (SSJ + SSE) / (n(k − 1)).
    pub ms_within: f64,
    /// ICC(1,1): one-way random, (MSB − MSW) / (MSB + (k − 1)·MSW).
    pub icc_1_1: Icc,
    /// ICC(2,1) = ICC(A,1): two-way random, absolute agreement,
    /// (MSB − MSE) / (MSB + (k − 1)·MSE + k·(MSJ − MSE)/n).
    pub icc_2_1: Icc,
    /// ICC(3,1) = ICC(C,1): two-way mixed, consistency, (MSB − MSE) / (MSB + (k − 1)·MSE).
    pub icc_3_1: Icc,
}

/// The ICCs of a complete table given row-major: `values[i·k + j]` is subject i, rater
/// (trial) j. Every value must be finite (the callers drop incomplete rows first).
/// `confidence_level` in (0, 1) (checked by the callers' parameters).
///
/// Errors: `values.len()` not a multiple of k ([`AgreementError::InvalidParam`]); n < 2 or
/// k < 2 ([`AgreementError::TooFewPairs`]); an error mean square of zero up
/// to rounding (√MSE ≤ 1e-12·max |value|), where the F statistic is infinite
/// ([`AgreementError::ConstantData`]).
pub fn icc(values: &[f64], k: usize, confidence_level: f64) -> Result<IccResult, AgreementError> {
    const W: &str = "ICC";
    let n = values.len().checked_div(k).unwrap_or(0);
    if k < 2 || n < 2 {
        return Err(AgreementError::TooFewPairs {
            what: W,
            needed: 2,
            got: if k < 2 { k } else { n },
            dropped: 0,
            unit: if k < 2 { "raters (trials)" } else { "subjects" },
        });
    }
    if values.len() != n * k {
        return Err(AgreementError::InvalidParam {
            name: "k",
            value: format!("{k} (with {} values)", values.len()),
            reason: "the number of values must be a multiple of k",
        });
    }
    let ms = MeanSquares::of(values, n, k);
    let scale = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if ms.mse.sqrt() <= super::bland_altman::ROUNDING * scale {
        return Err(AgreementError::ConstantData {
            what: W,
            detail: format!(
                "the error mean square is {:e}: every subject differs from every other by the \
                 same amount on every {} (the F statistic is infinite)",
                ms.mse,
                if k == 2 { "rater" } else { "trial" }
            ),
        });
    }
    let alpha = 1.0 - confidence_level;
    let out = IccResult {
        n_subjects: n,
        k,
        ms_subjects: ms.msb,
        ms_raters: ms.msj,
        ms_error: ms.mse,
        ms_within: ms.msw,
        icc_1_1: ms.icc1(alpha),
        icc_2_1: ms.icc2(alpha)?,
        icc_3_1: ms.icc3(alpha),
    };
    Ok(out)
}

/// Mean squares of an n × k table.
struct MeanSquares {
    n: f64,
    k: f64,
    msb: f64,
    msj: f64,
    mse: f64,
    msw: f64,
}

impl MeanSquares {
    fn of(values: &[f64], n: usize, k: usize) -> Self {
        let grand = values.iter().sum::<f64>() / (n * k) as f64;
        let grand = grand + values.iter().map(|v| v - grand).sum::<f64>() / (n * k) as f64;
        let rows: Vec<f64> = values
            .chunks_exact(k)
            .map(|r| r.iter().sum::<f64>() / k as f64)
            .collect();
        let cols: Vec<f64> = (0..k)
            .map(|j| (0..n).map(|i| values[i * k + j]).sum::<f64>() / n as f64)
            .collect();
        let ss_rows = k as f64 * rows.iter().map(|m| (m - grand).powi(2)).sum::<f64>();
        let ss_cols = n as f64 * cols.iter().map(|m| (m - grand).powi(2)).sum::<f64>();
        let ss_err: f64 = values
            .chunks_exact(k)
            .zip(&rows)
            .flat_map(|(r, rm)| r.iter().zip(&cols).map(move |(x, cm)| x - rm - cm + grand))
            .map(|e| e * e)
            .sum();
        let (nf, kf) = (n as f64, k as f64);
        MeanSquares {
            n: nf,
            k: kf,
            msb: ss_rows / (nf - 1.0),
            msj: ss_cols / (kf - 1.0),
            mse: ss_err / ((nf - 1.0) * (kf - 1.0)),
            msw: (ss_cols + ss_err) / (nf * (kf - 1.0)),
        }
    }

    /// ICC(1,1) and its interval (Shrout & Fleiss 1979, case 1).
    fn icc1(&self, alpha: f64) -> Icc {
        let (n, k) = (self.n, self.k);
        let value = (self.msb - self.msw) / (self.msb + (k - 1.0) * self.msw);
        let f = self.msb / self.msw;
        let (df1, df2) = (n - 1.0, n * (k - 1.0));
        let fl = f / f_isf(alpha / 2.0, df1, df2);
        let fu = f * f_isf(alpha / 2.0, df2, df1);
        Icc {
            value,
            f,
            df1,
            df2,
            pvalue: f_sf(f, df1, df2),
            ci_low: (fl - 1.0) / (fl + (k - 1.0)),
            ci_high: (fu - 1.0) / (fu + (k - 1.0)),
        }
    }

    /// ICC(3,1) and its interval (Shrout & Fleiss 1979, case 3; McGraw & Wong 1996, ICC(C,1)).
    fn icc3(&self, alpha: f64) -> Icc {
        let (n, k) = (self.n, self.k);
        let value = (self.msb - self.mse) / (self.msb + (k - 1.0) * self.mse);
        let f = self.msb / self.mse;
        let (df1, df2) = (n - 1.0, (n - 1.0) * (k - 1.0));
        let fl = f / f_isf(alpha / 2.0, df1, df2);
        let fu = f * f_isf(alpha / 2.0, df2, df1);
        Icc {
            value,
            f,
            df1,
            df2,
            pvalue: f_sf(f, df1, df2),
            ci_low: (fl - 1.0) / (fl + (k - 1.0)),
            ci_high: (fu - 1.0) / (fu + (k - 1.0)),
        }
    }

    /// ICC(2,1) = ICC(A,1) and its interval (McGraw & Wong 1996, Table 7, case 2A: an F
    /// quantile with the approximate degrees of freedom v).
    fn icc2(&self, alpha: f64) -> Result<Icc, AgreementError> {
        let (n, k, msb, msj, mse) = (self.n, self.k, self.msb, self.msj, self.mse);
        let value = (msb - mse) / (msb + (k - 1.0) * mse + k * (msj - mse) / n);
        let f = msb / mse;
        let (df1, df2) = (n - 1.0, (n - 1.0) * (k - 1.0));
        let fj = msj / mse;
        let a = n * (1.0 + (k - 1.0) * value) - k * value;
        let vn = df2 * (k * value * fj + a).powi(2);
        let vd = df1 * k * k * value * value * fj * fj + a * a;
        let v = vn / vd;
        if !(v > 0.0 && v.is_finite()) {
            return Err(AgreementError::ConstantData {
                what: "ICC(2,1) confidence interval",
                detail: format!("its degrees of freedom v = {v} are not positive"),
            });
        }
        let f2u = f_isf(alpha / 2.0, df1, v);
        let f2l = f_isf(alpha / 2.0, v, df1);
        let c = k * msj + (k * n - k - n) * mse;
        Ok(Icc {
            value,
            f,
            df1,
            df2,
            pvalue: f_sf(f, df1, df2),
            ci_low: n * (msb - f2u * mse) / (f2u * c + n * msb),
            ci_high: n * (f2l * msb - mse) / (c + n * f2l * msb),
        })
    }
}
