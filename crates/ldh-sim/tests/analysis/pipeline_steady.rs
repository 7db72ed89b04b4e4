//! Steady-state walking in the pipeline (issue 36): a simulated treadmill walk whose belt
//! starts up (`ldh simulate --ramp-s`) loses its start-up strides, and its stride-time CV is
//! the steady truth's.

use ldh_core::gait::STEADY_REASON;
use ldh_core::pipeline::*;
use ldh_sim::{analyze_simulated, CohortParams, SimSubject, StrideTruth};

/// Stride-time CV (SD with n − 1 / mean) of the truth's steady strides.
fn steady_truth_cv(strides: &[StrideTruth]) -> f64 {
    let t: Vec<f64> = strides
        .iter()
        .filter(|s| !s.accelerating && !s.bout_edge && !s.turning)
        .map(|s| s.stride_time_s)
        .collect();
    let n = t.len() as f64;
    let mean = t.iter().sum::<f64>() / n;
    let var = t.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    var.sqrt() / mean
}

fn treadmill(ramp_s: f64) -> CohortParams {
    CohortParams {
        healthy: 2,
        ldh: 2,
        duration_s: 90.0,
        seed: 36,
        turn: false,
        ramp_s,
        ..CohortParams::default()
    }
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

#[test]
fn belt_start_up_is_excluded_and_the_cv_is_the_steady_truths() {
    let c = treadmill(10.0);
    let mut errors = Vec::new();
    for i in 0..c.len() {
        let s = c.simulate(i).unwrap();
        let id = &s.params.subject_id;
        let t = s.truth();
        let on = analyse(&s, true);
        let off = analyse(&s, false);
        for ((leg, leg_off), tr) in [(&on.left, &off.left), (&on.right, &off.right)]
            .into_iter()
            .zip([&t.left, &t.right])
        {
            let (leg, leg_off) = (leg.as_ref().unwrap(), leg_off.as_ref().unwrap());
            let truth = steady_truth_cv(&tr.strides);
            let cv = leg.parameters.stride_time_cv;
            let cv_off = leg_off.parameters.stride_time_cv;
            let ramp_end = tr
                .strides
                .iter()
                .filter(|x| x.accelerating)
                .map(|x| x.next_hs_time_s)
                .fold(0.0, f64::max);
            let ideal: Vec<f64> = leg_off
                .strides
                .iter()
                .filter(|x| x.valid && x.hs_time_s > ramp_end - 0.2)
                .map(|x| x.stride_time_s)
                .collect();
            let n = ideal.len() as f64;
            let m = ideal.iter().sum::<f64>() / n;
            let ideal_cv =
                (ideal.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt() / m;
            eprintln!(
                "{id} {:?}: truth {:.2} %, ldh {:.2} %, ldh on the true window {:.2} %, without the rule {:.2} %, window {:?} ramp end {ramp_end:.2}",
                tr.side,
                100.0 * truth,
                100.0 * cv,
                100.0 * ideal_cv,
                100.0 * cv_off,
                leg.steady
            );
            // The rule's own error: against ldh's strides on the truth's steady window.
            assert!(
                (cv - ideal_cv).abs() <= 0.003,
                "{id} {:?}: CV {cv} against {ideal_cv} on the true window",
                tr.side
            );
            // Against the truth (issue 36: 0.3 points); what the event timing adds on the true
            // window (≤ 0.28 points on these legs) is in it, so 0.4 per leg, 0.3 on average.
            assert!(
                (cv - truth).abs() <= 0.004,
                "{id} {:?}: CV {cv} against the steady truth {truth}",
                tr.side
            );
            errors.push((cv - truth).abs());
            // The start-up is what the rule removed: without it the CV is far off.
            assert!(
                cv_off - truth > 0.005,
                "{id} {:?}: {cv_off} {truth}",
                tr.side
            );
            let w = leg.steady.unwrap();
            assert!(w.excluded_start >= 2, "{id} {:?}: {w:?}", tr.side);
            assert!(w.enough);
            // The first half of the start-up (strides ≥ 12.5 % longer) is out, with its reason.
            let half = s.params.standing_s + 0.5 * c.ramp_s;
            for st in leg.strides.iter().filter(|x| x.hs_time_s < half) {
                assert!(!st.valid, "{id} {:?}: {st:?}", tr.side);
            }
            assert!(leg.strides.iter().any(|x| x.reason.contains(STEADY_REASON)));
            assert!(leg.warnings.iter().any(|x| x.code == codes::STEADY_WINDOW));
        }
    }
    let mean = errors.iter().sum::<f64>() / errors.len() as f64;
    eprintln!("mean |CV − steady truth| {:.3} points", 100.0 * mean);
    assert!(mean <= 0.003, "{errors:?}");
}

#[test]
fn a_steady_walk_loses_nothing() {
    let c = treadmill(0.0);
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
