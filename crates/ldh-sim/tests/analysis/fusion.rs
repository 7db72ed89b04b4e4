//! The attitude fusion on a simulated walk against its true pitch, with and without a
//! gyroscope bias (from `ldh-core`'s attitude/fusion.rs; the segment-length test stayed there).

use ldh_core::align::{align, AlignParams, Aligned};
use ldh_core::attitude::{estimate, AttitudeParams};
use ldh_core::preprocess::{preprocess, PreprocessParams};
use ldh_sim::CohortParams;

/// A simulated 70 s walk (family A) and its true pitch, the signals aligned as the pipeline
/// aligns them.
fn walk() -> (Aligned, Vec<f64>) {
    let c = CohortParams {
        healthy: 1,
        ldh: 0,
        seed: 11,
        duration_s: 70.0,
        ..CohortParams::default()
    };
    let s = c.simulate(0).unwrap();
    let rec = &s.left.recording;
    let pre = preprocess(rec, &PreprocessParams::default().check(rec.fs_hz).unwrap()).unwrap();
    let al = align(&pre, &AlignParams::default().check().unwrap()).unwrap();
    (al, s.left.truth.pitch_deg.clone())
}

fn rmse(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    ((0..n).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>() / n as f64).sqrt()
}

fn worst(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn a_gyroscope_bias_of_several_deg_per_s_does_not_drift_the_pitch() {
    let (mut al, truth) = walk();
    // 6 deg/s on the sagittal axis and 4 on the anterior one, left after alignment (as when
    // a recording has no quiet standing to measure it).
    al.gyro_dps[0].iter_mut().for_each(|w| *w += 4.0);
    al.gyro_dps[1].iter_mut().for_each(|w| *w += 6.0);
    let p = AttitudeParams::default().check().unwrap();
    let att = estimate(&al, &p).unwrap();
    // Over the whole minute (plain integration: 6 deg/s x 70 s = 420 deg).
    let (e, w) = (rmse(&att.pitch_deg, &truth), worst(&att.pitch_deg, &truth));
    assert!(e < 1.5 && w < 6.0, "pitch RMSE {e:.2}, worst {w:.2} deg");
    let b = att.gyro_bias_dps;
    assert!(
        (b[1] - 6.0).abs() < 1.0,
        "sagittal bias estimated {:.2} deg/s",
        b[1]
    );
    assert!(
        att.gravity_windows > 50,
        "{} gravity windows",
        att.gravity_windows
    );
    // The same filter without bias states and gravity re-acquisition is worse.
    let mut off = AttitudeParams::default();
    off.reacquire_gravity = false;
    off.gyro_bias_sd_dps = 1e-6;
    off.gyro_bias_walk_dps = 1e-9;
    let plain = estimate(&al, &off.check().unwrap()).unwrap();
    let e0 = rmse(&plain.pitch_deg, &truth);
    assert!(
        e0 > 1.5 * e,
        "without the additions: pitch RMSE {e0:.2} vs {e:.2} deg"
    );
}

#[test]
fn an_unbiased_walk_keeps_its_accuracy() {
    let (al, truth) = walk();
    let att = estimate(&al, &AttitudeParams::default().check().unwrap()).unwrap();
    let e = rmse(&att.pitch_deg, &truth);
    assert!(e < 1.0, "pitch RMSE {e:.2} deg");
    assert!(
        att.gyro_bias_dps.iter().all(|b| b.abs() < 1.0),
        "{:?}",
        att.gyro_bias_dps
    );
}
