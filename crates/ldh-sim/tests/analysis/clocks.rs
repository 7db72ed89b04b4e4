//! Two sensors without one clock (`ldh_core::pipeline::quality::clocks`, docs/quality.md
//! `clock_offset` and `two_clocks`): the check's statistic — the smaller of the walk's two
//! double supports as a share of their sum — printed per walk, with whether a finding fired.
//! Every simulated walk (both families, every condition, the LDH and hemiparetic asymmetric
//! walkers included; one clock) and every HuGaDB walk (one file holds both shanks) must pass;
//! TRIPOD's runs at 3.7 and 4.4 km/h (Physilog units on their own clocks, the right shank 149
//! and 184 ms late against OptoGait) must be flagged `clock_offset`. The 3.0 km/h run (55 ms,
//! an apparent 53 ms) is not: its double supports split 0.19 / 0.11, as the simulators' slow
//! asymmetric walkers' do on one clock. It is `two_clocks` instead: two files, and a right
//! step 117 ms longer of which the legs' own swing times back 9 ms. Either way the run
//! reports no step time nor double support, so its page names no step asymmetry.
//!
//! `cargo test --profile ci -p ldh-sim --test analysis clocks -- --nocapture --test-threads 1`
//! (`LDH_SEEDS=…` for other simulator seeds; the thresholds were set on seeds 4949 and 100 and
//! HuGaDB's first nine files, and are reported on seed 2026, the other nine files and TRIPOD;
//! `clocks_observables` prints the step, double-support and swing differences of each walk,
//! with clock offsets injected).

use super::events_accuracy::{no_sta, sim_conditions_at};
use super::real_data::{real_walks, RealSet};
use ldh_core::domain::{Parameter, ReasonCode, WarningCode};
use ldh_core::pipeline::quality::{clock_balance, codes, MAX_UNBACKED_STEP_SHARE, MIN_DS_SHARE};
use ldh_core::pipeline::{Analysis, SubjectResult};
use ldh_sim::analyze_simulated;

/// The walk's statistic (smaller double support's share, apparent offset ms) recomputed from
/// the result's strides and events, and whether the warning fired.
fn statistic(res: &SubjectResult) -> (String, bool) {
    let fired = res
        .warnings
        .iter()
        .any(|w| [codes::CLOCK_OFFSET, codes::TWO_CLOCKS].contains(&w.code));
    let (Ok(l), Ok(r)) = (res.left.as_ref(), res.right.as_ref()) else {
        return ("a leg failed".into(), fired);
    };
    let d = r.t0_s - l.t0_s;
    let on = |v: &[f64], by: f64| v.iter().map(|t| t + by).collect::<Vec<f64>>();
    let (rh, rt) = (on(&r.events.hs_s, d), on(&r.events.to_s, d));
    let (lh, lt) = (on(&l.events.hs_s, -d), on(&l.events.to_s, -d));
    let text = match clock_balance(&l.strides, &r.strides, (&rh, &rt), (&lh, &lt)) {
        Some(b) => format!(
            "DS after left HS {:.3}, after right HS {:.3}, smaller share {:.2}, apparent offset {:+.0} ms, {} strides",
            b.after_left_hs,
            b.after_right_hs,
            b.min_share(),
            1e3 * b.apparent_offset_s(),
            b.strides
        ),
        None => "too few strides".into(),
    };
    (text, fired)
}

fn seeds() -> Vec<u64> {
    std::env::var("LDH_SEEDS")
        .ok()
        .map(|s| s.split(',').filter_map(|x| x.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![4949, 100, 2026])
}

#[test]
fn no_clock_finding_on_simulated_walks_on_one_clock() {
    let mut false_flags = Vec::new();
    for seed in seeds() {
        for (cond, subjects) in sim_conditions_at(seed) {
            for s in &subjects {
                let res = analyze_simulated(s, &no_sta());
                let (text, fired) = statistic(&res);
                let name = format!("seed {seed} {cond} {}", s.params.subject_id);
                println!("{name}: {text}; fired {fired}");
                if fired {
                    false_flags.push(name);
                }
            }
        }
    }
    assert!(false_flags.is_empty(), "{false_flags:?}");
}

#[test]
fn no_clock_finding_on_hugadb_and_one_on_every_tripod_run() {
    let Some(walks) = real_walks() else {
        return;
    };
    let analysis = Analysis::new(no_sta().check().unwrap());
    let mut false_flags = Vec::new();
    let mut missed = Vec::new();
    for walk in &walks {
        let res = walk.analyse(&analysis);
        let (text, fired) = statistic(&res);
        println!("{}: {text}; fired {fired}", walk.name());
        let run = walk.id.as_str();
        if walk.set == RealSet::HuGaDb {
            if fired {
                false_flags.push(walk.id.clone());
            }
            continue;
        }
        // 3.7 and 4.4 km/h: the double supports; 3.0 km/h: two files, a step asymmetry no
        // swing asymmetry backs.
        let want = if run == "PWS-20" {
            WarningCode::TwoClocks
        } else {
            WarningCode::ClockOffset
        };
        if !fired || !res.warnings.iter().any(|w| w.code == want) {
            missed.push(run);
            continue;
        }
        // Between-leg timings withheld with the reason, each leg's own kept.
        for leg in [&res.left, &res.right] {
            let p = &leg.as_ref().unwrap().parameters;
            for q in [Parameter::StepTime, Parameter::DoubleSupport] {
                assert!(p[q].is_nan(), "{run}: {q:?}");
                assert_eq!(
                    p.withheld.get(q).map(|r| r.code.clone()),
                    Some(ReasonCode::Finding(want)),
                    "{run}"
                );
            }
            assert!(p[Parameter::StrideTime].is_finite() && p[Parameter::StanceRatio].is_finite());
        }
    }
    println!("threshold: smaller double support ≤ {MIN_DS_SHARE} of their sum; two files: a step-time difference more than {MAX_UNBACKED_STEP_SHARE} of the stride beyond what the swing backs");
    assert!(false_flags.is_empty(), "{false_flags:?}");
    assert!(missed.is_empty(), "TRIPOD runs not flagged: {missed:?}");
}
