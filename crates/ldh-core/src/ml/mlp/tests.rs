//! Unit tests of `ml::mlp`.

mod errors;

use super::train::{backprop, stratified_split};
use super::*;
use linfa::traits::Predict;
use linfa::Dataset;
use ndarray::{Array1, Array2, Axis};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

const REFERENCE: &str = include_str!("../../../../../data-fixtures/golden/ml/mlp_reference.json");

fn accuracy(pred: &Array1<usize>, y: &[usize]) -> f64 {
    assert_eq!(pred.len(), y.len());
    pred.iter().zip(y).filter(|(a, b)| a == b).count() as f64 / y.len() as f64
}

/// sklearn's `make_moons`: two interleaved half circles plus Gaussian noise.
fn moons(n_per_class: usize, noise: f64, seed: u64) -> (Array2<f64>, Vec<usize>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, noise).unwrap();
    let mut x = Array2::zeros((2 * n_per_class, 2));
    let mut y = Vec::with_capacity(2 * n_per_class);
    for i in 0..n_per_class {
        let t = std::f64::consts::PI * i as f64 / (n_per_class - 1) as f64;
        x[[i, 0]] = t.cos() + normal.sample(&mut rng);
        x[[i, 1]] = t.sin() + normal.sample(&mut rng);
        y.push(0);
    }
    for i in 0..n_per_class {
        let t = std::f64::consts::PI * i as f64 / (n_per_class - 1) as f64;
        x[[n_per_class + i, 0]] = 1.0 - t.cos() + normal.sample(&mut rng);
        x[[n_per_class + i, 1]] = 0.5 - t.sin() + normal.sample(&mut rng);
        y.push(1);
    }
    (x, y)
}

/// Three Gaussian blobs (sd 0.5) around well separated centres, labels 3, 7, 9.
pub(super) fn blobs(n_per_class: usize, seed: u64) -> (Array2<f64>, Vec<usize>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, 0.5).unwrap();
    let centres = [(0.0, 0.0, 3), (4.0, 0.0, 7), (2.0, 4.0, 9)];
    let mut x = Array2::zeros((3 * n_per_class, 2));
    let mut y = Vec::new();
    for (k, &(cx, cy, label)) in centres.iter().enumerate() {
        for i in 0..n_per_class {
            let r = k * n_per_class + i;
            x[[r, 0]] = cx + normal.sample(&mut rng);
            x[[r, 1]] = cy + normal.sample(&mut rng);
            y.push(label);
        }
    }
    (x, y)
}

#[test]
fn defaults_match_sklearn() {
    let p = MlpParams::default().check().unwrap();
    assert_eq!(p.hidden_layer_sizes(), &[100]);
    assert_eq!(p.alpha(), 1e-4);
    assert_eq!(p.batch_size(), None);
    assert_eq!(p.learning_rate_init(), 1e-3);
    assert_eq!((p.beta_1(), p.beta_2(), p.epsilon()), (0.9, 0.999, 1e-8));
    assert_eq!(p.max_iter(), 200);
    assert_eq!(p.tol(), 1e-4);
    assert_eq!(p.n_iter_no_change(), 10);
    assert!(!p.early_stopping());
    assert_eq!(p.validation_fraction(), 0.1);
    assert!(p.shuffle());
    assert_eq!(p.seed(), 0);
}

#[test]
fn learns_two_moons() {
    let (x, y) = moons(100, 0.1, 1);
    let params = MlpParams::default().max_iter(500).seed(3).check().unwrap();
    let model = Mlp::fit(&params, x.view(), &y).unwrap();
    let acc = accuracy(&model.predict(x.view()).unwrap(), &y);
    assert!(acc >= 0.95, "moons training accuracy {acc}");
    // the loss went down substantially
    let curve = model.loss_curve();
    assert_eq!(curve.len(), model.n_epochs());
    assert!(curve[curve.len() - 1] < 0.5 * curve[0], "{curve:?}");
}

#[test]
fn learns_xor_with_two_hidden_layers() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let n = 200;
    let mut x = Array2::zeros((n, 2));
    let mut y = Vec::new();
    for i in 0..n {
        let (a, b): (f64, f64) = (rng.gen_range(-1.0..1.0), rng.gen_range(-1.0..1.0));
        x[[i, 0]] = a;
        x[[i, 1]] = b;
        y.push(usize::from((a > 0.0) != (b > 0.0)));
    }
    let params = MlpParams::default()
        .hidden_layer_sizes([16, 16])
        .learning_rate_init(1e-2)
        .max_iter(500)
        .seed(5)
        .check()
        .unwrap();
    let model = Mlp::fit(&params, x.view(), &y).unwrap();
    assert_eq!(model.coefs().len(), 3);
    let acc = accuracy(&model.predict(&x).unwrap(), &y);
    assert!(acc >= 0.95, "XOR training accuracy {acc}");
}

#[test]
fn learns_three_separable_classes_with_arbitrary_labels() {
    let (x, y) = blobs(50, 2);
    let params = MlpParams::default()
        .hidden_layer_sizes([32])
        .check()
        .unwrap();
    let model = Mlp::fit(&params, x.view(), &y).unwrap();
    assert_eq!(model.classes(), &[3, 7, 9]);
    let pred = model.predict(&x).unwrap();
    assert!(pred.iter().all(|p| [3, 7, 9].contains(p)));
    let acc = accuracy(&pred, &y);
    assert!(acc >= 0.95, "3-class training accuracy {acc}");
    let proba = model.predict_proba(&x).unwrap();
    assert_eq!(proba.dim(), (150, 3));
}

#[derive(serde::Deserialize)]
struct Reference {
    hidden_layer_sizes: Vec<usize>,
    max_iter: usize,
    x: Vec<Vec<f64>>,
    y: Vec<usize>,
    folds: Vec<Vec<usize>>,
    sklearn_fold_accuracy: Vec<f64>,
    sklearn_mean_accuracy: f64,
}

#[test]
fn iris_cv_accuracy_close_to_sklearn() {
    let r: Reference = serde_json::from_str(REFERENCE).unwrap();
    let n = r.x.len();
    let x = Array2::from_shape_fn((n, r.x[0].len()), |(i, j)| r.x[i][j]);
    let params = MlpParams::default()
        .hidden_layer_sizes(r.hidden_layer_sizes.clone())
        .max_iter(r.max_iter)
        .seed(0)
        .check()
        .unwrap();
    let mut ours = Vec::new();
    for test in &r.folds {
        let train: Vec<usize> = (0..n).filter(|i| !test.contains(i)).collect();
        let y_train: Vec<usize> = train.iter().map(|&i| r.y[i]).collect();
        let y_test: Vec<usize> = test.iter().map(|&i| r.y[i]).collect();
        let model = Mlp::fit(&params, x.select(Axis(0), &train).view(), &y_train).unwrap();
        let pred = model.predict(x.select(Axis(0), test)).unwrap();
        ours.push(accuracy(&pred, &y_test));
    }
    let mean = ours.iter().sum::<f64>() / ours.len() as f64;
    eprintln!(
        "iris 5-fold CV accuracy: ours {mean:.4} {ours:?}; sklearn {:.4} {:?}",
        r.sklearn_mean_accuracy, r.sklearn_fold_accuracy
    );
    assert_eq!(ours.len(), 5);
    assert!(
        (mean - r.sklearn_mean_accuracy).abs() <= 0.05,
        "ours {mean} vs sklearn {}",
        r.sklearn_mean_accuracy
    );
}

#[test]
fn deterministic_for_a_seed() {
    let (x, y) = moons(60, 0.2, 9);
    let make = |seed: u64| {
        MlpParams::default()
            .hidden_layer_sizes([8, 4])
            .batch_size(Some(16))
            .max_iter(50)
            .early_stopping(true)
            .seed(seed)
            .check()
            .unwrap()
    };
    let params = make(42);
    let a = Mlp::fit(&params, x.view(), &y).unwrap();
    let b = Mlp::fit(&params, x.view(), &y).unwrap();
    let bits = |m: &Mlp| -> Vec<u64> {
        m.coefs()
            .iter()
            .flat_map(|w| w.iter().map(|v| v.to_bits()).collect::<Vec<_>>())
            .chain(
                m.intercepts()
                    .iter()
                    .flat_map(|b| b.iter().map(|v| v.to_bits()).collect::<Vec<_>>()),
            )
            .collect()
    };
    assert_eq!(bits(&a), bits(&b));
    assert_eq!(a, b);
    let pa = a.predict_proba(&x).unwrap();
    let pb = b.predict_proba(&x).unwrap();
    assert!(pa
        .iter()
        .zip(pb.iter())
        .all(|(u, v)| u.to_bits() == v.to_bits()));
    assert_eq!(a.predict(&x).unwrap(), b.predict(&x).unwrap());
    // another seed gives other weights
    let c = Mlp::fit(&make(43), x.view(), &y).unwrap();
    assert_ne!(bits(&a), bits(&c));
}

#[test]
fn early_stopping_keeps_best_validation_weights() {
    let (x, y) = moons(100, 0.15, 4);
    let params = MlpParams::default()
        .hidden_layer_sizes([32])
        .batch_size(Some(20))
        .early_stopping(true)
        .max_iter(300)
        .seed(1)
        .check()
        .unwrap();
    let model = Mlp::fit(&params, x.view(), &y).unwrap();
    let scores = model.validation_scores();
    assert_eq!(scores.len(), model.n_epochs());
    assert_eq!(model.loss_curve().len(), model.n_epochs());
    assert!(scores.iter().all(|s| (0.0..=1.0).contains(s)));
    // sklearn's rule: stopped after n_iter_no_change + 1 = 11 epochs without beating the best
    // earlier score by tol
    assert!(model.converged() && model.n_epochs() < 300, "{scores:?}");
    let best = scores.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let best_before_tail = scores[..scores.len() - 11]
        .iter()
        .cloned()
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(scores[scores.len() - 11..]
        .iter()
        .all(|&s| s < best_before_tail + 1e-4));
    assert_eq!(best, best_before_tail);
    // the split is the first use of the seeded stream: rebuild it and check that the kept
    // weights are those of the best validation epoch, not of the last one
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let (train, val) = stratified_split(&y, 2, 0.1, &mut rng);
    assert_eq!((train.len(), val.len()), (180, 20));
    let y_val: Vec<usize> = val.iter().map(|&i| y[i]).collect();
    let val_acc = accuracy(&model.predict(x.select(Axis(0), &val)).unwrap(), &y_val);
    assert_eq!(val_acc, best);
    // a 20-row validation set stops training early (as in sklearn): well above chance only
    let acc = accuracy(&model.predict(&x).unwrap(), &y);
    assert!(
        acc >= 0.7,
        "accuracy with early stopping {acc}, scores {scores:?}"
    );
}

#[test]
fn backprop_gradients_match_finite_differences() {
    // two hidden layers, three classes, L2 on: every analytic gradient against a central
    // difference of the mini-batch loss
    let mut rng = ChaCha8Rng::seed_from_u64(17);
    let sizes = [3usize, 5, 4, 3];
    let mut coefs: Vec<Array2<f64>> = sizes
        .windows(2)
        .map(|s| Array2::from_shape_fn((s[0], s[1]), |_| rng.gen_range(-1.0..1.0)))
        .collect();
    let mut intercepts: Vec<Array1<f64>> = sizes[1..]
        .iter()
        .map(|&n| Array1::from_shape_fn(n, |_| rng.gen_range(-0.5..0.5)))
        .collect();
    let x = Array2::from_shape_fn((7, 3), |_| rng.gen_range(-2.0..2.0));
    let y = [0, 1, 2, 2, 1, 0, 1];
    let alpha = 0.3;
    let (_, g_w, g_b) = backprop(&coefs, &intercepts, x.view(), &y, alpha);
    let h = 1e-6;
    let mut checked = 0;
    for l in 0..coefs.len() {
        for idx in 0..coefs[l].len() {
            let (r, c) = (idx / coefs[l].ncols(), idx % coefs[l].ncols());
            let orig = coefs[l][[r, c]];
            coefs[l][[r, c]] = orig + h;
            let up = backprop(&coefs, &intercepts, x.view(), &y, alpha).0;
            coefs[l][[r, c]] = orig - h;
            let down = backprop(&coefs, &intercepts, x.view(), &y, alpha).0;
            coefs[l][[r, c]] = orig;
            let numeric = (up - down) / (2.0 * h);
            assert!(
                (numeric - g_w[l][[r, c]]).abs() < 1e-6,
                "W{l}[{r},{c}]: {numeric} vs {}",
                g_w[l][[r, c]]
            );
            checked += 1;
        }
        for j in 0..intercepts[l].len() {
            let orig = intercepts[l][j];
            intercepts[l][j] = orig + h;
            let up = backprop(&coefs, &intercepts, x.view(), &y, alpha).0;
            intercepts[l][j] = orig - h;
            let down = backprop(&coefs, &intercepts, x.view(), &y, alpha).0;
            intercepts[l][j] = orig;
            let numeric = (up - down) / (2.0 * h);
            assert!(
                (numeric - g_b[l][j]).abs() < 1e-6,
                "b{l}[{j}]: {numeric} vs {}",
                g_b[l][j]
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 3 * 5 + 5 * 4 + 4 * 3 + 5 + 4 + 3);
}

#[test]
fn stratified_split_is_balanced() {
    let y_idx: Vec<usize> = (0..100).map(|i| usize::from(i >= 70)).collect();
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    let (train, val) = stratified_split(&y_idx, 2, 0.1, &mut rng);
    assert_eq!(val.len(), 10);
    assert_eq!(train.len(), 90);
    assert_eq!(val.iter().filter(|&&i| y_idx[i] == 1).count(), 3);
    let mut all: Vec<usize> = train.iter().chain(&val).copied().collect();
    all.sort_unstable();
    assert_eq!(all, (0..100).collect::<Vec<_>>());
}

#[test]
fn fits_and_predicts_through_linfa_traits() {
    let (x, y) = blobs(30, 5);
    let dataset = Dataset::new(x.clone(), Array1::from(y.clone()));
    // checked params implement `Fit`, and unchecked ones through linfa's `ParamGuard`
    let valid = MlpParams::default()
        .hidden_layer_sizes([16])
        .seed(2)
        .check()
        .unwrap();
    let model: Mlp = valid.fit(&dataset).unwrap();
    let model2: Mlp = MlpParams::default()
        .hidden_layer_sizes([16])
        .seed(2)
        .fit(&dataset)
        .unwrap();
    assert_eq!(model, model2);
    // linfa's infallible `Predict` (via `PredictInplace`)
    let by_trait: Array1<usize> = Predict::predict(&model, &dataset);
    let inherent = model.predict(&dataset).unwrap();
    assert_eq!(by_trait, inherent);
    assert!(accuracy(&by_trait, &y) >= 0.95);
    // predicting a dataset into a dataset, and linfa's metrics on top
    let pred_ds = Predict::predict(&model, Dataset::new(x.clone(), Array1::from(y.clone())));
    assert_eq!(pred_ds.targets, inherent);
    use linfa::prelude::ToConfusionMatrix;
    let cm = by_trait.confusion_matrix(&dataset).unwrap();
    assert!(cm.accuracy() >= 0.95);
    // generic code bound on linfa's traits only
    fn predict_generic<M: PredictInplace<Array2<f64>, Array1<usize>>>(
        m: &M,
        x: &Array2<f64>,
    ) -> Array1<usize> {
        let mut y = m.default_target(x);
        m.predict_inplace(x, &mut y);
        y
    }
    assert_eq!(predict_generic(&model, &x), inherent);
    // a fit error through the linfa path
    let one_class = Dataset::new(x.clone(), Array1::from(vec![1usize; x.nrows()]));
    assert!(matches!(
        valid.fit(&one_class),
        Err(MlpError::TooFewClasses(1))
    ));
    let bad: Result<Mlp, MlpError> = MlpParams::default().alpha(-1.0).fit(&dataset);
    assert!(matches!(
        bad,
        Err(MlpError::InvalidParameter { name: "alpha", .. })
    ));
}

#[test]
#[should_panic(expected = "shape mismatch")]
fn linfa_predict_panics_on_shape_mismatch() {
    let (x, y) = blobs(10, 1);
    let params = MlpParams::default()
        .hidden_layer_sizes([4])
        .max_iter(5)
        .check()
        .unwrap();
    let model = Mlp::fit(&params, x.view(), &y).unwrap();
    let wrong = Array2::<f64>::zeros((3, 5));
    let _: Array1<usize> = Predict::predict(&model, &wrong);
}

#[test]
fn json_round_trip() {
    let (x, y) = blobs(20, 3);
    let params = MlpParams::default()
        .hidden_layer_sizes([8, 6])
        .max_iter(30)
        .check()
        .unwrap();
    let model = Mlp::fit(&params, x.view(), &y).unwrap();
    let json = serde_json::to_string(&model).unwrap();
    let back: Mlp = serde_json::from_str(&json).unwrap();
    // serde_json parses floats exactly only with its `float_roundtrip` feature; without it a
    // weight may come back 1 ulp off, so compare with a relative tolerance
    let close = |a: f64, b: f64| (a - b).abs() <= 4.0 * f64::EPSILON * a.abs().max(b.abs());
    for (wa, wb) in model.coefs().iter().zip(back.coefs()) {
        assert_eq!(wa.dim(), wb.dim());
        assert!(wa.iter().zip(wb.iter()).all(|(&a, &b)| close(a, b)));
    }
    for (ba, bb) in model.intercepts().iter().zip(back.intercepts()) {
        assert!(ba.iter().zip(bb.iter()).all(|(&a, &b)| close(a, b)));
    }
    assert_eq!(back.classes(), model.classes());
    assert_eq!(back.n_features(), model.n_features());
    assert_eq!(back.n_epochs(), model.n_epochs());
    assert_eq!(back.converged(), model.converged());
    assert_eq!(back.loss_curve().len(), model.loss_curve().len());
    assert_eq!(back.predict(&x).unwrap(), model.predict(&x).unwrap());
    let (pa, pb) = (
        model.predict_proba(&x).unwrap(),
        back.predict_proba(&x).unwrap(),
    );
    assert!(pa.iter().zip(pb.iter()).all(|(a, b)| (a - b).abs() < 1e-12));
    // inconsistent layer shapes are refused
    let mut v: serde_json::Value = serde_json::from_str(&json).unwrap();
    v["n_features"] = serde_json::json!(3);
    let err = serde_json::from_value::<Mlp>(v).unwrap_err().to_string();
    assert!(err.contains("layer 0"), "{err}");
    // params round trip, and partial configs take defaults
    let p = MlpParams::default().hidden_layer_sizes([7]).seed(9);
    let pj = serde_json::to_string(&p).unwrap();
    assert_eq!(serde_json::from_str::<MlpParams>(&pj).unwrap(), p);
    let partial: MlpParams = serde_json::from_str(r#"{"alpha": 0.01}"#).unwrap();
    assert_eq!(partial, MlpParams::default().alpha(0.01));
    assert!(serde_json::from_str::<MlpParams>(r#"{"alpah": 0.01}"#).is_err());
}
