//! Physics and determinism tests of the simulator.

use super::*;
use ldh_core::io::{FormatSpec, WriteOptions};
use ldh_core::recording::{Side, STANDARD_GRAVITY_MPS2};

fn ideal_subject(fs_hz: f64, turn: bool) -> SimSubject {
    let mut p = SubjectParams::healthy("T01");
    p.fs_hz = fs_hz;
    p.turn = turn;
    p.duration_s = 22.0;
    let mut rng = CohortParams::default().rng(0);
    simulate_subject(&p, &SensorModel::ideal(), &mut rng).unwrap()
}

#[test]
fn one_g_along_the_shank_axis_at_rest() {
    let s = ideal_subject(100.0, true);
    for leg in [&s.left, &s.right] {
        let r = &leg.recording;
        for i in [10, 100, 250] {
            assert!(
                (r.acc_g[0][i] - 1.0).abs() < 1e-12,
                "acc_x {}",
                r.acc_g[0][i]
            );
            assert!(r.acc_g[1][i].abs() < 1e-12 && r.acc_g[2][i].abs() < 1e-12);
            for k in 0..3 {
                assert!(r.gyro_dps[k][i].abs() < 1e-12);
            }
        }
    }
    // With misalignment the direction changes, the magnitude does not.
    let mut rng = CohortParams::default().rng(3);
    let p = SubjectParams::healthy("T02");
    let sensor = SensorModel {
        noise: false,
        ..SensorModel::default()
    };
    let s = simulate_subject(&p, &sensor, &mut rng).unwrap();
    let r = &s.right.recording;
    let m = (r.acc_g[0][50].powi(2) + r.acc_g[1][50].powi(2) + r.acc_g[2][50].powi(2)).sqrt();
    assert!((m - 1.0).abs() < 1e-12, "|acc| at rest {m}");
    assert!(r.acc_g[0][50] > 0.95, "x still close to the shank axis");
}

/// Integrating the Euler-angle rates obtained from the gyroscope reproduces the true angles.
#[test]
fn integrated_gyro_equals_the_true_angles() {
    let fs = 1000.0;
    let s = ideal_subject(fs, true);
    for leg in [&s.left, &s.right] {
        let d = &leg.dense;
        let m = leg.truth.sensor.device_axes_in_f;
        let n = leg.recording.len();
        let rates = |i: usize| -> [f64; 3] {
            let wd = [
                d.gyro_clean_dps[0][i],
                d.gyro_clean_dps[1][i],
                d.gyro_clean_dps[2][i],
            ]
            .map(f64::to_radians);
            let w: [f64; 3] = std::array::from_fn(|a| (0..3).map(|b| m[a][b] * wd[b]).sum());
            let (phi, theta) = (d.euler_rad[0][i], d.euler_rad[1][i]);
            let (sp, cp, tt, ct) = (phi.sin(), phi.cos(), theta.tan(), theta.cos());
            [
                w[0] + sp * tt * w[1] + cp * tt * w[2],
                cp * w[1] - sp * w[2],
                (sp * w[1] + cp * w[2]) / ct,
            ]
        };
        let mut ang = [d.euler_rad[0][0], d.euler_rad[1][0], d.euler_rad[2][0]];
        let mut prev = rates(0);
        let mut max_err = 0.0f64;
        for i in 1..n {
            let r = rates(i);
            for k in 0..3 {
                ang[k] += 0.5 / fs * (prev[k] + r[k]);
                max_err = max_err.max((ang[k] - d.euler_rad[k][i]).abs().to_degrees());
            }
            prev = r;
        }
        assert!(
            max_err < 0.01,
            "{}: max angle error {max_err} deg",
            leg.truth.side
        );
    }
}

/// Rotating the accelerometer to the world, adding gravity back and integrating twice gives
/// the sensor's true displacement.
#[test]
fn double_integrated_acceleration_equals_the_displacement() {
    let fs = 1000.0;
    let s = ideal_subject(fs, true);
    for leg in [&s.left, &s.right] {
        let d = &leg.dense;
        let acc_w = |i: usize| -> [f64; 3] {
            let f = [
                d.acc_clean_g[0][i],
                d.acc_clean_g[1][i],
                d.acc_clean_g[2][i],
            ];
            let r = d.r_world_device[i];
            let mut a: [f64; 3] = std::array::from_fn(|k| {
                (0..3).map(|j| r[k][j] * f[j]).sum::<f64>() * STANDARD_GRAVITY_MPS2
            });
            a[2] -= STANDARD_GRAVITY_MPS2;
            a
        };
        // Over each stride and over the whole walk including the turn.
        let hs = &leg.truth.hs_times_s;
        let mut spans: Vec<(usize, usize)> = hs
            .windows(2)
            .map(|w| ((w[0] * fs) as usize, (w[1] * fs) as usize))
            .collect();
        spans.push((1000, leg.recording.len() - 1000));
        for (a, b) in spans {
            let mut v = [
                d.sensor_vel_mps[0][a],
                d.sensor_vel_mps[1][a],
                d.sensor_vel_mps[2][a],
            ];
            let mut p = [
                d.sensor_pos_m[0][a],
                d.sensor_pos_m[1][a],
                d.sensor_pos_m[2][a],
            ];
            let mut prev = acc_w(a);
            for i in a + 1..=b {
                let acc = acc_w(i);
                for k in 0..3 {
                    let v_new = v[k] + 0.5 / fs * (prev[k] + acc[k]);
                    p[k] += 0.5 / fs * (v[k] + v_new) + (prev[k] - acc[k]) / (12.0 * fs * fs);
                    v[k] = v_new;
                }
                prev = acc;
            }
            for k in 0..3 {
                let err = (p[k] - d.sensor_pos_m[k][b]).abs();
                let tol = 1e-3 + 1e-4 * (b - a) as f64 / fs;
                assert!(
                    err < tol,
                    "{} axis {k} samples {a}..{b}: position error {err} m",
                    leg.truth.side
                );
                assert!((v[k] - d.sensor_vel_mps[k][b]).abs() < 1e-3);
            }
        }
    }
}

#[test]
fn stride_truth_matches_the_parameters() {
    let s = ideal_subject(100.0, false);
    let p = &s.params;
    for leg in [&s.left, &s.right] {
        let t = &leg.truth;
        assert!(t.strides.len() >= 10, "{} strides", t.strides.len());
        // HS and TO alternate and increase.
        let mut ev: Vec<(f64, u8)> = t
            .hs_times_s
            .iter()
            .map(|&x| (x, 0))
            .chain(t.to_times_s.iter().map(|&x| (x, 1)))
            .collect();
        ev.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap());
        for w in ev.windows(2) {
            assert_ne!(w[0].1, w[1].1, "events alternate");
            assert!(w[1].0 > w[0].0);
        }
        let steady: Vec<&StrideTruth> = t
            .strides
            .iter()
            .filter(|s| !s.bout_edge && !s.turning)
            .collect();
        assert!(steady.len() >= 8);
        for st in &steady {
            assert!(
                (st.stride_time_s - p.stride_time_s).abs() < 0.1 * p.stride_time_s,
                "{st:?}"
            );
            assert!((st.stance_ratio - 0.60).abs() < 0.03, "{st:?}");
            assert!(
                (st.stride_length_m - p.stride_length_m).abs() < 0.1 * p.stride_length_m,
                "{st:?}"
            );
            assert!((44.0..56.0).contains(&st.max_pitch_deg), "{st:?}");
            assert!((-26.0..-16.0).contains(&st.min_pitch_deg), "{st:?}");
        }
    }
    // Both feet travel the same distance.
    let total = |leg: &SimLeg| {
        leg.truth
            .strides
            .iter()
            .map(|s| s.stride_length_m)
            .sum::<f64>()
    };
    let (l, r) = (total(&s.left), total(&s.right));
    assert!(l > 10.0 && r > 10.0, "{l} {r}");
    // The left starts at 0 and the right closes beside the left's last contact, so the sums
    // of stride lengths (left strides 1..N, right 2..N+1) differ by at most one step.
    assert!((l - r).abs() < 0.6 * s.params.stride_length_m, "{l} {r}");
}

#[test]
fn ldh_affected_side_differs_as_specified() {
    let c = CohortParams {
        healthy: 0,
        ldh: 1,
        turn: false,
        duration_s: 30.0,
        ..CohortParams::default()
    };
    let s = c.simulate(0).unwrap();
    let aff = s.params.affected_side.unwrap();
    let (a, u) = if aff == Side::Left {
        (&s.left, &s.right)
    } else {
        (&s.right, &s.left)
    };
    let mean = |leg: &SimLeg, f: fn(&StrideTruth) -> f64| {
        let v: Vec<f64> = leg
            .truth
            .strides
            .iter()
            .filter(|s| !s.bout_edge)
            .map(f)
            .collect();
        v.iter().sum::<f64>() / v.len() as f64
    };
    assert!(mean(a, |s| s.stance_ratio) > mean(u, |s| s.stance_ratio) + 0.01);
    assert!(mean(a, |s| s.max_pitch_deg) < mean(u, |s| s.max_pitch_deg) - 2.0);
    assert!(mean(a, |s| s.roll_swing_excursion_deg) > mean(u, |s| s.roll_swing_excursion_deg));
    // Equal mean stride length on both sides (same distance walked).
    let (la, lu) = (
        mean(a, |s| s.stride_length_m),
        mean(u, |s| s.stride_length_m),
    );
    assert!((la - lu).abs() < 0.03 * lu, "{la} vs {lu}");
}

#[test]
fn slow_ldh_subjects_are_slow_come_last_and_leave_the_others_unchanged() {
    let c = CohortParams {
        healthy: 1,
        ldh: 1,
        slow_ldh: 2,
        turn: false,
        duration_s: 30.0,
        ..CohortParams::default()
    };
    c.validate().unwrap();
    assert_eq!(c.len(), 4);
    let ids: Vec<String> = (0..4).map(|i| c.subject_id(i)).collect();
    assert_eq!(ids, ["H01", "L01", "S01", "S02"]);
    for i in 2..4 {
        let s = c.simulate(i).unwrap();
        assert_eq!(s.params.group, Group::Ldh);
        assert!((1.35..=2.0).contains(&s.params.stride_time_s));
        let speed = s.params.stride_length_m / s.params.stride_time_s;
        assert!((0.28..=0.75).contains(&speed), "{speed}");
        let steady: Vec<&StrideTruth> = s
            .left
            .truth
            .strides
            .iter()
            .filter(|s| !s.bout_edge)
            .collect();
        assert!(steady.len() >= 4, "{}", steady.len());
        assert!(steady.iter().all(|s| s.stance_ratio > 0.6));
    }
    // Adding slow subjects draws nothing from the others' random streams.
    let plain = CohortParams {
        slow_ldh: 0,
        ..c.clone()
    };
    let fmt = FormatSpec::default();
    let csv = |c: &CohortParams, i| {
        ldh_core::io::recording_to_csv(
            &c.simulate(i).unwrap().left.recording,
            &fmt,
            &WriteOptions::default(),
        )
        .unwrap()
    };
    assert_eq!(csv(&c, 1), csv(&plain, 1));
    // … and the slow subjects do not depend on how many others there are.
    let only_slow = CohortParams {
        healthy: 0,
        ldh: 0,
        ..c.clone()
    };
    assert_eq!(only_slow.subject_id(1), "S02");
    assert_eq!(csv(&c, 3), csv(&only_slow, 1));
    // A cohort without slow subjects writes the same parameters as before the option existed.
    let json = serde_json::to_string(&plain).unwrap();
    assert!(!json.contains("slow_ldh"), "{json}");
    let short = CohortParams {
        duration_s: 16.0,
        ..c
    };
    assert!(short.validate().unwrap_err().to_string().contains("20 s"));
}

#[test]
fn the_right_sensor_is_mirrored_and_the_sagittal_gyro_flips_sign() {
    let c = CohortParams {
        healthy: 1,
        ldh: 0,
        sensor: SensorModel {
            noise: false,
            axial_misalignment_deg_max: 0.0,
            tilt_misalignment_deg_sd: 0.0,
            ..SensorModel::default()
        },
        ..CohortParams::default()
    };
    let s = c.simulate(0).unwrap();
    let min = |v: &[f64]| v.iter().cloned().fold(f64::MAX, f64::min);
    // Mid-swing: the foot swings forward, so θ falls fast (θ̇ ≪ 0 about +e2, the left's z axis).
    assert!(min(&s.left.recording.gyro_dps[2]) < -300.0);
    let neg: Vec<f64> = s.right.recording.gyro_dps[2].iter().map(|v| -v).collect();
    assert!(min(&neg) < -300.0);
}

#[test]
fn same_seed_same_bytes_and_other_seed_other_bytes() {
    let c = CohortParams {
        healthy: 1,
        ldh: 1,
        duration_s: 12.0,
        ..CohortParams::default()
    };
    let fmt = FormatSpec::default();
    let csv = |c: &CohortParams, i| {
        ldh_core::io::recording_to_csv(
            &c.simulate(i).unwrap().left.recording,
            &fmt,
            &WriteOptions::default(),
        )
        .unwrap()
    };
    assert_eq!(csv(&c, 1), csv(&c, 1));
    let other = CohortParams {
        seed: 2,
        ..c.clone()
    };
    assert_ne!(csv(&c, 1), csv(&other, 1));
}

#[test]
fn saturation_is_applied_and_flagged() {
    let mut p = SubjectParams::healthy("S01");
    p.duration_s = 12.0;
    let sensor = SensorModel::default()
        .acc_range_g(1.5)
        .gyro_range_dps(250.0);
    let mut rng = CohortParams::default().rng(0);
    let s = simulate_subject(&p, &sensor, &mut rng).unwrap();
    let r = &s.left.recording;
    assert!(r.saturated_count() > 10);
    assert_eq!(r.saturated_count(), s.left.truth.sensor.saturated_samples);
    assert!(r.gyro_dps.iter().flatten().all(|v| v.abs() <= 250.0));
    // One mask per sensor, as the reader gives: each sensor clipped on its own samples, and
    // the combined mask is their union.
    let (a, g) = (&r.acc_saturated, &r.gyro_saturated);
    assert_eq!((a.len(), g.len()), (r.len(), r.len()));
    assert!(a.iter().any(|&x| x) && g.iter().any(|&x| x));
    assert!(
        a.iter().zip(g).any(|(a, g)| a != g),
        "the sensors clip apart"
    );
    for i in 0..r.len() {
        assert_eq!(r.saturated[i], a[i] || g[i]);
        let at_range = |ch: &[Vec<f64>; 3], range: f64| ch.iter().any(|c| c[i].abs() >= range);
        assert_eq!(a[i], at_range(&r.acc_g, 1.5), "acc sample {i}");
    }
}

#[test]
fn rejects_impossible_parameters() {
    let mut p = SubjectParams::healthy("X");
    p.duration_s = 8.0;
    let mut rng = CohortParams::default().rng(0);
    let e = simulate_subject(&p, &SensorModel::default(), &mut rng).unwrap_err();
    assert!(e.to_string().contains("duration_s"), "{e}");
    p.duration_s = 20.0;
    p.left.stance_ratio = 0.9;
    assert!(simulate_subject(&p, &SensorModel::default(), &mut rng)
        .unwrap_err()
        .to_string()
        .contains("stance_ratio"));
}

#[test]
fn sizes_beyond_the_declared_limits_are_refused_with_exact_arithmetic() {
    let big = CohortParams {
        duration_s: 86_400.0,
        fs_hz: 2000.0,
        ..CohortParams::default()
    };
    let e = big.validate().unwrap_err().to_string();
    assert!(
        e.contains("at most 1000000 samples (500 s at 2000.0 Hz)"),
        "{e}"
    );
    let overflow = CohortParams {
        healthy: usize::MAX,
        ldh: 1,
        ..CohortParams::default()
    };
    assert_eq!(overflow.len(), usize::MAX, "saturates instead of wrapping");
    let e = overflow.validate().unwrap_err().to_string();
    assert!(e.contains("at most 100000 subjects"), "{e}");
    // At the limits: accepted.
    assert!(check_size(100_000, 0, 10_000.0, 100.0).is_ok());
    assert!(check_size(100_000, 1, 25.0, 100.0).is_err());
    assert!(check_samples(10_000.1, 100.0).is_err());
    assert!(check_samples(f64::NAN, 100.0).is_err());
    let mut p = SubjectParams::healthy("X");
    p.duration_s = 20_000.0;
    assert!(p
        .validate()
        .unwrap_err()
        .to_string()
        .contains("1000000 samples"));
}
