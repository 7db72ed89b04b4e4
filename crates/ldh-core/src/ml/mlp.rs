//! A small multi-layer perceptron (MLP) classifier on `ndarray`, in the linfa style.
//!
//! linfa 0.8 has no neural network, and no maintained crate offers a small dense
//! classifier without pulling in a deep-learning framework (burn, candle: +70-90 s of build),
//! so the numerics here are hand-written: a few matrix products (ndarray's `dot`),
//! ReLU, softmax and Adam.
//!
//! # Method
//!
//! * Architecture: `n_features -> hidden_layer_sizes[0] (-> hidden_layer_sizes[1]) -> n_classes`,
//!   ReLU on the hidden layers, softmax on the output layer.
//! * Loss: mean cross-entropy over a mini-batch plus the L2 penalty
//!   `0.5 * alpha * sum(W^2) / batch_len` (biases are not penalised), as in sklearn.
//! * Initialisation: Glorot uniform as sklearn's `_init_coef` for ReLU networks:
//!   weights *and* biases of every layer drawn from `U(-b, b)`, `b = sqrt(6 / (fan_in + fan_out))`.
//! * Optimiser: Adam with sklearn's bias-corrected step
//!   `lr_t = lr * sqrt(1 - beta2^t) / (1 - beta1^t)`, `p -= lr_t * m / (sqrt(v) + eps)`.
//! * Epochs: the training rows are shuffled (if `shuffle`) and cut into mini-batches of
//!   `batch_size` rows (the last one may be shorter). The epoch loss is the batch losses
//!   weighted by batch length.
//! * Stopping (sklearn's rule): without early stopping, an epoch counts as "no improvement"
//!   when its training loss is `> best_loss - tol`; with early stopping, when the accuracy on
//!   the held-out validation set is `< best_score + tol`. Training stops once the count of
//!   consecutive such epochs exceeds `n_iter_no_change`, or after `max_iter` epochs. With
//!   early stopping the weights of the best validation epoch are kept.
//! * Randomness: one `ChaCha8Rng` seeded with `seed` drives, in this order, the
//!   validation split, the initial weights and the per-epoch shuffles, so the same seed and
//!   data give bit-identical weights and predictions (on the same build and CPU).
//!
//! # Defaults (as sklearn's `MLPClassifier`)
//!
//! `hidden_layer_sizes = [100]`, `alpha = 1e-4`, `batch_size = min(200, n_train)`,
//! `learning_rate_init = 1e-3`, `beta_1 = 0.9`, `beta_2 = 0.999`, `epsilon = 1e-8`,
//! `max_iter = 200`, `tol = 1e-4`, `n_iter_no_change = 10`, `early_stopping = false`,
//! `validation_fraction = 0.1`, `shuffle = true`, `seed = 0`.
//!
//! # Differences from sklearn
//!
//! * Only the ReLU activation and the Adam solver (no `sgd`/`lbfgs`, no learning-rate schedules).
//! * Two classes also use a two-unit softmax output (sklearn uses one logistic unit); the model
//!   is equivalent, but the number of weights and hence the random stream differ.
//! * Random numbers come from ChaCha8, not numpy's Mersenne twister: results match sklearn
//!   statistically, not bit for bit.
//! * The early-stopping split is stratified by largest remainders (sklearn uses
//!   `train_test_split(stratify=y)`); it takes `ceil(validation_fraction * n)` rows like sklearn.
//! * At most two hidden layers; sample weights of a linfa dataset are ignored.
//! * Non-finite inputs and a diverging (non-finite) training loss are errors.
//!
//! # Example
//!
//! ```
//! use ldh_core::ml::mlp::{Mlp, MlpError, MlpParams};
//! use linfa::prelude::*;
//! use ndarray::{array, Array1};
//!
//! # fn main() -> Result<(), MlpError> {
//! let x = array![[0.0, 0.1], [0.1, 0.0], [0.9, 1.0], [1.0, 0.9], [0.0, 1.0], [0.1, 0.9]];
//! let y = vec![0, 0, 1, 1, 2, 2];
//! let params = MlpParams::default().hidden_layer_sizes([16]).max_iter(300).seed(7).check()?;
//! let model = Mlp::fit(&params, x.view(), &y)?; // inherent API
//! let labels = model.predict(&x)?; // Result<Array1<usize>, MlpError>
//! let proba = model.predict_proba(&x)?; // columns in `model.classes()` order
//! assert_eq!(proba.dim(), (6, 3));
//! assert_eq!(labels.len(), 6);
//!
//! // linfa style: `Fit` on a dataset, infallible `Predict` through `PredictInplace`
//! let dataset = Dataset::new(x.clone(), Array1::from(y.clone()));
//! let model2 = params.fit(&dataset)?;
//! let labels2: Array1<usize> = Predict::predict(&model2, &dataset);
//! assert_eq!(labels2, labels); // same seed, same data: same model
//!
//! // save / load as JSON
//! let json = serde_json::to_string(&model).expect("serialise");
//! let loaded: Mlp = serde_json::from_str(&json).expect("deserialise");
//! assert_eq!(loaded.predict(&x)?, labels);
//! # Ok(())
//! # }
//! ```

use linfa::dataset::{DatasetBase, Records};
use linfa::traits::{Fit, PredictInplace};
use linfa::ParamGuard;
use ndarray::{Array1, Array2, ArrayBase, ArrayView2, Axis, Data, Ix1, Ix2, Zip};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Errors of parameter checking, fitting and prediction.
#[derive(Debug, Error)]
pub enum MlpError {
    /// A hyper-parameter is out of range (`name` is the field, `reason` says what is allowed).
    #[error("invalid MLP parameter `{name}`: {reason}")]
    InvalidParameter {
        /// Name of the offending field of [`MlpParams`].
        name: &'static str,
        /// What was wrong with the value.
        reason: String,
    },
    /// The training matrix has no rows or no columns.
    #[error(
        "empty training data: got {n_samples} samples x {n_features} features, need at least 1 x 1"
    )]
    EmptyData {
        /// Rows of the training matrix.
        n_samples: usize,
        /// Columns of the training matrix.
        n_features: usize,
    },
    /// The targets contain fewer than two distinct labels.
    #[error("need at least 2 distinct classes in the targets, found {0}")]
    TooFewClasses(usize),
    /// A feature value is NaN or infinite.
    #[error("non-finite feature value {value} at row {row}, column {col}")]
    NonFiniteFeature {
        /// Row of the value.
        row: usize,
        /// Column of the value.
        col: usize,
        /// The value itself (NaN or ±inf).
        value: f64,
    },
    /// The number of feature rows and targets differ.
    #[error("mismatched lengths: {n_samples} feature rows but {n_targets} targets")]
    LengthMismatch {
        /// Rows of the feature matrix.
        n_samples: usize,
        /// Length of the target vector.
        n_targets: usize,
    },
    /// The matrix given to a prediction has a different number of columns than the training data.
    #[error(
        "shape mismatch: the model was trained on {expected} features but the input has {found}"
    )]
    FeatureMismatch {
        /// Number of features at training time.
        expected: usize,
        /// Number of columns of the input.
        found: usize,
    },
    /// Early stopping needs at least one training and one validation row.
    #[error(
        "early stopping with validation_fraction {validation_fraction} leaves {n_train} training and \
         {n_validation} validation samples of {n_samples}; need at least 1 of each"
    )]
    TooFewSamplesForValidation {
        /// Total number of samples.
        n_samples: usize,
        /// Rows left for training.
        n_train: usize,
        /// Rows held out for validation.
        n_validation: usize,
        /// The requested fraction.
        validation_fraction: f64,
    },
    /// The training loss became NaN or infinite (learning rate too large for the data scale).
    #[error("training diverged: the loss of epoch {epoch} is {loss}; scale the features or lower learning_rate_init")]
    Diverged {
        /// 1-based epoch whose loss was not finite.
        epoch: usize,
        /// The loss value.
        loss: f64,
    },
    /// An error reported by linfa (required by linfa's `Fit` trait).
    #[error(transparent)]
    Linfa(#[from] linfa::Error),
}

/// Checked hyper-parameters of [`Mlp`]; obtain them with [`MlpParams::check`].
///
/// Serialisable so that a configuration can be stored; [`Mlp::fit`] re-validates the values,
/// so a hand-edited deserialised `ValidMlpParams` cannot train with invalid settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ValidMlpParams {
    hidden_layer_sizes: Vec<usize>,
    alpha: f64,
    batch_size: Option<usize>,
    learning_rate_init: f64,
    beta_1: f64,
    beta_2: f64,
    epsilon: f64,
    max_iter: usize,
    tol: f64,
    n_iter_no_change: usize,
    early_stopping: bool,
    validation_fraction: f64,
    shuffle: bool,
    seed: u64,
}

impl Default for ValidMlpParams {
    fn default() -> Self {
        Self {
            hidden_layer_sizes: vec![100],
            alpha: 1e-4,
            batch_size: None,
            learning_rate_init: 1e-3,
            beta_1: 0.9,
            beta_2: 0.999,
            epsilon: 1e-8,
            max_iter: 200,
            tol: 1e-4,
            n_iter_no_change: 10,
            early_stopping: false,
            validation_fraction: 0.1,
            shuffle: true,
            seed: 0,
        }
    }
}

fn invalid(name: &'static str, reason: impl Into<String>) -> MlpError {
    MlpError::InvalidParameter {
        name,
        reason: reason.into(),
    }
}

impl ValidMlpParams {
    fn validate(&self) -> Result<(), MlpError> {
        let h = &self.hidden_layer_sizes;
        if h.is_empty() || h.len() > 2 {
            return Err(invalid(
                "hidden_layer_sizes",
                format!("need 1 or 2 hidden layers, got {}", h.len()),
            ));
        }
        if h.contains(&0) {
            return Err(invalid(
                "hidden_layer_sizes",
                format!("every layer needs at least 1 unit, got {h:?}"),
            ));
        }
        if !(self.alpha.is_finite() && self.alpha >= 0.0) {
            return Err(invalid(
                "alpha",
                format!("must be finite and >= 0, got {}", self.alpha),
            ));
        }
        if self.batch_size == Some(0) {
            return Err(invalid("batch_size", "must be >= 1 (or None for auto)"));
        }
        if !(self.learning_rate_init.is_finite() && self.learning_rate_init > 0.0) {
            return Err(invalid(
                "learning_rate_init",
                format!("must be finite and > 0, got {}", self.learning_rate_init),
            ));
        }
        for (name, v) in [("beta_1", self.beta_1), ("beta_2", self.beta_2)] {
            if !(0.0..1.0).contains(&v) {
                return Err(invalid(name, format!("must be in [0, 1), got {v}")));
            }
        }
        if !(self.epsilon.is_finite() && self.epsilon > 0.0) {
            return Err(invalid(
                "epsilon",
                format!("must be finite and > 0, got {}", self.epsilon),
            ));
        }
        if self.max_iter == 0 {
            return Err(invalid("max_iter", "must be >= 1"));
        }
        if !(self.tol.is_finite() && self.tol >= 0.0) {
            return Err(invalid(
                "tol",
                format!("must be finite and >= 0, got {}", self.tol),
            ));
        }
        if self.n_iter_no_change == 0 {
            return Err(invalid("n_iter_no_change", "must be >= 1"));
        }
        if !(self.validation_fraction > 0.0 && self.validation_fraction < 1.0) {
            return Err(invalid(
                "validation_fraction",
                format!("must be in (0, 1), got {}", self.validation_fraction),
            ));
        }
        Ok(())
    }

    /// Sizes of the hidden layers (default `[100]`).
    pub fn hidden_layer_sizes(&self) -> &[usize] {
        &self.hidden_layer_sizes
    }
    /// L2 penalty (default `1e-4`).
    pub fn alpha(&self) -> f64 {
        self.alpha
    }
    /// Mini-batch size; `None` (default) means `min(200, n_train)`.
    pub fn batch_size(&self) -> Option<usize> {
        self.batch_size
    }
    /// Adam step size (default `1e-3`).
    pub fn learning_rate_init(&self) -> f64 {
        self.learning_rate_init
    }
    /// Adam first-moment decay (default `0.9`).
    pub fn beta_1(&self) -> f64 {
        self.beta_1
    }
    /// Adam second-moment decay (default `0.999`).
    pub fn beta_2(&self) -> f64 {
        self.beta_2
    }
    /// Adam denominator offset (default `1e-8`).
    pub fn epsilon(&self) -> f64 {
        self.epsilon
    }
    /// Maximum number of epochs (default `200`).
    pub fn max_iter(&self) -> usize {
        self.max_iter
    }
    /// Improvement threshold of the stopping rule (default `1e-4`).
    pub fn tol(&self) -> f64 {
        self.tol
    }
    /// Epochs without improvement tolerated before stopping (default `10`).
    pub fn n_iter_no_change(&self) -> usize {
        self.n_iter_no_change
    }
    /// Whether to stop on a held-out validation accuracy (default `false`).
    pub fn early_stopping(&self) -> bool {
        self.early_stopping
    }
    /// Fraction held out (stratified) when early stopping (default `0.1`).
    pub fn validation_fraction(&self) -> f64 {
        self.validation_fraction
    }
    /// Whether the training rows are shuffled every epoch (default `true`).
    pub fn shuffle(&self) -> bool {
        self.shuffle
    }
    /// Seed of the random stream (default `0`).
    pub fn seed(&self) -> u64 {
        self.seed
    }
}

/// Unchecked hyper-parameters of [`Mlp`], with sklearn's `MLPClassifier` defaults
/// (see the module documentation). Set values with the builder methods, then call
/// [`check`](MlpParams::check) (or let linfa's `Fit` on `MlpParams` do it).
///
/// Serialises as a flat object of the fields; missing fields take their defaults.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(transparent)]
pub struct MlpParams(ValidMlpParams);

impl MlpParams {
    /// The default parameters (same as `MlpParams::default()`).
    pub fn new() -> Self {
        Self::default()
    }
    /// Sizes of the 1 or 2 hidden layers (default `[100]`).
    pub fn hidden_layer_sizes(mut self, sizes: impl Into<Vec<usize>>) -> Self {
        self.0.hidden_layer_sizes = sizes.into();
        self
    }
    /// L2 penalty `alpha >= 0` (default `1e-4`).
    pub fn alpha(mut self, alpha: f64) -> Self {
        self.0.alpha = alpha;
        self
    }
    /// Mini-batch size; `None` (default) means `min(200, n_train)`. Larger values are
    /// clipped to the number of training rows, as in sklearn.
    pub fn batch_size(mut self, batch_size: Option<usize>) -> Self {
        self.0.batch_size = batch_size;
        self
    }
    /// Adam step size `> 0` (default `1e-3`).
    pub fn learning_rate_init(mut self, lr: f64) -> Self {
        self.0.learning_rate_init = lr;
        self
    }
    /// Adam first-moment decay in `[0, 1)` (default `0.9`).
    pub fn beta_1(mut self, beta_1: f64) -> Self {
        self.0.beta_1 = beta_1;
        self
    }
    /// Adam second-moment decay in `[0, 1)` (default `0.999`).
    pub fn beta_2(mut self, beta_2: f64) -> Self {
        self.0.beta_2 = beta_2;
        self
    }
    /// Adam denominator offset `> 0` (default `1e-8`).
    pub fn epsilon(mut self, epsilon: f64) -> Self {
        self.0.epsilon = epsilon;
        self
    }
    /// Maximum number of epochs `>= 1` (default `200`).
    pub fn max_iter(mut self, max_iter: usize) -> Self {
        self.0.max_iter = max_iter;
        self
    }
    /// Improvement threshold of the stopping rule, `>= 0` (default `1e-4`).
    pub fn tol(mut self, tol: f64) -> Self {
        self.0.tol = tol;
        self
    }
    /// Epochs without improvement tolerated before stopping, `>= 1` (default `10`).
    pub fn n_iter_no_change(mut self, n: usize) -> Self {
        self.0.n_iter_no_change = n;
        self
    }
    /// Stop on held-out validation accuracy and keep the best weights (default `false`).
    pub fn early_stopping(mut self, early_stopping: bool) -> Self {
        self.0.early_stopping = early_stopping;
        self
    }
    /// Fraction in `(0, 1)` held out (stratified) when early stopping (default `0.1`).
    pub fn validation_fraction(mut self, fraction: f64) -> Self {
        self.0.validation_fraction = fraction;
        self
    }
    /// Shuffle the training rows every epoch (default `true`).
    pub fn shuffle(mut self, shuffle: bool) -> Self {
        self.0.shuffle = shuffle;
        self
    }
    /// Seed of the random stream (default `0`).
    pub fn seed(mut self, seed: u64) -> Self {
        self.0.seed = seed;
        self
    }
    /// Validates the parameters.
    ///
    /// # Errors
    /// [`MlpError::InvalidParameter`] naming the first field out of range.
    pub fn check(self) -> Result<ValidMlpParams, MlpError> {
        self.0.validate()?;
        Ok(self.0)
    }
}

impl ParamGuard for MlpParams {
    type Checked = ValidMlpParams;
    type Error = MlpError;

    fn check_ref(&self) -> Result<&ValidMlpParams, MlpError> {
        self.0.validate()?;
        Ok(&self.0)
    }

    fn check(self) -> Result<ValidMlpParams, MlpError> {
        MlpParams::check(self)
    }
}

/// Anything the inherent [`Mlp::predict`] / [`Mlp::predict_proba`] accept as a feature matrix:
/// any 2-D `f64` ndarray (owned or view), a reference to one, or a linfa dataset of one.
pub trait FeatureMatrix {
    /// A `(n_samples, n_features)` view of the features.
    fn feature_view(&self) -> ArrayView2<'_, f64>;
}

impl<D: Data<Elem = f64>> FeatureMatrix for ArrayBase<D, Ix2> {
    fn feature_view(&self) -> ArrayView2<'_, f64> {
        self.view()
    }
}

impl<R: FeatureMatrix + Records, T> FeatureMatrix for DatasetBase<R, T> {
    fn feature_view(&self) -> ArrayView2<'_, f64> {
        self.records.feature_view()
    }
}

impl<F: FeatureMatrix + ?Sized> FeatureMatrix for &F {
    fn feature_view(&self) -> ArrayView2<'_, f64> {
        (**self).feature_view()
    }
}

/// A fitted multi-layer perceptron classifier.
///
/// Serialises to JSON with [`serde_json`] (weights as ndarray's `{"v","dim","data"}` objects);
/// deserialisation checks that the layer shapes fit together.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "MlpRepr")]
pub struct Mlp {
    coefs: Vec<Array2<f64>>,
    intercepts: Vec<Array1<f64>>,
    classes: Vec<usize>,
    n_features: usize,
    loss_curve: Vec<f64>,
    validation_scores: Vec<f64>,
    n_epochs: usize,
    converged: bool,
}

/// Unvalidated mirror of [`Mlp`] for deserialisation.
#[derive(Deserialize)]
struct MlpRepr {
    coefs: Vec<Array2<f64>>,
    intercepts: Vec<Array1<f64>>,
    classes: Vec<usize>,
    n_features: usize,
    loss_curve: Vec<f64>,
    validation_scores: Vec<f64>,
    n_epochs: usize,
    converged: bool,
}

impl TryFrom<MlpRepr> for Mlp {
    type Error = String;

    fn try_from(r: MlpRepr) -> Result<Self, String> {
        if r.coefs.len() < 2 || r.coefs.len() != r.intercepts.len() {
            return Err(format!(
                "need >= 2 weight matrices and as many bias vectors, got {} and {}",
                r.coefs.len(),
                r.intercepts.len()
            ));
        }
        let mut fan_in = r.n_features;
        for (l, (w, b)) in r.coefs.iter().zip(&r.intercepts).enumerate() {
            if w.nrows() != fan_in || w.ncols() != b.len() || w.ncols() == 0 {
                return Err(format!(
                    "layer {l}: weights {:?} and bias {} do not follow a layer of {fan_in} units",
                    w.shape(),
                    b.len()
                ));
            }
            fan_in = w.ncols();
        }
        if fan_in != r.classes.len() || r.classes.len() < 2 {
            return Err(format!(
                "output layer has {fan_in} units for {} classes",
                r.classes.len()
            ));
        }
        Ok(Mlp {
            coefs: r.coefs,
            intercepts: r.intercepts,
            classes: r.classes,
            n_features: r.n_features,
            loss_curve: r.loss_curve,
            validation_scores: r.validation_scores,
            n_epochs: r.n_epochs,
            converged: r.converged,
        })
    }
}

fn check_finite(x: &ArrayView2<'_, f64>) -> Result<(), MlpError> {
    for ((row, col), &value) in x.indexed_iter() {
        if !value.is_finite() {
            return Err(MlpError::NonFiniteFeature { row, col, value });
        }
    }
    Ok(())
}

/// Row-wise softmax in place (max-subtracted).
fn softmax_rows(z: &mut Array2<f64>) {
    for mut row in z.rows_mut() {
        let max = row.fold(f64::NEG_INFINITY, |a, &b| a.max(b));
        row.mapv_inplace(|v| (v - max).exp());
        let sum = row.sum();
        row.mapv_inplace(|v| v / sum);
    }
}

/// Forward pass: the activations of every layer, input first, softmax output last.
fn forward(
    coefs: &[Array2<f64>],
    intercepts: &[Array1<f64>],
    x: ArrayView2<'_, f64>,
) -> Vec<Array2<f64>> {
    let n_layers = coefs.len();
    let mut acts = Vec::with_capacity(n_layers + 1);
    acts.push(x.to_owned());
    for (l, (w, b)) in coefs.iter().zip(intercepts).enumerate() {
        let mut z = acts[l].dot(w) + b;
        if l + 1 < n_layers {
            z.mapv_inplace(|v| v.max(0.0));
        } else {
            softmax_rows(&mut z);
        }
        acts.push(z);
    }
    acts
}

/// Index of the first maximum of each row.
fn argmax_rows(p: &Array2<f64>) -> Vec<usize> {
    p.rows()
        .into_iter()
        .map(|row| {
            let mut best = 0;
            for (j, &v) in row.iter().enumerate() {
                if v > row[best] {
                    best = j;
                }
            }
            best
        })
        .collect()
}

/// Adam moment estimates for all layers (sklearn's `AdamOptimizer`).
struct Adam {
    lr: f64,
    beta_1: f64,
    beta_2: f64,
    eps: f64,
    t: i32,
    m_w: Vec<Array2<f64>>,
    v_w: Vec<Array2<f64>>,
    m_b: Vec<Array1<f64>>,
    v_b: Vec<Array1<f64>>,
}

impl Adam {
    fn new(p: &ValidMlpParams, coefs: &[Array2<f64>], intercepts: &[Array1<f64>]) -> Self {
        Self {
            lr: p.learning_rate_init,
            beta_1: p.beta_1,
            beta_2: p.beta_2,
            eps: p.epsilon,
            t: 0,
            m_w: coefs.iter().map(|w| Array2::zeros(w.raw_dim())).collect(),
            v_w: coefs.iter().map(|w| Array2::zeros(w.raw_dim())).collect(),
            m_b: intercepts
                .iter()
                .map(|b| Array1::zeros(b.raw_dim()))
                .collect(),
            v_b: intercepts
                .iter()
                .map(|b| Array1::zeros(b.raw_dim()))
                .collect(),
        }
    }

    fn step(
        &mut self,
        coefs: &mut [Array2<f64>],
        intercepts: &mut [Array1<f64>],
        g_w: &[Array2<f64>],
        g_b: &[Array1<f64>],
    ) {
        self.t = self.t.saturating_add(1);
        let (b1, b2, eps) = (self.beta_1, self.beta_2, self.eps);
        let lr_t = self.lr * (1.0 - b2.powi(self.t)).sqrt() / (1.0 - b1.powi(self.t));
        let upd = |p: &mut f64, m: &mut f64, v: &mut f64, &g: &f64| {
            *m = b1 * *m + (1.0 - b1) * g;
            *v = b2 * *v + (1.0 - b2) * g * g;
            *p += -lr_t * *m / (v.sqrt() + eps);
        };
        for l in 0..coefs.len() {
            Zip::from(&mut coefs[l])
                .and(&mut self.m_w[l])
                .and(&mut self.v_w[l])
                .and(&g_w[l])
                .for_each(upd);
            Zip::from(&mut intercepts[l])
                .and(&mut self.m_b[l])
                .and(&mut self.v_b[l])
                .and(&g_b[l])
                .for_each(upd);
        }
    }
}

/// Stratified hold-out split: `ceil(fraction * n)` validation rows, allocated to the classes
/// by largest remainder, drawn at random within each class. Returns `(train, validation)`.
fn stratified_split(
    y_idx: &[usize],
    n_classes: usize,
    fraction: f64,
    rng: &mut ChaCha8Rng,
) -> (Vec<usize>, Vec<usize>) {
    let n = y_idx.len();
    let n_val = ((fraction * n as f64).ceil() as usize).min(n);
    let mut by_class: Vec<Vec<usize>> = vec![Vec::new(); n_classes];
    for (i, &c) in y_idx.iter().enumerate() {
        by_class[c].push(i);
    }
    let exact: Vec<f64> = by_class
        .iter()
        .map(|v| v.len() as f64 * n_val as f64 / n as f64)
        .collect();
    let mut take: Vec<usize> = exact.iter().map(|e| e.floor() as usize).collect();
    let mut order: Vec<usize> = (0..n_classes).collect();
    // largest remainder first; ties to the lower class index (stable sort)
    order.sort_by(|&a, &b| {
        let ra = exact[a] - exact[a].floor();
        let rb = exact[b] - exact[b].floor();
        rb.total_cmp(&ra)
    });
    let mut missing = n_val - take.iter().sum::<usize>();
    for &c in order.iter().cycle().take(n_classes * 2) {
        if missing == 0 {
            break;
        }
        if take[c] < by_class[c].len() {
            take[c] += 1;
            missing -= 1;
        }
    }
    let (mut train, mut val) = (Vec::new(), Vec::new());
    for (c, rows) in by_class.iter_mut().enumerate() {
        rows.shuffle(rng);
        val.extend_from_slice(&rows[..take[c]]);
        train.extend_from_slice(&rows[take[c]..]);
    }
    train.sort_unstable();
    val.sort_unstable();
    (train, val)
}

impl Mlp {
    /// Default (unchecked) hyper-parameters, linfa style: `Mlp::params().seed(1).check()?`.
    pub fn params() -> MlpParams {
        MlpParams::default()
    }

    /// Trains a network on `x` (`n_samples x n_features`) and class labels `y`.
    ///
    /// The labels may be any `usize` values; [`classes`](Mlp::classes) keeps them sorted and
    /// predictions return them as given.
    ///
    /// # Errors
    /// [`MlpError::InvalidParameter`], [`MlpError::EmptyData`], [`MlpError::LengthMismatch`],
    /// [`MlpError::NonFiniteFeature`], [`MlpError::TooFewClasses`],
    /// [`MlpError::TooFewSamplesForValidation`] (early stopping), [`MlpError::Diverged`].
    pub fn fit(
        params: &ValidMlpParams,
        x: ArrayView2<'_, f64>,
        y: &[usize],
    ) -> Result<Mlp, MlpError> {
        params.validate()?;
        let (n, n_features) = x.dim();
        if n == 0 || n_features == 0 {
            return Err(MlpError::EmptyData {
                n_samples: n,
                n_features,
            });
        }
        if y.len() != n {
            return Err(MlpError::LengthMismatch {
                n_samples: n,
                n_targets: y.len(),
            });
        }
        check_finite(&x)?;
        let mut classes = y.to_vec();
        classes.sort_unstable();
        classes.dedup();
        if classes.len() < 2 {
            return Err(MlpError::TooFewClasses(classes.len()));
        }
        let n_classes = classes.len();
        let y_idx: Vec<usize> = y
            .iter()
            .map(|c| classes.binary_search(c).expect("label is in classes"))
            .collect();

        let mut rng = ChaCha8Rng::seed_from_u64(params.seed);
        let (mut train, val) = if params.early_stopping {
            let (train, val) =
                stratified_split(&y_idx, n_classes, params.validation_fraction, &mut rng);
            if train.is_empty() || val.is_empty() {
                return Err(MlpError::TooFewSamplesForValidation {
                    n_samples: n,
                    n_train: train.len(),
                    n_validation: val.len(),
                    validation_fraction: params.validation_fraction,
                });
            }
            (train, val)
        } else {
            ((0..n).collect(), Vec::new())
        };

        // Glorot-uniform initialisation as sklearn's `_init_coef` (factor 6 for ReLU).
        let mut sizes = vec![n_features];
        sizes.extend_from_slice(&params.hidden_layer_sizes);
        sizes.push(n_classes);
        let mut coefs = Vec::with_capacity(sizes.len() - 1);
        let mut intercepts = Vec::with_capacity(sizes.len() - 1);
        for pair in sizes.windows(2) {
            let (fan_in, fan_out) = (pair[0], pair[1]);
            let bound = (6.0 / (fan_in + fan_out) as f64).sqrt();
            coefs.push(Array2::from_shape_fn((fan_in, fan_out), |_| {
                rng.gen_range(-bound..bound)
            }));
            intercepts.push(Array1::from_shape_fn(fan_out, |_| {
                rng.gen_range(-bound..bound)
            }));
        }

        let n_train = train.len();
        let batch = params.batch_size.unwrap_or(200).clamp(1, n_train);
        let mut adam = Adam::new(params, &coefs, &intercepts);
        let x_val = x.select(Axis(0), &val);
        let y_val: Vec<usize> = val.iter().map(|&i| y_idx[i]).collect();

        let mut loss_curve = Vec::new();
        let mut validation_scores = Vec::new();
        let mut best_loss = f64::INFINITY;
        let mut best_score = f64::NEG_INFINITY;
        let mut best_weights: Option<Weights> = None;
        let mut no_improvement = 0usize;
        let mut converged = false;

        for epoch in 1..=params.max_iter {
            if params.shuffle {
                train.shuffle(&mut rng);
            }
            let mut acc_loss = 0.0;
            for rows in train.chunks(batch) {
                let xb = x.select(Axis(0), rows);
                let yb: Vec<usize> = rows.iter().map(|&i| y_idx[i]).collect();
                let (loss, g_w, g_b) = backprop(&coefs, &intercepts, xb.view(), &yb, params.alpha);
                adam.step(&mut coefs, &mut intercepts, &g_w, &g_b);
                acc_loss += loss * rows.len() as f64;
            }
            let loss = acc_loss / n_train as f64;
            if !loss.is_finite() {
                return Err(MlpError::Diverged { epoch, loss });
            }
            loss_curve.push(loss);

            // sklearn's `_update_no_improvement_count`
            if params.early_stopping {
                let p = forward(&coefs, &intercepts, x_val.view())
                    .pop()
                    .expect("output layer");
                let correct = argmax_rows(&p)
                    .iter()
                    .zip(&y_val)
                    .filter(|(a, b)| a == b)
                    .count();
                let score = correct as f64 / y_val.len() as f64;
                validation_scores.push(score);
                if score < best_score + params.tol {
                    no_improvement += 1;
                } else {
                    no_improvement = 0;
                }
                if score > best_score {
                    best_score = score;
                    best_weights = Some((coefs.clone(), intercepts.clone()));
                }
            } else {
                if loss > best_loss - params.tol {
                    no_improvement += 1;
                } else {
                    no_improvement = 0;
                }
                if loss < best_loss {
                    best_loss = loss;
                }
            }
            if no_improvement > params.n_iter_no_change {
                converged = true;
                break;
            }
        }
        if let Some((w, b)) = best_weights {
            coefs = w;
            intercepts = b;
        }
        Ok(Mlp {
            coefs,
            intercepts,
            classes,
            n_features,
            n_epochs: loss_curve.len(),
            loss_curve,
            validation_scores,
            converged,
        })
    }

    fn check_input(&self, x: &ArrayView2<'_, f64>) -> Result<(), MlpError> {
        if x.ncols() != self.n_features {
            return Err(MlpError::FeatureMismatch {
                expected: self.n_features,
                found: x.ncols(),
            });
        }
        check_finite(x)
    }

    /// Class probabilities, shape `(n_samples, n_classes)`, columns in the order of
    /// [`classes`](Mlp::classes); every row sums to 1. Accepts any [`FeatureMatrix`].
    ///
    /// # Errors
    /// [`MlpError::FeatureMismatch`] for a wrong number of columns,
    /// [`MlpError::NonFiniteFeature`] for NaN / infinite values.
    pub fn predict_proba<X: FeatureMatrix>(&self, x: X) -> Result<Array2<f64>, MlpError> {
        let x = x.feature_view();
        self.check_input(&x)?;
        Ok(forward(&self.coefs, &self.intercepts, x)
            .pop()
            .expect("output layer"))
    }

    /// Most probable class label of every row (ties go to the smaller label). Accepts any
    /// [`FeatureMatrix`], so `model.predict(&dataset)` and `model.predict(x.view())` both work
    /// and return a `Result`; linfa's infallible `Predict` is available through the
    /// [`PredictInplace`] impl (`linfa::traits::Predict::predict(&model, &dataset)`).
    ///
    /// # Errors
    /// As [`predict_proba`](Mlp::predict_proba).
    pub fn predict<X: FeatureMatrix>(&self, x: X) -> Result<Array1<usize>, MlpError> {
        let p = self.predict_proba(x)?;
        Ok(argmax_rows(&p)
            .into_iter()
            .map(|k| self.classes[k])
            .collect())
    }

    /// The distinct training labels, sorted; column order of [`predict_proba`](Mlp::predict_proba).
    pub fn classes(&self) -> &[usize] {
        &self.classes
    }
    /// Number of features the model was trained on.
    pub fn n_features(&self) -> usize {
        self.n_features
    }
    /// Weight matrices, `(fan_in, fan_out)` per layer, input layer first.
    pub fn coefs(&self) -> &[Array2<f64>] {
        &self.coefs
    }
    /// Bias vectors per layer, input layer first.
    pub fn intercepts(&self) -> &[Array1<f64>] {
        &self.intercepts
    }
    /// Training loss (cross-entropy + L2 term) after every epoch.
    pub fn loss_curve(&self) -> &[f64] {
        &self.loss_curve
    }
    /// Validation accuracy after every epoch (empty without early stopping).
    pub fn validation_scores(&self) -> &[f64] {
        &self.validation_scores
    }
    /// Number of epochs run.
    pub fn n_epochs(&self) -> usize {
        self.n_epochs
    }
    /// `true` if the stopping rule ended training before `max_iter` epochs.
    pub fn converged(&self) -> bool {
        self.converged
    }
}

/// Weight matrices and bias vectors of all layers.
type Weights = (Vec<Array2<f64>>, Vec<Array1<f64>>);
/// Mini-batch loss and its gradients.
type Grads = (f64, Vec<Array2<f64>>, Vec<Array1<f64>>);

/// Loss and gradients of one mini-batch (sklearn's `_backprop`).
fn backprop(
    coefs: &[Array2<f64>],
    intercepts: &[Array1<f64>],
    xb: ArrayView2<'_, f64>,
    yb: &[usize],
    alpha: f64,
) -> Grads {
    let m = xb.nrows() as f64;
    let acts = forward(coefs, intercepts, xb);
    let out = acts.last().expect("output layer");
    let eps = f64::EPSILON;
    let mut loss = 0.0;
    for (row, &c) in yb.iter().enumerate() {
        loss -= out[[row, c]].clamp(eps, 1.0 - eps).ln();
    }
    loss /= m;
    let l2: f64 = coefs
        .iter()
        .map(|w| w.iter().map(|v| v * v).sum::<f64>())
        .sum();
    loss += 0.5 * alpha * l2 / m;

    let n_layers = coefs.len();
    let mut delta = out.clone();
    for (row, &c) in yb.iter().enumerate() {
        delta[[row, c]] -= 1.0;
    }
    let mut g_w = vec![Array2::zeros((0, 0)); n_layers];
    let mut g_b = vec![Array1::zeros(0); n_layers];
    for l in (0..n_layers).rev() {
        let mut gw = acts[l].t().dot(&delta);
        gw.scaled_add(alpha, &coefs[l]);
        gw /= m;
        g_w[l] = gw;
        g_b[l] = delta.sum_axis(Axis(0)) / m;
        if l > 0 {
            let mut d = delta.dot(&coefs[l].t());
            Zip::from(&mut d).and(&acts[l]).for_each(|d, &a| {
                if a <= 0.0 {
                    *d = 0.0;
                }
            });
            delta = d;
        }
    }
    (loss, g_w, g_b)
}

impl<D, T> Fit<ArrayBase<D, Ix2>, ArrayBase<T, Ix1>, MlpError> for ValidMlpParams
where
    D: Data<Elem = f64>,
    T: Data<Elem = usize>,
{
    type Object = Mlp;

    /// Fits on a linfa dataset (records `f64`, one `usize` label per row); sample weights are
    /// ignored. Same errors as [`Mlp::fit`].
    fn fit(
        &self,
        dataset: &DatasetBase<ArrayBase<D, Ix2>, ArrayBase<T, Ix1>>,
    ) -> Result<Mlp, MlpError> {
        let y: Vec<usize> = dataset.targets.iter().copied().collect();
        Mlp::fit(self, dataset.records.view(), &y)
    }
}

impl<D: Data<Elem = f64>> PredictInplace<ArrayBase<D, Ix2>, Array1<usize>> for Mlp {
    /// linfa's prediction hook (used by `Predict::predict` on arrays and datasets).
    ///
    /// # Panics
    /// linfa's trait cannot return errors: panics with the [`MlpError`] message if `x` has the
    /// wrong number of columns or non-finite values, or if `y.len() != x.nrows()`.
    /// Use the inherent [`Mlp::predict`] for a `Result`.
    fn predict_inplace<'a>(&'a self, x: &'a ArrayBase<D, Ix2>, y: &mut Array1<usize>) {
        assert_eq!(
            x.nrows(),
            y.len(),
            "Mlp::predict_inplace: {} rows but {} targets",
            x.nrows(),
            y.len()
        );
        match Mlp::predict(self, x.view()) {
            Ok(pred) => y.assign(&pred),
            Err(e) => panic!("Mlp::predict_inplace: {e}"),
        }
    }

    fn default_target(&self, x: &ArrayBase<D, Ix2>) -> Array1<usize> {
        Array1::zeros(x.nrows())
    }
}

#[cfg(test)]
#[path = "mlp_tests.rs"]
mod tests;
