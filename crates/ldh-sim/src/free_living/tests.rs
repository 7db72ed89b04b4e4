//! Tests of the free-living simulator and its scorer.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::plan::{plan, up_from_angles};
use super::stream::push_fixed;
use super::*;
use crate::SubjectParams;

fn small(hours: f64, fs_hz: f64) -> FreeLivingParams {
    FreeLivingParams {
        duration_h: hours,
        fs_hz,
        ..FreeLivingParams::default()
    }
}

#[test]
fn fixed_point_cells() {
    let mut b = Vec::new();
    for (v, d) in [
        (1.0, 5),
        (-0.000004, 5),
        (-0.25, 3),
        (604_800.0, 4),
        (0.009999, 4),
    ] {
        push_fixed(&mut b, v, d);
        b.push(b' ');
    }
    assert_eq!(
        String::from_utf8(b).unwrap(),
        "1.00000 0.00000 -0.250 604800.0000 0.0100 "
    );
}

#[test]
fn activity_names_round_trip() {
    for a in Activity::ALL {
        assert_eq!(a.as_str().parse::<Activity>().unwrap(), a);
    }
    assert!("jogging".parse::<Activity>().is_err());
}

#[test]
fn standing_gravity_is_along_the_shank() {
    let u = up_from_angles(0.0, 0.0);
    assert!((u[2] - 1.0).abs() < 1e-12 && u[0].abs() < 1e-12);
    // Knee forward (θ > 0): gravity's reaction points backwards in F.
    assert!(up_from_angles(30.0, 0.0)[0] < -0.49);
}

#[test]
fn a_week_plan_is_contiguous_with_nights_and_non_wear() {
    let p = FreeLivingParams {
        duration_h: 168.0,
        ..FreeLivingParams::default()
    };
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let base = SubjectParams::healthy("H01");
    let segs = plan(&p, &base, &mut rng);
    let mut t = 0.0;
    let mut time = std::collections::HashMap::new();
    let mut walks = Vec::new();
    for s in &segs {
        assert!((s.start_s - t).abs() < 1e-6, "gap at {t}");
        assert!(s.duration_s > 0.0);
        t = s.start_s + s.duration_s;
        *time.entry(s.activity).or_insert(0.0) += s.duration_s;
        if s.activity == Activity::Walking {
            walks.push(s.duration_s);
        }
    }
    assert!((t - 168.0 * 3600.0).abs() < 1e-6);
    let h = |a| time.get(&a).copied().unwrap_or(0.0) / 3600.0 / 7.0;
    for a in Activity::ALL {
        println!("{a}: {:.2} h/day", h(a));
    }
    // Per day: 6–10 h lying (nights), some non-wear, 0.5–2.5 h of walking bouts.
    assert!(
        (6.0..11.0).contains(&h(Activity::Lying)),
        "lying {} h/day",
        h(Activity::Lying)
    );
    assert!(
        h(Activity::NonWear) > 0.2,
        "non-wear {}",
        h(Activity::NonWear)
    );
    assert!(
        (0.4..2.5).contains(&h(Activity::Walking)),
        "walking {} h/day",
        h(Activity::Walking)
    );
    assert!(time.contains_key(&Activity::Cycling) && time.contains_key(&Activity::Stairs));
    // Many short bouts, few long ones.
    walks.sort_by(f64::total_cmp);
    let median = walks[walks.len() / 2];
    assert!((10.0..30.0).contains(&median), "median bout {median} s");
    assert!(walks.iter().filter(|&&w| w > 120.0).count() * 10 < walks.len());
}

#[test]
fn simulation_streams_files_with_truth_and_drift() {
    let dir = tempfile::tempdir().unwrap();
    let p = FreeLivingParams {
        drift_ppm: Some(1000.0 / 36.0), // ≈ 27.8 ppm: 0.1 s in the hour
        ..small(1.0, 50.0)
    };
    let out = simulate_free_living(&p, dir.path(), &|| {}).unwrap();
    assert_eq!(out.len(), 1);
    let s = &out[0];
    assert_eq!(s.subject_id, "H01");
    let n = 3600 * 50;
    assert_eq!(s.truth.samples_left, n);
    // The right clock runs fast: more right samples, 5 more over the hour at 50 Hz.
    let extra = s.truth.samples_right as i64 - n as i64;
    assert!((4..=6).contains(&extra), "{extra} extra right samples");
    let bouts = read_truth_bouts(&s.dir.join("truth_bouts.csv")).unwrap();
    assert!((bouts[0].start_s).abs() < 1e-9);
    assert!((bouts.last().unwrap().end_s - 3600.0).abs() < 0.1);
    for w in bouts.windows(2) {
        assert!((w[0].end_s - w[1].start_s).abs() < 1e-3);
    }
    let walking: Vec<_> = bouts
        .iter()
        .filter(|b| b.activity == Activity::Walking)
        .collect();
    for b in &walking {
        let cadence = b.steps() as f64 / b.duration_s() * 60.0;
        assert!(b.steps() >= 6 && (70.0..160.0).contains(&cadence), "{b:?}");
    }
    let (rec, report) =
        ldh_core::io::read_recording(s.dir.join("left.csv"), None, &Default::default()).unwrap();
    assert_eq!(
        report.recorded_at.map(|r| r.at.iso()).as_deref(),
        Some("2026-03-02T08:00:00")
    );
    assert_eq!(rec.len() as u64, n);
    assert!((rec.fs_hz - 50.0).abs() < 1e-6);
    // A worn still posture reads ≈ 1 g.
    let sit = bouts
        .iter()
        .find(|b| {
            matches!(b.activity, Activity::Sitting | Activity::Lying) && b.duration_s() > 30.0
        })
        .expect("a rest bout");
    let i = ((sit.start_s + 10.0) * 50.0) as usize;
    let g = (0..3).map(|k| rec.acc_g[k][i].powi(2)).sum::<f64>().sqrt();
    assert!((g - 1.0).abs() < 0.05, "{g} g at rest");
    let truth = FreeLivingTruth::read(&s.dir.join("truth.json")).unwrap();
    assert_eq!(&truth, &s.truth);
    assert!(dir.path().join("manifest.csv").exists());
}

#[test]
fn same_seed_same_bytes() {
    let p = small(0.1, 50.0);
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    simulate_free_living(&p, a.path(), &|| {}).unwrap();
    simulate_free_living(&p, b.path(), &|| {}).unwrap();
    for f in ["left.csv", "right.csv", "truth_bouts.csv", "truth.json"] {
        let x = std::fs::read(a.path().join("H01").join(f)).unwrap();
        let y = std::fs::read(b.path().join("H01").join(f)).unwrap();
        assert!(x == y, "{f} differs between runs");
    }
}

fn tb(start_s: f64, end_s: f64, activity: Activity, steps: usize) -> TruthBout {
    TruthBout {
        bout: 0,
        start_s,
        end_s,
        activity,
        steps_left: steps / 2,
        steps_right: steps - steps / 2,
    }
}

#[test]
fn score_of_the_truth_is_perfect_and_false_walking_is_counted() {
    let truth = vec![
        tb(0.0, 100.0, Activity::Sitting, 0),
        tb(100.0, 130.0, Activity::Walking, 56),
        tb(130.0, 135.0, Activity::Standing, 0),
        tb(135.0, 141.0, Activity::Walking, 12),
        tb(141.0, 241.0, Activity::Cycling, 0),
    ];
    let found: Vec<FoundBout> = truth
        .iter()
        .filter(|b| b.activity == Activity::Walking)
        .map(|b| FoundBout {
            start_s: b.start_s,
            end_s: b.end_s,
            steps: b.steps() as f64,
            stairs: false,
        })
        .collect();
    let s = score(&truth, &found);
    assert_eq!((s.true_bouts_10s, s.found_bouts_10s), (1, 1));
    assert_eq!(s.walking_time_error_pct, Some(0.0));
    assert_eq!(s.steps_error_pct, Some(0.0));
    assert_eq!(s.false_walking_pct, Some(0.0));
    assert!(s.misses(&ScoreTargets::default()).is_empty());
    // Walking "found" over 20 s of the cycling: 20 of 205 s of rest and cycling.
    let mut more = found.clone();
    more.push(FoundBout {
        start_s: 150.0,
        end_s: 170.0,
        steps: 30.0,
        stairs: false,
    });
    let s = score(&truth, &more);
    assert!((s.false_walking_pct.unwrap() - 100.0 * 20.0 / 205.0).abs() < 1e-9);
    let cyc = s
        .false_walking_pct_by_activity
        .iter()
        .find(|(a, _)| *a == Activity::Cycling)
        .unwrap();
    assert!((cyc.1 - 20.0).abs() < 1e-9);
    assert_eq!(s.misses(&ScoreTargets::default()).len(), 3);
    // A bout found only for 40 % of its length is missed.
    let part = vec![FoundBout {
        start_s: 100.0,
        end_s: 112.0,
        steps: 22.0,
        stairs: false,
    }];
    assert_eq!(score(&truth, &part).recall_10s, Some(0.0));
    assert!((drift_error_s_per_day(30.0, 35.0) - 0.432).abs() < 1e-9);
}

#[test]
fn stairs_are_scored_apart_from_level_walking() {
    let truth = vec![
        tb(0.0, 20.0, Activity::Walking, 36),
        tb(20.0, 30.0, Activity::Standing, 0),
        tb(30.0, 45.0, Activity::Stairs, 24),
        tb(45.0, 60.0, Activity::Standing, 0),
        tb(60.0, 75.0, Activity::Stairs, 26),
    ];
    let f = |a: f64, b: f64, steps: f64, stairs: bool| FoundBout {
        start_s: a,
        end_s: b,
        steps,
        stairs,
    };
    // The walk and the first flight found and told apart; the second flight found as walking.
    let found = vec![
        f(0.0, 20.0, 36.0, false),
        f(30.0, 45.0, 24.0, true),
        f(60.0, 75.0, 26.0, false),
    ];
    let s = score(&truth, &found);
    assert_eq!((s.true_stair_bouts, s.found_stair_bouts), (2, 1));
    assert_eq!(s.stairs_recall, Some(0.5));
    assert_eq!((s.labelled_stair_bouts, s.right_stair_bouts), (1, 1));
    assert_eq!(s.stairs_precision, Some(1.0));
    assert_eq!(s.false_stairs_in_walking_pct, Some(0.0));
    // Level walking compares the bouts not labelled stairs: the unlabelled flight is extra.
    assert!((s.walking_time_error_pct.unwrap() - 75.0).abs() < 1e-9);
    // A level walk labelled stairs: a wrong stair bout and level walking missed.
    let wrong = vec![f(0.0, 20.0, 36.0, true)];
    let s = score(&truth, &wrong);
    assert_eq!((s.labelled_stair_bouts, s.right_stair_bouts), (1, 0));
    assert_eq!(s.stairs_precision, Some(0.0));
    assert_eq!(s.false_stairs_in_walking_pct, Some(100.0));
    assert_eq!(s.walking_time_error_pct, Some(-100.0));
}

#[test]
fn bad_parameters_are_refused() {
    let p = FreeLivingParams {
        duration_h: 400.0,
        ..FreeLivingParams::default()
    };
    assert!(p.validate().is_err());
    let p = FreeLivingParams {
        healthy: 0,
        ..FreeLivingParams::default()
    };
    assert!(p.validate().is_err());
    let p = FreeLivingParams {
        drift_ppm: Some(f64::NAN),
        ..FreeLivingParams::default()
    };
    assert!(p.validate().is_err());
}
