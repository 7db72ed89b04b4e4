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
//! 5. At each end of the walk, the transient there (a belt's start-up, gait initiation, a
//!    slowing down) may go on inside the band (a 30 s ramp keeps its last 10 s there), the run
//!    may stop short of it by chance (a walk's level brushes the band's edge: issue 50's L02
//!    ended its run at 63 s of a walk that slowed down from 76 s) or go on through it (a
//!    transient of a few strides is half hidden by the running median at an end). So the
//!    transient is measured from the walk's end itself, at both ends alike, over the strides
//!    up to the run's middle, by a segmented regression (Muggeo 2003, Stat Med
//!    22:3055–3071): a ramp that meets a constant level (`level + β·(c − i)` over its first `c`
//!    strides) or a step to it, of longer or shorter strides, fitted by least squares for every
//!    `c`. A model counts when its excursion at the end lies beyond the band of step 4 (the
//!    walk's own variation stays inside; for a transient shorter than the running median,
//!    beyond the band's half-width around the level, ±2 σ) and it reduces the squared error by
//!    more than `2 ln n` σ² (Schwarz 1978, Ann Stat 6:461–464, for its two parameters); the
//!    window begins (ends) after the `c` strides of the one that reduces it more. Its
//!    direction is the data's, not the level's just outside the run: TRIPOD's PWS run ended
//!    its run at a dip of shorter strides 20 s before the belt slowed to a stop, and only
//!    shorter strides were looked for there until 2026-12-02.
//! 6. A walk whose longest such run, or whose window, holds fewer than `min_steady_share`
//!    (half) of its valid strides has no steady pace: it speeds up or slows down throughout, or changes its pace
//!    more than once. So has a walk whose window still holds a trend: the least-squares line
//!    of stride time across it changes by more than `max_trend_share` (8 %) of the median
//!    (≈ 7 standard errors of that change on a 110-stride walk with a CV of 3.4 %, room for
//!    the slow wander of a variable walker; an 8 % trend over a whole walk is caught by the
//!    half-of-the-walk rule first), or by more than `max_continued_trend_share` (6 %, the
//!    band's floor: a steady walk's wander) when its line goes on the way the strides cut
//!    before or after it lie (`window::continues_a_cut`: the rest of a change throughout
//!    the walk whose first or last part the segmented fit took for a transient, since a trend
//!    has no break and where the fit cuts it is chance; issue 50's family B walker slowing by
//!    25 % kept 40 strides drifting 7.7 % after a 28-stride cut). Either drift must also
//!    exceed `trend_ses` (3) standard errors of the line's change for the short-term σ (the
//!    least-squares slope's, σ / √Sxx; Draper & Smith, *Applied Regression Analysis*, 3rd ed.
//!    1998, ch. 1), so a short window of a variable walker is not a trend by noise alone.
//!    Nothing is excluded, its means are of the whole walk, and
//!    its variability is withheld (`never_steady`) rather than reported as the trend's.
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
//!   what it leaves out at either end, only the half-of-the-walk rule of step 6.
//!
//! When the two legs are not one walk (their recordings do not overlap, or the pair's checks
//! doubt it), each leg gets its own window by the same rule.

use serde::{Deserialize, Serialize};

use super::{Stride, StrideCode, StrideFinding};
use crate::error::{LdhError, Result};

mod window;
pub use window::{walk_window, WalkWindow};

/// The reason given on a stride outside the steady window.
pub const STEADY_REASON: &str =
    "not steady walking (acceleration, deceleration or a change of pace)";

/// The reason a side's variability is withheld when too few steady strides remain.
pub const TOO_LITTLE_STEADY: &str = "too little steady walking";

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
    /// share of the median; a window with more (and more than `trend_ses` standard errors of
    /// it) never becomes steady. Default 0.08.
    pub max_trend_share: f64,
    /// The same for a window whose line goes on the way the strides cut before or after it
    /// lie (the rest of a change throughout the walk, not a level after a transient): the
    /// most a steady walk's slow wander moves it. Default 0.06 (as `min_range_share`).
    pub max_continued_trend_share: f64,
    /// How many standard errors of that change (from the short-term SD σ and the window's
    /// length) a change beyond `max_trend_share` must also exceed to count as a trend. ≥ 0.
    /// Default 3.
    pub trend_ses: f64,
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
            max_trend_share: 0.08,
            max_continued_trend_share: 0.06,
            trend_ses: 3.0,
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
        if !(self.max_continued_trend_share.is_finite() && self.max_continued_trend_share > 0.0) {
            return Err(LdhError::param(
                "max_continued_trend_share",
                self.max_continued_trend_share,
                "must be > 0",
            ));
        }
        if !(self.trend_ses.is_finite() && self.trend_ses >= 0.0) {
            return Err(LdhError::param("trend_ses", self.trend_ses, "must be ≥ 0"));
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
mod tests;
