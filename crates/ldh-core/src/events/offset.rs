//! The clock offset between the ldh and the reference event trains of one recording (the two
//! systems' clocks were started apart), found as the offset that matches the most events.
//!
//! 1. Grid: every offset d = g·step in [−max, +max] ([`AgreementParams`](crate::stats::agreement::AgreementParams)
//!    `clock_offset_step_s`, `max_clock_offset_s`) is scored by the number of matches of
//!    (ldh − d) with the reference under the rule of [`super::matching::match_events`], summed over all
//!    trains (sides, event kinds) of the recording, which share one clock.
//! 2. Peaks: each maximal run of grid offsets with the same count, higher than its neighbours on
//!    both sides, is one candidate; its middle grid offset is matched and refined to the
//!    **median of ldh − reference** of those matches (off the grid; kept when it matches at least
//!    as many events as the grid offset, else the grid offset stays).
//! 3. Choice: most matches, then the smallest MAE of the remaining errors, then the smallest
//!    |offset|, then the smaller offset — deterministic.
//! 4. Ambiguity: gait is periodic, so an offset one stride away pairs every event with its
//!    neighbour's partner and can match as many events (when one system recorded a few strides
//!    more at either end). The runner-up is the best candidate at least `separation_s` from the
//!    chosen one — half the median interval between consecutive reference events (half a
//!    stride: any offset that far pairs events with another stride), at least 2·tolerance —
//!    and the estimate is `ambiguous` when it matches as many events as the chosen one.
//!
//! The offset is ldh clock − reference clock: subtract it from the ldh times.

use serde::{Deserialize, Serialize};

use super::matching::{check_train, for_each_match};
use crate::stats::agreement::{AgreementError, ValidAgreementParams};
use crate::stats::{median, EvenMedian};

/// One offset and how well it matches.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OffsetCandidate {
    /// ldh clock − reference clock, s.
    pub offset_s: f64,
    /// Events matched after subtracting the offset from the ldh times (all trains).
    pub n_matched: usize,
    /// MAE of the matched events' remaining errors, s.
    pub mae_s: f64,
}

/// The estimated clock offset.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ClockOffset {
    /// The chosen offset: ldh clock − reference clock, s; subtract it from the ldh times.
    pub best: OffsetCandidate,
    /// The best other offset at least `separation_s` away, if any matches an event.
    pub runner_up: Option<OffsetCandidate>,
    /// The runner-up matches as many events as the chosen offset: the offset is not
    /// determined by the events (e.g. off by a whole stride); check it by other means.
    pub ambiguous: bool,
    /// Distance from the chosen offset beyond which another offset is a different alignment, s.
    pub separation_s: f64,
}

/// Estimate the clock offset shared by the `trains` (ldh times, reference times) of one
/// recording; each train sorted ascending. See the module docs for the method.
///
/// Errors: a train not finite or not sorted; no offset in range matches any event.
pub fn estimate_clock_offset(
    trains: &[(&[f64], &[f64])],
    params: &ValidAgreementParams,
) -> Result<ClockOffset, AgreementError> {
    let p = params.params();
    for (l, r) in trains {
        check_train("ldh", l)?;
        check_train("reference", r)?;
    }
    let tol = p.tolerance_s;
    let g_max = (p.max_clock_offset_s / p.clock_offset_step_s + 1e-9).floor() as i64;
    let grid: Vec<f64> = (-g_max..=g_max)
        .map(|g| g as f64 * p.clock_offset_step_s)
        .collect();
    let counts: Vec<usize> = grid.iter().map(|&d| count(trains, d, tol)).collect();
    let mut candidates: Vec<OffsetCandidate> = peaks(&counts)
        .into_iter()
        .map(|g| refine(trains, grid[g], tol))
        .collect();
    if candidates.is_empty() {
        let total = |f: fn(&(&[f64], &[f64])) -> usize| trains.iter().map(f).sum();
        return Err(AgreementError::NoOffset {
            max_offset_s: p.max_clock_offset_s,
            tolerance_s: tol,
            ldh_events: total(|t| t.0.len()),
            reference_events: total(|t| t.1.len()),
        });
    }
    candidates.sort_by(|a, b| {
        b.n_matched
            .cmp(&a.n_matched)
            .then(a.mae_s.total_cmp(&b.mae_s))
            .then(a.offset_s.abs().total_cmp(&b.offset_s.abs()))
            .then(a.offset_s.total_cmp(&b.offset_s))
    });
    let best = candidates[0];
    let separation_s = separation(trains, tol);
    let runner_up = candidates[1..]
        .iter()
        .find(|c| (c.offset_s - best.offset_s).abs() >= separation_s)
        .copied();
    Ok(ClockOffset {
        best,
        ambiguous: runner_up.is_some_and(|r| r.n_matched == best.n_matched),
        runner_up,
        separation_s,
    })
}

/// Matches of all trains at offset `d`.
fn count(trains: &[(&[f64], &[f64])], d: f64, tol: f64) -> usize {
    let mut n = 0;
    for (l, r) in trains {
        for_each_match(l, r, d, tol, |_, _, _| n += 1);
    }
    n
}

/// Middle index of each maximal run of equal, non-zero counts higher than both neighbours.
fn peaks(counts: &[usize]) -> Vec<usize> {
    let mut out = Vec::new();
    let mut s = 0;
    while s < counts.len() {
        let mut e = s;
        while e + 1 < counts.len() && counts[e + 1] == counts[s] {
            e += 1;
        }
        let c = counts[s];
        let left_lower = s == 0 || counts[s - 1] < c;
        let right_lower = e + 1 == counts.len() || counts[e + 1] < c;
        if c > 0 && left_lower && right_lower {
            out.push((s + e) / 2);
        }
        s = e + 1;
    }
    out
}

/// The matches at `d`: their raw differences ldh − reference and |remaining error|.
fn matches_at(trains: &[(&[f64], &[f64])], d: f64, tol: f64) -> (Vec<f64>, f64) {
    let mut raw = Vec::new();
    let mut abs_sum = 0.0;
    for (l, r) in trains {
        for_each_match(l, r, d, tol, |i, j, e| {
            raw.push(l[i] - r[j]);
            abs_sum += e.abs();
        });
    }
    let mae = if raw.is_empty() {
        f64::INFINITY
    } else {
        abs_sum / raw.len() as f64
    };
    (raw, mae)
}

/// A grid offset refined to the median ldh − reference of its matches (kept on the grid when
/// the median matches fewer events).
fn refine(trains: &[(&[f64], &[f64])], d: f64, tol: f64) -> OffsetCandidate {
    let (mut raw, mae) = matches_at(trains, d, tol);
    let on_grid = OffsetCandidate {
        offset_s: d,
        n_matched: raw.len(),
        mae_s: mae,
    };
    let Some(m) = median(&mut raw, EvenMedian::Mean) else {
        return on_grid;
    };
    let (raw_m, mae_m) = matches_at(trains, m, tol);
    if raw_m.len() >= on_grid.n_matched {
        OffsetCandidate {
            offset_s: m,
            n_matched: raw_m.len(),
            mae_s: mae_m,
        }
    } else {
        on_grid
    }
}

/// Half the median interval between consecutive reference events (ldh events when the
/// reference has no two in a train), at least 2·`tol`.
fn separation(trains: &[(&[f64], &[f64])], tol: f64) -> f64 {
    let intervals = |reference: bool| -> Vec<f64> {
        trains
            .iter()
            .flat_map(|t| (if reference { t.1 } else { t.0 }).windows(2))
            .map(|w| w[1] - w[0])
            .filter(|d| *d > 0.0)
            .collect()
    };
    let mut iv = intervals(true);
    if iv.is_empty() {
        iv = intervals(false);
    }
    median(&mut iv, EvenMedian::Mean).map_or(2.0 * tol, |m| (0.5 * m).max(2.0 * tol))
}

/// Polish an offset `d` (e.g. [`estimate_clock_offset`]'s): match the trains at `d`, move `d` to
/// the median ldh − reference of those matches, and repeat until it no longer moves (at most 20
/// times). The grid search ranks offsets by the number of matches, which is flat within about
/// ± the tolerance of the true offset (and one spurious match of an unpaired event at the edge
/// of a walk can tip it); the median of the matched pairs is not. Returns the polished offset
/// with its matches and MAE; `d` itself when nothing matches there.
pub fn polish_offset(
    trains: &[(&[f64], &[f64])],
    d: f64,
    params: &ValidAgreementParams,
) -> OffsetCandidate {
    let tol = params.params().tolerance_s;
    let mut d = d;
    for _ in 0..20 {
        let (mut raw, _) = matches_at(trains, d, tol);
        match median(&mut raw, EvenMedian::Mean) {
            Some(m) if m != d => d = m,
            _ => break,
        }
    }
    let (raw, mae) = matches_at(trains, d, tol);
    OffsetCandidate {
        offset_s: d,
        n_matched: raw.len(),
        mae_s: mae,
    }
}
