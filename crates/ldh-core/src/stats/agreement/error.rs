//! The error type of the agreement module.

/// Why an agreement or reliability statistic, or an event matching, could not be computed.
///
/// Every case where pingouin or scipy return NaN, ±inf or raise is an error here (see
/// `docs/agreement.md`, "Statistics"); no function of [`crate::stats::agreement`] or [`crate::events::matching`] returns a NaN.
/// [`crate::LdhError`] wraps it with `#[from]`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AgreementError {
    /// Fewer usable pairs (or subjects) than the statistic needs, after NaN pairs were dropped.
    #[error("{what}: needs at least {needed} {unit} with both values, got {got} ({dropped} dropped for a missing value)")]
    TooFewPairs {
        /// The statistic, e.g. `"limits of agreement"`.
        what: &'static str,
        /// The minimum.
        needed: usize,
        /// How many were usable.
        got: usize,
        /// How many were dropped because one value was missing (NaN).
        dropped: usize,
        /// `"pairs"` or `"subjects"`.
        unit: &'static str,
    },
    /// The two inputs have different lengths.
    #[error("{what}: the ldh and reference values have different lengths ({ldh_len} vs {reference_len})")]
    LengthMismatch {
        /// The statistic.
        what: &'static str,
        /// Number of ldh values.
        ldh_len: usize,
        /// Number of reference values.
        reference_len: usize,
    },
    /// An infinite value (NaN is "missing" and dropped; ±inf is an error).
    #[error("{what}: {value} in {input} at index {index}")]
    NonFinite {
        /// The statistic.
        what: &'static str,
        /// Which input (`"ldh"`, `"reference"`, `"subject 3"`, `"ldh events"`, ...).
        input: String,
        /// Index of the first offending value.
        index: usize,
        /// The value.
        value: f64,
    },
    /// Constant data for which the statistic is undefined (zero variance where one divides by it).
    #[error("{what}: constant data: {detail}")]
    ConstantData {
        /// The statistic.
        what: &'static str,
        /// What is constant, e.g. `"all 12 differences equal 0.1"`.
        detail: String,
    },
    /// Event times that are not sorted ascending.
    #[error("{input} event times are not sorted: {earlier} s at index {index} after {later} s")]
    UnsortedEvents {
        /// `"ldh"` or `"reference"`.
        input: &'static str,
        /// Index of the first value smaller than its predecessor.
        index: usize,
        /// That value, s.
        earlier: f64,
        /// Its predecessor, s.
        later: f64,
    },
    /// No offset within the search range pairs any event (the clock-offset estimate).
    #[error("clock offset: no offset within ±{max_offset_s} s matches any event within {tolerance_s} s ({ldh_events} ldh, {reference_events} reference events)")]
    NoOffset {
        /// The search range, s.
        max_offset_s: f64,
        /// The matching tolerance, s.
        tolerance_s: f64,
        /// Number of ldh events.
        ldh_events: usize,
        /// Number of reference events.
        reference_events: usize,
    },
    /// A parameter outside its domain (see [`super::AgreementParams`]).
    #[error("{name} = {value}: {reason}")]
    InvalidParam {
        /// Parameter name (with unit).
        name: &'static str,
        /// The offending value, formatted.
        value: String,
        /// The rule it breaks.
        reason: &'static str,
    },
    /// A statistic of [`crate::stats`] refused the data.
    #[error(transparent)]
    Stats(#[from] crate::stats::StatsError),
}
