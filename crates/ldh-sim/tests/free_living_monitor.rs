//! `ldh monitor` (ldh_core::monitor) scored on simulated free-living hours against the
//! simulator's truth (issue 52's targets: walking bouts ≥ 10 s found with recall ≥ 0.95,
//! walking time and steps within 5 %, false walking in rest, non-wear and cycling ≤ 2 % of
//! their time, drift within 0.5 s a day). The numbers are printed; the assertions are the
//! bounds the monitor meets today (docs/free-living.md lists the targets and the measured
//! values), so a regression fails and progress is seen in the printed line.

use ldh_core::monitor::{monitor_subject, MonitorParams};
use ldh_core::pipeline::{bare_subject, Source};
use ldh_sim::free_living::{
    drift_error_s_per_day, read_truth_bouts, score, simulate_free_living, FoundBout,
    FreeLivingParams, ScoreTargets,
};

#[test]
fn monitor_on_six_simulated_hours_scored_against_the_truth() {
    let dir = tempfile::tempdir().unwrap();
    let params = FreeLivingParams {
        duration_h: 6.0,
        drift_ppm: Some(40.0),
        seed: 7,
        ..FreeLivingParams::default()
    };
    let subjects = simulate_free_living(&params, dir.path(), &|| {}).unwrap();
    let s = &subjects[0];
    let input = ldh_core::pipeline::SubjectInput {
        left: Some(Source::Path(s.dir.join("left.csv"))),
        right: Some(Source::Path(s.dir.join("right.csv"))),
        ..bare_subject(&s.subject_id)
    };
    let p = MonitorParams::default().check().unwrap();
    let res = monitor_subject(&input, &p);
    assert!(res.errors.is_empty(), "{:?}", res.errors);
    let truth = read_truth_bouts(&s.dir.join("truth_bouts.csv")).unwrap();
    let found: Vec<FoundBout> = res
        .bouts
        .iter()
        .map(|b| FoundBout {
            start_s: b.start_s,
            end_s: b.end_s,
            steps: b.steps as f64,
        })
        .collect();
    let sc = score(&truth, &found);
    let drift_err = drift_error_s_per_day(s.truth.drift_ppm, res.drift.ppm());
    println!(
        "free-living 6 h: recall(>=10 s) {:?} ({}/{}), walking time error {:?} %, steps error {:?} %, false walking {:?} % ({:?}), drift {:.1} ppm vs {:.1} true: {:.3} s/day error; misses: {:?}",
        sc.recall_10s,
        sc.found_bouts_10s,
        sc.true_bouts_10s,
        sc.walking_time_error_pct,
        sc.steps_error_pct,
        sc.false_walking_pct,
        sc.false_walking_pct_by_activity,
        res.drift.ppm(),
        s.truth.drift_ppm,
        drift_err,
        sc.misses(&ScoreTargets::default())
    );
    assert!(sc.recall_10s.unwrap_or(0.0) >= 0.5, "{sc:?}");
    assert!(sc.false_walking_pct.unwrap_or(0.0) <= 10.0, "{sc:?}");
}
