//! Two sensors that are not on one clock (issue 49/50, TRIPOD): every left–right timing — step
//! time and its asymmetry, step frequency, double support — compares one leg's events with the
//! other's, so a clock offset between the two files moves it while each leg's own stride time,
//! stance, swing and stride length stay right. TRIPOD's Physilog units are offset by 55–184 ms
//! (its PROVENANCE.md; measured against OptoGait), and the report stated "the right step takes
//! 82 % longer" of a healthy adult.
//!
//! **The observable.** Each leg's stance holds the other leg's whole swing between two double
//! supports (Perry & Burnfield 2010, *Gait Analysis*, 2nd ed., ch. 2): `A`, from the left heel
//! strike to the right toe off, and `B`, from the right heel strike to the left toe off (the
//! left leg's initial and terminal double support; the right leg's terminal and initial).
//! Their sum is stance + stance − stride of the two legs and does not depend on the clocks; a
//! right clock late by `d` moves `A` to `A + d` and `B` to `B − d`. On one clock both are
//! positive in walking (a non-positive one is a moment with neither foot on the ground, or
//! both legs' heels landing before either leaves: a flight phase or a leg that lifts after
//! the other lands twice), and in a healthy walker equal (≈ 0.10 of the stride each). A
//! genuinely asymmetric walker moves them apart too (the double support before the paretic
//! leg's swing is longer after stroke: Olney & Richards 1996, Gait Posture 4:136–148), so the
//! rule asks for more than any walker does: the smaller one at most [`MIN_DS_SHARE`] of their
//! sum (a ratio of 1 : 4 or beyond; the walk's medians, [`balance`]).
//!
//! **Two files, a smaller offset** (TRIPOD at 3.0 km/h: 55 ms). With stride `T`, the right
//! step (left heel strike → right heel strike) is `A + swing_R` and the left `B + swing_L`, so
//! the step-time difference is `(A − B) + (swing_R − swing_L)`: an offset makes the first part
//! and leaves the second (each leg's own swing) alone. Walkers on one clock split `A` and `B`
//! without a matching swing asymmetry too (the simulators' slow LDH walkers: `(A − B)·T` of
//! 113 ms against 24 ms of swing), so no rule on one walk tells a 55 ms offset from them
//! (docs/accuracy.md "Two clocks a little apart"). What is known instead is whether the legs
//! came from one file ([`Clocks`]): when they came from two and the step-time difference is
//! more than [`MAX_UNBACKED_STEP_SHARE`] of the stride beyond what the swing difference backs
//! ([`DsBalance::unbacked_step_share`]), the timings between the legs cannot be vouched for and
//! are withheld ([`two_clocks_warning`], `two_clocks`). One file never is.
//!
//! **Alternatives measured** (docs/accuracy.md "Two sensors without one clock"): the phase of
//! one leg's heel strike in the other's stride drifting over the walk (a clock *rate*; TRIPOD's
//! offsets are constant, within 1.7 ms of scatter), and the impact of each heel strike felt in
//! the other shank (an event-triggered average on TRIPOD shows the other leg's own push-off at
//! the same lags, so no offset could be read from it): neither is used.

use super::warning::{codes, Severity, Warning};
use crate::domain::Parameter;
use crate::gait::Stride;
use crate::pipeline::Clocks;

/// Largest share of the sum of the two double supports the smaller one may have before the
/// two legs are taken for two clocks (0.2: a ratio of 1 : 4). Set on the simulators (both
/// families, every condition) and HuGaDB's first half of files; reported on the rest and on
/// TRIPOD (docs/quality.md, docs/accuracy.md "Two sensors without one clock").
pub const MIN_DS_SHARE: f64 = 0.2;

/// Largest part of the step-time difference between the legs, as a share of the stride, that
/// the legs' own swing times need not back when the two legs come from two files (0.05: a
/// step-time symmetry index of 10 %, the asymmetry gait reports name). Beyond it the
/// difference could be a clock offset of (share × stride / 2) or more, which two files do not
/// rule out. Set on the simulators (seeds 4949 and 100, both families, every condition) and
/// HuGaDB's first nine files, each read as if from two files: the healthy walkers' largest
/// 0.024; reported on seed 2026 (0.032), the other nine files (0.022) and TRIPOD at 3.0 km/h
/// (0.074; docs/accuracy.md "Two clocks a little apart").
pub const MAX_UNBACKED_STEP_SHARE: f64 = 0.05;

/// Fewest strides with both double supports for the check (10).
pub const MIN_BALANCE_STRIDES: usize = 10;

/// Largest distance of the other leg's event from where it is looked for, as a share of the
/// stride (0.5: the nearest one, however far an offset has moved it).
const SEARCH_STRIDE: f64 = 0.5;

/// The walk's two double supports, the medians over the valid strides of both legs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DsBalance {
    /// `A`: left heel strike to right toe off, fraction of the stride.
    pub after_left_hs: f64,
    /// `B`: right heel strike to left toe off, fraction of the stride.
    pub after_right_hs: f64,
    /// Strides that gave both.
    pub strides: usize,
    /// The median stride time, s.
    pub stride_s: f64,
    /// The left leg's median swing, fraction of its stride (no clock enters it).
    pub swing_left: f64,
    /// The right leg's median swing, fraction of its stride.
    pub swing_right: f64,
}

impl DsBalance {
    /// The smaller double support's share of their sum (0.5 when equal; ≤ 0 when one is not
    /// positive); NaN when the sum is not positive.
    pub fn min_share(&self) -> f64 {
        let (a, b) = (self.after_left_hs, self.after_right_hs);
        if a + b > 0.0 {
            a.min(b) / (a + b)
        } else {
            f64::NAN
        }
    }
    /// The clock offset that would make the two equal, s: how late the right sensor's events
    /// lie against the left's (negative: early), if the walk is symmetric.
    pub fn apparent_offset_s(&self) -> f64 {
        0.5 * (self.after_left_hs - self.after_right_hs) * self.stride_s
    }
    /// The right leg's swing minus the left's, fraction of the stride (0 when either is
    /// unknown: an unknown swing backs nothing).
    pub fn swing_difference(&self) -> f64 {
        let d = self.swing_right - self.swing_left;
        if d.is_finite() {
            d
        } else {
            0.0
        }
    }
    /// The right step minus the left, fraction of the stride: `(A − B) + (swing_R − swing_L)`.
    pub fn step_difference(&self) -> f64 {
        self.after_left_hs - self.after_right_hs + self.swing_difference()
    }
    /// The part of [`Self::step_difference`] that the swing difference does not back (same
    /// sign, up to its size), fraction of the stride: what a clock offset alone could have
    /// made. 0 when the swing difference accounts for all of it.
    pub fn unbacked_step_share(&self) -> f64 {
        let (step, swing) = (self.step_difference(), self.swing_difference());
        let backed = if step * swing > 0.0 {
            swing.abs().min(step.abs())
        } else {
            0.0
        };
        step.abs() - backed
    }
}

fn sorted(v: &[f64]) -> Vec<f64> {
    let mut v: Vec<f64> = v.iter().copied().filter(|t| t.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    v
}

/// The event of sorted `v` nearest to `t`, within `w`.
fn nearest(v: &[f64], t: f64, w: f64) -> Option<f64> {
    let i = v.partition_point(|&x| x < t);
    [i.checked_sub(1), Some(i)]
        .into_iter()
        .flatten()
        .filter_map(|k| v.get(k).copied())
        .filter(|x| (x - t).abs() <= w)
        .min_by(|a, b| (a - t).abs().total_cmp(&(b - t).abs()))
}

/// Per valid stride of one leg: (initial, terminal) double support, fractions of the stride —
/// the other leg's toe off nearest to the heel strike, and its heel strike nearest to the toe
/// off (s, on this leg's clock), within [`SEARCH_STRIDE`] of the stride. Unlike
/// `gait::double_support` it keeps a double support that an offset has made negative.
fn per_stride(strides: &[Stride], other_hs: &[f64], other_to: &[f64]) -> Vec<(f64, f64)> {
    let (o_hs, o_to) = (sorted(other_hs), sorted(other_to));
    strides
        .iter()
        .filter(|s| s.valid && s.stride_time_s > 0.0 && s.to_time_s > s.hs_time_s)
        .filter_map(|s| {
            let (t, w) = (s.stride_time_s, SEARCH_STRIDE * s.stride_time_s);
            let to = nearest(&o_to, s.hs_time_s, w)?;
            let hs = nearest(&o_hs, s.to_time_s, w)?;
            Some(((to - s.hs_time_s) / t, (s.to_time_s - hs) / t))
        })
        .collect()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.retain(|x| x.is_finite());
    crate::stats::median(&mut v, crate::stats::EvenMedian::Mean).unwrap_or(f64::NAN)
}

/// The walk's two double supports ([`DsBalance`]) from both legs' valid strides and the other
/// leg's events on each leg's clock (`right_on_left`: the right leg's heel strikes and toe offs
/// shifted onto the left recording's clock; `left_on_right` the reverse); `None` with fewer
/// than [`MIN_BALANCE_STRIDES`].
pub fn balance(
    left: &[Stride],
    right: &[Stride],
    right_on_left: (&[f64], &[f64]),
    left_on_right: (&[f64], &[f64]),
) -> Option<DsBalance> {
    let l = per_stride(left, right_on_left.0, right_on_left.1);
    let r = per_stride(right, left_on_right.0, left_on_right.1);
    if l.len() + r.len() < MIN_BALANCE_STRIDES {
        return None;
    }
    // Left initial = A = right terminal; left terminal = B = right initial.
    let a: Vec<f64> = l.iter().map(|x| x.0).chain(r.iter().map(|x| x.1)).collect();
    let b: Vec<f64> = l.iter().map(|x| x.1).chain(r.iter().map(|x| x.0)).collect();
    let times = left
        .iter()
        .chain(right)
        .filter(|s| s.valid)
        .map(|s| s.stride_time_s)
        .collect();
    let swing = |v: &[Stride]| {
        median(
            v.iter()
                .filter(|s| s.valid)
                .map(|s| 1.0 - s.stance_ratio)
                .collect(),
        )
    };
    Some(DsBalance {
        after_left_hs: median(a),
        after_right_hs: median(b),
        strides: l.len() + r.len(),
        stride_s: median(times),
        swing_left: swing(left),
        swing_right: swing(right),
    })
}

/// The parameters that compare one leg's events with the other's.
pub const BETWEEN_LEGS: [Parameter; 3] = [
    Parameter::StepTime,
    Parameter::StepFrequency,
    Parameter::DoubleSupport,
];

/// The `clock_offset` finding when the walk's double supports say the two sensors are not on
/// one clock ([`MIN_DS_SHARE`]): it withholds [`BETWEEN_LEGS`] on both legs.
pub fn clock_warning(b: &DsBalance) -> Option<Warning> {
    let share = b.min_share();
    if share.is_finite() && share > MIN_DS_SHARE {
        return None;
    }
    let off_ms = 1e3 * b.apparent_offset_s();
    let (late, by) = if off_ms >= 0.0 {
        ("late", off_ms)
    } else {
        ("early", -off_ms)
    };
    Some(
        Warning::new(codes::CLOCK_OFFSET, Severity::Warning, format!(
            "the two sensors' clocks do not agree: the double support after the left heel strike is {:.1} % of the stride and after the right one {:.1} % (median of {} strides), a split no walker on one clock shows (each should be positive, and within 1 : 4 of the other); the right sensor's events lie about {by:.0} ms {late} against the left's if the walk is symmetric. Step time, its asymmetry, step frequency and double support, which compare one leg's events with the other's, are not measured; each leg's stride time, stance, swing and stride length are. Synchronise the two sensors before recording",
            100.0 * b.after_left_hs,
            100.0 * b.after_right_hs,
            b.strides
        ))
        .withholding(&BETWEEN_LEGS),
    )
}

/// The `two_clocks` finding (withholds [`BETWEEN_LEGS`] on both legs) for a walk whose legs
/// come from two files, or two arrays not said to share a clock ([`Clocks::Two`]), and whose
/// step-time difference is more than [`MAX_UNBACKED_STEP_SHARE`] of the stride beyond what the
/// swing difference backs; never for one clock, nor when the swing is unknown.
pub fn two_clocks_warning(b: &DsBalance, clocks: Option<Clocks>) -> Option<Warning> {
    let unbacked = b.unbacked_step_share();
    if clocks != Some(Clocks::Two) || !(unbacked > MAX_UNBACKED_STEP_SHARE) {
        return None;
    }
    let step = b.step_difference();
    let (longer, shorter) = if step >= 0.0 {
        ("right", "left")
    } else {
        ("left", "right")
    };
    Some(
        Warning::new(codes::TWO_CLOCKS, Severity::Warning, format!(
            "the two sensors are not known to share a clock: the legs come from two separate recordings, and the {longer} step is {:.0} ms longer than the {shorter} while the legs' own swing times differ by {:.0} ms (medians of {} strides); a clock offset of {:.0} ms between the sensors would make that difference alone. Step time, its asymmetry, step frequency and double support, which compare one leg's events with the other's, are not measured; each leg's stride time, stance, swing and stride length are. Synchronise the two sensors before recording",
            1e3 * step.abs() * b.stride_s,
            1e3 * b.swing_difference().abs() * b.stride_s,
            b.strides,
            1e3 * 0.5 * unbacked * b.stride_s,
        ))
        .withholding(&BETWEEN_LEGS),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Symmetric strides of 1 s, stance 0.6, the right leg half a stride later and shifted by
    /// `d_s` on its clock.
    fn walk(d_s: f64, right_stance: f64) -> (Vec<Stride>, Vec<Stride>, [Vec<f64>; 4]) {
        let mk = |t0: f64, stance: f64| -> Vec<Stride> {
            (0..20)
                .map(|k| {
                    let mut s = crate::pipeline::quality::tests::stride(k, 1.0, stance);
                    s.hs_time_s += t0;
                    s.to_time_s += t0;
                    s
                })
                .collect()
        };
        let (l, r) = (mk(0.0, 0.6), mk(0.5 + d_s, right_stance));
        let hs = |v: &[Stride], d: f64| v.iter().map(|s| s.hs_time_s + d).collect::<Vec<_>>();
        let to = |v: &[Stride], d: f64| v.iter().map(|s| s.to_time_s + d).collect::<Vec<_>>();
        let ev = [hs(&r, 0.0), to(&r, 0.0), hs(&l, 0.0), to(&l, 0.0)];
        (l, r, ev)
    }

    fn check(d_s: f64, right_stance: f64) -> (DsBalance, Option<Warning>) {
        let (l, r, [rh, rt, lh, lt]) = walk(d_s, right_stance);
        let b = balance(&l, &r, (&rh, &rt), (&lh, &lt)).unwrap();
        let w = clock_warning(&b);
        (b, w)
    }

    #[test]
    fn one_clock_gives_equal_double_supports_and_no_finding() {
        let (b, w) = check(0.0, 0.6);
        assert!((b.after_left_hs - 0.1).abs() < 1e-9 && (b.after_right_hs - 0.1).abs() < 1e-9);
        assert!(w.is_none());
        // A genuinely asymmetric walker (right stance 0.7): 0.2 against 0.1, no finding.
        let (b, w) = check(0.0, 0.7);
        assert!((b.after_left_hs - 0.2).abs() < 1e-9, "{b:?}");
        assert!(w.is_none());
    }

    #[test]
    fn an_offset_moves_the_split_and_withholds_the_timings_between_the_legs() {
        // 80 ms late: 0.18 against 0.02.
        let (b, w) = check(0.08, 0.6);
        assert!((b.apparent_offset_s() - 0.08).abs() < 1e-9, "{b:?}");
        let w = w.expect("an offset of 80 ms");
        assert_eq!(w.code, codes::CLOCK_OFFSET);
        assert!(BETWEEN_LEGS.iter().all(|&p| w.withholds(p)));
        assert!(!w.withholds(Parameter::StrideTime) && !w.withholds(Parameter::StanceRatio));
        assert_eq!(w.reason(), "the two sensors' clocks do not agree");
        assert!(w.message.contains("80 ms late"), "{}", w.message);
        // Beyond a double support (a flight phase), early.
        let (b, w) = check(-0.15, 0.6);
        assert!(b.after_left_hs < 0.0, "{b:?}");
        assert!(w.unwrap().message.contains("150 ms early"));
    }

    #[test]
    fn two_files_withhold_a_step_asymmetry_no_swing_backs_and_one_file_never() {
        // The right clock 55 ms late on a symmetric walker (the same events as a right step
        // 55 ms longer): 0.155 against 0.045 is within what walkers show, no clock_offset.
        let (b, w) = check(0.055, 0.6);
        assert!(w.is_none(), "{b:?}");
        assert!((b.step_difference() - 0.11).abs() < 1e-9, "{b:?}");
        assert!((b.unbacked_step_share() - 0.11).abs() < 1e-9, "{b:?}");
        let w = two_clocks_warning(&b, Some(Clocks::Two)).expect("two files");
        assert_eq!(w.code, codes::TWO_CLOCKS);
        assert!(BETWEEN_LEGS.iter().all(|&p| w.withholds(p)));
        assert!(!w.withholds(Parameter::StrideTime) && !w.withholds(Parameter::SwingRatio));
        assert_eq!(w.reason(), "the two sensors are not known to share a clock");
        assert!(
            w.message.contains("right step is 110 ms longer"),
            "{}",
            w.message
        );
        assert!(w.message.contains("offset of 55 ms"), "{}", w.message);
        // An unknown swing backs nothing.
        let unknown = DsBalance {
            swing_left: f64::NAN,
            ..b
        };
        assert!((unknown.unbacked_step_share() - 0.11).abs() < 1e-9);
        // One file (one clock) never; legs handed over without their sources are not judged.
        assert!(two_clocks_warning(&b, Some(Clocks::One)).is_none());
        assert!(two_clocks_warning(&b, None).is_none());
        // 20 ms: a step-time difference of 0.04 of the stride, below the rule.
        let (b, _) = check(0.02, 0.6);
        assert!(two_clocks_warning(&b, Some(Clocks::Two)).is_none(), "{b:?}");
    }

    #[test]
    fn a_step_asymmetry_the_swing_times_back_is_kept_on_two_files() {
        // Right swing 0.5 of the stride against 0.4, the right heel strike 0.55 after the
        // left: the right step 0.1 longer, all of it the right leg's own longer swing.
        let (b, w) = check(0.05, 0.5);
        assert!(w.is_none());
        assert!((b.step_difference() - 0.1).abs() < 1e-9, "{b:?}");
        assert!(b.unbacked_step_share().abs() < 1e-9, "{b:?}");
        assert!(two_clocks_warning(&b, Some(Clocks::Two)).is_none());
        // A swing asymmetry the other way backs nothing: the asymmetric walker of the test
        // above (right stance 0.7) with its right heel strike 0.1 of the stride later.
        let (b, _) = check(0.1, 0.7);
        assert!((b.unbacked_step_share() - 0.2).abs() < 1e-9, "{b:?}");
        assert!(two_clocks_warning(&b, Some(Clocks::Two)).is_some());
        assert!(two_clocks_warning(&b, Some(Clocks::One)).is_none());
    }

    #[test]
    fn too_few_strides_decide_nothing() {
        let (l, r, [rh, rt, lh, lt]) = walk(0.1, 0.6);
        assert!(balance(&l[..4], &r[..4], (&rh, &rt), (&lh, &lt)).is_none());
    }
}
