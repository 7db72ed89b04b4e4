//! The error type of the statistics module.

/// Why a statistic could not be computed.
///
/// Every case where `scipy.stats` returns NaN (or ±inf, or only warns that
/// the result is meaningless) is an error here; see `docs/statistics.md` for
/// the case-by-case list. The host crate wraps this with `#[from]`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StatsError {
    /// A sample is shorter than the test needs.
    #[error("{test} needs at least {needed} observations{what}, got {got}")]
    TooFewObservations {
        /// scipy-style name of the test, e.g. `"shapiro"`.
        test: &'static str,
        /// Minimum number of observations.
        needed: usize,
        /// Number of observations supplied.
        got: usize,
        /// Extra qualification, e.g. `" in each sample"` (may be empty).
        what: &'static str,
    },
    /// One group of a k-sample test is empty.
    #[error("group {index} of {test} is empty")]
    EmptyGroup {
        /// scipy-style name of the test.
        test: &'static str,
        /// Zero-based index of the empty group.
        index: usize,
    },
    /// A k-sample test got fewer than two groups.
    #[error("{test} needs at least 2 groups, got {got}")]
    TooFewGroups {
        /// scipy-style name of the test.
        test: &'static str,
        /// Number of groups supplied.
        got: usize,
    },
    /// Paired samples of different lengths.
    #[error("{test}: the two samples have different lengths ({x_len} vs {y_len})")]
    LengthMismatch {
        /// scipy-style name of the test.
        test: &'static str,
        /// Length of the first sample.
        x_len: usize,
        /// Length of the second sample.
        y_len: usize,
    },
    /// A NaN or infinite value in the input.
    #[error("{test}: {} in sample {sample} at index {index}", if value.is_nan() { "NaN".to_string() } else { value.to_string() })]
    NonFinite {
        /// scipy-style name of the test.
        test: &'static str,
        /// Which argument (`"x"`, `"y"`, `"group 2"`, ...).
        sample: String,
        /// Index of the first offending value.
        index: usize,
        /// The value itself (NaN or ±inf).
        value: f64,
    },
    /// Constant (zero-variance / zero-range / all-tied) input for which the
    /// statistic is undefined (scipy: NaN, ±inf, or a warning).
    #[error("{test}: constant input: the statistic is undefined ({detail})")]
    ConstantInput {
        /// scipy-style name of the test.
        test: &'static str,
        /// What exactly is constant, e.g. `"all 5 values equal 1.0"`.
        detail: String,
    },
    /// An argument outside its domain (e.g. a p-value outside [0, 1]).
    #[error("{test}: invalid argument: {detail}")]
    InvalidArgument {
        /// Function that rejected the argument.
        test: &'static str,
        /// What was wrong.
        detail: String,
    },
    /// The exact null distribution is too large to tabulate.
    #[error("{test}: {detail}")]
    TooLarge {
        /// scipy-style name of the test.
        test: &'static str,
        /// What overflowed.
        detail: String,
    },
}
