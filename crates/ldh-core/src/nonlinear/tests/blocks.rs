//! Building blocks and entry points: params and their nolds defaults, embedding
//! layout, lag rules, linear-algebra kernels, thread-count independence, orbit entry.

use super::*;

#[test]
fn params_round_trip_through_serde_and_defaults_match_nolds() {
    let r = RosensteinParams::default();
    assert_eq!(
        (
            r.emb_dim,
            r.lag,
            r.min_tsep,
            r.tau,
            r.min_neighbors,
            r.trajectory_len,
            r.fit_offset
        ),
        (10, None, None, 1.0, 20, 20, 0)
    );
    let e = EckmannParams::default();
    assert_eq!(
        (e.emb_dim, e.matrix_dim, e.min_nb, e.min_tsep, e.tau),
        (10, 4, None, 0, 1.0)
    );
    let json = serde_json::to_string(&r.clone().lag(Some(3))).unwrap();
    let back: RosensteinParams = serde_json::from_str(&json).unwrap();
    assert_eq!(back, r.lag(Some(3)));
    let partial: EckmannParams =
        serde_json::from_str(r#"{"emb_dim": 7, "matrix_dim": 3}"#).unwrap();
    assert_eq!(partial, EckmannParams::default().emb_dim(7).matrix_dim(3));
    let g: GaitStaParams = serde_json::from_str(r#"{"lag": {"fixed": 12}}"#).unwrap();
    assert_eq!(g.lag, LagRule::Fixed(12));
}

#[test]
fn delay_and_state_embeddings_have_nolds_layout() {
    let x: Vec<f64> = (0..10).map(|v| v as f64).collect();
    let e = delay_embed(&x, 3, 2).unwrap();
    assert_eq!(e.dim(), (6, 3));
    assert_eq!(e.row(0).to_vec(), vec![0.0, 2.0, 4.0]);
    assert_eq!(e.row(5).to_vec(), vec![5.0, 7.0, 9.0]);
    let s = state_embed(&[&[1.0, 2.0], &[3.0, 4.0]]).unwrap();
    assert_eq!(s.row(1).to_vec(), vec![2.0, 4.0]);
}

#[test]
fn lag_rules_on_a_sine() {
    // for a sine the AMI has its first minimum near a quarter period and the
    // autocorrelation cos(2πτ/P) reaches 1/e at τ = P·acos(1/e)/2π ≈ 0.19·P
    let period = 80.0;
    let x: Vec<f64> = (0..4_000)
        .map(|i| (2.0 * std::f64::consts::PI * i as f64 / period).sin())
        .collect();
    // the histogram AMI of a noise-free sampled sine is jagged (deterministic
    // bin occupancy); with 10 % noise its first minimum sits near P/4 = 20
    use rand::SeedableRng;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2);
    let noisy: Vec<f64> = x
        .iter()
        .map(|v| v + 0.1 * rand_distr_free::normal(&mut rng))
        .collect();
    let ami = lag_ami(&noisy, 60, None).unwrap();
    assert!((12..=26).contains(&ami), "AMI lag {ami}");
    let acf = lag_acf(&x, 60).unwrap();
    let expect = (period * (1.0 / std::f64::consts::E).acos() / (2.0 * std::f64::consts::PI)).ceil()
        as usize;
    assert_eq!(acf, expect);
}

#[test]
fn linear_algebra_kernels() {
    use crate::nonlinear::linalg::{lstsq_min_norm, matmul, qr_positive};
    // over-determined, consistent system
    let a = [1.0, 2.0, 3.0, 4.0, 5.0, 7.0, 2.0, -1.0];
    let x_true = [0.5, -2.0];
    let b: Vec<f64> = a
        .chunks(2)
        .map(|r| r[0] * x_true[0] + r[1] * x_true[1])
        .collect();
    let x = lstsq_min_norm(&a, 4, 2, &b);
    assert!(
        (x[0] - 0.5).abs() < 1e-12 && (x[1] + 2.0).abs() < 1e-12,
        "{x:?}"
    );
    // rank deficient: identical columns -> minimum-norm solution splits evenly
    let a = [1.0, 1.0, 2.0, 2.0, 3.0, 3.0];
    let x = lstsq_min_norm(&a, 3, 2, &[2.0, 4.0, 6.0]);
    assert!(
        (x[0] - 1.0).abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12,
        "{x:?}"
    );
    // QR with a positive diagonal reconstructs the matrix, Q orthogonal
    let m = [0.0, 1.0, 0.0, 0.0, 0.0, 1.0, -0.3, 2.0, -1.5];
    let (q, r) = qr_positive(&m, 3);
    let qr = matmul(&q, &r, 3);
    for (u, v) in qr.iter().zip(&m) {
        assert!((u - v).abs() < 1e-12);
    }
    let qt: Vec<f64> = (0..9).map(|k| q[(k % 3) * 3 + k / 3]).collect();
    let qtq = matmul(&qt, &q, 3);
    for i in 0..3 {
        assert!(r[i * 3 + i] >= 0.0);
        for j in 0..3 {
            assert!((qtq[i * 3 + j] - if i == j { 1.0 } else { 0.0 }).abs() < 1e-12);
        }
    }
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let x = logistic(3_000);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let r = lyap_r(
                    &x,
                    &RosensteinParams::default().lag(Some(1)).min_tsep(Some(5)),
                )
                .unwrap();
                let e = lyap_e(&x, &EckmannParams::default()).unwrap();
                (r, e)
            })
    };
    let (r1, e1) = run(1);
    let (r3, e3) = run(3);
    assert_eq!(r1.exponent.to_bits(), r3.exponent.to_bits());
    assert_eq!(r1.divergence, r3.divergence);
    assert_eq!(e1.exponents, e3.exponents);
}

#[test]
fn orbit_entry_point_equals_series_entry_point() {
    let x = logistic(1_000);
    let p = RosensteinParams::default()
        .emb_dim(3)
        .lag(Some(2))
        .min_tsep(Some(4))
        .trajectory_len(8)
        .fit_offset(1)
        .tau(0.5);
    let a = lyap_r(&x, &p).unwrap();
    let orbit = delay_embed(&x, 3, 2).unwrap();
    let b = lyap_r_orbit(orbit.view(), 4, 8, 0.5, 1).unwrap();
    assert_eq!(a.exponent.to_bits(), b.exponent.to_bits());
    assert_eq!(a.divergence, b.divergence);
    assert_eq!((a.lag, b.lag), (Some(2), None));
}
