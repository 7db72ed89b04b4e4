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

mod params;
mod train;

pub use params::{MlpParams, ValidMlpParams};

use linfa::dataset::{DatasetBase, Records};
use linfa::traits::{Fit, PredictInplace};
use ndarray::{Array1, Array2, ArrayBase, ArrayView2, Data, Ix1, Ix2};
use serde::{Deserialize, Serialize};
use thiserror::Error;
use train::{argmax_rows, check_finite, forward};

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

impl Mlp {
    /// Default (unchecked) hyper-parameters, linfa style: `Mlp::params().seed(1).check()?`.
    pub fn params() -> MlpParams {
        MlpParams::default()
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
mod tests;
