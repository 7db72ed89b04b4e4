//! `ldh monitor` (ldh_core::monitor) scored on simulated free-living hours against the
//! simulator's truth (issue 52's targets: walking bouts ≥ 10 s found with recall ≥ 0.95,
//! walking time and steps within 5 %, false walking in rest, non-wear and cycling ≤ 2 % of
//! their time, drift within 0.5 s a day). The rules were tuned on seed 7 and are reported on
//! seed 11 and seed 13 (docs/free-living.md "Accuracy on simulated days"), where every target
//! holds. The stair rule (`ldh_core::monitor::stairs`) is scored too: flights of stairs found
//! as stair bouts (recall), stair bouts that are stairs (precision), stairs labelled inside
//! level walking. `LDH_FL_DUMP=DIR` writes the truth and the bouts found for a closer look.

use ldh_core::monitor::{monitor_subject, BoutKind, MonitorParams};
use ldh_core::pipeline::{bare_subject, Source};
use ldh_sim::free_living::{
    drift_error_s_per_day, read_truth_bouts, score, simulate_free_living, FoundBout,
    FreeLivingParams, Score, ScoreTargets,
};

/// Six simulated hours of seed `seed` (right clock +40 ppm) through the monitor, scored.
fn scored(seed: u64) -> (Score, f64) {
    let dir = tempfile::tempdir().unwrap();
    let params = FreeLivingParams {
        duration_h: 6.0,
        drift_ppm: Some(40.0),
        seed,
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
            stairs: b.kind == BoutKind::Stairs,
        })
        .collect();
    if let Ok(d) = std::env::var("LDH_FL_DUMP") {
        let d = std::path::Path::new(&d).join(format!("seed{seed}"));
        std::fs::create_dir_all(&d).unwrap();
        std::fs::copy(s.dir.join("truth_bouts.csv"), d.join("truth_bouts.csv")).unwrap();
        let mut out = String::from("start_s,end_s,steps,legs,kind,stride_rise_m,withheld\n");
        for b in &res.bouts {
            out.push_str(&format!(
                "{},{},{},{},{},{},\"{}\"\n",
                b.start_s, b.end_s, b.steps, b.legs, b.kind, b.stride_rise_m, b.withheld
            ));
        }
        std::fs::write(d.join("found.csv"), out).unwrap();
        std::fs::write(d.join("notes.txt"), res.notes.join("\n")).unwrap();
    }
    let sc = score(&truth, &found);
    let drift_err = drift_error_s_per_day(s.truth.drift_ppm, res.drift.ppm());
    println!(
        "free-living 6 h, seed {seed}: recall(>=10 s) {:?} ({}/{}), walking time error {:?} %, steps error {:?} %, found in stairs {:.1} s of {:.1} s, false walking {:?} % ({:?}), drift {:.1} ppm vs {:.1} true: {:.3} s/day error; misses: {:?}",
        sc.recall_10s,
        sc.found_bouts_10s,
        sc.true_bouts_10s,
        sc.walking_time_error_pct,
        sc.steps_error_pct,
        sc.found_in_stairs_s,
        sc.stairs_s,
        sc.false_walking_pct,
        sc.false_walking_pct_by_activity,
        res.drift.ppm(),
        s.truth.drift_ppm,
        drift_err,
        sc.misses(&ScoreTargets::default())
    );
    println!(
        "  stairs, seed {seed}: recall {:?} ({}/{} flights), precision {:?} ({}/{} bouts labelled), stairs labelled in level walking {:?} %",
        sc.stairs_recall,
        sc.found_stair_bouts,
        sc.true_stair_bouts,
        sc.stairs_precision,
        sc.right_stair_bouts,
        sc.labelled_stair_bouts,
        sc.false_stairs_in_walking_pct
    );
    (sc, drift_err)
}

/// The targets met, and walking time and steps within `amount_pct`; stairs found with recall
/// ≥ 0.6 (measured 5/6, 3/3 and 4/6 flights: a flight whose every stride's integration the
/// velocity-drift check refuses has no rise to judge, docs/free-living.md) and precision
/// ≥ 0.9, and labelled in ≤ 1 % of the level walking time.
fn check(sc: &Score, drift_err: f64, amount_pct: f64) {
    let t = ScoreTargets::default();
    assert!(sc.stairs_recall.unwrap_or(1.0) >= 0.6, "{sc:?}");
    assert!(sc.stairs_precision.unwrap_or(1.0) >= 0.9, "{sc:?}");
    assert!(
        sc.false_stairs_in_walking_pct.unwrap_or(0.0) <= 1.0,
        "{sc:?}"
    );
    assert!(sc.recall_10s.unwrap_or(0.0) >= t.recall_min, "{sc:?}");
    assert!(
        sc.false_walking_pct.unwrap_or(100.0) <= t.false_walking_pct_max,
        "{sc:?}"
    );
    assert!(drift_err <= t.drift_error_s_per_day_max, "{drift_err}");
    assert!(
        sc.walking_time_error_pct.unwrap_or(100.0).abs() <= amount_pct,
        "{sc:?}"
    );
    assert!(
        sc.steps_error_pct.unwrap_or(100.0).abs() <= amount_pct,
        "{sc:?}"
    );
}

#[test]
fn monitor_on_six_simulated_hours_tuning_seed() {
    let (sc, d) = scored(7);
    check(&sc, d, ScoreTargets::default().walking_time_error_pct_max);
}

#[test]
fn monitor_on_six_simulated_hours_second_report_seed_meets_the_targets() {
    let (sc, d) = scored(13);
    check(&sc, d, ScoreTargets::default().walking_time_error_pct_max);
}

#[test]
fn monitor_on_six_simulated_hours_report_seed_meets_the_targets() {
    let (sc, d) = scored(11);
    check(&sc, d, ScoreTargets::default().walking_time_error_pct_max);
}
