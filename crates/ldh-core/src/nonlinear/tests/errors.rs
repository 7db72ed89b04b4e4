//! Error paths: too-short series with nolds' lengths, bad input and parameters,
//! and arbitrary inputs that must never panic.

use super::*;
use proptest::prelude::*;

#[test]
fn rosenstein_too_short_is_an_error_with_nolds_length() {
    let x = logistic(500);
    let p = RosensteinParams::default()
        .emb_dim(10)
        .lag(Some(3))
        .min_tsep(Some(40))
        .trajectory_len(20);
    let needed = lyap_r_len(10, 3, 20, 40);
    assert_eq!(needed, 9 * 3 + 1 + 19 + 81);
    let x = &x[..needed - 1];
    let err = lyap_r(x, &p).unwrap_err();
    assert_eq!(
        err,
        NonlinearError::TooShortRosenstein {
            len: needed - 1,
            emb_dim: 10,
            lag: 3,
            min_tsep: 40,
            trajectory_len: 20,
            needed
        }
    );
    assert!(
        err.to_string()
            .contains("Rosenstein needs at least 128 samples (nolds lyap_r_len)"),
        "{err}"
    );
    // exactly the minimum length works
    assert!(lyap_r(&logistic(needed), &p).is_ok());
}

#[test]
fn eckmann_too_short_is_an_error_with_nolds_length() {
    let p = EckmannParams::default();
    let needed = lyap_e_len(10, 4, 8, 0);
    assert_eq!(needed, 10 + 3 + 8);
    let err = lyap_e(&logistic(needed - 1), &p).unwrap_err();
    assert!(
        matches!(
            err,
            NonlinearError::TooShortEckmann {
                needed: 21,
                len: 20,
                ..
            }
        ),
        "{err}"
    );
    assert!(err.to_string().contains("nolds lyap_e_len"));
    assert!(lyap_e(&logistic(needed), &p).is_ok());
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let p = RosensteinParams::default().lag(Some(1)).min_tsep(Some(2));
    assert_eq!(lyap_r(&[], &p).unwrap_err(), NonlinearError::Empty);
    let mut x = logistic(300);
    x[17] = f64::NAN;
    assert!(matches!(
        lyap_r(&x, &p),
        Err(NonlinearError::NonFinite { index: 17, .. })
    ));
    assert!(matches!(
        lyap_e(&x, &EckmannParams::default()),
        Err(NonlinearError::NonFinite { index: 17, .. })
    ));
    assert!(matches!(
        lyap_r(&[2.5; 400], &p),
        Err(NonlinearError::Constant { len: 400, .. })
    ));
    assert!(matches!(
        lyap_e(&[2.5; 400], &EckmannParams::default()),
        Err(NonlinearError::Constant { .. })
    ));
    let x = logistic(300);
    for bad in [
        p.clone().lag(Some(0)),
        p.clone().emb_dim(0),
        p.clone().tau(0.0),
        p.clone().tau(f64::NAN),
        p.clone().trajectory_len(1),
        p.clone().trajectory_len(5).fit_offset(4),
    ] {
        assert!(
            matches!(
                lyap_r(&x, &bad),
                Err(NonlinearError::InvalidParameter { .. })
            ),
            "{bad:?}"
        );
    }
    for bad in [
        EckmannParams::default().emb_dim(9),
        EckmannParams::default().matrix_dim(1),
        EckmannParams::default().emb_dim(3).matrix_dim(4),
        EckmannParams::default().min_nb(Some(0)),
        EckmannParams::default().tau(-1.0),
    ] {
        assert!(
            matches!(
                lyap_e(&x, &bad),
                Err(NonlinearError::InvalidParameter { .. })
            ),
            "{bad:?}"
        );
    }
    // a series long enough for lyap_r_len but with every divergence step
    // collapsing to exact repeats -> degenerate fit (nolds would return -inf)
    let periodic: Vec<f64> = (0..200).map(|i| (i % 4) as f64).collect();
    let err = lyap_r(
        &periodic,
        &RosensteinParams::default()
            .emb_dim(2)
            .lag(Some(1))
            .min_tsep(Some(3))
            .trajectory_len(5),
    );
    assert!(
        matches!(err, Err(NonlinearError::DegenerateFit { finite: 0, .. })),
        "{err:?}"
    );
    assert!(matches!(
        state_embed(&[&[1.0, 2.0, 3.0], &[1.0, 2.0]]),
        Err(NonlinearError::ChannelLength {
            channel: 1,
            len: 2,
            expected: 3
        })
    ));
    assert!(matches!(
        delay_embed(&[1.0, 2.0], 3, 1),
        Err(NonlinearError::TooShort { needed: 3, .. })
    ));
    assert!(matches!(
        lag_ami(&logistic(20), 10, None),
        Err(NonlinearError::TooShort { .. })
    ));
    assert!(matches!(
        emb_dim_fnn(&logistic(11), 1, &FnnParams::default()),
        Err(NonlinearError::TooShort {
            len: 11,
            needed: 12,
            ..
        })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Arbitrary short inputs and parameters give `Ok` or `Err`, never a panic,
    /// and `Ok` exactly when the series is at least `lyap_r_len` long.
    #[test]
    fn arbitrary_inputs_never_panic(
        x in proptest::collection::vec(prop_oneof![-3.0f64..3.0, Just(0.0), Just(f64::NAN)], 0..120),
        emb_dim in 0usize..12,
        lag in 0usize..6,
        min_tsep in 0usize..20,
        trajectory_len in 0usize..12,
        matrix_dim in 0usize..5,
        min_nb in 0usize..10,
    ) {
        let p = RosensteinParams::default()
            .emb_dim(emb_dim)
            .lag(Some(lag))
            .min_tsep(Some(min_tsep))
            .trajectory_len(trajectory_len);
        let r = lyap_r(&x, &p);
        let clean = !x.is_empty() && x.iter().all(|v| v.is_finite()) && x.iter().any(|&v| v != x[0]);
        if clean && emb_dim >= 1 && lag >= 1 && trajectory_len >= 2 {
            let long_enough = x.len() >= lyap_r_len(emb_dim, lag, trajectory_len, min_tsep);
            prop_assert_eq!(
                long_enough,
                !matches!(r, Err(NonlinearError::TooShortRosenstein { .. })),
                "{:?}", r
            );
        } else {
            prop_assert!(r.is_err());
        }
        let e = EckmannParams::default()
            .emb_dim(emb_dim)
            .matrix_dim(matrix_dim)
            .min_nb(Some(min_nb))
            .min_tsep(min_tsep);
        let _ = lyap_e(&x, &e);
        let _ = lyap_r(&x, &RosensteinParams::default().trajectory_len(trajectory_len.max(2)));
        let _ = gait_sta(&x, 10.0, 1.0, &GaitStaParams::default());
        let _ = lag_ami(&x, lag.max(1), None);
        let _ = emb_dim_fnn(&x, lag, &FnnParams { max_dim: emb_dim, ..FnnParams::default() });
    }
}

/// Issue 37: `lyap_r` on 10⁷ samples took 3.4 GB and more than a minute; a series whose delay
/// embedding exceeds `MAX_ORBIT_VALUES` is refused at once, naming the size and the limit, as
/// a parameter error (Python: `LdhParamError`).
#[test]
fn lyap_r_refuses_a_series_beyond_its_size_limit() {
    let n = crate::nonlinear::MAX_ORBIT_VALUES / 10 + 1;
    let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.1).sin()).collect();
    let p = crate::nonlinear::RosensteinParams::nolds().check().unwrap();
    let t = std::time::Instant::now();
    let e = crate::nonlinear::lyap_r(&x, &p).unwrap_err();
    assert!(t.elapsed().as_secs_f64() < 1.0);
    let s = e.to_string();
    assert!(
        s.contains(&format!("{n} samples")) && s.contains("limit of 10000000"),
        "{s}"
    );
    let e: crate::LdhError = e.into();
    assert_eq!(e.kind(), crate::ErrorKind::Param);
    assert!(crate::nonlinear::check_orbit_size(n - 1, 10).is_ok());
}
