//! Tests of the stride-length integration and its checks.

use super::*;
use crate::align::Alignment;
use crate::attitude::AttitudeModel;

/// A level 1 s stride at 100 Hz, shank upright and not rotating (the sensor moves with the
/// ankle): forward velocity 2 sin²(π t) m/s (1.00 m), with `lost` m/s of forward
/// acceleration missing, evenly over the samples `run`, which are marked clipped.
fn stride(run: std::ops::Range<usize>, lost: f64) -> (Aligned, Attitude) {
    let (fs, n) = (100.0, 101);
    let ax: Vec<f64> = (0..n)
        .map(|i| {
            let t = i as f64 / fs;
            let a = 2.0 * std::f64::consts::PI * (2.0 * std::f64::consts::PI * t).sin();
            let cut = if run.contains(&i) {
                lost * fs / run.len() as f64
            } else {
                0.0
            };
            (a - cut) / STANDARD_GRAVITY_MPS2
        })
        .collect();
    let al = Aligned {
        fs_hz: fs,
        acc_g: [ax, vec![0.0; n], vec![1.0; n]],
        gyro_dps: [vec![0.0; n], vec![0.0; n], vec![0.0; n]],
        acc_clipped: run.collect(),
        acc_motion_g: None,
        alignment: Alignment::identity(),
    };
    let att = Attitude {
        model: AttitudeModel::Fusion,
        fs_hz: fs,
        roll_deg: vec![0.0; n],
        pitch_deg: vec![0.0; n],
        yaw_deg: vec![0.0; n],
        final_weights: vec![],
        final_tilt_noise_deg: vec![],
        gyro_bias_dps: [0.0; 2],
        gravity_windows: 0,
    };
    (al, att)
}

/// What a reconstruction of clipped samples misses is a step in velocity at a known time:
/// linear de-drifting leaves drift × duration × (φ − ½) of it in the length, which is
/// exactly what `clip_step_m` bounds, and the stride is withheld when that exceeds 15 %.
#[test]
fn a_step_left_at_the_clipped_samples_is_bounded_and_withheld_when_large() {
    let est = |run, lost| {
        let (al, att) = stride(run, lost);
        stride_length(&al, &att, 0, 100, 0.1)
    };
    // Fully reconstructed (nothing lost): the length, no drift, no bound.
    let e = est(88..97, 0.0);
    assert!((e.length_m - 1.0).abs() < 2e-3, "{}", e.length_m);
    assert!(e.clip_step_m < 1e-3 && e.clipped_samples == 9);
    assert_eq!(e.implausible(f64::NAN), None);
    // 0.5 m/s lost in terminal swing (φ = 0.92): 0.21 m too long. The tilt correction takes
    // the drift for a 2.9° tilt and removes it, but then the ankle ends δ·L = 6 cm off the
    // floor, which says the 0.5 m/s were not a tilt: unexplained, and the step bound says
    // 0.21 m = 17 %: withheld.
    let e = est(88..97, 0.5);
    let expected = 0.5 * 1.0 * (0.92 - 0.5);
    assert!((e.length_m - 1.0 - expected).abs() < 3e-3, "{}", e.length_m);
    assert!((e.clip_step_m - expected).abs() < 5e-3, "{}", e.clip_step_m);
    assert!((e.tilt_deg - 0.5f64.atan2(STANDARD_GRAVITY_MPS2).to_degrees()).abs() < 0.05);
    assert!(e.drift_mps < 0.02, "{}", e.drift_mps); // |S| vs g T: vertical
    assert!(
        (e.unexplained_mps - 0.5).abs() < 0.01,
        "{}",
        e.unexplained_mps
    );
    assert!(
        (e.vertical_m.abs() - 0.062).abs() < 3e-3,
        "{}",
        e.vertical_m
    );
    let r = e.implausible(f64::NAN).unwrap();
    assert!(
        r.contains("clipped on 9 samples") && r.contains("21 cm (17 % of the 1.21 m stride)"),
        "{r}"
    );
    // The same loss in early swing (φ = 0.66): 0.08 m (7 %), reported.
    let e = est(62..71, 0.5);
    assert!(
        (e.length_m - 1.0 - 0.5 * 0.16).abs() < 3e-3,
        "{}",
        e.length_m
    );
    assert_eq!(e.implausible(f64::NAN), None);
}

/// An attitude whose pitch and roll are off by 5° and 3° over the whole stride (a foot-flat
/// anchor read while the sensor accelerated) leaks g·sin δ into the horizontal: 1.0 m/s of
/// drift at the next mid-stance, withheld before. The tilt correction recovers the 5.8° tilt,
/// leaves no drift and no floor-level miss, and the length stays the true 1.00 m.
#[test]
fn a_tilted_attitude_is_corrected_from_the_velocity_at_the_next_mid_stance() {
    let (al, mut att) = stride(0..0, 0.0);
    att.pitch_deg.iter_mut().for_each(|p| *p = -5.0);
    att.roll_deg.iter_mut().for_each(|r| *r = 3.0);
    let e = stride_length(&al, &att, 0, 100, 0.1);
    let tilt = (5f64.to_radians().cos() * 3f64.to_radians().cos()).acos();
    assert!(
        (e.tilt_deg - tilt.to_degrees()).abs() < 0.01,
        "{}",
        e.tilt_deg
    );
    assert!((e.length_m - 1.0).abs() < 2e-3, "{}", e.length_m);
    assert!(e.drift_mps < 1e-3 && e.unexplained_mps < 5e-3, "{e:?}");
    assert!(e.vertical_m.abs() < 5e-3, "{}", e.vertical_m);
    assert_eq!(e.implausible(f64::NAN), None);
    // Without the correction the drift would be g·sin δ over the 1 s stride: withheld.
    assert!(tilt.sin() * STANDARD_GRAVITY_MPS2 > MAX_DRIFT_MPS + 0.3);
    // A larger tilt than a shank pivoting over a resting foot can produce is withheld.
    att.pitch_deg.iter_mut().for_each(|p| *p = -25.0);
    let e = stride_length(&al, &att, 0, 100, 0.1);
    let r = e.implausible(f64::NAN).unwrap();
    assert!(r.contains("25 deg tilt correction"), "{r}");
}

#[test]
fn pendulum_estimate_of_a_normal_stride() {
    // θ from −20° at HS to +40° at TO over 60 % of the stride: ≈ 1.0 m.
    let l = pendulum_length_m(-20.0, 40.0, 0.6);
    assert!(
        (l - 1.7 * 0.43 * (0.6428 + 0.3420) / 0.6).abs() < 1e-3,
        "{l}"
    );
    assert!(pendulum_length_m(0.0, 10.0, 0.1).is_nan());
}

#[test]
fn implausible_lengths_say_why() {
    let ok = LengthEstimate {
        length_m: 1.3,
        drift_mps: 0.1,
        unexplained_mps: 0.1,
        tilt_deg: 4.0,
        vertical_m: 0.01,
        clipped_samples: 0,
        clip_step_m: 0.0,
    };
    assert_eq!(ok.implausible(1.1), None);
    assert_eq!(ok.implausible(f64::NAN), None);
    let r = ok.implausible(0.4).unwrap();
    assert!(r.contains("shank-pendulum"), "{r}");
    let drift = LengthEstimate {
        drift_mps: 1.5,
        ..ok
    };
    assert!(drift.implausible(1.1).unwrap().contains("drift"));
    let hidden = LengthEstimate {
        unexplained_mps: 0.7,
        ..ok
    };
    let r = hidden.implausible(1.1).unwrap();
    assert!(
        r.contains("0.70 m/s") && r.contains("does not explain"),
        "{r}"
    );
    // 11 cm off the floor: withheld on a 0.59 m stride (19 %), not on a 1.3 m one (8 %).
    let slow = LengthEstimate {
        length_m: 0.59,
        vertical_m: 0.11,
        ..ok
    };
    let r = slow.implausible(0.6).unwrap();
    assert!(
        r.contains("11 cm off the floor level (19 % of the 0.59 m stride)"),
        "{r}"
    );
    let brisk = LengthEstimate {
        vertical_m: -0.11,
        ..ok
    };
    assert_eq!(brisk.implausible(1.1), None);
    let up = LengthEstimate {
        vertical_m: 0.3,
        ..ok
    };
    assert!(up.implausible(1.1).unwrap().contains("floor"));
    // Clipped and reconstructed: reported unless the drift left, as a step at a clipped
    // run, could move the ankle by more than 15 % of the length.
    let clipped = LengthEstimate {
        clipped_samples: 3,
        clip_step_m: 0.15,
        ..ok
    };
    assert_eq!(clipped.implausible(1.1), None);
    let step = LengthEstimate {
        clip_step_m: 0.21,
        ..clipped
    };
    let r = step.implausible(1.1).unwrap();
    assert!(
        r.contains("clipped on 3 samples") && r.contains("21 cm (16 % of the 1.30 m stride)"),
        "{r}"
    );
    assert_eq!(clipped_between(&[2, 5, 9, 12], 5, 9), &[5, 9]);
    assert!(clipped_between(&[2, 5, 9, 12], 6, 8).is_empty());
    assert!(clipped_between(&[], 0, 100).is_empty());
    // runs centred at 20 % and 85 % of a 100-sample integration: the later one is worse
    assert!((worst_step_share(&[29, 30, 31, 94, 95, 96], 10, 110) - 0.35).abs() < 1e-12);
    assert_eq!(worst_step_share(&[], 10, 110), 0.0);
    assert_eq!(
        "min-gyro".parse::<ZeroVelocity>().unwrap(),
        ZeroVelocity::MinGyro
    );
    assert!("x".parse::<ZeroVelocity>().is_err());
}
