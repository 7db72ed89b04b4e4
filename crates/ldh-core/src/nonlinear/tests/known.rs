//! Known exponents of textbook systems: Lorenz (Rosenstein and Eckmann), the
//! logistic map, white noise and a pure sine.

use super::*;

/// Lorenz (σ = 10, ρ = 28, β = 8/3), classic RK4 with step `dt`, start (1,1,1).
fn lorenz(n: usize, dt: f64, transient: usize) -> Vec<[f64; 3]> {
    let f = |s: [f64; 3]| {
        [
            10.0 * (s[1] - s[0]),
            s[0] * (28.0 - s[2]) - s[1],
            s[0] * s[1] - 8.0 / 3.0 * s[2],
        ]
    };
    let add =
        |a: [f64; 3], b: [f64; 3], h: f64| [a[0] + h * b[0], a[1] + h * b[1], a[2] + h * b[2]];
    let mut s = [1.0, 1.0, 1.0];
    let mut out = Vec::with_capacity(n);
    for i in 0..n + transient {
        let k1 = f(s);
        let k2 = f(add(s, k1, dt / 2.0));
        let k3 = f(add(s, k2, dt / 2.0));
        let k4 = f(add(s, k3, dt));
        for d in 0..3 {
            s[d] += dt / 6.0 * (k1[d] + 2.0 * k2[d] + 2.0 * k3[d] + k4[d]);
        }
        if i >= transient {
            out.push(s);
        }
    }
    out
}

const LORENZ_LAMBDA: f64 = 0.9056;

#[test]
fn lorenz_state_recovers_largest_exponent() {
    // 3-D state, dt = 0.01, 20 000 samples after a 2 000-step transient;
    // Theiler window 1 time unit; fit from 0.3 to 3 time units (the linear
    // region: before it the separation aligns with the unstable direction,
    // after it the divergence saturates at the attractor size).
    let l = lorenz(20_000, 0.01, 2_000);
    let ch: Vec<Vec<f64>> = (0..3).map(|d| l.iter().map(|s| s[d]).collect()).collect();
    let st = state_embed(&[&ch[0], &ch[1], &ch[2]]).unwrap();
    let r = lyap_r_orbit(st.view(), 100, 300, 0.01, 30).unwrap();
    assert!(
        (r.exponent - LORENZ_LAMBDA).abs() < 0.1 * LORENZ_LAMBDA,
        "lambda {} vs {LORENZ_LAMBDA}",
        r.exponent
    );
    assert_eq!(r.lag, None);
    assert_eq!(r.emb_dim, 3);
}

#[test]
fn lorenz_x_delay_embedding_recovers_largest_exponent() {
    // x coordinate only: lag from AMI, dimension from FNN, same fit region.
    let l = lorenz(20_000, 0.01, 2_000);
    let x: Vec<f64> = l.iter().map(|s| s[0]).collect();
    let lag = lag_ami(&x, 100, None).unwrap();
    assert!((10..=25).contains(&lag), "AMI lag {lag}");
    let fnn = emb_dim_fnn(&x, lag, &FnnParams::default()).unwrap();
    assert!(fnn.converged);
    assert_eq!(fnn.emb_dim, 3, "FNN fractions {:?}", fnn.fractions);
    let p = RosensteinParams::default()
        .emb_dim(fnn.emb_dim)
        .lag(Some(lag))
        .min_tsep(Some(100))
        .trajectory_len(300)
        .fit_offset(50)
        .tau(0.01);
    let r = lyap_r(&x, &p).unwrap();
    assert!(
        (r.exponent - LORENZ_LAMBDA).abs() < 0.1 * LORENZ_LAMBDA,
        "lambda {} vs {LORENZ_LAMBDA}",
        r.exponent
    );
    assert_eq!(r.lag, Some(lag));
}

#[test]
fn logistic_map_gives_ln2_per_iteration() {
    let x = logistic(5_000);
    let p = RosensteinParams::default()
        .emb_dim(2)
        .lag(Some(1))
        .min_tsep(Some(1))
        .trajectory_len(6);
    let r = lyap_r(&x, &p).unwrap();
    let ln2 = std::f64::consts::LN_2;
    assert!(
        (r.exponent - ln2).abs() < 0.1 * ln2,
        "lambda {}",
        r.exponent
    );
}

#[test]
fn lorenz_eckmann_spectrum() {
    // Eckmann's method is far more parameter-sensitive than Rosenstein's; with
    // x sampled every 0.05 time units (4 000 samples), emb_dim = matrix_dim = 3
    // and a Theiler window of 10 samples it recovers λ1 ≈ 0.906 and λ2 ≈ 0.
    let l = lorenz(20_000, 0.01, 2_000);
    let x: Vec<f64> = l.iter().step_by(5).map(|s| s[0]).collect();
    let p = EckmannParams::default()
        .emb_dim(3)
        .matrix_dim(3)
        .min_tsep(10)
        .tau(0.05);
    let e = lyap_e(&x, &p).unwrap();
    assert_eq!(e.exponents.len(), 3);
    assert!(
        (e.exponents[0] - LORENZ_LAMBDA).abs() < 0.1 * LORENZ_LAMBDA,
        "{:?}",
        e.exponents
    );
    assert!(e.exponents[1].abs() < 0.1, "{:?}", e.exponents);
    assert!(e.exponents[2] < -5.0, "{:?}", e.exponents);
    assert_eq!((e.step, e.min_nb), (1, 6));
}

#[test]
fn white_noise_divergence_is_flat_after_the_embedding_window() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let x: Vec<f64> = (0..5_000).map(|_| rng.gen::<f64>() - 0.5).collect();
    let r = lyap_r(
        &x,
        &RosensteinParams::default()
            .emb_dim(5)
            .lag(Some(1))
            .min_tsep(Some(10))
            .trajectory_len(30),
    )
    .unwrap();
    // the curve rises while the noisy coordinates leave the embedding window
    // (k < emb_dim) and is flat after it: no exponential divergence
    let tail: Vec<f64> = (5..30).map(|k| k as f64).collect();
    let (slope, _) = crate::nonlinear::linalg::line_fit(&tail, &r.divergence[5..]);
    assert!(slope.abs() < 0.005, "tail slope {slope}");
    assert!(r.divergence[4] - r.divergence[0] > 1.0);
}

#[test]
fn pure_sine_has_zero_exponent() {
    // period 50·√2 samples (incommensurate: no exact repetitions)
    let period = 50.0 * std::f64::consts::SQRT_2;
    let x: Vec<f64> = (0..5_000)
        .map(|i| (2.0 * std::f64::consts::PI * i as f64 / period).sin())
        .collect();
    let p = RosensteinParams::default()
        .emb_dim(3)
        .lag(Some(18))
        .min_tsep(Some(71))
        .trajectory_len(71);
    let r = lyap_r(&x, &p).unwrap();
    assert!(
        r.exponent.abs() < 1e-3,
        "sine lambda {} per sample",
        r.exponent
    );
}
