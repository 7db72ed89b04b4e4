//! Peaks with a minimum height, prominence and distance in time linear in the samples: the same
//! peaks, in the same order of preference, as the `find_peaks` crate (0.1.5) gives with
//! `with_min_height`, `with_min_prominence` and `with_min_distance` (issue 19).
//!
//! The crate finds a peak's prominence by walking outwards from it while the samples are not
//! higher (`x <= peak`), and keeps for its distance rule the tallest remaining peak then filters
//! every other one; both are O(samples × peaks) when strides repeat (a recording of identical
//! strides walks every prominence search to the ends of the signal). Here:
//!
//! * local maxima and the height rule: the crate itself (its plateau rules, linear);
//! * the lowest sample of each outward walk (the valley floors): one pass in each direction with
//!   a monotonic stack of (sample, lowest sample since the previous stack entry) — the classic
//!   "previous greater element" stack, which yields the minimum between a sample and the
//!   previous strictly higher one (or NaN, which also stops the crate's walk) in amortised O(1);
//!   prominence = peak − the higher of the two floors, exactly the crate's expression;
//! * the distance rule: the crate's own order (the same `sort_unstable_by` on the same
//!   [`Peak`] values, so equal heights are preferred in the same order), then a greedy pass
//!   that suppresses, around each kept peak, the candidates closer than the minimum distance —
//!   each candidate lies within reach of at most two kept peaks.

use std::cmp::Ordering;

use find_peaks::{Peak, PeakFinder};

/// Middle sample of every peak of `y` at least `min_height` high, `min_prominence` prominent and
/// `min_distance` samples from any taller kept peak, in increasing order (the crate's peaks).
pub(super) fn peaks(
    y: &[f64],
    min_height: f64,
    min_prominence: f64,
    min_distance: usize,
) -> Vec<usize> {
    let mut pf = PeakFinder::new(y);
    pf.with_min_height(min_height);
    // Without a distance rule the crate returns the local maxima above the height sorted by
    // height; position order is the order its prominence filter sees them in.
    let mut cand = pf.find_peaks();
    cand.sort_unstable_by_key(|p| p.position.start);
    let left = floors(
        y.iter().copied().enumerate(),
        cand.iter().map(|p| p.position.start),
    );
    let right = floors(
        y.iter().copied().enumerate().rev(),
        cand.iter().rev().map(|p| p.position.end - 1),
    );
    let mut kept: Vec<Peak<f64>> = Vec::with_capacity(cand.len());
    for (k, mut p) in cand.into_iter().enumerate() {
        let h = y[p.position.start];
        let prom = match (left[k], right[right.len() - 1 - k]) {
            (None, None) => 0.0,
            (Some(v), None) | (None, Some(v)) => h - v,
            (Some(v1), Some(v2)) => h - (if v1 >= v2 { v1 } else { v2 }),
        };
        if prom >= min_prominence {
            p.height = Some(h);
            p.prominence = Some(prom);
            kept.push(p);
        }
    }
    distance_rule(kept, min_distance)
}

/// For each query position (in the order of `samples`), the lowest sample met walking from it
/// against that order while samples are ≤ its own (`None` when the first step already stops).
fn floors(
    samples: impl Iterator<Item = (usize, f64)>,
    queries: impl Iterator<Item = usize>,
) -> Vec<Option<f64>> {
    let mut queries = queries.peekable();
    let mut out = Vec::new();
    // (sample, lowest sample from just after the entry below it up to this one); the samples
    // strictly decrease from the bottom of the stack to its top.
    let mut stack: Vec<(f64, f64)> = Vec::new();
    for (i, v) in samples {
        let mut floor: Option<f64> = None;
        while let Some(&(top, low)) = stack.last() {
            // The walk goes on while `top <= v` (false for a NaN `v`).
            if !matches!(top.partial_cmp(&v), Some(Ordering::Less | Ordering::Equal)) {
                break;
            }
            floor = Some(match floor {
                Some(f) if f <= low => f,
                _ => low,
            });
            stack.pop();
        }
        if queries.peek() == Some(&i) {
            out.push(floor);
            queries.next();
        }
        if v.is_nan() {
            // No walk crosses a NaN (`NaN <= peak` is false).
            stack.clear();
        } else {
            stack.push((v, floor.map_or(v, |f| if f <= v { f } else { v })));
        }
    }
    out
}

/// The crate's distance rule: the tallest peak first (its sort, its tie order), every peak
/// closer than `min_distance` samples to a kept one dropped; the middles of the kept peaks in
/// increasing order.
fn distance_rule(mut cand: Vec<Peak<f64>>, min_distance: usize) -> Vec<usize> {
    let middles: Vec<usize> = cand.iter().map(|p| p.middle_position()).collect();
    cand.sort_unstable_by(|a, b| b.height.partial_cmp(&a.height).unwrap_or(Ordering::Equal));
    let mut dropped = vec![false; middles.len()];
    let mut out = Vec::new();
    for p in &cand {
        let x = p.middle_position();
        let Ok(r) = middles.binary_search(&x) else {
            continue;
        };
        if dropped[r] {
            continue;
        }
        out.push(x);
        for j in (0..r).rev() {
            if x - middles[j] >= min_distance {
                break;
            }
            dropped[j] = true;
        }
        for (j, &m) in middles.iter().enumerate().skip(r + 1) {
            if m - x >= min_distance {
                break;
            }
            dropped[j] = true;
        }
    }
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests;
