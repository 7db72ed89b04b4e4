//! scipy's `nan_policy` argument: what a test does with NaN in its samples.
//!
//! scipy (`scipy.stats._axis_nan_policy`): `"propagate"` (the default) returns NaN statistic and
//! p-value when any sample holds a NaN; `"omit"` drops the NaNs — from each sample on its own for
//! independent samples, the whole pair for paired samples (`ttest_rel`, `wilcoxon` with `y`,
//! `pearsonr`); `"raise"` refuses the input. The tests themselves never return NaN: a
//! propagated NaN is [`NanOutcome::Propagate`], which the caller turns into NaN values.

use serde::{Deserialize, Serialize};

use super::StatsError;

/// What a test does with NaN in its input (scipy's `nan_policy=`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NanPolicy {
    /// `"propagate"` (scipy's default): NaN in, NaN statistic and p-value out.
    #[default]
    Propagate,
    /// `"omit"`: leave NaNs out (pairwise for paired samples).
    Omit,
    /// `"raise"`: an error naming the sample and the position of the first NaN.
    Raise,
}

impl std::str::FromStr for NanPolicy {
    type Err = StatsError;

    /// Parses the scipy spelling (`"propagate"`, `"omit"`, `"raise"`).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "propagate" => Ok(NanPolicy::Propagate),
            "omit" => Ok(NanPolicy::Omit),
            "raise" => Ok(NanPolicy::Raise),
            other => Err(StatsError::InvalidArgument {
                test: "nan_policy",
                detail: format!("expected \"propagate\", \"omit\" or \"raise\", got {other:?}"),
            }),
        }
    }
}

/// The samples a test runs on after the policy, or `Propagate` (the result is NaN).
#[derive(Debug, Clone, PartialEq)]
pub enum NanOutcome {
    /// Run the test on these samples (without NaN under `Omit`; unchanged when there was none).
    Run(Vec<Vec<f64>>),
    /// A NaN under `Propagate`: the statistic and the p-value are NaN, the test is not run.
    Propagate,
}

/// Apply `policy` to `samples` of `test`; `paired`: the samples are paired element by element
/// (all of equal length), so `Omit` drops a pair where any member is NaN. ±inf is not NaN and is
/// left for the test to refuse.
pub fn apply_nan_policy(
    test: &'static str,
    samples: Vec<Vec<f64>>,
    paired: bool,
    policy: NanPolicy,
) -> Result<NanOutcome, StatsError> {
    let first_nan = samples
        .iter()
        .enumerate()
        .find_map(|(i, s)| s.iter().position(|v| v.is_nan()).map(|j| (i, j)));
    let Some((sample, index)) = first_nan else {
        return Ok(NanOutcome::Run(samples));
    };
    match policy {
        NanPolicy::Propagate => Ok(NanOutcome::Propagate),
        NanPolicy::Raise => Err(StatsError::NonFinite {
            test,
            sample: format!("sample {sample} (nan_policy=\"raise\")"),
            index,
            value: f64::NAN,
        }),
        NanPolicy::Omit if paired && samples.iter().all(|s| s.len() == samples[0].len()) => {
            let keep: Vec<bool> = (0..samples[0].len())
                .map(|k| samples.iter().all(|s| !s[k].is_nan()))
                .collect();
            Ok(NanOutcome::Run(
                samples
                    .into_iter()
                    .map(|s| {
                        s.into_iter()
                            .zip(&keep)
                            .filter(|(_, k)| **k)
                            .map(|(v, _)| v)
                            .collect()
                    })
                    .collect(),
            ))
        }
        NanPolicy::Omit => Ok(NanOutcome::Run(
            samples
                .into_iter()
                .map(|s| s.into_iter().filter(|v| !v.is_nan()).collect())
                .collect(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const NAN: f64 = f64::NAN;

    #[test]
    fn omit_drops_values_or_pairs() {
        let s = vec![vec![1.0, NAN, 3.0], vec![4.0, 5.0, NAN]];
        let ind = apply_nan_policy("t", s.clone(), false, NanPolicy::Omit).unwrap();
        assert_eq!(ind, NanOutcome::Run(vec![vec![1.0, 3.0], vec![4.0, 5.0]]));
        let pair = apply_nan_policy("t", s.clone(), true, NanPolicy::Omit).unwrap();
        assert_eq!(pair, NanOutcome::Run(vec![vec![1.0], vec![4.0]]));
        let prop = apply_nan_policy("t", s.clone(), true, NanPolicy::Propagate).unwrap();
        assert_eq!(prop, NanOutcome::Propagate);
        let e = apply_nan_policy("t", s, false, NanPolicy::Raise).unwrap_err();
        assert!(e.to_string().contains("sample 0"), "{e}");
    }

    #[test]
    fn without_nan_every_policy_runs_the_test_unchanged() {
        let s = vec![vec![1.0, f64::INFINITY]];
        for p in [NanPolicy::Propagate, NanPolicy::Omit, NanPolicy::Raise] {
            assert_eq!(
                apply_nan_policy("t", s.clone(), false, p).unwrap(),
                NanOutcome::Run(s.clone())
            );
        }
        assert!("bogus".parse::<NanPolicy>().is_err());
    }
}
