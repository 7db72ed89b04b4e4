//! `gait_sta` on a gait-like signal: defaults, time normalisation, bad input.

use super::*;

/// Gait-like angular velocity: 1 Hz stride fundamental + 2 harmonics at
/// 100 Hz, 2 % stride-time jitter, small noise; also returns stride starts.
fn gait_like(n: usize, seed: u64) -> (Vec<f64>, Vec<usize>) {
    use rand::SeedableRng;
    use rand_distr_free::normal;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::with_capacity(n);
    let mut starts = vec![0];
    let (mut phase, mut period) = (0.0f64, 1.0f64);
    let tau = 2.0 * std::f64::consts::PI;
    for i in 0..n {
        out.push(
            2.0 * (tau * phase).sin()
                + 0.8 * (2.0 * tau * phase + 0.5).sin()
                + 0.3 * (3.0 * tau * phase + 1.1).sin()
                + 0.05 * normal(&mut rng),
        );
        phase += 1.0 / (100.0 * period);
        if phase >= 1.0 {
            phase -= 1.0;
            period = 1.0 + 0.02 * normal(&mut rng);
            starts.push(i + 1);
        }
    }
    (out, starts)
}

#[test]
fn gait_sta_defaults_use_ami_fnn_and_one_stride_window() {
    let (x, _) = gait_like(6_000, 3);
    let g = gait_sta(&x, 100.0, 1.0, &GaitStaParams::default()).unwrap();
    assert!(g.lambda_per_s.is_finite() && g.lambda_per_s > 0.0, "{g:?}");
    assert!((g.lambda_per_stride - g.lambda_per_s * 1.0).abs() < 1e-12);
    assert_eq!(g.rosenstein.min_tsep, 100, "Theiler window = one stride");
    assert_eq!(
        g.rosenstein.trajectory_len, 51,
        "fit over the first half stride"
    );
    assert!(g.fnn.as_ref().is_some_and(|f| f.emb_dim == g.emb_dim));
    assert!((1..=100).contains(&g.lag));
    assert_eq!(g.rosenstein.lag, Some(g.lag));
    assert!((g.fs_hz - 100.0).abs() < 1e-12 && (g.samples_per_stride - 100.0).abs() < 1e-12);
}

#[test]
fn gait_sta_time_normalisation() {
    let (x, starts) = gait_like(6_000, 5);
    let fixed = GaitStaParams::default()
        .lag(LagRule::Fixed(10))
        .emb_dim(Some(5));
    let raw = gait_sta(&x, 100.0, 1.0, &fixed).unwrap();
    // resampling to 100 samples per 1 s stride at 100 Hz is the identity
    let same = gait_sta(
        &x,
        100.0,
        1.0,
        &fixed
            .clone()
            .time_normalisation(TimeNormalisation::MeanStride {
                samples_per_stride: 100,
            }),
    )
    .unwrap();
    assert!((raw.lambda_per_s - same.lambda_per_s).abs() < 1e-12 * raw.lambda_per_s.abs());
    // 50 samples per stride: half the rate, same exponent in 1/s within 25 %
    let half = gait_sta(
        &x,
        100.0,
        1.0,
        &fixed
            .clone()
            .lag(LagRule::Fixed(5))
            .time_normalisation(TimeNormalisation::MeanStride {
                samples_per_stride: 50,
            }),
    )
    .unwrap();
    assert!((half.fs_hz - 50.0).abs() < 1e-12);
    assert_eq!(half.rosenstein.min_tsep, 50);
    assert!(
        (half.lambda_per_s - raw.lambda_per_s).abs() < 0.25 * raw.lambda_per_s.abs(),
        "{} vs {}",
        half.lambda_per_s,
        raw.lambda_per_s
    );
    // per-stride resampling between true stride starts
    let mean_stride =
        (starts[starts.len() - 1] - starts[0]) as f64 / (starts.len() - 1) as f64 / 100.0;
    let strided = gait_sta(
        &x,
        100.0,
        mean_stride,
        &fixed
            .clone()
            .time_normalisation(TimeNormalisation::StrideBoundaries {
                boundaries: starts.clone(),
                samples_per_stride: 100,
            }),
    )
    .unwrap();
    assert_eq!(strided.samples_per_stride.round() as usize, 100);
    assert!(strided.lambda_per_stride.is_finite() && strided.lambda_per_stride > 0.0);
    assert!((strided.lambda_per_stride - strided.lambda_per_s * mean_stride).abs() < 1e-12);
}

#[test]
fn gait_sta_rejects_bad_input() {
    let (x, _) = gait_like(3_000, 1);
    let p = GaitStaParams::default();
    assert!(matches!(
        gait_sta(&x, 0.0, 1.0, &p),
        Err(NonlinearError::InvalidParameter { name: "fs_hz", .. })
    ));
    assert!(matches!(
        gait_sta(&x, 100.0, f64::NAN, &p),
        Err(NonlinearError::InvalidParameter {
            name: "mean_stride_s",
            ..
        })
    ));
    let bad = p
        .clone()
        .time_normalisation(TimeNormalisation::StrideBoundaries {
            boundaries: vec![10, 5],
            samples_per_stride: 100,
        });
    assert!(matches!(
        gait_sta(&x, 100.0, 1.0, &bad),
        Err(NonlinearError::InvalidParameter {
            name: "boundaries",
            ..
        })
    ));
    let short = gait_sta(&x[..150], 100.0, 1.0, &p);
    assert!(
        matches!(
            short,
            Err(NonlinearError::TooShort { .. }) | Err(NonlinearError::TooShortRosenstein { .. })
        ),
        "{short:?}"
    );
    assert!(matches!(
        gait_sta(&[1.0; 500], 100.0, 1.0, &p),
        Err(NonlinearError::Constant { .. })
    ));
}
