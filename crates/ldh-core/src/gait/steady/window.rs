//! The steady window of a walk's strides ([module docs](super): a control chart on a running
//! median finds the longest stretch at one pace, a segmented regression from each end of the
//! walk it did not reach finds where the transient there ends).

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
    let max_trend_s = p.max_trend_share * centre;
    let min_strides = p.min_steady_share * n as f64;
    let fails = |(a, b): (usize, usize)| {
        if a > b || ((b + 1 - a) as f64) < min_strides {
            return true;
        }
        // A window whose line goes on the way the strides cut before or after it lie is the
        // rest of that change, not a level after a transient: no more than a steady walk's
        // wander.
        let most_s = if continues_a_cut(t, (a, b)) {
            p.max_continued_trend_share * centre
        } else {
            max_trend_s
        };
        holds_trend(&t[a..=b], sigma, most_s, p.trend_ses)
    };
    let mut ab = trim_transients(t, core, range, sigma, p.smooth_strides);
    if fails(ab) {
        // The lower bar for short transients (±2 σ) is a cut the walk must be able to afford:
        // on a short, variable walk (a simulated LDH walker's 40 s with a turn, 20 strides a
        // leg) it cut the first 3 strides, 0.1 s shorter than the rest, as a "transient", and
        // what was left read as a trend, so a walk the full band calls steady read "never
        // steady". Then only transients beyond the whole band are cut, as for the long ones.
        ab = trim_transients(t, core, range, sigma, 0);
    }
    let (a, b) = ab;
    if longest_share < p.min_steady_share || fails(ab) {
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

/// Step 5 of the [module docs](super): at each end of the walk the transient there (a
/// start-up, a slowing down) is measured from that end to the middle of the longest stretch at
/// one pace (`core`) by [`transient_length`], whichever way it goes. Both ends are treated
/// alike, whether the core reaches them or not: a running median hides a transient of a few
/// strides at an end (its window there is half as wide), and the core's last stride says
/// nothing about the direction of what lies beyond it (TRIPOD's PWS run: a dip of shorter
/// strides ended the core 20 s before the belt slowed to a stop, and only longer strides,
/// the slowing down, were looked for). `range` is the band of step 4 (an excursion inside it is
/// the walk's own variation), `sigma` the short-term SD and `smooth` the running median's
/// length. Returns the window, `(0, n − 1)` when nothing is cut.
fn trim_transients(
    t: &[f64],
    (core_a, core_b): (usize, usize),
    range: f64,
    sigma: f64,
    smooth: usize,
) -> (usize, usize) {
    let n = t.len();
    let mid = (core_a + core_b) / 2;
    let a = transient_length(&t[..=mid], range, sigma, smooth);
    let inward: Vec<f64> = t[mid..].iter().rev().copied().collect();
    (a, n - 1 - transient_length(&inward, range, sigma, smooth))
}

/// How many strides of `y` (stride times from an end of the walk inward) are a transient, of
/// longer or of shorter strides. Two models of the transient's first `c` strides against a
/// constant level after them are fitted by least squares for every `c` (segmented regression,
/// Muggeo 2003, Stat Med 22:3055–3071): a ramp that meets the level at `c` (`level + β·(c − i)`,
/// a belt's start-up or a slowing down) and a step (`level + β`, a different pace). A model
/// counts when its excursion at the end of the walk (|β·c|, or |β|) lies beyond `range` (a
/// transient, not the walk's own variation: `range` bounds the running median's wander) and
/// its reduction of the squared error exceeds `2 ln n` σ² (Schwarz's criterion for its two
/// parameters, Schwarz 1978, Ann Stat 6:461–464); of those, the larger reduction gives the
/// length, else 0. A transient shorter than the running median (`c < smooth` strides) is
/// never a wander of the median's level, so its excursion need only leave the band around the
/// level, `range / 2` (±2 σ), as a few strides of a slow patient's start-up do.
pub(super) fn transient_length(y: &[f64], range: f64, sigma: f64, smooth: usize) -> usize {
    let n = y.len();
    if n < 5 || !(sigma > 0.0) {
        return 0;
    }
    let nf = n as f64;
    let mean = y.iter().sum::<f64>() / nf;
    let penalty = 2.0 * nf.ln() * sigma * sigma;
    // Prefix sums of the centred values d and of i·d.
    let (mut p, mut q) = (0.0, 0.0);
    let mut best = (0.0, 0usize);
    for c in 1..n - 2 {
        let d = y[c - 1] - mean;
        p += d;
        q += (c - 1) as f64 * d;
        if c < 2 {
            continue;
        }
        let cf = c as f64;
        // Step: x = 1 for i < c. Ramp: x = c − i for i < c.
        let step = (p, cf - cf * cf / nf, 1.0);
        let sx = cf * (cf + 1.0) / 2.0;
        let ramp = (
            cf * p - q,
            cf * (cf + 1.0) * (2.0 * cf + 1.0) / 6.0 - sx * sx / nf,
            cf,
        );
        for (sxy, sxx, scale) in [step, ramp] {
            if !(sxx > 0.0) {
                continue;
            }
            let gain = sxy * sxy / sxx;
            let bar = if c < smooth { 0.5 * range } else { range };
            if (sxy / sxx * scale).abs() > bar && gain > penalty && gain > best.0 {
                best = (gain, c);
            }
        }
    }
    best.1
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

/// Whether a window's stride times `t` (both legs, in heel-strike order) still hold a trend
/// (step 6 of the [module docs](super)): the change along their least-squares line
/// ([`fitted_change`]) is larger than `max_change_s` (the most a steady walk's slow wander
/// moves it) and than `ses` standard errors of that change for stride-to-stride noise of SD
/// `sigma` ([`change_se`]: a short, variable window's line wanders that far by chance).
pub(super) fn holds_trend(t: &[f64], sigma: f64, max_change_s: f64, ses: f64) -> bool {
    let change = fitted_change(t).abs();
    change > max_change_s && change > ses * change_se(sigma, t.len())
}

/// Whether the window `[a, b]` of `t` goes on the way the strides cut before or after it lie
/// (step 6 of the [module docs](super)): its least-squares line rises (falls) while the
/// strides cut before it are on average shorter (longer) than the window's mean, or those cut
/// after it longer (shorter). A belt's start-up or a slowing down ends in a level, or the walk
/// turns back from it; a walk that changes its pace throughout goes on past wherever the
/// segmented fit cut it.
pub(super) fn continues_a_cut(t: &[f64], (a, b): (usize, usize)) -> bool {
    if a > b || b >= t.len() {
        return false;
    }
    let mean = |x: &[f64]| x.iter().sum::<f64>() / x.len() as f64;
    let (level, change) = (mean(&t[a..=b]), fitted_change(&t[a..=b]));
    (a > 0 && (mean(&t[..a]) - level) * change < 0.0)
        || (b + 1 < t.len() && (mean(&t[b + 1..]) - level) * change > 0.0)
}

/// The standard error of [`fitted_change`] over `n` strides of independent noise of SD `sigma`:
/// the least-squares slope's, σ / √Sxx with Sxx = n (n² − 1) / 12 for the indices 0 … n − 1
/// (Draper & Smith, *Applied Regression Analysis*, 3rd ed. 1998, ch. 1), times the n − 1
/// strides the change spans. Infinite below 3 strides (no change is fitted there).
pub(super) fn change_se(sigma: f64, n: usize) -> f64 {
    if n < 3 {
        return f64::INFINITY;
    }
    let nf = n as f64;
    sigma * (nf - 1.0) / (nf * (nf * nf - 1.0) / 12.0).sqrt()
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
