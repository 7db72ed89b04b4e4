//! Training of the [`Mlp`](super::Mlp): initialisation, forward pass, back-propagation, Adam
//! and sklearn's stopping rule (see the parent module's documentation for the method).

use ndarray::{Array1, Array2, ArrayView2, Axis, Zip};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::{Mlp, MlpError, ValidMlpParams};

pub(super) fn check_finite(x: &ArrayView2<'_, f64>) -> Result<(), MlpError> {
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
pub(super) fn forward(
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
pub(super) fn argmax_rows(p: &Array2<f64>) -> Vec<usize> {
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
pub(super) fn stratified_split(
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
        let (classes, y_idx) = check_training_data(x, y)?;
        let n_classes = classes.len();

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

        let mut sizes = vec![n_features];
        sizes.extend_from_slice(&params.hidden_layer_sizes);
        sizes.push(n_classes);
        let (mut coefs, mut intercepts) = glorot_uniform(&sizes, &mut rng);

        let n_train = train.len();
        let batch = params.batch_size.unwrap_or(200).clamp(1, n_train);
        let mut adam = Adam::new(params, &coefs, &intercepts);
        let x_val = x.select(Axis(0), &val);
        let y_val: Vec<usize> = val.iter().map(|&i| y_idx[i]).collect();
        let mut stop = Stopping::new(params);

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
            let score = if params.early_stopping {
                let p = forward(&coefs, &intercepts, x_val.view())
                    .pop()
                    .expect("output layer");
                let correct = argmax_rows(&p)
                    .iter()
                    .zip(&y_val)
                    .filter(|(a, b)| a == b)
                    .count();
                Some(correct as f64 / y_val.len() as f64)
            } else {
                None
            };
            if stop.update(loss, score, &coefs, &intercepts) {
                break;
            }
        }
        if let Some((w, b)) = stop.best_weights.take() {
            coefs = w;
            intercepts = b;
        }
        Ok(Mlp {
            coefs,
            intercepts,
            classes,
            n_features,
            n_epochs: stop.loss_curve.len(),
            loss_curve: stop.loss_curve,
            validation_scores: stop.validation_scores,
            converged: stop.converged,
        })
    }
}

/// Checks the training table; returns the sorted distinct classes and each row's class index.
fn check_training_data(
    x: ArrayView2<'_, f64>,
    y: &[usize],
) -> Result<(Vec<usize>, Vec<usize>), MlpError> {
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
    let y_idx = y
        .iter()
        .map(|c| classes.binary_search(c).expect("label is in classes"))
        .collect();
    Ok((classes, y_idx))
}

/// Glorot-uniform initialisation as sklearn's `_init_coef` (factor 6 for ReLU): weights and
/// biases of every layer from `U(-b, b)`, `b = sqrt(6 / (fan_in + fan_out))`, layer by layer.
fn glorot_uniform(sizes: &[usize], rng: &mut ChaCha8Rng) -> Weights {
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
    (coefs, intercepts)
}

/// sklearn's stopping rule (`_update_no_improvement_count`) and the training history.
struct Stopping {
    tol: f64,
    n_iter_no_change: usize,
    loss_curve: Vec<f64>,
    validation_scores: Vec<f64>,
    best_loss: f64,
    best_score: f64,
    best_weights: Option<Weights>,
    no_improvement: usize,
    converged: bool,
}

impl Stopping {
    fn new(params: &ValidMlpParams) -> Self {
        Stopping {
            tol: params.tol,
            n_iter_no_change: params.n_iter_no_change,
            loss_curve: Vec::new(),
            validation_scores: Vec::new(),
            best_loss: f64::INFINITY,
            best_score: f64::NEG_INFINITY,
            best_weights: None,
            no_improvement: 0,
            converged: false,
        }
    }

    /// Records one epoch (its training loss, and its validation accuracy with early stopping);
    /// returns `true` when training should stop.
    fn update(
        &mut self,
        loss: f64,
        score: Option<f64>,
        coefs: &[Array2<f64>],
        intercepts: &[Array1<f64>],
    ) -> bool {
        self.loss_curve.push(loss);
        if let Some(score) = score {
            self.validation_scores.push(score);
            if score < self.best_score + self.tol {
                self.no_improvement += 1;
            } else {
                self.no_improvement = 0;
            }
            if score > self.best_score {
                self.best_score = score;
                self.best_weights = Some((coefs.to_vec(), intercepts.to_vec()));
            }
        } else {
            if loss > self.best_loss - self.tol {
                self.no_improvement += 1;
            } else {
                self.no_improvement = 0;
            }
            if loss < self.best_loss {
                self.best_loss = loss;
            }
        }
        self.converged = self.no_improvement > self.n_iter_no_change;
        self.converged
    }
}

/// Weight matrices and bias vectors of all layers.
type Weights = (Vec<Array2<f64>>, Vec<Array1<f64>>);
/// Mini-batch loss and its gradients.
type Grads = (f64, Vec<Array2<f64>>, Vec<Array1<f64>>);

/// Loss and gradients of one mini-batch (sklearn's `_backprop`).
pub(super) fn backprop(
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
