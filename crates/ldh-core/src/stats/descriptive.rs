//! Descriptive statistics used by the cohort tables (mean ± SD).

use super::{check_finite, StatsError};

/// Arithmetic mean, as `numpy.mean(x)`.
///
/// Errors: empty input ([`StatsError::TooFewObservations`]); NaN / ±inf
/// ([`StatsError::NonFinite`]).
pub fn mean(x: &[f64]) -> Result<f64, StatsError> {
    if x.is_empty() {
        return Err(StatsError::TooFewObservations {
            test: "mean",
            needed: 1,
            got: 0,
            what: "",
        });
    }
    check_finite("mean", "x", x)?;
    Ok(mean_unchecked(x))
}

/// Sample standard deviation with `ddof = 1`, as `numpy.std(x, ddof=1)`
/// (the "SD" of the paper's Table 3).
///
/// Errors: fewer than 2 values ([`StatsError::TooFewObservations`]); NaN /
/// ±inf ([`StatsError::NonFinite`]). A constant sample gives 0.0.
pub fn std_dev(x: &[f64]) -> Result<f64, StatsError> {
    if x.len() < 2 {
        return Err(StatsError::TooFewObservations {
            test: "std_dev",
            needed: 2,
            got: x.len(),
            what: "",
        });
    }
    check_finite("std_dev", "x", x)?;
    Ok(var_unchecked(x, 1.0).sqrt())
}

/// Which middle the [`median`] of an even count of values is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EvenMedian {
    /// The mean of the two middle values (`numpy.median`).
    Mean,
    /// The upper of the two (the value at `len / 2` of the sorted values): always one of the
    /// values.
    Upper,
}

/// The median of `values` in the order of [`f64::total_cmp`] (NaN sorts last); `None` when
/// empty. `values` is reordered: a selection in linear time, not a full sort. ldh's one median
/// (time bases, stride times, quality checks, clock offsets, RANSAC thresholds).
pub fn median(values: &mut [f64], even: EvenMedian) -> Option<f64> {
    let n = values.len();
    if n == 0 {
        return None;
    }
    let (below, mid, _) = values.select_nth_unstable_by(n / 2, f64::total_cmp);
    let mid = *mid;
    Some(match even {
        EvenMedian::Mean if n.is_multiple_of(2) => {
            let low = below.iter().copied().max_by(f64::total_cmp);
            0.5 * (low.expect("an even count of at least 2") + mid)
        }
        _ => mid,
    })
}

/// Mean of finite, non-empty input. Centred two-pass correction keeps it
/// accurate for large offsets.
pub(crate) fn mean_unchecked(x: &[f64]) -> f64 {
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    // one refinement step (corrects the rounding of the naive sum)
    m + x.iter().map(|v| v - m).sum::<f64>() / n
}

/// Variance with `ddof` of finite input with `len() > ddof`.
pub(crate) fn var_unchecked(x: &[f64], ddof: f64) -> f64 {
    let m = mean_unchecked(x);
    let ss: f64 = x.iter().map(|v| (v - m) * (v - m)).sum();
    ss / (x.len() as f64 - ddof)
}
