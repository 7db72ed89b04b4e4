//! The monitor's stair rule (`ldh_core::monitor::stairs`) on the lab pipeline's strides:
//! simulated flights of stairs (family A with a rise, `SubjectParams::stair_rise_m`) are
//! stairs, up or down; simulated level walks, and real level walks (HuGaDB's 18 overground
//! walks, TRIPOD's three treadmill runs, when `../shared/realdata` is present; one line when
//! skipped), have at most 1 % of their strides rising or falling like a stair and no bout
//! labelled stairs.
//!
//! `cargo test --profile ci -p ldh-sim --test analysis stairs -- --nocapture`

use super::real_data::real_walks;
use ldh_core::gait::Stride;
use ldh_core::monitor::{BoutKind, StairParams};
use ldh_core::pipeline::{Analysis, AnalysisParams, SubjectResult};
use ldh_sim::{analyze_simulated, simulate_subject, SensorModel, SubjectParams};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// The monitor's per-bout analysis: the defaults without STA.
fn params() -> AnalysisParams {
    AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    }
}

/// Both legs' strides of a result.
fn strides(r: &SubjectResult) -> Vec<&Stride> {
    [&r.left, &r.right]
        .into_iter()
        .filter_map(|l| l.as_ref().ok())
        .flat_map(|l| l.strides.iter())
        .collect()
}

/// A flight of stairs as the free-living simulator draws one (`free_living::plan`): slow short
/// strides, high clearance, more flexion, one riser of `rise_m` a step.
fn flight(id: &str, rise_m: f64, stride_time_s: f64) -> SubjectParams {
    let mut p = SubjectParams::healthy(id);
    p.duration_s = 22.0;
    p.turn = false;
    p.stride_time_s = stride_time_s;
    p.stride_length_m = 0.6;
    p.stair_rise_m = rise_m;
    for l in [&mut p.left, &mut p.right] {
        l.hip_scale = 1.35;
        l.knee_reduction = -0.25;
        l.swing_clearance_m = 0.18;
        l.stance_ratio = l.stance_ratio.max(0.64);
    }
    p
}

/// (stair strides, measured strides, verdict) of one simulated walk.
fn judged(p: &SubjectParams, seed: u64) -> (usize, usize, BoutKind, f64) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let s = simulate_subject(p, &SensorModel::default(), &mut rng).unwrap();
    let r = analyze_simulated(&s, &params());
    let v = StairParams::default().classify(strides(&r));
    (v.stair_strides, v.measured, v.kind, v.stride_rise_m)
}

#[test]
fn simulated_flights_are_stairs_and_level_walks_are_not() {
    let mut level = (0, 0);
    for (k, (rise, st)) in [(0.17, 1.25), (-0.17, 1.15), (0.15, 1.4), (-0.19, 1.1)]
        .into_iter()
        .enumerate()
    {
        let (n, m, kind, med) = judged(&flight("F", rise, st), 40 + k as u64);
        println!(
            "flight rise {rise:+.2} m, stride {st} s: {n} of {m} strides stair-like, median rise {med:+.3} m: {kind}"
        );
        assert_eq!(kind, BoutKind::Stairs, "rise {rise}");
        assert!(n as f64 >= 0.8 * m as f64, "{n} of {m}");
        assert!((med - 2.0 * rise).abs() < 0.1, "median {med} for {rise}");
    }
    for (k, (st, sl)) in [(1.05, 1.36), (1.3, 1.0), (0.95, 1.5), (1.6, 0.7)]
        .into_iter()
        .enumerate()
    {
        let mut p = SubjectParams::healthy("L");
        (p.stride_time_s, p.stride_length_m) = (st, sl);
        let (n, m, kind, med) = judged(&p, 50 + k as u64);
        println!("level walk {st} s, {sl} m: {n} of {m} strides stair-like, median rise {med:+.3} m: {kind}");
        assert_eq!(kind, BoutKind::Walking);
        level = (level.0 + n, level.1 + m);
    }
    assert!(level.0 as f64 <= 0.01 * level.1 as f64, "{level:?}");
}

/// (stair strides, measured strides) of a real walk, printed.
fn real(name: &str, r: &SubjectResult) -> (usize, usize) {
    let all = strides(r);
    let v = StairParams::default().classify(all.iter().copied());
    println!(
        "{name}: {} of {} measured strides ({} in all) stair-like, median rise {:+.3} m: {}",
        v.stair_strides,
        v.measured,
        all.len(),
        v.stride_rise_m,
        v.kind
    );
    assert_eq!(v.kind, BoutKind::Walking, "{name}");
    (v.stair_strides, v.measured)
}

#[test]
fn real_level_walks_have_no_stairs() {
    let Some(walks) = real_walks() else {
        return;
    };
    let analysis = Analysis::new(params().check().unwrap());
    let mut total = (0, 0);
    for walk in &walks {
        let (n, m) = real(&walk.name(), &walk.analyse(&analysis));
        total = (total.0 + n, total.1 + m);
    }
    println!(
        "real level walks: {} of {} strides stair-like ({:.2} %)",
        total.0,
        total.1,
        100.0 * total.0 as f64 / total.1.max(1) as f64
    );
    assert!(total.1 > 1000, "{total:?}");
    assert!(total.0 as f64 <= 0.01 * total.1 as f64, "{total:?}");
}
