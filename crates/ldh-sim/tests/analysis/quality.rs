//! The quality layer on the simulator and on synthetic strides (the HuGaDB checks are in
//! `tests/hugadb.rs`).

use ldh_core::domain::Parameter;
use ldh_core::pipeline::quality::*;

/// Both devices turned by `deg` about the shank axis (the device x axis): the mounting of real
/// sensors strapped on at any angle (stroke trials: 50-70°).
fn rotated_about_shank(
    rec: &ldh_core::recording::Recording,
    deg: f64,
) -> ldh_core::recording::Recording {
    let (s, c) = deg.to_radians().sin_cos();
    let rot = |v: &[Vec<f64>; 3]| -> [Vec<f64>; 3] {
        let y = v[1].iter().zip(&v[2]).map(|(y, z)| c * y - s * z).collect();
        let z = v[1].iter().zip(&v[2]).map(|(y, z)| s * y + c * z).collect();
        [v[0].clone(), y, z]
    };
    let mut out = rec.clone();
    out.acc_g = rot(&rec.acc_g);
    out.gyro_dps = rot(&rec.gyro_dps);
    out
}

#[test]
fn sensors_rotated_about_the_shank_never_look_swapped() {
    let c = ldh_sim::CohortParams {
        healthy: 1,
        ldh: 0,
        duration_s: 25.0,
        seed: 11,
        ..ldh_sim::CohortParams::default()
    };
    let mut sub = c.simulate(0).unwrap();
    let (l0, r0) = (sub.left.recording.clone(), sub.right.recording.clone());
    let params = without_sta();
    let mut failures = Vec::new();
    for k in 0..12 {
        let deg = 30.0 * k as f64;
        sub.left.recording = rotated_about_shank(&l0, deg);
        sub.right.recording = rotated_about_shank(&r0, deg);
        let res = ldh_sim::analyze_simulated(&sub, &params);
        let mut all: Vec<Warning> = res.warnings.clone();
        for (side, leg) in res.legs() {
            let Ok(leg) = leg else {
                failures.push(format!("{deg} deg {side}: failed"));
                continue;
            };
            if leg.parameters.strides_valid < 5 || !leg.parameters[Parameter::Wqk].is_finite() {
                failures.push(format!(
                    "{deg} deg {side}: not analysed: {:?}",
                    leg.warnings
                ));
            }
            all.extend(leg.warnings.iter().cloned());
        }
        for w in &all {
            // A turn of 180° makes identical lateral devices face inward, as exchanged files
            // do: only with both faces more than MEDIAL_FACE_DEG inward may the swap appear.
            let inward = (deg - 180.0).abs() < 90.0 - MEDIAL_FACE_DEG;
            let swap_ok = w.code == codes::POSSIBLE_SWAP && inward;
            if [codes::POSSIBLE_SWAP, codes::RUNNING, codes::UPSIDE_DOWN].contains(&w.code)
                && !swap_ok
            {
                failures.push(format!("{deg} deg: false {}: {}", w.code, w.message));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Issue 50: a manifest that names the right leg's file as left. Identical devices worn
/// laterally (family A's right device mirrored) with the files exchanged: the swap warning, on
/// every subject of a cohort; with the files as recorded: none.
#[test]
fn exchanged_files_are_warned_about() {
    let c = ldh_sim::CohortParams {
        healthy: 3,
        ldh: 3,
        duration_s: 25.0,
        seed: 50,
        ..ldh_sim::CohortParams::default()
    };
    for i in 0..c.len() {
        let mut sub = c.simulate(i).unwrap();
        let swap = |res: &ldh_core::pipeline::SubjectResult| {
            res.warnings
                .iter()
                .find(|w| w.code == codes::POSSIBLE_SWAP)
                .cloned()
        };
        let id = sub.params.subject_id.clone();
        assert!(
            swap(&ldh_sim::analyze_simulated(&sub, &without_sta())).is_none(),
            "{id}"
        );
        let (l, r) = (sub.left.recording.clone(), sub.right.recording.clone());
        sub.left.recording = r.with_side(ldh_core::recording::Side::Left);
        sub.right.recording = l.with_side(ldh_core::recording::Side::Right);
        let w = swap(&ldh_sim::analyze_simulated(&sub, &without_sta()));
        let w = w.unwrap_or_else(|| panic!("{id}: no swap warning"));
        assert_eq!(w.severity, Severity::Warning);
        assert!(w.message.contains("may be swapped"), "{}", w.message);
    }
}

fn stride(i: usize, t: f64, stance: f64) -> ldh_core::gait::Stride {
    ldh_core::gait::Stride {
        stride_index: i,
        hs_time_s: i as f64 * t,
        to_time_s: i as f64 * t + stance * t,
        next_hs_time_s: (i + 1) as f64 * t,
        stride_time_s: t,
        stance_ratio: stance,
        double_support_ratio: f64::NAN,
        stride_length_m: 1.4,
        speed_mps: 1.4 / t,
        wqk_deg: 40.0,
        pbi_deg: 20.0,
        bdk_deg: 8.0,
        heading_change_deg: 0.0,
        bout: 0,
        valid: true,
        reason: String::new(),
        findings: Vec::new(),
        vertical_m: f64::NAN,
    }
}

fn codes_of(t: f64, stance: f64) -> Vec<ldh_core::pipeline::quality::WarningCode> {
    let st: Vec<ldh_core::gait::Stride> = (0..20).map(|i| stride(i, t, stance)).collect();
    let p = ldh_core::gait::side_parameters(&st, None);
    let al = ldh_core::align::Alignment {
        shank_axis_tilt_deg: 3.0,
        sagittal_variance_share: 0.9,
        ..ldh_core::align::Alignment::identity()
    };
    leg_warnings(&al, &st, &p, 100.0)
        .into_iter()
        .map(|w| w.code)
        .collect()
}

#[test]
fn running_needs_a_flight_phase_and_brisk_walking_is_walking() {
    // Brisk walking: 0.79-0.8 s strides (150 steps/min), 60 % stance.
    assert!(codes_of(0.8, 0.60).is_empty(), "{:?}", codes_of(0.8, 0.60));
    assert!(codes_of(0.79, 0.60).is_empty());
    assert!(codes_of(0.72, 0.58).is_empty());
    // Running: a flight phase (35 % stance), at any cadence.
    assert_eq!(codes_of(0.7, 0.35), vec![codes::RUNNING]);
    assert_eq!(codes_of(0.9, 0.40), vec![codes::RUNNING]);
    // 0.6 s strides with 60 % stance: no gait; the time base is wrong.
    assert_eq!(
        codes_of(0.6, 0.60),
        vec![codes::IMPLAUSIBLE_CADENCE_FOR_RATE]
    );
}

/// The samples `a..b` of a recording (a walk with its standing cut off).
fn samples(
    rec: &ldh_core::recording::Recording,
    a: usize,
    b: usize,
) -> ldh_core::recording::Recording {
    let cut = |v: &[Vec<f64>; 3]| -> [Vec<f64>; 3] {
        [
            v[0][a..b].to_vec(),
            v[1][a..b].to_vec(),
            v[2][a..b].to_vec(),
        ]
    };
    ldh_core::recording::Recording::new(rec.fs_hz, cut(&rec.acc_g), cut(&rec.gyro_dps), vec![])
        .unwrap()
}

/// Issue 37: the same simulated walk without its quiet standing moved WQK and PBI by 9-12°
/// with no warning. Now the leg says so (`no_quiet_standing`) and withholds both; BDK and the
/// stride parameters stay. A standing window longer than the recording is named.
#[test]
fn a_walk_without_quiet_standing_withholds_its_inclinations() {
    let c = ldh_sim::CohortParams {
        healthy: 1,
        ldh: 0,
        duration_s: 30.0,
        seed: 11,
        ..ldh_sim::CohortParams::default()
    };
    let rec = c.simulate(0).unwrap().left.recording;
    let params = without_sta();
    let side = ldh_core::recording::Side::Left;
    let full = ldh_core::pipeline::Analysis::new(params.check().unwrap())
        .leg(&rec, side, Some(0.1))
        .unwrap()
        .leg;
    assert!(
        full.parameters[Parameter::Wqk].is_finite() && full.parameters[Parameter::Pbi].is_finite()
    );
    assert!(full
        .warnings
        .iter()
        .all(|w| w.code != codes::NO_QUIET_STANDING));
    // 3 s of standing at each end (family A): keep 3.5 s .. end - 3.5 s
    let fs = rec.fs_hz as usize;
    let n = rec.acc_g[0].len();
    let walk = samples(&rec, 7 * fs / 2, n - 7 * fs / 2);
    let cut = ldh_core::pipeline::Analysis::new(params.check().unwrap())
        .leg(&walk, side, Some(0.1))
        .unwrap()
        .leg;
    let w = cut
        .warnings
        .iter()
        .find(|w| w.code == codes::NO_QUIET_STANDING)
        .expect("no_quiet_standing");
    assert_eq!(w.severity, Severity::Warning);
    assert_eq!(w.affects, params::INCLINATIONS);
    let p = &cut.parameters;
    assert!(p[Parameter::Wqk].is_nan() && p[Parameter::Pbi].is_nan());
    assert!(
        p.withheld
            .reason(ldh_core::domain::Parameter::Wqk)
            .unwrap()
            .starts_with("no quiet standing"),
        "{:?}",
        p.withheld
    );
    assert!(p[Parameter::Bdk].is_finite() && p[Parameter::StrideTime].is_finite());
    assert!(cut.strides.iter().all(|s| s.wqk_deg.is_nan()));
    // A standing window longer than the recording finds none, and says which parameter.
    let mut long = params.clone();
    long.align.min_still_s = 30.0;
    let l = ldh_core::pipeline::Analysis::new(long.check().unwrap())
        .leg(&walk, side, Some(0.1))
        .unwrap()
        .leg;
    let w = l
        .warnings
        .iter()
        .find(|w| w.code == codes::NO_QUIET_STANDING)
        .expect("no_quiet_standing");
    assert!(
        w.message
            .contains("align.min_still_s = 30 s is longer than the"),
        "{}",
        w.message
    );
}

/// Issue 37: absurd analysis parameters are refused with the name, value and range.
#[test]
fn absurd_windows_and_cutoffs_are_refused_with_their_range() {
    let refused = |f: &dyn Fn(&mut ldh_core::pipeline::AnalysisParams), name: &str| {
        let mut p = ldh_core::pipeline::AnalysisParams::default();
        f(&mut p);
        let e = p.check().unwrap_err().to_string();
        assert!(e.contains(name) && e.contains("range"), "{name}: {e}");
    };
    refused(&|p| p.align.min_still_s = 320.0, "align.min_still_s = 320");
    refused(
        &|p| p.align.still_window_s = 320.0,
        "align.still_window_s = 320",
    );
    refused(&|p| p.align.still_window_s = 0.01, "align.still_window_s");
    refused(&|p| p.align.still_gyro_dps = 500.0, "align.still_gyro_dps");
    refused(
        &|p| p.align.walking_gyro_dps = 5000.0,
        "align.walking_gyro_dps",
    );
    refused(
        &|p| p.attitude.anchor_window_s = 30.0,
        "attitude.anchor_window_s",
    );
    refused(&|p| p.attitude.reacquire_s = 600.0, "attitude.reacquire_s");
    refused(
        &|p| p.attitude.acc_only_cutoff_hz = 0.001,
        "attitude.acc_only_cutoff_hz",
    );
    refused(
        &|p| p.preprocess.cutoff_hz = 0.1,
        "preprocess.cutoff_hz = 0.1",
    );
    refused(
        &|p| p.events.min_midswing_dps = 5000.0,
        "events.min_midswing_dps",
    );
    let e = ldh_core::gait::check_stride_range(0.7, 300.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("max_stride_s") && e.contains("<= 10 s"), "{e}");
    assert!(ldh_core::pipeline::AnalysisParams::default()
        .check()
        .is_ok());
}

/// The default analysis without STA (the checks here do not need it).
fn without_sta() -> ldh_core::pipeline::AnalysisParams {
    ldh_core::pipeline::AnalysisParams {
        compute_sta: false,
        ..ldh_core::pipeline::AnalysisParams::default()
    }
}
