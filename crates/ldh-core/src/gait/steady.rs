//! Steady-state walking, one window per walk (issue 50): the stretch of the walk at one pace,
//! found on both legs' strides together on the walk's clock, so that the belt's start-up, gait
//! initiation, slowing down and any trend in stride time are left out of every mean and CV, and
//! both legs are of the same stretch of walking.
//!
//! The rule is an individuals control chart on the smoothed stride time (Montgomery,
//! *Introduction to Statistical Quality Control*, 6th ed. 2009, §6.4: a process is in control
//! while its level stays within limits set from its own short-term variation, estimated from
//! the moving range of successive observations, which a trend does not inflate), applied to a
//! running median (Tukey, *Exploratory Data Analysis*, 1977, ch. 7: a running median follows
//! a level or a trend and ignores single odd values):
//!
//! 1. The walk's valid strides of both legs, in the order of their heel strikes on the walk's
//!    clock (each leg's stride time from its own heel strikes).
//! 2. The short-term variation σ: the median moving range of each leg's successive valid
//!    strides, pooled, / 0.954 (the median of |X₁ − X₂| of a normal variable is 0.954 σ).
//! 3. The level: the running median of `smooth_strides` (7: ≈ 3.5 strides of each leg).
//! 4. The steady window is the longest run of strides whose levels all lie within a range of
//!    `range_sds` σ (4: ±2 σ, ±4 SDs of a 7-stride median of independent strides, which noise
//!    alone does not leave), never narrower than `min_range_share` (6 %) of the median stride
//!    time (the slow wandering of a healthy walk's stride time, Hausdorff 2005, stays within
//!    it).
//! 5. A walk whose longest such run holds fewer than `min_steady_share` (half) of its valid
//!    strides has no steady pace: it speeds up or slows down throughout, or changes its pace
//!    more than once. So has a walk whose window still holds a trend: the least-squares line
//!    of stride time across it changes by more than `max_trend_share` (5 %) of the median
//!    (≈ 5 standard errors of that change on a 70-stride walk with a CV of 4 %; a 5 % trend
//!    adds 5 % / √12 in quadrature to a CV, the most a window may hold). Nothing is
//!    excluded, its means are of the whole walk, and its variability is withheld
//!    (`never_steady`) rather than reported as the trend's.
//!
//! Thresholds, from the literature rather than from the tests:
//! - `min_steady_strides` 10 (per leg): fewer steady strides leave the CV too uncertain (its
//!   relative standard error ≈ 1/√(2n) is > 20 % below 10 strides; Hausdorff 2005, J NeuroEng
//!   Rehabil 2:19), so the variability is withheld with [`TOO_LITTLE_STEADY`].
//! - `min_strides_to_trim` 20 (per leg, 2 × `min_steady_strides`): on a shorter walk the
//!   median and the moving range of a handful of strides cannot tell a transient from the
//!   walk's own variation, so nothing is trimmed there (the first and last stride of every
//!   bout are still dropped, `StrideParams::drop_bout_edges`).
//! - Steady walking speed is reached within 2–3 strides of gait initiation in adults
//!   (Lindemann et al. 2008, Gait Posture 27:91–96); a treadmill belt's start-up takes longer
//!   (≈ 15 s on the real trials of issue 36, 30 s on issue 50's): the window has no cap on
//!   what it leaves out at either end, only the half-of-the-walk rule of step 5.
//!
//! When the two legs are not one walk (their recordings do not overlap, or the pair's checks
//! doubt it), each leg gets its own window by the same rule.

use serde::{Deserialize, Serialize};

use super::{Stride, StrideCode, StrideFinding};
use crate::error::{LdhError, Result};
use crate::stats::{median, EvenMedian};

/// The reason given on a stride outside the steady window.
pub const STEADY_REASON: &str =
    "not steady walking (acceleration, deceleration or a change of pace)";

/// The reason a side's variability is withheld when too few steady strides remain.
pub const TOO_LITTLE_STEADY: &str = "too little steady walking";

/// The median of |X₁ − X₂| for two independent normal values of SD 1 (√2 · 0.6745).
const MEDIAN_MOVING_RANGE: f64 = 0.954;

/// Parameters of the steady-state rule (module docs give the sources of the defaults).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SteadyParams {
    /// Apply the rule. Default true.
    pub enabled: bool,
    /// Strides (both legs together) of the running median that gives the level. Odd, ≥ 1.
    /// Default 7.
    pub smooth_strides: usize,
    /// Range the level may span inside the window, in short-term SDs σ (median moving range /
    /// 0.954). Default 4.
    pub range_sds: f64,
    /// Smallest such range, as a share of the median stride time. Default 0.06.
    pub min_range_share: f64,
    /// Smallest share of the walk's valid strides the window must hold; a walk whose longest
    /// stretch at one pace is shorter never becomes steady. Default 0.5.
    pub min_steady_share: f64,
    /// Largest change of stride time across the window along its least-squares line, as a
    /// share of the median; a window with more never becomes steady. Default 0.05.
    pub max_trend_share: f64,
    /// Fewest steady strides of a leg for its variability (CV). Default 10.
    pub min_steady_strides: usize,
    /// Fewest valid strides per leg for the rule to exclude any: a shorter walk's median and
    /// moving range do not tell a transient from its own variation, so nothing is excluded
    /// (and with fewer than `min_steady_strides` the variability is withheld). Default 20.
    pub min_strides_to_trim: usize,
}

impl Default for SteadyParams {
    fn default() -> Self {
        SteadyParams {
            enabled: true,
            smooth_strides: 7,
            range_sds: 4.0,
            min_range_share: 0.06,
            min_steady_share: 0.5,
            max_trend_share: 0.05,
            min_steady_strides: 10,
            min_strides_to_trim: 20,
        }
    }
}

/// [`SteadyParams`] after [`SteadyParams::check`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ValidSteadyParams(pub(crate) SteadyParams);

impl SteadyParams {
    /// Validate.
    pub fn check(&self) -> Result<ValidSteadyParams> {
        if !(self.range_sds.is_finite() && self.range_sds > 0.0) {
            return Err(LdhError::param("range_sds", self.range_sds, "must be > 0"));
        }
        if !(self.min_range_share.is_finite() && (0.0..1.0).contains(&self.min_range_share)) {
            return Err(LdhError::param(
                "min_range_share",
                self.min_range_share,
                "must lie in [0, 1)",
            ));
        }
        if !(self.min_steady_share.is_finite() && (0.0..=1.0).contains(&self.min_steady_share)) {
            return Err(LdhError::param(
                "min_steady_share",
                self.min_steady_share,
                "must lie in [0, 1]",
            ));
        }
        if !(self.max_trend_share.is_finite() && self.max_trend_share > 0.0) {
            return Err(LdhError::param(
                "max_trend_share",
                self.max_trend_share,
                "must be > 0",
            ));
        }
        if self.smooth_strides == 0 || self.smooth_strides.is_multiple_of(2) {
            return Err(LdhError::param(
                "smooth_strides",
                self.smooth_strides,
                "must be odd and ≥ 1",
            ));
        }
        Ok(ValidSteadyParams(*self))
    }
}

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
    let (a, b) = longest_within(&level, range);
    let longest_share = (b + 1 - a) as f64 / n as f64;
    let trend = fitted_change(&t[a..=b]).abs();
    if longest_share < p.min_steady_share || trend > p.max_trend_share * centre {
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

/// The short-term SD of the stride time: the median absolute difference of each leg's
/// successive strides, pooled, / 0.954 (`None` without two strides of a leg).
fn moving_range_sd(t: &[f64], leg: &[usize]) -> Option<f64> {
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
fn fitted_change(t: &[f64]) -> f64 {
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
fn running_median(t: &[f64], h: usize) -> Vec<f64> {
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
fn longest_within(x: &[f64], range: f64) -> (usize, usize) {
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

/// The steady window a leg's analysis used (`recordings.csv` columns `steady_start_s`,
/// `steady_end_s`, `steady_excluded_start`, `steady_excluded_end`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SteadySpan {
    /// Heel strike that begins the walk's first steady stride, s on the walk's clock (the left
    /// recording's, the same on both legs; a leg alone: its own). NaN when no steady walking.
    pub start_s: f64,
    /// Heel strike that ends the walk's last steady stride, s on the walk's clock (NaN when no
    /// steady walking).
    pub end_s: f64,
    /// Valid strides of this leg excluded before the window (accelerating).
    pub excluded_start: usize,
    /// Valid strides of this leg excluded after the window (slowing down).
    pub excluded_end: usize,
    /// Valid strides of this leg inside the window.
    pub steady_strides: usize,
    /// Whether enough steady strides remain for the variability (`min_steady_strides`).
    pub enough: bool,
    /// The walk never becomes steady ([`WalkWindow::never_steady`]): nothing excluded, the
    /// variability withheld.
    #[serde(default)]
    pub never_steady: bool,
    /// Share of the walk's valid strides (both legs) in its longest stretch at one pace.
    #[serde(default)]
    pub longest_share: f64,
}

/// Apply the steady-state rule to one leg's strides (in time order): the walk is this leg
/// alone ([`exclude_unsteady_walk`]).
pub fn exclude_unsteady(strides: &mut [Stride], p: &ValidSteadyParams) -> Option<SteadySpan> {
    exclude_unsteady_walk(&mut [(strides, 0.0)], p)
        .pop()
        .flatten()
}

/// Apply the steady-state rule to a walk's legs, each with the offset (s) that puts its times
/// on the walk's clock: one window from all their valid strides ([`walk_window`]), and each
/// leg's valid strides outside it become invalid with [`STEADY_REASON`], so every mean and CV
/// of both legs is of the same steady walking. A walk that never becomes steady loses nothing
/// (its span says so: `never_steady`, times NaN) and the caller withholds the variability.
/// One span per leg, `None` when the rule is disabled or the leg has no stride.
///
/// Idempotent: strides an earlier call excluded (reason [`STEADY_REASON`]) are taken back
/// first, so legs re-segmented or re-checked can be given to it again.
pub fn exclude_unsteady_walk(
    legs: &mut [(&mut [Stride], f64)],
    p: &ValidSteadyParams,
) -> Vec<Option<SteadySpan>> {
    for (strides, _) in legs.iter_mut() {
        for s in strides.iter_mut() {
            if s.has(&StrideCode::NotSteady) {
                // Only valid strides are ever excluded, so without this reason it is valid again.
                s.remove(&StrideCode::NotSteady);
                s.valid = true;
            }
        }
    }
    if !p.0.enabled {
        return vec![None; legs.len()];
    }
    // (heel strike, next heel strike on the walk's clock, stride time, leg, index).
    let mut m: Vec<(f64, f64, f64, usize, usize)> = Vec::new();
    for (li, (strides, off)) in legs.iter().enumerate() {
        for (si, s) in strides.iter().enumerate() {
            if s.valid && s.stride_time_s.is_finite() && s.hs_time_s.is_finite() {
                m.push((
                    s.hs_time_s + off,
                    s.next_hs_time_s + off,
                    s.stride_time_s,
                    li,
                    si,
                ));
            }
        }
    }
    m.sort_by(|a, b| a.0.total_cmp(&b.0));
    let t: Vec<f64> = m.iter().map(|x| x.2).collect();
    let leg: Vec<usize> = m.iter().map(|x| x.3).collect();
    let w = walk_window(&t, &leg, p);
    let (start_s, end_s) = match w.range {
        Some((a, b)) => (
            m[a].0,
            m[a..=b].iter().map(|x| x.1).fold(f64::MIN, f64::max),
        ),
        None => (f64::NAN, f64::NAN),
    };
    let mut spans = Vec::with_capacity(legs.len());
    for (li, (strides, _)) in legs.iter_mut().enumerate() {
        if strides.is_empty() {
            spans.push(None);
            continue;
        }
        let (mut before, mut inside, mut after) = (0, 0, 0);
        for (k, x) in m.iter().enumerate().filter(|(_, x)| x.3 == li) {
            let Some((a, b)) = w.range else { continue };
            if k >= a && k <= b {
                inside += 1;
                continue;
            }
            if k < a {
                before += 1;
            } else {
                after += 1;
            }
            let s = &mut strides[x.4];
            s.valid = false;
            s.push(StrideFinding::new(StrideCode::NotSteady, STEADY_REASON));
        }
        spans.push(Some(SteadySpan {
            start_s,
            end_s,
            excluded_start: before,
            excluded_end: after,
            steady_strides: inside,
            enough: inside >= p.0.min_steady_strides,
            never_steady: w.never_steady,
            longest_share: w.longest_share,
        }));
    }
    spans
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p() -> ValidSteadyParams {
        SteadyParams::default().check().unwrap()
    }

    /// Deterministic stride-to-stride jitter of about `sd` (a sum of incommensurate sines).
    fn jitter(i: usize, sd: f64) -> f64 {
        let x = i as f64;
        sd * ((x * 2.3).sin() + (x * 0.77 + 1.0).sin())
    }

    /// One leg: stride time of `f(i)` plus jitter.
    fn walk(n: usize, f: impl Fn(usize) -> f64) -> Vec<f64> {
        (0..n).map(|i| f(i) + jitter(i, 0.012)).collect()
    }

    fn one_leg(t: &[f64]) -> WalkWindow {
        walk_window(t, &vec![0; t.len()], &p())
    }

    #[test]
    fn a_belt_ramp_is_excluded() {
        // 1.2 s falling to 1.0 s over the first 8 strides.
        let t = walk(60, |i| if i < 8 { 1.2 - 0.025 * i as f64 } else { 1.0 });
        let w = one_leg(&t);
        let (a, b) = w.range.unwrap();
        assert!((4..=8).contains(&a), "{w:?}");
        assert_eq!(b, 59);
    }

    #[test]
    fn a_long_start_up_is_excluded_whatever_its_length() {
        // Issue 50: 2.2 s falling to 1.1 s over the first 30 s (≈ 18 strides), then 70 strides.
        let t = walk(88, |i| {
            if i < 18 {
                2.2 - 1.1 * i as f64 / 18.0
            } else {
                1.1
            }
        });
        let (a, b) = one_leg(&t).range.unwrap();
        assert!((15..=19).contains(&a), "{a}");
        assert_eq!(b, 87);
    }

    #[test]
    fn a_steady_walk_keeps_everything() {
        let t = walk(40, |_| 1.05);
        let w = one_leg(&t);
        assert_eq!(w.range, Some((0, 39)));
        assert!(!w.never_steady);
    }

    #[test]
    fn slowing_down_at_the_end_is_excluded() {
        let mut t = walk(40, |_| 1.0);
        t.extend([1.08, 1.15, 1.25, 1.4]);
        assert_eq!(one_leg(&t).range, Some((0, 39)));
    }

    #[test]
    fn a_walker_who_speeds_up_throughout_never_becomes_steady() {
        // Issue 50: 2.0 s falling to 1.5 s over 3 minutes.
        let t = walk(100, |i| 2.0 - 0.5 * i as f64 / 99.0);
        let w = one_leg(&t);
        assert!(w.never_steady && w.range.is_none(), "{w:?}");
        assert!(w.longest_share < 0.5);
        // And one who slows down throughout.
        let t = walk(100, |i| 1.0 + 0.3 * i as f64 / 99.0);
        assert!(one_leg(&t).never_steady);
    }

    #[test]
    fn a_change_of_pace_keeps_the_longer_stretch() {
        // 60 strides at 0.88 s, then 30 at 0.98 s.
        let mut t = walk(60, |_| 0.88);
        t.extend(walk(30, |_| 0.98));
        let (a, b) = one_leg(&t).range.unwrap();
        assert!(a <= 1 && (58..=62).contains(&b), "{a} {b}");
    }

    #[test]
    fn both_legs_give_one_window() {
        // Two legs interleaved in time: the left's strides begin the ramp, the right's end it.
        let left = walk(40, |i| if i < 6 { 1.3 - 0.05 * i as f64 } else { 1.0 });
        let right = walk(40, |i| if i < 6 { 1.275 - 0.05 * i as f64 } else { 1.0 });
        let (mut t, mut leg) = (Vec::new(), Vec::new());
        for i in 0..40 {
            t.extend([left[i], right[i]]);
            leg.extend([0, 1]);
        }
        let (a, b) = walk_window(&t, &leg, &p()).range.unwrap();
        assert!((8..=14).contains(&a), "{a}");
        assert_eq!(b, 79);
    }

    #[test]
    fn a_short_walk_is_not_trimmed() {
        let mut t = vec![1.35, 1.36, 1.34];
        t.extend([1.25, 1.24, 1.23, 1.28]);
        assert_eq!(one_leg(&t).range, Some((0, 6)));
        assert_eq!(one_leg(&[]).range, None);
    }

    #[test]
    fn the_longest_run_within_a_range() {
        let x = [5.0, 1.0, 1.2, 0.9, 1.1, 3.0, 1.0];
        assert_eq!(longest_within(&x, 0.3), (1, 4));
        assert_eq!(longest_within(&x, 10.0), (0, 6));
        assert_eq!(longest_within(&[2.0], 0.0), (0, 0));
        assert_eq!(
            running_median(&[1.0, 9.0, 2.0, 3.0], 1),
            vec![5.0, 2.0, 3.0, 2.5]
        );
        // Each leg's successive strides: |1 − 1.1|, |1.1 − 1.0| and |2 − 2.2|.
        let s = moving_range_sd(&[1.0, 2.0, 1.1, 2.2, 1.0], &[0, 1, 0, 1, 0]).unwrap();
        assert!((s - 0.1 / MEDIAN_MOVING_RANGE).abs() < 1e-12, "{s}");
    }

    #[test]
    fn disabled_rule_keeps_everything_and_bad_params_fail() {
        let t = walk(30, |i| 1.0 + 0.02 * i as f64);
        let q = SteadyParams {
            enabled: false,
            ..Default::default()
        }
        .check()
        .unwrap();
        assert_eq!(walk_window(&t, &[0; 30], &q).range, Some((0, 29)));
        let bad = |q: SteadyParams| q.check().is_err();
        let d = SteadyParams::default();
        assert!(bad(SteadyParams {
            range_sds: 0.0,
            ..d
        }));
        assert!(bad(SteadyParams {
            min_range_share: 1.0,
            ..d
        }));
        assert!(bad(SteadyParams {
            min_steady_share: 1.5,
            ..d
        }));
        assert!(bad(SteadyParams {
            smooth_strides: 4,
            ..d
        }));
        assert!(bad(SteadyParams {
            smooth_strides: 0,
            ..d
        }));
        assert!(bad(SteadyParams {
            max_trend_share: 0.0,
            ..d
        }));
        assert!((fitted_change(&[1.0, 1.1, 1.2, 1.3]) - 0.3).abs() < 1e-12);
    }
}
