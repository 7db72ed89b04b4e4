//! Steady-state walking in the pipeline (issues 36 and 50): a simulated treadmill walk whose belt
//! starts up (`SubjectParams::ramp_s`), whose walker slows down before the end (`slowdown_s`)
//! or both loses those strides on both legs at once (one window per walk), and its stride-time
//! CV is the steady truth's within 0.3 points; a walker who speeds up or slows down throughout
//! (`trend_share`) never becomes steady, and his variability is withheld. The same on family B
//! (its own `ramp_s`, `slowdown_s`, `trend_share`), which the rule was not tuned on.

use ldh_core::domain::Parameter;
use ldh_core::gait::STEADY_REASON;
use ldh_core::pipeline::*;
use ldh_core::recording::Setting;
use ldh_sim::family_b::{simulate_subject_b, CohortParamsB, SubjectParamsB};
use ldh_sim::{
    analyze_simulated, simulate_subject, CohortParams, SimSubject, StrideTruth, SubjectParams,
};

/// Stride-time CV (SD with n − 1 / mean) of the truth's steady strides.
fn steady_truth_cv(strides: &[StrideTruth]) -> f64 {
    cv(&strides
        .iter()
        .filter(|s| !s.accelerating && !s.decelerating && !s.bout_edge && !s.turning)
        .map(|s| s.stride_time_s)
        .collect::<Vec<_>>())
}

/// The two parts of a leg's |CV − steady truth| (issue 50; docs/accuracy.md "One steady window
/// per walk", 2026-12-03), each ldh's valid strides matched to the truth's by heel strike
/// (within 0.25 s): the **window's**, the CV of the *true* stride times of the strides ldh keeps
/// against the steady truth's (which strides are in, nothing else), and the **events'**, the CV
/// of *ldh's* stride times of the truth's own steady strides against it (how the strides are
/// timed, nothing else). Returns (window, events), signed.
fn window_and_event_errors(leg: &LegResult, truth: &[StrideTruth]) -> (f64, f64) {
    let steady = |s: &StrideTruth| !s.accelerating && !s.decelerating && !s.bout_edge && !s.turning;
    let matched = |hs: f64| truth.iter().find(|t| (t.hs_time_s - hs).abs() < 0.25);
    let kept = leg.strides.iter().filter(|x| x.valid);
    let window: Vec<f64> = kept
        .clone()
        .filter_map(|x| matched(x.hs_time_s).map(|t| t.stride_time_s))
        .collect();
    let events: Vec<f64> = kept
        .filter(|x| matched(x.hs_time_s).is_some_and(steady))
        .map(|x| x.stride_time_s)
        .collect();
    let truth_cv = steady_truth_cv(truth);
    (cv(&window) - truth_cv, cv(&events) - truth_cv)
}

fn cv(t: &[f64]) -> f64 {
    let n = t.len() as f64;
    let mean = t.iter().sum::<f64>() / n;
    let var = t.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    var.sqrt() / mean
}

fn treadmill() -> CohortParams {
    CohortParams {
        healthy: 2,
        ldh: 2,
        duration_s: 90.0,
        seed: 36,
        turn: false,
        ..CohortParams::default()
    }
}

/// Subject `i` of `c` with its parameters changed by `f` (the same random stream).
fn simulate(c: &CohortParams, i: usize, f: impl Fn(&mut SubjectParams)) -> SimSubject {
    let (mut p, mut rng) = c.draw(i);
    f(&mut p);
    simulate_subject(&p, &c.sensor, &mut rng).unwrap()
}

/// Family B's treadmill cohort of the same size and length (2 healthy, 2 slow hemiparetic
/// walkers with 1.6–2.3 s strides), every subject changed by `f`.
fn cohort_b(f: impl Fn(&mut SubjectParamsB)) -> Vec<SimSubject> {
    let c = CohortParamsB {
        healthy: 2,
        patients: 2,
        duration_s: 90.0,
        seed: 36,
        setting: Some(Setting::Treadmill),
        ..CohortParamsB::default()
    };
    (0..c.len())
        .map(|i| {
            let (mut p, mut rng) = c.draw(i);
            f(&mut p);
            simulate_subject_b(&p, &c.sensor, &mut rng).unwrap()
        })
        .collect()
}

/// Family A's treadmill cohort, every subject changed by `f`.
fn cohort_a(f: impl Fn(&mut SubjectParams)) -> Vec<SimSubject> {
    let c = treadmill();
    (0..c.len()).map(|i| simulate(&c, i, &f)).collect()
}

fn analyse(s: &SimSubject, steady: bool) -> SubjectResult {
    let mut p = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    }
    .for_treadmill();
    p.steady.enabled = steady;
    analyze_simulated(s, &p)
}

/// Every subject of a treadmill cohort with transients: both legs' windows are one, the
/// transients are out, and the CV is the steady truth's within 0.3 points on average and
/// `leg_max` on each leg. Returns |CV − truth| per leg.
fn transients_are_excluded(name: &str, subjects: Vec<SimSubject>, leg_max: f64) -> Vec<f64> {
    let mut errors = Vec::new();
    for s in subjects {
        let id = &s.params.subject_id;
        let t = s.truth();
        let (on, off) = (analyse(&s, true), analyse(&s, false));
        let (l, r) = (on.left.as_ref().unwrap(), on.right.as_ref().unwrap());
        let (wl, wr) = (l.steady.unwrap(), r.steady.unwrap());
        // One window per walk (both recordings start together here).
        assert_eq!(
            (wl.start_s, wl.end_s),
            (wr.start_s, wr.end_s),
            "{name} {id}"
        );
        for ((leg, leg_off), tr) in [(l, &off.left), (r, &off.right)]
            .into_iter()
            .zip([&t.left, &t.right])
        {
            let leg_off = leg_off.as_ref().unwrap();
            let truth = steady_truth_cv(&tr.strides);
            let cv_on = leg.parameters[Parameter::StrideTimeCv];
            let cv_off = leg_off.parameters[Parameter::StrideTimeCv];
            let w = leg.steady.unwrap();
            let (by_window, by_events) = window_and_event_errors(leg, &tr.strides);
            eprintln!(
                "{name} {id} {:?}: truth {:.2} %, ldh {:.2} %, without the rule {:.2} %, window {:.1}–{:.1} s, excluded {} + {}; of the error, the window's {:+.2}, the events' {:+.2}",
                tr.side,
                100.0 * truth,
                100.0 * cv_on,
                100.0 * cv_off,
                w.start_s,
                w.end_s,
                w.excluded_start,
                w.excluded_end,
                100.0 * by_window,
                100.0 * by_events
            );
            // The window's own part is within 0.3 points on every leg of every case, family B's
            // 10 s start-ups too (docs/accuracy.md, 2026-12-03).
            assert!(
                by_window.abs() <= 0.003,
                "{name} {id} {:?}: the window's part of the CV's error {by_window}",
                tr.side
            );
            // Issue 50: within 0.3 points on average; what the event timing adds on the true
            // window (≤ 0.28 points on family A's legs, issue 36) is in it, so more per leg.
            assert!(
                (cv_on - truth).abs() <= leg_max,
                "{name} {id} {:?}: CV {cv_on} against the steady truth {truth}",
                tr.side
            );
            errors.push((cv_on - truth).abs());
            assert!(w.enough && !w.never_steady, "{w:?}");
            // The transients are what the rule removed: without it the CV is far off. On
            // family B's slowest walker (2.2 s strides, CV 5.6 %) a 10 s transient is 2–3
            // strides that do not show in the CV (within `leg_max` without the rule): the
            // rule need not find them there.
            let shows = cv_off - truth > leg_max;
            assert!(
                shows || s.family_b.is_some(),
                "{name} {id} {:?}: {cv_off} {truth}",
                tr.side
            );
            if !shows {
                continue;
            }
            // No stride of the first or last half of a transient is steady.
            let early = s.params.standing_s + 0.5 * s.params.ramp_s;
            let last_hs = tr.hs_times_s.last().copied().unwrap_or(f64::MAX);
            let late = last_hs - 0.5 * s.params.slowdown_s;
            for st in leg.strides.iter().filter(|x| {
                (s.params.ramp_s > 0.0 && x.hs_time_s < early)
                    || (s.params.slowdown_s > 0.0 && x.next_hs_time_s > late)
            }) {
                assert!(!st.valid, "{name} {id} {:?}: {st:?}", tr.side);
            }
            assert!(leg.strides.iter().any(|x| x.reason.contains(STEADY_REASON)));
            assert!(leg.warnings.iter().any(|x| x.code == codes::STEADY_WINDOW));
        }
    }
    let mean = errors.iter().sum::<f64>() / errors.len() as f64;
    eprintln!(
        "{name}: mean |CV − steady truth| {:.3} points, largest {:.3}",
        100.0 * mean,
        100.0 * errors.iter().fold(0.0_f64, |a, &b| a.max(b))
    );
    assert!(mean <= 0.003, "{name}: {errors:?}");
    errors
}

#[test]
fn belt_start_up_is_excluded_on_both_legs_and_the_cv_is_the_steady_truths() {
    transients_are_excluded("ramp 10 s", cohort_a(|p| p.ramp_s = 10.0), 0.003);
    // Family B's slow walkers: a 10 s start-up is 3 valid strides 5–12 % long. 0.3 points
    // since weak impacts found at the crossing take the leg's delay (0.5 before: docs/accuracy.md
    // "Heel strikes at the crossing", 2026-12-03).
    transients_are_excluded("B ramp 10 s", cohort_b(|p| p.ramp_s = 10.0), 0.003);
}

#[test]
fn a_long_belt_start_up_is_excluded() {
    // Issue 50's walk: steady only after ≈ 30 s.
    transients_are_excluded("ramp 30 s", cohort_a(|p| p.ramp_s = 30.0), 0.003);
    transients_are_excluded("B ramp 30 s", cohort_b(|p| p.ramp_s = 30.0), 0.003);
}

#[test]
fn slowing_down_before_the_end_is_excluded() {
    transients_are_excluded("slow-down 10 s", cohort_a(|p| p.slowdown_s = 10.0), 0.003);
    transients_are_excluded(
        "ramp 10 s + slow-down 10 s",
        cohort_a(|p| {
            p.ramp_s = 10.0;
            p.slowdown_s = 10.0;
        }),
        0.003,
    );
}

#[test]
fn slowing_down_before_the_end_is_excluded_on_family_b() {
    // The belt slowing to a stop over the walk's last 10 s (TRIPOD's runs end so).
    transients_are_excluded("B slow-down 10 s", cohort_b(|p| p.slowdown_s = 10.0), 0.003);
    transients_are_excluded(
        "B ramp 10 s + slow-down 10 s",
        cohort_b(|p| {
            p.ramp_s = 10.0;
            p.slowdown_s = 10.0;
        }),
        0.003,
    );
}

#[test]
fn a_walker_who_speeds_up_or_slows_down_throughout_never_becomes_steady() {
    for trend in [-0.25, 0.25] {
        let mut subjects = cohort_a(|p| p.trend_share = trend);
        subjects.extend(cohort_b(|p| p.trend_share = trend));
        let mut checked = 0;
        for s in subjects {
            let id = &s.params.subject_id;
            let on = analyse(&s, true);
            let valid = |l: &Result<LegResult, _>| {
                l.as_ref()
                    .map_or(0, |l| l.strides.iter().filter(|x| x.valid).count())
            };
            if valid(&on.left).min(valid(&on.right)) < 20 {
                // Family B's slowest walker slowing by 25 % (2.3 → 2.9 s) leaves the
                // detector's plausible stride times: too few strides for the rule to judge.
                eprintln!("trend {trend} {id}: fewer than 20 valid strides a leg, not judged");
                continue;
            }
            checked += 1;
            for leg in [&on.left, &on.right] {
                let leg = leg.as_ref().unwrap();
                let w = leg.steady.unwrap();
                eprintln!("trend {trend} {id} {:?}: {w:?}", leg.side);
                assert!(w.never_steady && !w.enough, "{id} {:?}: {w:?}", leg.side);
                assert!(w.start_s.is_nan() && w.end_s.is_nan());
                // Nothing excluded as not steady; the variability withheld, with the reason.
                assert!(!leg.strides.iter().any(|x| x.reason.contains(STEADY_REASON)));
                let p = &leg.parameters;
                assert!(
                    p[Parameter::StrideTimeCv].is_nan() && p[Parameter::StrideLengthCv].is_nan()
                );
                let why = p
                    .withheld
                    .get(ldh_core::domain::Parameter::StrideTimeCv)
                    .unwrap();
                assert_eq!(
                    why.code,
                    ldh_core::domain::ReasonCode::Finding(
                        ldh_core::domain::WarningCode::NeverSteady
                    ),
                    "{why:?}"
                );
                assert!(leg.warnings.iter().any(|x| x.code == codes::NEVER_STEADY));
                // The trend's stride lengths are kept at both ends (a local median); family B
                // withholds more of its lengths for reasons of their own (docs/accuracy.md).
                if s.family_b.is_some() {
                    continue;
                }
                let kept = |a: usize, b: usize| {
                    leg.strides[a..b]
                        .iter()
                        .filter(|x| x.valid && x.stride_length_m.is_finite())
                        .count()
                };
                let n = leg.strides.len();
                assert!(
                    kept(0, n / 5) >= n / 10,
                    "{id} {:?}: early lengths dropped",
                    leg.side
                );
                assert!(
                    kept(n - n / 5, n) >= n / 10,
                    "{id} {:?}: late lengths dropped",
                    leg.side
                );
            }
        }
        // Every subject but at most family B's slowest slowing walker is judged.
        assert!(checked >= 7, "trend {trend}: {checked} of 8 judged");
    }
}

#[test]
fn a_steady_walk_loses_nothing() {
    let c = treadmill();
    let s = c.simulate(0).unwrap();
    let on = analyse(&s, true);
    let off = analyse(&s, false);
    for (leg, leg_off) in [(&on.left, &off.left), (&on.right, &off.right)] {
        let (leg, leg_off) = (leg.as_ref().unwrap(), leg_off.as_ref().unwrap());
        let w = leg.steady.unwrap();
        assert_eq!((w.excluded_start, w.excluded_end), (0, 0), "{w:?}");
        // (Debug: NaN STA compares equal as text.)
        assert_eq!(
            format!("{:?}", leg.parameters),
            format!("{:?}", leg_off.parameters)
        );
    }
}
