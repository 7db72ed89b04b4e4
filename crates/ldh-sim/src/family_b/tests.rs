use super::*;
use ldh_core::recording::STANDARD_GRAVITY_MPS2;

fn subject(group: Group, setting: Setting, speed: Option<f64>, seed: u64) -> SimSubject {
    let c = CohortParamsB {
        healthy: usize::from(group == Group::Healthy),
        patients: usize::from(group == Group::Ldh),
        seed,
        speed_mps: speed,
        setting: Some(setting),
        sensor: SensorModelB::ideal(),
        ..CohortParamsB::default()
    };
    c.simulate(0).unwrap()
}

#[test]
fn gravity_only_while_standing() {
    let s = subject(Group::Healthy, Setting::Overground, None, 3);
    for leg in [&s.left, &s.right] {
        for i in [5, 50, 150] {
            let a = &leg.dense.acc_clean_g;
            let norm = (a[0][i].powi(2) + a[1][i].powi(2) + a[2][i].powi(2)).sqrt();
            assert!((norm - 1.0).abs() < 1e-6, "|a| = {norm}");
            for k in 0..3 {
                assert!(leg.dense.gyro_clean_dps[k][i].abs() < 1e-6);
            }
        }
    }
}

/// The accelerometer is the second derivative of the sensor position plus gravity, and the
/// gyroscope the body rate of R_wd: both checked against the dense truth by finite differences.
#[test]
fn signals_are_the_derivatives_of_the_dense_kinematics() {
    for (setting, seed) in [(Setting::Overground, 5), (Setting::Treadmill, 6)] {
        // Without the heel-strike wobble (14–22 Hz: a 100 Hz finite difference cannot follow it).
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let sensor = SensorModelB::ideal();
        let mut p = SubjectParamsB::draw(
            "T",
            Group::Healthy,
            1000.0,
            30.0,
            None,
            setting,
            &sensor,
            &mut rng,
        );
        p.left.hs_transient_mm = 0.0;
        p.right.hs_transient_mm = 0.0;
        p.left.hs_transient_rot_deg = 0.0;
        p.right.hs_transient_rot_deg = 0.0;
        let s = simulate_subject_b(&p, &sensor, &mut rng).unwrap();
        let fs = s.params.fs_hz;
        for leg in [&s.left, &s.right] {
            let d = &leg.dense;
            let n = d.sensor_pos_m[0].len();
            let mut worst_a: f64 = 0.0;
            let mut worst_w: f64 = 0.0;
            let events: Vec<f64> = leg
                .truth
                .hs_times_s
                .iter()
                .chain(leg.truth.to_times_s.iter())
                .copied()
                .collect();
            for i in 1..n - 1 {
                // The canonical-phase map is C¹ at toe off and heel strike: the angular
                // acceleration (and so the lever-arm acceleration) jumps there, which a central
                // difference straddling the event averages.
                if events.iter().any(|&e| (e - i as f64 / fs).abs() < 0.002) {
                    continue;
                }
                let r = nalgebra::Matrix3::from_fn(|a, b| d.r_world_device[i][a][b]);
                let f = nalgebra::Vector3::new(
                    d.acc_clean_g[0][i],
                    d.acc_clean_g[1][i],
                    d.acc_clean_g[2][i],
                ) * STANDARD_GRAVITY_MPS2;
                let a_w = r * f - nalgebra::Vector3::new(0.0, 0.0, STANDARD_GRAVITY_MPS2);
                for k in 0..3 {
                    let fd = (d.sensor_vel_mps[k][i + 1] - d.sensor_vel_mps[k][i - 1]) * fs / 2.0;
                    worst_a = worst_a.max((fd - a_w[k]).abs());
                }
                let r0 = nalgebra::Matrix3::from_fn(|a, b| d.r_world_device[i - 1][a][b]);
                let r1 = nalgebra::Matrix3::from_fn(|a, b| d.r_world_device[i + 1][a][b]);
                let om = r.transpose() * (r1 - r0) * (fs / 2.0);
                let w = [om[(2, 1)], om[(0, 2)], om[(1, 0)]];
                for (wk, g) in w.iter().zip(&d.gyro_clean_dps) {
                    worst_w = worst_w.max((wk.to_degrees() - g[i]).abs());
                }
            }
            // 1 kHz central differences: O(h²) truncation only.
            assert!(worst_a < 0.05, "{setting:?}: acc mismatch {worst_a} m/s²");
            assert!(worst_w < 0.5, "{setting:?}: gyro mismatch {worst_w} deg/s");
        }
    }
}

#[test]
fn events_and_strides_are_consistent() {
    for (group, setting, speed) in [
        (Group::Healthy, Setting::Overground, None),
        (Group::Ldh, Setting::Overground, Some(0.3)),
        (Group::Ldh, Setting::Treadmill, None),
    ] {
        let s = subject(group, setting, speed, 11);
        let p = s.family_b.as_ref().unwrap();
        for leg in [&s.left, &s.right] {
            let t = &leg.truth;
            assert!(t.strides.len() >= 4);
            for st in &t.strides {
                assert!(st.hs_time_s < st.to_time_s && st.to_time_s < st.next_hs_time_s);
                assert!(
                    (0.5..0.82).contains(&st.stance_ratio),
                    "{}",
                    st.stance_ratio
                );
                if !st.turning && !st.bout_edge {
                    let rel = st.stride_length_m / p.stride_length_m();
                    assert!((0.6..1.4).contains(&rel), "stride length {rel}");
                }
            }
            assert!(t.pitch_deg.iter().all(|x| x.abs() < 70.0));
        }
        if setting == Setting::Treadmill {
            assert!(s.left.truth.strides.iter().all(|x| !x.turning));
            assert!(s.left.truth.yaw_deg.iter().all(|&y| y == 0.0));
        }
    }
}

#[test]
fn slow_paretic_gait_is_slow() {
    let s = subject(Group::Ldh, Setting::Overground, Some(0.3), 2);
    let p = s.family_b.as_ref().unwrap();
    assert!(
        (1.6..2.35).contains(&p.stride_time_s),
        "{}",
        p.stride_time_s
    );
    let paretic = match p.affected_side.unwrap() {
        Side::Left => &s.left,
        Side::Right => &s.right,
    };
    let peak = paretic
        .dense
        .gyro_clean_dps
        .iter()
        .fold(0.0f64, |m, ch| ch.iter().fold(m, |m, x| m.max(x.abs())));
    assert!(peak < 200.0, "paretic peak {peak} deg/s");
}

#[test]
fn the_stance_foot_does_not_slip() {
    let s = subject(Group::Healthy, Setting::Overground, None, 8);
    let p = s.family_b.as_ref().unwrap();
    for leg in [&s.left, &s.right] {
        let t = &leg.truth;
        let lp = p.leg(t.side);
        let d = &leg.dense;
        for st in t.strides.iter().filter(|s| !s.turning) {
            // Mid foot flat: ankle at rest, so the sensor velocity is ω × r only.
            let tm =
                st.hs_time_s + (st.to_time_s - st.hs_time_s) * 0.5 * (lp.foot_flat + lp.heel_off);
            let i = (tm * p.fs_hz).round() as usize;
            let v = (0..3)
                .map(|k| d.sensor_vel_mps[k][i].powi(2))
                .sum::<f64>()
                .sqrt();
            let w = (0..3)
                .map(|k| d.gyro_clean_dps[k][i].to_radians().powi(2))
                .sum::<f64>()
                .sqrt();
            let lever = (lp.sensor_height_m.powi(2) + 0.06f64.powi(2)).sqrt() + 0.01;
            assert!(v <= w * lever + 1e-3, "v {v} > ω r {}", w * lever);
        }
    }
}

#[test]
fn same_seed_same_subject_and_family_parses() {
    let a = subject(Group::Healthy, Setting::Overground, None, 4);
    let b = subject(Group::Healthy, Setting::Overground, None, 4);
    assert_eq!(a.left.recording, b.left.recording);
    assert_eq!("B".parse::<Family>().unwrap(), Family::B);
    assert!("c".parse::<Family>().is_err());
    let j = serde_json::to_string(&a.truth()).unwrap();
    let back: crate::SubjectTruth = serde_json::from_str(&j).unwrap();
    assert!(back.family_b.is_some());
}
