//! Hyper-parameters of the [`Mlp`](super::Mlp): the unchecked builder [`MlpParams`] and the
//! checked [`ValidMlpParams`] (linfa's `ParamGuard` convention), with sklearn's defaults.

use linfa::ParamGuard;
use serde::{Deserialize, Serialize};

use super::MlpError;

/// Checked hyper-parameters of [`Mlp`]; obtain them with [`MlpParams::check`].
///
/// Serialisable so that a configuration can be stored; [`Mlp::fit`] re-validates the values,
/// so a hand-edited deserialised `ValidMlpParams` cannot train with invalid settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ValidMlpParams {
    pub(super) hidden_layer_sizes: Vec<usize>,
    pub(super) alpha: f64,
    pub(super) batch_size: Option<usize>,
    pub(super) learning_rate_init: f64,
    pub(super) beta_1: f64,
    pub(super) beta_2: f64,
    pub(super) epsilon: f64,
    pub(super) max_iter: usize,
    pub(super) tol: f64,
    pub(super) n_iter_no_change: usize,
    pub(super) early_stopping: bool,
    pub(super) validation_fraction: f64,
    pub(super) shuffle: bool,
    pub(super) seed: u64,
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
    pub(super) fn validate(&self) -> Result<(), MlpError> {
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
