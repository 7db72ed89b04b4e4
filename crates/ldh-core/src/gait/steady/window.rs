//! The steady window of a walk's strides ([module docs](super): a control chart on a running
//! median finds the longest stretch at one pace, a CUSUM on each leg trims its ends).

use super::ValidSteadyParams;
use crate::stats::{median, EvenMedian};

/// The median of |X₁ − X₂| for two independent normal values of SD 1 (√2 · 0.6745).
pub(super) const MEDIAN_MOVING_RANGE: f64 = 0.954;

/// The steady window of a walk's valid strides (both legs, in heel-strike order).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WalkWindow {
    /// First and last stride of the window (inclusive, indices of the input); `None` when the
    /// walk has no stride or never becomes steady.
    pub range: Option<(usize, usize)>,
    /// The walk never becomes steady: its longest stretch at one pace holds fewer than
    /// `min_steady_share` of its strides.
    pub never_steady: bool,
    /// Share of the walk's strides in its longest stretch at one pace (1 when the rule did not
    /// trim: disabled or too few strides).
    pub longest_share: f64,
}

/// The steady window of a walk ([module docs](self)): `stride_time_s` are the valid strides of
/// both legs in the order of their heel strikes on the walk's clock, `leg[i]` the leg of each
/// (0 or 1; it pairs a leg's successive strides for the moving range). Values must be finite.
/// With the rule disabled or fewer than `min_strides_to_trim` strides per leg, the window is
/// everything.
pub fn walk_window(stride_time_s: &[f64], leg: &[usize], p: &ValidSteadyParams) -> WalkWindow {
    let p = p.0;
    let n = stride_time_s.len().min(leg.len());
    if n == 0 {
        return WalkWindow {
            range: None,
            never_steady: false,
            longest_share: 0.0,
        };
    }
    let whole = WalkWindow {
        range: Some((0, n - 1)),
        never_steady: false,
        longest_share: 1.0,
    };
    let (t, leg) = (&stride_time_s[..n], &leg[..n]);
    let legs = 1 + leg.iter().copied().max().unwrap_or(0).min(1);
    if !p.enabled || n < 3 || n < p.min_strides_to_trim * legs {
        return whole;
    }
    let Some(centre) = median(&mut t.to_vec(), EvenMedian::Mean) else {
        return whole;
    };
    let sigma = moving_range_sd(t, leg).unwrap_or(0.0);
    let range = (p.range_sds * sigma).max(p.min_range_share * centre);
    let level = running_median(t, p.smooth_strides / 2);
    let core = longest_within(&level, range);
    let longest_share = (core.1 + 1 - core.0) as f64 / n as f64;
    let (a, b) = trim_tails(t, leg, &level, core, &p);
    if a > b
        || longest_share < p.min_steady_share
        || fitted_change(&t[a..=b]).abs() > p.max_trend_share * centre
    {
        return WalkWindow {
            range: None,
            never_steady: true,
            longest_share,
        };
    }
    WalkWindow {
        range: Some((a, b)),
        never_steady: false,
        longest_share,
    }
}

/// Step 5 of the [module docs](super): where the longest stretch at one pace (`core`) stops
/// short of an end of the walk, the transient it left out may go on inside it, below the band.
/// For each leg, from the core's edge inward to its middle, the deviations from the leg's
/// median stride time in the core, in the transient's direction (the level just outside the
/// core against the core's median) and in units of the leg's short-term SD σ (its moving
/// range in the core), are summed less `cusum_allowance_sds` per stride ([`tail_length`]); the
/// window starts (ends) after the strides where that sum peaks, when it peaks above
/// `cusum_limit_sds`. Both legs' cuts apply to the one window.
fn trim_tails(
    t: &[f64],
    leg: &[usize],
    level: &[f64],
    (core_a, core_b): (usize, usize),
    p: &super::SteadyParams,
) -> (usize, usize) {
    let n = t.len();
    let (mut a, mut b) = (core_a, core_b);
    let mid = (core_a + core_b) / 2;
    let Some(core_median) = median(&mut t[core_a..=core_b].to_vec(), EvenMedian::Mean) else {
        return (a, b);
    };
    // The direction of the transient left out at each end (None: nothing left out).
    let dir = |k: Option<usize>| k.map(|k| if level[k] > core_median { 1.0 } else { -1.0 });
    let head = dir(core_a.checked_sub(1));
    let tail = dir((core_b + 1 < n).then_some(core_b + 1));
    for l in 0..2 {
        let mine: Vec<usize> = (core_a..=core_b).filter(|&i| leg[i].min(1) == l).collect();
        let x: Vec<f64> = mine.iter().map(|&i| t[i]).collect();
        let (Some(m), Some(s)) = (
            median(&mut x.clone(), EvenMedian::Mean),
            moving_range_sd(&x, &vec![0; x.len()]),
        ) else {
            continue;
        };
        if s <= 0.0 {
            continue;
        }
        let (k, h) = (p.cusum_allowance_sds, p.cusum_limit_sds);
        let split = mine.partition_point(|&i| i < mid);
        if let Some(d) = head {
            let inward = &mine[..split];
            let j = tail_length(inward.iter().map(|&i| d * (t[i] - m) / s), k, h);
            if j > 0 {
                a = a.max(inward[j - 1] + 1);
            }
        }
        if let Some(d) = tail {
            let inward: Vec<usize> = mine[split..].iter().rev().copied().collect();
            let j = tail_length(inward.iter().map(|&i| d * (t[i] - m) / s), k, h);
            if j > 0 {
                b = b.min(inward[j - 1].saturating_sub(1));
            }
        }
    }
    (a, b)
}

/// How many of `z` (standardised deviations in a transient's direction, from the edge of the
/// window inward) are the transient's tail: the count after which the sum of `z − allowance`
/// peaks (Page's CUSUM, Page 1954, Biometrika 41:100–115, read from the transient's end: its
/// peak is the most likely change point of a shift of at least 2 × `allowance`; Montgomery
/// 2009 §9.1), or 0 when the peak is not above `limit`.
pub(super) fn tail_length(z: impl IntoIterator<Item = f64>, allowance: f64, limit: f64) -> usize {
    let (mut sum, mut peak, mut at) = (0.0, 0.0, 0);
    for (i, z) in z.into_iter().enumerate() {
        sum += z - allowance;
        if sum > peak {
            peak = sum;
            at = i + 1;
        }
    }
    if peak > limit {
        at
    } else {
        0
    }
}

/// The short-term SD of the stride time: the median absolute difference of each leg's
/// successive strides, pooled, / 0.954 (`None` without two strides of a leg).
pub(super) fn moving_range_sd(t: &[f64], leg: &[usize]) -> Option<f64> {
    let mut last: [Option<f64>; 2] = [None, None];
    let mut d = Vec::with_capacity(t.len());
    for (&x, &l) in t.iter().zip(leg) {
        let l = l.min(1);
        if let Some(prev) = last[l] {
            d.push((x - prev).abs());
        }
        last[l] = Some(x);
    }
    median(&mut d, EvenMedian::Mean).map(|m| m / MEDIAN_MOVING_RANGE)
}

/// The change of `t` from its first to its last value along its least-squares line in the
/// index (the strides of both legs interleave evenly in time).
pub(super) fn fitted_change(t: &[f64]) -> f64 {
    let n = t.len();
    if n < 3 {
        return 0.0;
    }
    let xm = (n - 1) as f64 / 2.0;
    let ym = t.iter().sum::<f64>() / n as f64;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (i, y) in t.iter().enumerate() {
        let dx = i as f64 - xm;
        sxy += dx * (y - ym);
        sxx += dx * dx;
    }
    sxy / sxx * (n - 1) as f64
}

/// The running median of `t` over `2h + 1` values (fewer at the ends).
pub(super) fn running_median(t: &[f64], h: usize) -> Vec<f64> {
    let n = t.len();
    let mut buf = Vec::with_capacity(2 * h + 1);
    (0..n)
        .map(|i| {
            buf.clear();
            buf.extend_from_slice(&t[i.saturating_sub(h)..(i + h + 1).min(n)]);
            median(&mut buf, EvenMedian::Mean).unwrap_or(f64::NAN)
        })
        .collect()
}

/// The longest run `[a, b]` of `x` whose largest and smallest values differ by at most `range`
/// (the earliest of equal runs); sliding extremes in monotone queues, linear time.
pub(super) fn longest_within(x: &[f64], range: f64) -> (usize, usize) {
    use std::collections::VecDeque;
    let (mut hi, mut lo): (VecDeque<usize>, VecDeque<usize>) = Default::default();
    let (mut left, mut best) = (0, (0, 0));
    for right in 0..x.len() {
        while hi.back().is_some_and(|&k| x[k] <= x[right]) {
            hi.pop_back();
        }
        hi.push_back(right);
        while lo.back().is_some_and(|&k| x[k] >= x[right]) {
            lo.pop_back();
        }
        lo.push_back(right);
        while x[hi[0]] - x[lo[0]] > range {
            left += 1;
            while hi[0] < left {
                hi.pop_front();
            }
            while lo[0] < left {
                lo.pop_front();
            }
        }
        if right - left > best.1 - best.0 {
            best = (left, right);
        }
    }
    best
}
