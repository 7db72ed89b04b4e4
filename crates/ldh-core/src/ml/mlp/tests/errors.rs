//! Unit tests of `ml::mlp`: errors (parameters, data, training, prediction) and the
//! predict_proba invariants (moved out of tests.rs to keep files short).

use super::super::*;
use super::blobs;
use ndarray::{array, Array2};
use proptest::prelude::*;
use std::sync::OnceLock;

#[test]
fn parameter_errors_name_the_field() {
    let cases: Vec<(MlpParams, &str)> = vec![
        (
            MlpParams::default().hidden_layer_sizes(Vec::<usize>::new()),
            "hidden_layer_sizes",
        ),
        (
            MlpParams::default().hidden_layer_sizes([4, 4, 4]),
            "hidden_layer_sizes",
        ),
        (
            MlpParams::default().hidden_layer_sizes([4, 0]),
            "hidden_layer_sizes",
        ),
        (MlpParams::default().alpha(f64::NAN), "alpha"),
        (MlpParams::default().batch_size(Some(0)), "batch_size"),
        (
            MlpParams::default().learning_rate_init(0.0),
            "learning_rate_init",
        ),
        (MlpParams::default().beta_1(1.0), "beta_1"),
        (MlpParams::default().beta_2(-0.1), "beta_2"),
        (MlpParams::default().epsilon(0.0), "epsilon"),
        (MlpParams::default().max_iter(0), "max_iter"),
        (MlpParams::default().tol(-1.0), "tol"),
        (MlpParams::default().n_iter_no_change(0), "n_iter_no_change"),
        (
            MlpParams::default().validation_fraction(1.0),
            "validation_fraction",
        ),
    ];
    for (p, field) in cases {
        match p.check() {
            Err(e @ MlpError::InvalidParameter { name, .. }) => {
                assert_eq!(name, field);
                assert!(e.to_string().contains(field), "{e}");
            }
            other => panic!("{field}: expected InvalidParameter, got {other:?}"),
        }
    }
}

#[test]
fn data_errors_are_clear() {
    let p = MlpParams::default()
        .hidden_layer_sizes([4])
        .max_iter(5)
        .check()
        .unwrap();
    let x = array![[0.0, 1.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]];

    let e = Mlp::fit(&p, Array2::<f64>::zeros((0, 2)).view(), &[]).unwrap_err();
    assert!(
        matches!(
            e,
            MlpError::EmptyData {
                n_samples: 0,
                n_features: 2
            }
        ),
        "{e}"
    );
    let e = Mlp::fit(&p, Array2::<f64>::zeros((3, 0)).view(), &[0, 1, 0]).unwrap_err();
    assert!(
        matches!(e, MlpError::EmptyData { n_features: 0, .. }),
        "{e}"
    );

    let e = Mlp::fit(&p, x.view(), &[0, 1, 0]).unwrap_err();
    assert!(matches!(
        e,
        MlpError::LengthMismatch {
            n_samples: 4,
            n_targets: 3
        }
    ));
    assert!(
        e.to_string().contains("4 feature rows but 3 targets"),
        "{e}"
    );

    let e = Mlp::fit(&p, x.view(), &[2, 2, 2, 2]).unwrap_err();
    assert!(matches!(e, MlpError::TooFewClasses(1)));
    assert!(e.to_string().contains("at least 2 distinct classes"), "{e}");

    let mut xn = x.clone();
    xn[[2, 1]] = f64::NAN;
    let e = Mlp::fit(&p, xn.view(), &[0, 1, 0, 1]).unwrap_err();
    assert!(
        matches!(e, MlpError::NonFiniteFeature { row: 2, col: 1, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("row 2, column 1"), "{e}");
}

#[test]
fn training_that_cannot_succeed_is_refused_or_reported() {
    let x = array![[0.0, 1.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]];
    // early stopping that leaves no training rows: ceil(0.99 * 4) = 4 validation rows
    let pe = MlpParams::default()
        .early_stopping(true)
        .validation_fraction(0.99)
        .check()
        .unwrap();
    let e = Mlp::fit(&pe, x.view(), &[0, 1, 0, 1]).unwrap_err();
    assert!(
        matches!(
            e,
            MlpError::TooFewSamplesForValidation {
                n_train: 0,
                n_validation: 4,
                ..
            }
        ),
        "{e}"
    );

    // divergence is reported, not turned into a NaN model
    let big = array![
        [1e300, -1e300],
        [-1e300, 1e300],
        [1e300, 1e300],
        [-1e300, -1e300]
    ];
    let pd = MlpParams::default()
        .learning_rate_init(1e6)
        .max_iter(20)
        .check()
        .unwrap();
    match Mlp::fit(&pd, big.view(), &[0, 1, 0, 1]) {
        Err(MlpError::Diverged { epoch, loss }) => assert!(epoch >= 1 && !loss.is_finite()),
        Ok(m) => panic!(
            "expected divergence, got a model with loss {:?}",
            m.loss_curve()
        ),
        Err(e) => panic!("unexpected {e}"),
    }
}

#[test]
fn prediction_errors_are_clear() {
    let p = MlpParams::default()
        .hidden_layer_sizes([4])
        .max_iter(5)
        .check()
        .unwrap();
    let x = array![[0.0, 1.0], [1.0, 0.0], [1.0, 1.0], [0.0, 0.0]];
    let model = Mlp::fit(&p, x.view(), &[0, 1, 1, 0]).unwrap();
    let e = model.predict(Array2::<f64>::zeros((2, 3))).unwrap_err();
    assert!(matches!(
        e,
        MlpError::FeatureMismatch {
            expected: 2,
            found: 3
        }
    ));
    assert!(
        e.to_string()
            .contains("trained on 2 features but the input has 3"),
        "{e}"
    );
    let e = model
        .predict_proba(array![[f64::INFINITY, 0.0]])
        .unwrap_err();
    assert!(
        matches!(e, MlpError::NonFiniteFeature { row: 0, col: 0, .. }),
        "{e}"
    );
    // zero rows is not an error at prediction time
    assert_eq!(
        model.predict(Array2::<f64>::zeros((0, 2))).unwrap().len(),
        0
    );
    // linfa's error converts
    let e: MlpError = linfa::Error::NotEnoughSamples.into();
    assert!(matches!(e, MlpError::Linfa(_)));
}

fn proba_model() -> &'static Mlp {
    static MODEL: OnceLock<Mlp> = OnceLock::new();
    MODEL.get_or_init(|| {
        let (x, y) = blobs(20, 8);
        let p = MlpParams::default()
            .hidden_layer_sizes([16, 8])
            .max_iter(40)
            .check()
            .unwrap();
        Mlp::fit(&p, x.view(), &y).unwrap()
    })
}

proptest! {
    #[test]
    fn predict_proba_rows_sum_to_one(
        rows in prop::collection::vec((-1e6f64..1e6, -1e6f64..1e6), 1..40),
    ) {
        let model = proba_model();
        let x = Array2::from_shape_fn((rows.len(), 2), |(i, j)| if j == 0 { rows[i].0 } else { rows[i].1 });
        let p = model.predict_proba(&x).unwrap();
        prop_assert_eq!(p.dim(), (rows.len(), 3));
        for row in p.rows() {
            prop_assert!(row.iter().all(|v| (0.0..=1.0).contains(v)));
            prop_assert!((row.sum() - 1.0).abs() < 1e-12, "row sum {}", row.sum());
        }
        let pred = model.predict(&x).unwrap();
        for (i, &label) in pred.iter().enumerate() {
            let k = model.classes().iter().position(|&c| c == label).unwrap();
            let max = p.row(i).fold(f64::NEG_INFINITY, |a, &b| a.max(b));
            prop_assert_eq!(p[[i, k]], max);
        }
    }
}
