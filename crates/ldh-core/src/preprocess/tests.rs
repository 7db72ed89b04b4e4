//! Preprocessing against numpy/scipy (`data-fixtures/golden/preprocess/`), parameter and
//! length errors, interpolation edges, and filter properties.

use super::*;
use crate::io::{read_recording, ReadParams};
use proptest::prelude::*;
use serde_json::Value;

const EXPECTED: &str = include_str!("../../../../data-fixtures/golden/preprocess/expected.json");

fn golden() -> Value {
    serde_json::from_str(EXPECTED).unwrap()
}

fn vec_of(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Largest |a − b| / (|b| + 1e-3 · max|b|): relative, with a floor at the channel's scale
/// so zero crossings do not divide by ~0.
fn max_rel_err(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / (y.abs() + 1e-3 * scale))
        .fold(0.0, f64::max)
}

#[test]
fn preprocessing_equals_numpy_and_scipy() {
    let g = golden();
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data-fixtures/golden/preprocess/input.csv"
    );
    let (rec, _) = read_recording(path, None, &ReadParams::default().check().unwrap()).unwrap();
    assert!((rec.fs_hz - g["fs_hz"].as_f64().unwrap()).abs() < 1e-9);
    let p = PreprocessParams::default()
        .outlier_channels(OutlierChannels::All)
        .check(rec.fs_hz)
        .unwrap();
    // The filter design equals scipy.signal.butter(…, output="sos").
    let sos_ref = g["sos"].as_array().unwrap();
    for (s, r) in p.sos.iter().zip(sos_ref) {
        let r = vec_of(r);
        let ours = [s.b[0], s.b[1], s.b[2], s.a[0], s.a[1], s.a[2]];
        assert!(max_rel_err(&ours, &r) < 1e-12, "{ours:?} vs {r:?}");
    }
    let out = preprocess(&rec, &p).unwrap();
    let outliers: Vec<usize> = g["outliers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap() as usize)
        .collect();
    assert_eq!(out.replaced, outliers);
    assert!((out.raw_norm_mean_g - g["norm_mean_g"].as_f64().unwrap()).abs() < 1e-12);
    assert!((out.raw_norm_sd_g - g["norm_sd_g"].as_f64().unwrap()).abs() < 1e-12);
    let names = ["acc_x", "acc_y", "acc_z", "gyro_x", "gyro_y", "gyro_z"];
    for (k, name) in names.iter().enumerate() {
        let ours = if k < 3 {
            &out.acc_g[k]
        } else {
            &out.gyro_dps[k - 3]
        };
        let err = max_rel_err(ours, &vec_of(&g["filtered"][name]));
        eprintln!("{name}: max relative error vs scipy {err:e}");
        assert!(err < 1e-9, "{name}: relative error {err:e}");
    }
    let err = max_rel_err(&out.acc_norm_g, &vec_of(&g["filtered_norm_g"]));
    assert!(err < 1e-9, "norm: {err:e}");
    // The default replaces acceleration-magnitude outliers on the acceleration channels only.
    let acc_only =
        preprocess(&rec, &PreprocessParams::default().check(rec.fs_hz).unwrap()).unwrap();
    for (k, name) in names.iter().enumerate() {
        let ours = if k < 3 {
            &acc_only.acc_g[k]
        } else {
            &acc_only.gyro_dps[k - 3]
        };
        let err = max_rel_err(ours, &vec_of(&g["filtered_acc_outliers_only"][name]));
        assert!(
            err < 1e-9,
            "{name} (acc-only replacement): relative error {err:e}"
        );
    }
}

#[test]
fn sosfiltfilt_equals_scipy_for_several_designs() {
    let g = golden();
    let noise = vec_of(&g["noise"]);
    for case in g["sosfiltfilt_cases"].as_array().unwrap() {
        let order = case["order"].as_u64().unwrap() as usize;
        let (fc, fs) = (
            case["cutoff_hz"].as_f64().unwrap(),
            case["fs_hz"].as_f64().unwrap(),
        );
        let y = butter_filtfilt(&noise, order, fc, fs).unwrap();
        let err = max_rel_err(&y, &vec_of(&case["y"]));
        assert!(err < 1e-9, "order {order} fc {fc} fs {fs}: {err:e}");
    }
}

/// The written-out zero-phase filter (one channel, and three side by side) gives sci-rs
/// `sosfiltfilt_dyn`'s bits (which the scipy
/// goldens above check to 1e-9): every even order the parameters accept and two odd orders
/// (a first-order section: fewer padding taps) and order 14 (7 sections), on noise, a ramp and the shortest signals.
#[test]
fn sosfiltfilt_is_sci_rs_bit_for_bit() {
    use sci_rs::signal::filter::sosfiltfilt_dyn;
    let noise = vec_of(&golden()["noise"]);
    let ramp: Vec<f64> = (0..500)
        .map(|i| (i as f64 * 0.37).sin() + i as f64 * 1e-3)
        .collect();
    for order in [1, 2, 3, 4, 6, 8, 10, 14] {
        let sos = butterworth_lowpass_sos(order, 7.0, 100.0).unwrap();
        let shortest = 3 * (2 * sos.len() + 1) + 1;
        for x in [
            &noise[..],
            &ramp[..],
            &ramp[..shortest],
            &noise[..shortest + 1],
        ] {
            let ours = sosfiltfilt(&sos, x).unwrap();
            let want = sosfiltfilt_dyn(x.iter(), &sos);
            assert_eq!(ours.len(), x.len());
            let same = ours
                .iter()
                .zip(&want)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "order {order}, {} samples", x.len());
        }
        // three channels side by side, of equal and of unequal lengths
        let n = noise.len().min(ramp.len());
        let neg: Vec<f64> = noise.iter().map(|v| -2.0 * v).collect();
        for xs in [
            [&noise[..n], &ramp[..n], &neg[..n]],
            [&noise[..], &ramp[..shortest], &neg[..n]],
        ] {
            let ours = sosfiltfilt_each(&sos, xs).unwrap();
            for (y, x) in ours.iter().zip(xs) {
                let want = sosfiltfilt_dyn(x.iter(), &sos);
                let same = y.len() == x.len()
                    && y.iter().zip(&want).all(|(a, b)| a.to_bits() == b.to_bits());
                assert!(same, "order {order}, channels of {} samples", x.len());
            }
        }
    }
}

#[test]
fn bad_parameters_and_short_signals_are_errors() {
    let e = PreprocessParams::default()
        .cutoff_hz(60.0)
        .check(100.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("cutoff_hz") && e.contains("(0, 50)"), "{e}");
    assert!(PreprocessParams::default()
        .filter_order(3)
        .check(100.0)
        .is_err());
    assert!(PreprocessParams::default()
        .outlier_sd(0.0)
        .check(100.0)
        .is_err());
    let e = butter_filtfilt(&[1.0; 15], 4, 10.0, 100.0)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("too short") && e.contains("15 samples") && e.contains("at least 16"),
        "{e}"
    );
    assert!(butter_filtfilt(&[f64::NAN; 40], 4, 10.0, 100.0).is_err());
    // Found by fuzzing: a recording claiming 9.3e74 Hz made sci-rs's design panic
    // (fuzz/regressions/pipeline/butterworth-huge-rate). Now a parameter error.
    for (fs, fc) in [(9.3e74, 10.0), (1e300, 10.0), (100.0, 49.999_999_999_9)] {
        let e = PreprocessParams::default()
            .cutoff_hz(fc)
            .check(fs)
            .unwrap_err()
            .to_string();
        assert!(e.contains("cutoff_hz") && e.contains("Nyquist"), "{e}");
        assert!(butterworth_lowpass_sos(4, fc, fs).is_err());
    }
    assert!(butterworth_lowpass_sos(4, 10.0, 100.0).is_ok());
    assert!(butterworth_lowpass_sos(0, 10.0, 100.0).is_err());
    let rec = Recording::new(
        100.0,
        [vec![1.0; 10], vec![0.0; 10], vec![0.0; 10]],
        [vec![0.0; 10], vec![0.0; 10], vec![0.0; 10]],
        vec![],
    )
    .unwrap();
    let p = PreprocessParams::default().check(100.0).unwrap();
    assert!(preprocess(&rec, &p)
        .unwrap_err()
        .to_string()
        .contains("at least 16"));
    let p50 = PreprocessParams::default().check(50.0).unwrap();
    assert!(preprocess(&rec, &p50).is_err());
}

#[test]
fn interpolation_handles_edges_and_runs() {
    let mut v = vec![0.0, 10.0, 10.0, 3.0, 4.0, 10.0];
    interpolate_over(&mut v, &[1, 2, 5]);
    assert_eq!(v, vec![0.0, 1.0, 2.0, 3.0, 4.0, 4.0]);
    let mut w = vec![9.0, 9.0, 2.0];
    interpolate_over(&mut w, &[0, 1]);
    assert_eq!(w, vec![2.0, 2.0, 2.0]);
}

proptest! {
    /// A zero-phase low-pass keeps a constant signal constant.
    #[test]
    fn filtfilt_keeps_constants(c in -1e3f64..1e3, n in 22usize..400, order in prop::sample::select(vec![2usize, 4, 6]), fc in 1.0f64..40.0) {
        let y = butter_filtfilt(&vec![c; n], order, fc, 100.0).unwrap();
        for v in y {
            prop_assert!((v - c).abs() <= 1e-9 * c.abs().max(1.0));
        }
    }

    /// Filtering is linear: filt(a·x + b) = a·filt(x) + b.
    #[test]
    fn filtfilt_is_linear(x in prop::collection::vec(-10.0f64..10.0, 20..200), a in -5.0f64..5.0, b in -5.0f64..5.0) {
        let fx = butter_filtfilt(&x, 4, 10.0, 100.0).unwrap();
        let ax: Vec<f64> = x.iter().map(|v| a * v + b).collect();
        let fax = butter_filtfilt(&ax, 4, 10.0, 100.0).unwrap();
        for (p, q) in fax.iter().zip(&fx) {
            prop_assert!((p - (a * q + b)).abs() < 1e-9 * (1.0 + a.abs() * 10.0 + b.abs()));
        }
    }
}

/// A heel-strike-like deceleration that the |a| outlier rule flags is interpolated in `acc_g`
/// (the paper's preprocessing) but kept in `acc_motion_g` (what the stride length integrates);
/// a clipped run is interpolated in `acc_g` and reconstructed in `acc_motion_g`, and with
/// neither nothing extra is stored.
#[test]
fn motion_acceleration_keeps_magnitude_outliers_and_replaces_clipped_samples() {
    let n = 200;
    let quiet = |i: usize| 1.0 + 0.05 * (i as f64 * 0.3).sin();
    let mut ax: Vec<f64> = (0..n).map(quiet).collect();
    // A 60 ms, 1.5 g impact: beyond 3 SD of the magnitude.
    for x in ax.iter_mut().skip(100).take(6) {
        *x += 1.5;
    }
    let zeros = || vec![0.0; n];
    let rec = Recording::new(
        100.0,
        [ax.clone(), zeros(), zeros()],
        [zeros(), zeros(), zeros()],
        vec![],
    )
    .unwrap();
    let p = PreprocessParams::default().check(100.0).unwrap();
    let pre = preprocess(&rec, &p).unwrap();
    assert!(pre.replaced.contains(&102), "{:?}", pre.replaced);
    let motion = pre.acc_motion_g.as_ref().expect("outliers were replaced");
    // The impact's area survives in the motion acceleration, not in acc_g.
    let area = |v: &[f64]| v[95..112].iter().sum::<f64>() - (95..112).map(quiet).sum::<f64>();
    assert!(area(&pre.acc_g[0]).abs() < 1.0, "{}", area(&pre.acc_g[0]));
    assert!((area(&motion[0]) - 9.0).abs() < 0.3, "{}", area(&motion[0]));
    // A broader 1.6 g bump (a swing deceleration, SD 60 ms) read by a ±2 g accelerometer: acc_g
    // interpolates the clipped run (the paper), the motion acceleration reconstructs it
    // (`declip`), with or without outlier replacement.
    let bump = |i: usize| 1.6 * (-((i as f64 - 102.5) / 6.0).powi(2) / 2.0).exp();
    let ax: Vec<f64> = (0..n).map(|i| (quiet(i) + bump(i)).min(2.0)).collect();
    let clipped: Vec<bool> = ax.iter().map(|&x| x >= 2.0).collect();
    let rec = Recording::new(
        100.0,
        [ax, zeros(), zeros()],
        [zeros(), zeros(), zeros()],
        vec![],
    )
    .unwrap()
    .with_sensor_saturation(clipped.clone(), vec![false; n])
    .unwrap();
    let truth: f64 = (80..126).map(bump).sum();
    let off = PreprocessParams {
        replace_outliers: false,
        ..PreprocessParams::default()
    }
    .check(100.0)
    .unwrap();
    for p in [&p, &off] {
        let pre = preprocess(&rec, p).unwrap();
        let run: Vec<usize> = (0..n).filter(|&i| clipped[i]).collect();
        assert!(run.len() >= 3 && pre.acc_clipped == run, "{run:?}");
        let area = |v: &[f64]| v[80..126].iter().sum::<f64>() - (80..126).map(quiet).sum::<f64>();
        let motion = pre
            .acc_motion_g
            .as_ref()
            .expect("clipped samples reconstructed");
        // at least half of the area the paper's signal loses comes back
        let (lost, left) = (truth - area(&pre.acc_g[0]), truth - area(&motion[0]));
        assert!(lost > 1.0 && left.abs() < 0.5 * lost, "{left} of {lost}");
    }
    // Nothing clipped and replacement off: nothing extra stored.
    let rec = Recording::new(
        100.0,
        [vec![1.0; n], zeros(), zeros()],
        [zeros(), zeros(), zeros()],
        vec![],
    )
    .unwrap();
    assert_eq!(preprocess(&rec, &off).unwrap().acc_motion_g, None);
}
