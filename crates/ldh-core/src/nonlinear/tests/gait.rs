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

/// `gait_sta`'s steps, each called on its own, give its result bit for bit (the Rosenstein
/// search reuses the tree false nearest neighbours built; a fresh search finds the same).
#[test]
fn gait_sta_equals_its_steps() {
    let (x, _) = gait_like(4_000, 7);
    let g = gait_sta(&x, 100.0, 1.0, &GaitStaParams::default()).unwrap();
    let lag = lag_ami(&x, 100, None).unwrap();
    let fnn = emb_dim_fnn(&x, lag, &FnnParams::default()).unwrap();
    let p = RosensteinParams::default()
        .emb_dim(fnn.emb_dim)
        .lag(Some(lag))
        .min_tsep(Some(100))
        .tau(0.01)
        .trajectory_len(51);
    let ros = lyap_r(&x, &p).unwrap();
    assert_eq!((g.lag, g.emb_dim), (lag, fnn.emb_dim));
    assert_eq!(g.fnn.as_ref(), Some(&fnn));
    assert_eq!(g.rosenstein.exponent.to_bits(), ros.exponent.to_bits());
    assert_eq!(g.rosenstein, ros);
}

/// False nearest neighbours equal a plain reference (every dimension embedded, its
/// neighbours by brute force, Kennel's criteria) bit for bit in every fraction computed, with
/// and without a Theiler window, on a gait-like, a quantised (tied) and a white-noise series
/// (on noise no fraction reaches 0, so every dimension up to `max_dim` is computed and the
/// index is rebuilt past the dimensions its first build covers).
#[test]
fn false_nearest_neighbours_equal_a_brute_force_reference() {
    use crate::nonlinear::neighbours::{nn_brute, np_euclidean};
    let reference = |x: &[f64], lag: usize, p: &FnnParams| -> Vec<f64> {
        let n = x.len();
        let mean = x.iter().sum::<f64>() / n as f64;
        let sd = (x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n as f64).sqrt();
        (1..=p.max_dim)
            .map(|d| {
                let rows = n - d * lag;
                let pts: Vec<f64> = (0..rows)
                    .flat_map(|i| (0..d).map(move |c| x[i + c * lag]))
                    .collect();
                let nb = nn_brute(&pts, d, p.min_tsep);
                let (mut bad, mut counted) = (0, 0);
                for (i, &j) in nb.iter().enumerate() {
                    let rd = np_euclidean(&pts[i * d..(i + 1) * d], &pts[j * d..(j + 1) * d]);
                    if rd == 0.0 {
                        continue;
                    }
                    counted += 1;
                    let extra = (x[i + d * lag] - x[j + d * lag]).abs();
                    let rd1 = (rd * rd + extra * extra).sqrt();
                    if extra / rd > p.r_tol || rd1 / sd > p.a_tol {
                        bad += 1;
                    }
                }
                if counted == 0 {
                    1.0
                } else {
                    bad as f64 / counted as f64
                }
            })
            .collect()
    };
    let (smooth, _) = gait_like(1_200, 11);
    let tied: Vec<f64> = smooth.iter().map(|v| (v * 8.0).round() / 8.0).collect();
    let noise: Vec<f64> = {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        (0..1_200)
            .map(|_| rand_distr_free::normal(&mut rng))
            .collect()
    };
    let mut longest = 0;
    for x in [&smooth, &tied, &noise] {
        for (min_tsep, max_dim) in [(0, 9), (30, 5)] {
            let p = FnnParams {
                max_dim,
                min_tsep,
                threshold: 1e-300,
                rows: FnnRows::All,
                ..FnnParams::default()
            };
            let want = reference(x, 9, &p);
            let got = emb_dim_fnn(x, 9, &p).unwrap();
            let bits = |v: &[f64]| v.iter().map(|f| f.to_bits()).collect::<Vec<_>>();
            // the loop stops at the first dimension that meets the criterion
            let computed = got.fractions.len();
            assert!(got.emb_dim <= computed);
            assert_eq!(
                bits(&got.fractions),
                bits(&want[..computed]),
                "min_tsep {min_tsep}"
            );
            longest = longest.max(computed);
            // stopping a rejected dimension early changes no decision; its fraction is a
            // lower bound above the threshold
            let early = FnnParams {
                rows: FnnRows::UntilRejected,
                ..p.clone()
            };
            let fast = emb_dim_fnn(x, 9, &early).unwrap();
            assert_eq!((fast.emb_dim, fast.converged), (got.emb_dim, got.converged));
            assert_eq!(fast.fractions.len(), computed);
            for (f, w) in fast.fractions.iter().zip(&got.fractions) {
                assert!(f == w || (*f > p.threshold && f <= w), "{f} vs {w}");
            }
        }
    }
    assert_eq!(longest, 9, "some case computes every dimension");
}

/// The default [`FnnRows::UntilRejected`] on a 30 s gait-like leg: dimensions are rejected
/// after a part of their rows (some fraction is a lower bound below the exact one), yet
/// `gait_sta` is bit for bit that of [`FnnRows::All`]; where no dimension converges (white
/// noise, at most 3 dimensions) every fraction is the exact one.
#[test]
fn false_nearest_neighbours_until_rejected_decide_as_all_rows() {
    let (x, _) = gait_like(3_000, 3);
    let all = GaitStaParams::default().fnn(FnnParams {
        rows: FnnRows::All,
        ..FnnParams::default()
    });
    let want = gait_sta(&x, 100.0, 1.0, &all).unwrap();
    let got = gait_sta(&x, 100.0, 1.0, &GaitStaParams::default()).unwrap();
    assert_eq!(got.rosenstein, want.rosenstein);
    assert_eq!((got.lag, got.emb_dim), (want.lag, want.emb_dim));
    let (f_got, f_want) = (got.fnn.unwrap(), want.fnn.unwrap());
    assert_eq!(f_got.converged, f_want.converged);
    let lower = f_got
        .fractions
        .iter()
        .zip(&f_want.fractions)
        .filter(|(g, w)| g < w)
        .count();
    assert!(
        lower >= 1,
        "{:?} vs {:?}",
        f_got.fractions,
        f_want.fractions
    );

    let noise: Vec<f64> = {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(8);
        (0..2_000)
            .map(|_| rand_distr_free::normal(&mut rng))
            .collect()
    };
    let p = FnnParams {
        max_dim: 3,
        ..FnnParams::default()
    };
    let exact = FnnParams {
        rows: FnnRows::All,
        ..p.clone()
    };
    let (fast, slow) = (
        emb_dim_fnn(&noise, 1, &p).unwrap(),
        emb_dim_fnn(&noise, 1, &exact).unwrap(),
    );
    assert!(!slow.converged);
    assert_eq!(fast, slow);
}
