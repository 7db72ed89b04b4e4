//! Test–retest reliability of one parameter from repeated trials of the same subjects.
//!
//! The table is subjects × trials; trials play the raters of the ICC. Reported: ICC(2,1)
//! and ICC(3,1) with confidence intervals ([`super::icc`]; Shrout & Fleiss 1979, McGraw &
//! Wong 1996), the standard error of measurement and the minimal detectable change after
//! Weir, J. P. (2005), "Quantifying test–retest reliability using the intraclass correlation
//! coefficient and the SEM", *Journal of Strength and Conditioning Research* 19(1), 231–240:
//!
//! - SEM = SD·√(1 − ICC(2,1)), SD the sample SD (ddof = 1) of all n·k values pooled (Weir's
//!   "SD of the scores from all subjects"); √MSE, Weir's preferred alternative that does not
//!   depend on the ICC chosen, is reported beside it;
//! - MDC95 = 1.96·√2·SEM (Weir's eq. 10: a change between two measurements of one subject
//!   larger than this is real with 95 % confidence);
//! - the within-subject coefficient of variation by the root-mean-square method,
//!   CVw = √(mean over subjects of (SDᵢ / meanᵢ)²), SDᵢ with ddof = 1 (Glüer et al. 1995,
//!   "Accurate assessment of precision errors", *Osteoporosis International* 5, 262–270; Bland's
//!   recommended within-subject CV), as a fraction;
//! - variance components by the ANOVA (method-of-moments) estimators, not truncated at 0.
//!
//! Missing trials: a subject with any missing trial (NaN, or a row shorter than the longest)
//! is dropped whole, like `pingouin.intraclass_corr(..., nan_policy="omit")`, and listed in
//! [`Reliability::dropped_subjects`].

use serde::{Deserialize, Serialize};

use super::icc::{icc, IccResult};
use super::{AgreementError, ValidAgreementParams};
use crate::stats::std_dev;

/// Fewest complete subjects [`test_retest`] accepts.
pub const MIN_SUBJECTS: usize = 2;

/// Variance components of a subjects × trials table (the parameter's unit squared).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct VarianceComponents {
    /// Between-subject variance of the one-way model, (MSB − MSW) / k.
    pub between_subject: f64,
    /// Within-subject variance of the one-way model, MSW (trial-to-trial variation of a
    /// subject, systematic trial effects included); its root is the within-subject SD.
    pub within_subject: f64,
    /// Subject variance of the two-way model, (MSB − MSE) / k.
    pub subject: f64,
    /// Systematic trial (learning, fatigue) variance of the two-way model, (MSJ − MSE) / n.
    pub trial: f64,
    /// Residual variance of the two-way model, MSE.
    pub error: f64,
}

/// Test–retest reliability of one parameter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Reliability {
    /// Subjects used (with every trial present).
    pub n_subjects: usize,
    /// Trials per subject, k.
    pub k_trials: usize,
    /// Zero-based rows dropped for a missing trial.
    pub dropped_subjects: Vec<usize>,
    /// The ICCs (ICC(2,1) the primary one for test–retest) and the mean squares.
    pub icc: IccResult,
    /// Sample SD (ddof = 1) of all n·k values.
    pub sd_all: f64,
    /// SEM = `sd_all`·√(1 − ICC(2,1)).
    pub sem: f64,
    /// √MSE, the SEM that does not depend on an ICC (Weir 2005).
    pub sem_from_mse: f64,
    /// MDC95 = 1.96·√2·`sem`.
    pub mdc95: f64,
    /// Within-subject CV, root mean square of the subjects' SD/mean (a fraction); `None` when
    /// a subject's mean is not > 0 (a CV of signed or zero-mean values means nothing).
    pub within_subject_cv: Option<f64>,
    /// Variance components.
    pub variance: VarianceComponents,
}

/// Test–retest reliability of `trials[subject][trial]`. NaN (or a short row) is a missing
/// trial; its subject is dropped. k = the longest row.
///
/// Errors: ±inf; k < 2; fewer than [`MIN_SUBJECTS`] complete subjects; a zero error mean
/// square (every trial shifts every subject by the same amount).
pub fn test_retest(
    trials: &[Vec<f64>],
    params: &ValidAgreementParams,
) -> Result<Reliability, AgreementError> {
    const W: &str = "test-retest reliability";
    let k = trials.iter().map(Vec::len).max().unwrap_or(0);
    let mut values = Vec::with_capacity(trials.len() * k);
    let mut dropped_subjects = Vec::new();
    for (i, row) in trials.iter().enumerate() {
        if let Some(j) = row.iter().position(|v| v.is_infinite()) {
            return Err(AgreementError::NonFinite {
                what: W,
                input: format!("subject {i}"),
                index: j,
                value: row[j],
            });
        }
        if row.len() < k || row.iter().any(|v| v.is_nan()) {
            dropped_subjects.push(i);
        } else {
            values.extend_from_slice(row);
        }
    }
    if k < 2 {
        return Err(AgreementError::TooFewPairs {
            what: W,
            needed: 2,
            got: k,
            dropped: 0,
            unit: "trials per subject",
        });
    }
    let n = values.len() / k;
    if n < MIN_SUBJECTS {
        return Err(AgreementError::TooFewPairs {
            what: W,
            needed: MIN_SUBJECTS,
            got: n,
            dropped: dropped_subjects.len(),
            unit: "subjects",
        });
    }
    let icc = icc(&values, k, params.params().confidence_level)?;
    let sd_all = std_dev(&values)?;
    let sem = sd_all * (1.0 - icc.icc_2_1.value).sqrt();
    let (nf, kf) = (n as f64, k as f64);
    let variance = VarianceComponents {
        between_subject: (icc.ms_subjects - icc.ms_within) / kf,
        within_subject: icc.ms_within,
        subject: (icc.ms_subjects - icc.ms_error) / kf,
        trial: (icc.ms_raters - icc.ms_error) / nf,
        error: icc.ms_error,
    };
    Ok(Reliability {
        n_subjects: n,
        k_trials: k,
        dropped_subjects,
        sd_all,
        sem,
        sem_from_mse: icc.ms_error.sqrt(),
        mdc95: 1.96 * std::f64::consts::SQRT_2 * sem,
        within_subject_cv: within_subject_cv(&values, k),
        variance,
        icc,
    })
}

/// Root mean square of the per-subject CVs (SD with ddof = 1 over mean); `None` when a
/// subject's mean is not > 0.
fn within_subject_cv(values: &[f64], k: usize) -> Option<f64> {
    let mut sum_sq = 0.0;
    let mut n = 0usize;
    for row in values.chunks_exact(k) {
        let m = row.iter().sum::<f64>() / k as f64;
        if !(m > 0.0) {
            return None;
        }
        let var = row.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / (k as f64 - 1.0);
        sum_sq += var / (m * m);
        n += 1;
    }
    Some((sum_sq / n as f64).sqrt())
}
