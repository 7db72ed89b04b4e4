//! One-to-one matching of two event trains (ldh and reference times of one event kind, one
//! side, one trial), and the detection rates and timing errors of the matches.
//!
//! The rule is the one of gaitmap's `gaitmap.evaluation_utils.match_stride_lists` (nearest
//! neighbours both ways, kept when mutual and within the tolerance; Küderle et al. (2024),
//! "Gaitmap — an open ecosystem for IMU-based human gait analysis and algorithm
//! benchmarking", *IEEE Open Journal of Engineering in Medicine and Biology*), with the tie and
//! tolerance rules made explicit:
//!
//! 1. for every ldh event a, its nearest reference event b(a); for every reference event b, its
//!    nearest ldh event a(b) (distance |a − b|; on a tie the earlier event, i.e. the lower index);
//! 2. (a, b) is a match when b(a) = b and a(b) = a (mutual nearest) and |a − b| ≤ tolerance
//!    (inclusive).
//!
//! Each event is in at most one match (each has one nearest partner), so the matching is
//! one-to-one and, for the same input, always the same. An event may stay unmatched although a
//! partner lies within the tolerance: when two ldh events compete for one reference event, only
//! the nearer wins and the other is a false positive, as in gaitmap.
//!
//! Rates: recall = matched / reference events (sensitivity), precision = matched / ldh events
//! (positive predictive value), F1 = 2·matched / (ldh + reference events). Errors are
//! ldh − reference, s: bias (mean), SD (ddof = 1), MAE, and the 95th percentile of |error|
//! (numpy's default linear interpolation, `np.percentile(|e|, 95)`).

use serde::{Deserialize, Serialize};

use crate::stats::agreement::{AgreementError, ValidAgreementParams};

/// The matching of one pair of event trains. Indices point into the inputs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EventMatch {
    /// Matched (ldh index, reference index), ascending in both.
    pub pairs: Vec<(usize, usize)>,
    /// ldh events without a match (false positives), ascending.
    pub unmatched_ldh: Vec<usize>,
    /// Reference events without a match (missed events), ascending.
    pub unmatched_reference: Vec<usize>,
    /// ldh − reference time of each pair, s, in the order of `pairs`.
    pub errors_s: Vec<f64>,
}

/// Detection rates and timing errors of one or more [`EventMatch`]es.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MatchSummary {
    /// Number of ldh events.
    pub n_ldh: usize,
    /// Number of reference events.
    pub n_reference: usize,
    /// Number of matches.
    pub n_matched: usize,
    /// matched / reference events; `None` without reference events.
    pub recall: Option<f64>,
    /// matched / ldh events; `None` without ldh events.
    pub precision: Option<f64>,
    /// 2·matched / (ldh + reference events); `None` when both are empty.
    pub f1: Option<f64>,
    /// Mean error (ldh − reference), s; `None` without matches.
    pub bias_s: Option<f64>,
    /// SD of the errors (ddof = 1), s; `None` with fewer than 2 matches.
    pub sd_s: Option<f64>,
    /// Mean |error|, s; `None` without matches.
    pub mae_s: Option<f64>,
    /// 95th percentile of |error| (linear interpolation), s; `None` without matches.
    pub p95_abs_s: Option<f64>,
}

/// Check that an event train is finite and sorted ascending (equal times allowed).
pub(crate) fn check_train(input: &'static str, t: &[f64]) -> Result<(), AgreementError> {
    if let Some(index) = t.iter().position(|v| !v.is_finite()) {
        return Err(AgreementError::NonFinite {
            what: "event matching",
            input: format!("{input} events"),
            index,
            value: t[index],
        });
    }
    if let Some(i) = t.windows(2).position(|w| w[1] < w[0]) {
        return Err(AgreementError::UnsortedEvents {
            input,
            index: i + 1,
            earlier: t[i + 1],
            later: t[i],
        });
    }
    Ok(())
}

/// Index of the element of the sorted sequence `at(0..len)` nearest to `target`: the lowest
/// index among equal values, the earlier of two equally near. `len > 0`.
fn nearest(len: usize, at: impl Fn(usize) -> f64, target: f64) -> usize {
    // first index with at(i) >= target
    let (mut lo, mut hi) = (0usize, len);
    while lo < hi {
        let mid = (lo + hi) / 2;
        if at(mid) < target {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    let above = lo;
    if above == 0 {
        return 0;
    }
    // lowest index holding the value just below the target
    let below_value = at(above - 1);
    let (mut l, mut h) = (0usize, above - 1);
    while l < h {
        let mid = (l + h) / 2;
        if at(mid) < below_value {
            l = mid + 1;
        } else {
            h = mid;
        }
    }
    let below = l;
    if above == len || (target - below_value) <= (at(above) - target) {
        below
    } else {
        above
    }
}

/// Visit the mutual-nearest pairs within `tol` of `ldh − shift` and `reference` (both sorted,
/// finite): `f(i, j, (ldh[i] − shift) − reference[j])`. The one rule behind
/// [`match_events`] and the clock-offset search.
pub(crate) fn for_each_match(
    ldh: &[f64],
    reference: &[f64],
    shift: f64,
    tol: f64,
    mut f: impl FnMut(usize, usize, f64),
) {
    if ldh.is_empty() || reference.is_empty() {
        return;
    }
    let a = |i: usize| ldh[i] - shift;
    let b = |j: usize| reference[j];
    for i in 0..ldh.len() {
        let j = nearest(reference.len(), b, a(i));
        let d = a(i) - b(j);
        if d.abs() <= tol && nearest(ldh.len(), a, b(j)) == i {
            f(i, j, d);
        }
    }
}

/// Match two sorted event trains one-to-one within `params.tolerance_s` (see the module docs
/// for the rule). Times in s, both on the same clock (remove an offset first:
/// [`super::offset::estimate_clock_offset`]).
///
/// Errors: a non-finite time; a train not sorted ascending.
pub fn match_events(
    ldh: &[f64],
    reference: &[f64],
    params: &ValidAgreementParams,
) -> Result<EventMatch, AgreementError> {
    check_train("ldh", ldh)?;
    check_train("reference", reference)?;
    let mut pairs = Vec::new();
    let mut errors_s = Vec::new();
    for_each_match(
        ldh,
        reference,
        0.0,
        params.params().tolerance_s,
        |i, j, d| {
            pairs.push((i, j));
            errors_s.push(d);
        },
    );
    let unmatched = |len: usize, used: &mut dyn Iterator<Item = usize>| {
        let mut taken = vec![false; len];
        used.for_each(|i| taken[i] = true);
        (0..len).filter(|&i| !taken[i]).collect::<Vec<_>>()
    };
    Ok(EventMatch {
        unmatched_ldh: unmatched(ldh.len(), &mut pairs.iter().map(|p| p.0)),
        unmatched_reference: unmatched(reference.len(), &mut pairs.iter().map(|p| p.1)),
        pairs,
        errors_s,
    })
}

/// [`match_events`] for each group of a recording or a study, e.g. keyed by (subject, trial,
/// side, event kind); the keys are passed through. Summarise with [`summarize`].
///
/// Errors: the first group's error.
pub fn match_groups<'a, K>(
    groups: impl IntoIterator<Item = (K, &'a [f64], &'a [f64])>,
    params: &ValidAgreementParams,
) -> Result<Vec<(K, EventMatch)>, AgreementError> {
    groups
        .into_iter()
        .map(|(k, l, r)| Ok((k, match_events(l, r, params)?)))
        .collect()
}

impl EventMatch {
    /// Number of ldh events (matched + unmatched).
    pub fn n_ldh(&self) -> usize {
        self.pairs.len() + self.unmatched_ldh.len()
    }

    /// Number of reference events (matched + unmatched).
    pub fn n_reference(&self) -> usize {
        self.pairs.len() + self.unmatched_reference.len()
    }

    /// Rates and errors of this matching.
    pub fn summary(&self) -> MatchSummary {
        summarize(std::slice::from_ref(self))
    }
}

/// Rates and errors of several matchings pooled (every event and every error counts once; e.g.
/// all trials of one event kind).
pub fn summarize(matches: &[EventMatch]) -> MatchSummary {
    let n_ldh: usize = matches.iter().map(EventMatch::n_ldh).sum();
    let n_reference: usize = matches.iter().map(EventMatch::n_reference).sum();
    let errors: Vec<f64> = matches
        .iter()
        .flat_map(|m| m.errors_s.iter().copied())
        .collect();
    let m = errors.len();
    let ratio = |num: usize, den: usize| (den > 0).then(|| num as f64 / den as f64);
    let bias = (m > 0).then(|| errors.iter().sum::<f64>() / m as f64);
    let sd = bias
        .filter(|_| m > 1)
        .map(|b| (errors.iter().map(|e| (e - b) * (e - b)).sum::<f64>() / (m - 1) as f64).sqrt());
    let mut abs: Vec<f64> = errors.iter().map(|e| e.abs()).collect();
    abs.sort_by(f64::total_cmp);
    MatchSummary {
        n_ldh,
        n_reference,
        n_matched: m,
        recall: ratio(m, n_reference),
        precision: ratio(m, n_ldh),
        f1: ratio(2 * m, n_ldh + n_reference),
        bias_s: bias,
        sd_s: sd,
        mae_s: (m > 0).then(|| abs.iter().sum::<f64>() / m as f64),
        p95_abs_s: percentile_sorted(&abs, 95.0),
    }
}

/// numpy's default (linear) percentile of sorted values; `None` when empty.
fn percentile_sorted(sorted: &[f64], q: f64) -> Option<f64> {
    let n = sorted.len();
    if n == 0 {
        return None;
    }
    let pos = q / 100.0 * (n - 1) as f64;
    let lo = pos.floor() as usize;
    let hi = (lo + 1).min(n - 1);
    let t = pos - lo as f64;
    let (a, b) = (sorted[lo], sorted[hi]);
    // numpy's _lerp: from the nearer end
    Some(if t >= 0.5 {
        b - (b - a) * (1.0 - t)
    } else {
        a + (b - a) * t
    })
}
