//! Tests of the steady window (synthetic stride-time series).

use super::window::*;
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
    // The ramp ends at 8; the fit may take a stride or two of the jitter's slow wave with it.
    assert!((4..=11).contains(&a), "{w:?}");
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
    let (a, b) = one_leg(&t).range.unwrap();
    assert!(a == 0 && (37..=39).contains(&b), "{a} {b}");
}

#[test]
fn a_slow_down_after_a_dip_of_shorter_strides_is_excluded() {
    // TRIPOD's PWS run (issue 50): a dip of shorter strides ends the longest stretch at one pace
    // 20 strides before the belt slows to a stop (1.22 → 1.96 s over the last 10 strides); the
    // slow-down is cut, the dip (inside the walk) kept.
    let mut t = walk(120, |i| if (100..105).contains(&i) { 1.15 } else { 1.22 });
    t.extend((1..=10).map(|i| 1.22 + 0.074 * i as f64));
    let (a, b) = one_leg(&t).range.unwrap();
    assert!(a == 0 && (117..=120).contains(&b), "{a} {b}");
}

#[test]
fn a_transient_of_a_few_strides_is_cut_at_either_end() {
    // Three strides 30 % long at one end (gait initiation, a last slowing step), which the
    // running median of 7 keeps inside the band: cut at the start and at the end alike.
    let mut t = vec![1.3, 1.3, 1.3];
    t.extend(walk(60, |_| 1.0));
    let (a, b) = one_leg(&t).range.unwrap();
    assert_eq!((a, b), (3, 62));
    let mut t = walk(60, |_| 1.0);
    t.extend([1.3, 1.3, 1.3]);
    let (a, b) = one_leg(&t).range.unwrap();
    assert_eq!((a, b), (0, 59));
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
    assert!(a <= 1 && (55..=62).contains(&b), "{a} {b}");
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
fn a_long_ramp_tail_inside_the_band_is_cut() {
    // Issue 50's miss: 25 % longer strides falling to 0 over 30 strides, then 60 steady; the
    // ramp's tail is inside the band of the running median (4σ): without the fit from the end the window
    // starts at 19.
    let t: Vec<f64> = (0..90)
        .map(|i| 1.0 + 0.25 * (1.0 - i as f64 / 30.0).max(0.0) + jitter(i, 0.025))
        .collect();
    let (a, b) = one_leg(&t).range.unwrap();
    assert!((25..=33).contains(&a) && b == 89, "{a} {b}");
}

#[test]
fn a_transient_is_measured_from_the_end_of_the_walk() {
    // From the end inward: a ramp of 6 strides (0.3 → 0.05 above the level), then steady.
    let mut y: Vec<f64> = (0..6).map(|i| 1.3 - 0.05 * i as f64).collect();
    y.extend((0..40).map(|i| 1.0 + jitter(i, 0.01)));
    assert_eq!(transient_length(&y, 0.08, 0.015, 1), 6);
    // Shorter strides (speeding up at the end, a hurried start) alike.
    let mirrored: Vec<f64> = y.iter().map(|x| 2.0 - x).collect();
    assert_eq!(transient_length(&mirrored, 0.08, 0.015, 1), 6);
    // An excursion inside the band, or noise alone: nothing.
    assert_eq!(transient_length(&y, 0.4, 0.015, 1), 0);
    let flat: Vec<f64> = (0..40).map(|i| 1.0 + jitter(i, 0.01)).collect();
    assert_eq!(transient_length(&flat, 0.06, 0.015, 1), 0);
    // A step to another pace: its length.
    let mut y = vec![1.12; 10];
    y.extend((0..40).map(|i| 1.0 + jitter(i, 0.01)));
    assert_eq!(transient_length(&y, 0.06, 0.015, 1), 10);
    assert_eq!(transient_length(&[1.0, 2.0], 0.0, 1.0, 1), 0);
    // Three strides 6 % long: inside the band as a wander of the level, beyond its half-width
    // as a transient shorter than the running median of 7.
    let mut y = vec![1.06; 3];
    y.extend((0..40).map(|i| 1.0 + jitter(i, 0.01)));
    assert_eq!(transient_length(&y, 0.08, 0.015, 1), 0);
    assert_eq!(transient_length(&y, 0.08, 0.015, 7), 3);
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
