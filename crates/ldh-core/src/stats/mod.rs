//! Hypothesis tests for the cohort analysis (spec §5, paper §3.4), with
//! `scipy.stats` parity.
//!
//! The paper's §3.4 compares gait features between the unaffected side of LDH
//! subjects (LDHH), the affected side (LDHE) and healthy subjects (H): a
//! Shapiro-Wilk normality check, then a t-test or Mann-Whitney U test per pair
//! of groups, and a one-way ANOVA (plus Kruskal-Wallis) across the three
//! groups. Both sides of one LDH subject are paired data, so the paired
//! t-test and the Wilcoxon signed-rank test are provided too, together with
//! Pearson's r (feature ranking) and Holm's step-down correction.
//!
//! Every function is named after, and returns the same numbers as, the
//! `scipy.stats` function of the same name with its default arguments (see
//! each function's docs and `docs/statistics.md`). The golden tests in
//! `tests.rs` compare statistic and p-value with scipy to 1e-6 relative
//! (1e-12 absolute for p-values below 1e-12).
//!
//! Shapiro-Wilk follows Royston, P. (1995) "Remark AS R94: A remark on
//! Algorithm AS 181: The W-test for normality", *Applied Statistics* 44(4),
//! 547-551, as translated in scipy's `swilk`.
//!
//! Where scipy returns NaN or ±inf (constant input, too few observations,
//! NaN in the data, ...), these functions return a typed [`StatsError`]
//! instead; no function here ever returns a NaN statistic or p-value.
//!
//! [`agreement`] holds the statistics of method agreement and test–retest reliability (Bland–
//! Altman limits, ICC, SEM, MDC95) with pingouin parity; [`median`] is the crate's one median.
//!
//! Distributions (normal, Student t, F, chi-squared, beta) come from
//! `statrs`. statrs 0.19 also ships `mannwhitneyu`, `f_oneway` and
//! `ttest_onesample`, but they are not used, for the reasons given at each
//! function (tail p-values computed as `1 - cdf`, a combinatorial exact
//! Mann-Whitney enumeration, and an `f_oneway` that rejects inputs scipy
//! accepts).

pub mod agreement;
mod anova;
mod correlation;
mod descriptive;
mod dist;
mod error;
mod mannwhitney;
mod multitest;
mod nan_policy;
mod rank;
mod shapiro;
mod ttest;
mod wilcoxon;

#[cfg(test)]
mod proptests;
#[cfg(test)]
mod tests;

pub use anova::{f_oneway, kruskal, FOnewayResult, KruskalResult};
pub use correlation::{pearsonr, PearsonRResult};
pub use descriptive::{mean, median, std_dev, EvenMedian};
pub use error::StatsError;
pub use mannwhitney::{mannwhitneyu, mannwhitneyu_with, MannWhitneyUResult, MwuMethod};
pub use multitest::holm;
pub use nan_policy::{apply_nan_policy, NanOutcome, NanPolicy};
pub use shapiro::{shapiro, ShapiroResult};
pub use ttest::{ttest_1samp, ttest_ind, ttest_rel, TTestResult};
pub use wilcoxon::{wilcoxon, wilcoxon_paired, WilcoxonResult};

use serde::{Deserialize, Serialize};

/// Alternative hypothesis, as scipy's `alternative=` argument.
///
/// * `TwoSided` — `"two-sided"` (scipy's default),
/// * `Less` — the distribution underlying the first sample is stochastically
///   less (or its mean / location is less) than the second / the reference,
/// * `Greater` — ... greater.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Alternative {
    /// `alternative="two-sided"` (the default).
    #[default]
    TwoSided,
    /// `alternative="less"`.
    Less,
    /// `alternative="greater"`.
    Greater,
}

impl Alternative {
    /// The scipy spelling: `"two-sided"`, `"less"` or `"greater"`.
    pub fn as_scipy_str(self) -> &'static str {
        match self {
            Alternative::TwoSided => "two-sided",
            Alternative::Less => "less",
            Alternative::Greater => "greater",
        }
    }
}

impl std::str::FromStr for Alternative {
    type Err = StatsError;

    /// Parses the scipy spelling (`"two-sided"`, `"less"`, `"greater"`).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "two-sided" => Ok(Alternative::TwoSided),
            "less" => Ok(Alternative::Less),
            "greater" => Ok(Alternative::Greater),
            other => Err(StatsError::InvalidArgument {
                test: "alternative",
                detail: format!("expected \"two-sided\", \"less\" or \"greater\", got {other:?}"),
            }),
        }
    }
}

/// How a p-value was obtained (reported by the rank tests).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PValueMethod {
    /// Exact null distribution (no ties).
    Exact,
    /// Normal (or chi-squared / t / F) approximation.
    Asymptotic,
    /// Exact permutation distribution over all 2^n sign flips (Wilcoxon with
    /// ties or zeros and n ≤ 13, as scipy's `PermutationMethod()` there).
    ExactPermutation,
}

/// Checks that every value is finite; `sample` names the argument in errors.
pub(crate) fn check_finite(test: &'static str, sample: &str, x: &[f64]) -> Result<(), StatsError> {
    match x.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(index) => Err(StatsError::NonFinite {
            test,
            sample: sample.to_string(),
            index,
            value: x[index],
        }),
    }
}

/// Clamps a probability into [0, 1] (scipy clips the same way).
pub(crate) fn clip01(p: f64) -> f64 {
    p.clamp(0.0, 1.0)
}
