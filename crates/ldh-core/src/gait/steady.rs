//! Steady-state walking: the window of a walk left after the acceleration and deceleration
//! strides at its start and end (treadmill belt start-up, gait initiation and termination).
//!
//! The rule is run-based and not fitted to any data: the walk's robust centre is the median
//! stride time of the valid strides, its robust spread 1.4826 × MAD (the normal-consistent
//! scale). A stride is *in band* when its time lies within `band_mads` robust SDs of the
//! median, never narrower than `min_band_share` of the median. Steady walking starts at the
//! first run of `run_strides` consecutive in-band valid strides (searched from the start) and
//! ends at the last such run (searched from the end); the strides before and after are
//! excluded with the reason [`STEADY_REASON`], as turn strides are excluded with theirs.
//!
//! Thresholds, from the literature rather than from the tests:
//! - `band_mads` 3: three SDs of the walk's own stride-to-stride variation, so a patient's larger
//!   variability widens the band instead of being cut (Hausdorff 2005, J NeuroEng Rehabil
//!   2:19: healthy stride-time CV ≈ 1–3 %, higher in neurological gait).
//! - `min_band_share` 0.05: ≈ 2.5 × a healthy adult's stride-time CV of ≈ 2 % (Hausdorff 2005),
//!   so a very regular walk does not make every ordinary stride look transient.
//! - `run_strides` 3: steady walking speed is reached within the first 2–3 strides of gait
//!   initiation in adults (Lindemann et al. 2008, Gait Posture 27:91–96, who report a few
//!   metres more in frail elderly people); three consecutive steady strides confirm it.
//! - `min_steady_strides` 10: fewer steady strides leave the CV too uncertain (its relative
//!   standard error ≈ 1/√(2n) is > 20 % below 10 strides; Hausdorff 2005 asks for many strides),
//!   so the variability is withheld with [`TOO_LITTLE_STEADY`] rather than guessed.
//! - `max_transient_strides` 12: a transient is short (gait initiation 2–3 strides, Lindemann
//!   2008; a treadmill belt's start-up ≈ 8 strides on the real trials of issue 36, steady after
//!   ≈ 15 s). A longer out-of-band stretch at an end is a change of walking speed (HuGaDB's
//!   walks "at various speeds": 08_02 walks its last 20 strides at 0.95 s against 0.88 s) and
//!   is kept as the walk's own, as speed changes inside a walk are.
//! - `min_strides_to_trim` 20 (2 × `min_steady_strides`): on a shorter walk the median and MAD
//!   of a handful of strides cannot tell a transient from the walk's own variation (the 25 s
//!   demo walks, 7 valid strides a leg, lost their first bout as "speeding up" when a slower
//!   pace before the turn fell outside the band), so nothing is trimmed there; the first and
//!   last stride of every bout are still dropped (`StrideParams::drop_bout_edges`).

use serde::{Deserialize, Serialize};

use super::{Stride, StrideCode, StrideFinding};
use crate::error::{LdhError, Result};
use crate::stats::{median, EvenMedian};

/// The reason given on a stride outside the steady window.
pub const STEADY_REASON: &str = "not steady walking (acceleration or deceleration)";

/// The reason a side's variability is withheld when too few steady strides remain.
pub const TOO_LITTLE_STEADY: &str = "too little steady walking";

/// Parameters of the steady-state rule (module docs give the sources of the defaults).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SteadyParams {
    /// Apply the rule. Default true.
    pub enabled: bool,
    /// Band half-width in robust SDs (1.4826 × MAD) of stride time. Default 3.
    pub band_mads: f64,
    /// Smallest band half-width as a share of the median stride time. Default 0.05.
    pub min_band_share: f64,
    /// Consecutive in-band strides that start (and, from the end, close) steady walking.
    /// Default 3.
    pub run_strides: usize,
    /// Fewest steady strides for the side's variability (CV). Default 10.
    pub min_steady_strides: usize,
    /// Most valid strides excluded at one end: a longer out-of-band stretch there is a change
    /// of walking speed, not a transient, and is kept. Default 12.
    pub max_transient_strides: usize,
    /// Fewest valid strides for the rule to exclude any: a shorter walk's median and MAD do
    /// not tell a transient from its own variation, so nothing is excluded (its first and last
    /// stride of each bout are dropped as always, and with fewer than `min_steady_strides`
    /// the variability is withheld). Default 20.
    pub min_strides_to_trim: usize,
}

impl Default for SteadyParams {
    fn default() -> Self {
        SteadyParams {
            enabled: true,
            band_mads: 3.0,
            min_band_share: 0.05,
            run_strides: 3,
            min_steady_strides: 10,
            max_transient_strides: 12,
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
        if !(self.band_mads.is_finite() && self.band_mads > 0.0) {
            return Err(LdhError::param("band_mads", self.band_mads, "must be > 0"));
        }
        if !(self.min_band_share.is_finite() && (0.0..1.0).contains(&self.min_band_share)) {
            return Err(LdhError::param(
                "min_band_share",
                self.min_band_share,
                "must lie in [0, 1)",
            ));
        }
        if self.run_strides == 0 {
            return Err(LdhError::param(
                "run_strides",
                self.run_strides,
                "must be ≥ 1",
            ));
        }
        Ok(ValidSteadyParams(*self))
    }
}

/// The steady window of one leg's strides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyWindow {
    /// Index of the first steady stride.
    pub first: usize,
    /// Index one past the last steady stride (`first == end`: no steady walking).
    pub end: usize,
    /// Valid strides excluded before the window.
    pub excluded_start: usize,
    /// Valid strides excluded after the window.
    pub excluded_end: usize,
    /// Valid strides inside the window.
    pub steady: usize,
    /// Whether enough steady strides remain (`steady ≥ min_steady_strides`).
    pub enough: bool,
}

/// The steady window of `stride_time_s` (one leg, in time order), counting only strides whose
/// `valid` is true (invalid ones neither start nor break a run). With the rule disabled or
/// fewer than 3 valid strides, the window is everything.
pub fn steady_window(stride_time_s: &[f64], valid: &[bool], p: &ValidSteadyParams) -> SteadyWindow {
    let p = p.0;
    let n = stride_time_s.len().min(valid.len());
    let ok: Vec<usize> = (0..n)
        .filter(|&i| valid[i] && stride_time_s[i].is_finite())
        .collect();
    let whole = |steady: usize| SteadyWindow {
        first: 0,
        end: n,
        excluded_start: 0,
        excluded_end: 0,
        steady,
        enough: steady >= p.min_steady_strides,
    };
    let Some((centre, half)) = band(
        &ok.iter().map(|&i| stride_time_s[i]).collect::<Vec<_>>(),
        &p,
    ) else {
        return whole(ok.len());
    };
    if !p.enabled || ok.len() < p.min_strides_to_trim {
        return whole(ok.len());
    }
    let inb = |i: usize| (stride_time_s[i] - centre).abs() <= half;
    let start = first_run(ok.iter().copied(), &inb, p.run_strides);
    let last = first_run(ok.iter().rev().copied(), &inb, p.run_strides);
    match (start, last) {
        (Some(a), Some(b)) if a <= b => {
            // A longer out-of-band stretch at an end is a change of speed, kept (module docs).
            let before = ok.iter().filter(|&&i| i < a).count();
            let after = ok.iter().filter(|&&i| i > b).count();
            let a = if before > p.max_transient_strides {
                0
            } else {
                a
            };
            let b = if after > p.max_transient_strides {
                n - 1
            } else {
                b
            };
            let steady = ok.iter().filter(|&&i| i >= a && i <= b).count();
            SteadyWindow {
                first: a,
                end: b + 1,
                excluded_start: ok.iter().filter(|&&i| i < a).count(),
                excluded_end: ok.iter().filter(|&&i| i > b).count(),
                steady,
                enough: steady >= p.min_steady_strides,
            }
        }
        _ => SteadyWindow {
            first: 0,
            end: 0,
            excluded_start: ok.len(),
            excluded_end: 0,
            steady: 0,
            enough: false,
        },
    }
}

/// The steady window a leg's analysis used, in its recording's time (`recordings.csv` columns
/// `steady_start_s`, `steady_end_s`, `steady_excluded_start`, `steady_excluded_end`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SteadySpan {
    /// Heel strike that begins the first steady stride, s (NaN when no steady walking was found).
    pub start_s: f64,
    /// Heel strike that ends the last steady stride, s (NaN when no steady walking was found).
    pub end_s: f64,
    /// Valid strides excluded before the window (accelerating).
    pub excluded_start: usize,
    /// Valid strides excluded after the window (slowing down).
    pub excluded_end: usize,
    /// Valid strides inside the window.
    pub steady_strides: usize,
    /// Whether enough steady strides remain for the variability (`min_steady_strides`).
    pub enough: bool,
}

/// Apply the steady-state rule to one leg's strides (in time order): the valid strides before
/// and after the window become invalid with [`STEADY_REASON`], so every mean and CV is of
/// steady walking. When no run of in-band strides exists at all (an irregular walk with no
/// steady part), nothing is excluded and the span says so (`steady_strides` 0, times NaN): the
/// means are then of the whole walk and the caller withholds the variability. `None` when the
/// rule is disabled or the leg has no stride.
///
/// Idempotent: strides an earlier call excluded (reason [`STEADY_REASON`]) are taken back
/// first, so a leg re-segmented or re-checked can be given to it again.
pub fn exclude_unsteady(strides: &mut [Stride], p: &ValidSteadyParams) -> Option<SteadySpan> {
    for s in strides.iter_mut() {
        if s.has(&StrideCode::NotSteady) {
            // Only valid strides are ever excluded, so without this reason it is valid again.
            s.remove(&StrideCode::NotSteady);
            s.valid = true;
        }
    }
    if !p.0.enabled || strides.is_empty() {
        return None;
    }
    let t: Vec<f64> = strides.iter().map(|s| s.stride_time_s).collect();
    let valid: Vec<bool> = strides.iter().map(|s| s.valid).collect();
    let w = steady_window(&t, &valid, p);
    if w.first == w.end {
        return Some(SteadySpan {
            start_s: f64::NAN,
            end_s: f64::NAN,
            excluded_start: 0,
            excluded_end: 0,
            steady_strides: 0,
            enough: false,
        });
    }
    for (i, s) in strides.iter_mut().enumerate() {
        if s.valid && (i < w.first || i >= w.end) {
            s.valid = false;
            s.push(StrideFinding::new(StrideCode::NotSteady, STEADY_REASON));
        }
    }
    Some(SteadySpan {
        start_s: strides[w.first].hs_time_s,
        end_s: strides[w.end - 1].next_hs_time_s,
        excluded_start: w.excluded_start,
        excluded_end: w.excluded_end,
        steady_strides: w.steady,
        enough: w.enough,
    })
}

/// Median and band half-width of the stride times (`None` for fewer than 3).
fn band(t: &[f64], p: &SteadyParams) -> Option<(f64, f64)> {
    if t.len() < 3 {
        return None;
    }
    let med = median(&mut t.to_vec(), EvenMedian::Mean)?;
    let mut deviations: Vec<f64> = t.iter().map(|x| (x - med).abs()).collect();
    let mad = median(&mut deviations, EvenMedian::Mean)?;
    Some((
        med,
        (p.band_mads * 1.4826 * mad).max(p.min_band_share * med),
    ))
}

/// The first index of `order` that begins `run` consecutive in-band entries.
fn first_run(
    order: impl Iterator<Item = usize>,
    inb: &dyn Fn(usize) -> bool,
    run: usize,
) -> Option<usize> {
    let mut count = 0;
    let mut begin = 0;
    for i in order {
        if inb(i) {
            if count == 0 {
                begin = i;
            }
            count += 1;
            if count == run {
                return Some(begin);
            }
        } else {
            count = 0;
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p() -> ValidSteadyParams {
        SteadyParams::default().check().unwrap()
    }

    /// A belt ramp: stride time falls from 1.2 s to 1.0 s over the first 8 strides.
    fn ramp_walk(n: usize) -> Vec<f64> {
        (0..n)
            .map(|i| {
                let jitter = 0.015 * ((i as f64) * 2.3).sin();
                if i < 8 {
                    1.2 - 0.2 * (i as f64) / 8.0 + jitter
                } else {
                    1.0 + jitter
                }
            })
            .collect()
    }

    #[test]
    fn ramp_strides_are_excluded() {
        let t = ramp_walk(60);
        let w = steady_window(&t, &[true; 60], &p());
        assert!(w.excluded_start >= 5 && w.excluded_start <= 8, "{w:?}");
        assert_eq!(w.excluded_end, 0);
        assert!(w.enough);
        assert_eq!(w.end, 60);
    }

    #[test]
    fn steady_walk_keeps_everything() {
        let t: Vec<f64> = (0..40)
            .map(|i| 1.05 + 0.02 * ((i as f64) * 1.7).sin())
            .collect();
        let w = steady_window(&t, &[true; 40], &p());
        assert_eq!(
            (w.first, w.end, w.excluded_start, w.excluded_end),
            (0, 40, 0, 0)
        );
    }

    #[test]
    fn termination_is_excluded_from_the_end() {
        let mut t: Vec<f64> = (0..30)
            .map(|i| 1.0 + 0.01 * ((i as f64) * 1.3).sin())
            .collect();
        t.extend([1.15, 1.25, 1.4]);
        let w = steady_window(&t, &[true; 33], &p());
        assert_eq!(w.excluded_end, 3);
        assert_eq!(w.end, 30);
    }

    #[test]
    fn invalid_strides_neither_start_nor_break_a_run() {
        let mut t = vec![1.3, 1.0, 1.0, 9.0, 1.0];
        t.extend(vec![1.0; 20]);
        let mut valid = vec![true; t.len()];
        valid[3] = false;
        let w = steady_window(&t, &valid, &p());
        assert_eq!(w.first, 1);
        assert_eq!(w.excluded_start, 1);
    }

    #[test]
    fn a_long_change_of_speed_at_an_end_is_kept() {
        let mut t: Vec<f64> = (0..60)
            .map(|i| 0.88 + 0.01 * ((i as f64) * 1.3).sin())
            .collect();
        t.extend((0..20).map(|i| 0.96 + 0.01 * ((i as f64) * 0.7).sin()));
        let w = steady_window(&t, &[true; 80], &p());
        assert_eq!((w.first, w.end, w.excluded_end), (0, 80, 0), "{w:?}");
        // Twelve such strides are still a transient.
        let w = steady_window(&t[..72], &[true; 72], &p());
        assert_eq!((w.end, w.excluded_end), (60, 12), "{w:?}");
    }

    #[test]
    fn a_short_walk_is_not_trimmed() {
        let mut t = vec![1.35, 1.36, 1.34];
        t.extend([1.25, 1.24, 1.23, 1.28]);
        let w = steady_window(&t, &[true; 7], &p());
        assert_eq!((w.first, w.end, w.excluded_start, w.steady), (0, 7, 0, 7));
        assert!(!w.enough);
    }

    #[test]
    fn too_little_steady_walking_is_said() {
        let t = vec![1.0; 6];
        let w = steady_window(&t, &[true; 6], &p());
        assert!(!w.enough);
        assert_eq!(w.steady, 6);
    }

    #[test]
    fn disabled_rule_keeps_everything_and_bad_params_fail() {
        let t = ramp_walk(30);
        let q = SteadyParams {
            enabled: false,
            ..Default::default()
        }
        .check()
        .unwrap();
        let w = steady_window(&t, &[true; 30], &q);
        assert_eq!((w.first, w.end, w.excluded_start), (0, 30, 0));
        assert!(SteadyParams {
            band_mads: 0.0,
            ..Default::default()
        }
        .check()
        .is_err());
        assert!(SteadyParams {
            min_band_share: 1.0,
            ..Default::default()
        }
        .check()
        .is_err());
        assert!(SteadyParams {
            run_strides: 0,
            ..Default::default()
        }
        .check()
        .is_err());
    }
}
