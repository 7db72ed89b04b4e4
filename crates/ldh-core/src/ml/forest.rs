//! Random forest: bagged CART trees ([`super::tree`]), each on a bootstrap sample of the rows,
//! with ⌊√p⌋ features (at least 1) drawn at every split and probabilities averaged over the trees — the
//! algorithm of scikit-learn's `RandomForestClassifier` with its defaults. Deterministic for a
//! seed (linfa-trees is not: see [`super::tree`]); serialisable, so a trained forest can be saved.

use ndarray::Array2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::tree::{grow, Node, TreeParams};
use crate::error::{LdhError, Result};

/// Forest parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ForestParams {
    /// Number of trees. Default 100.
    pub n_trees: usize,
    /// Features tried at each split; `None`: max(1, ⌊√p⌋) (scikit-learn's "sqrt"). Default None.
    pub max_features: Option<usize>,
    /// Maximum depth; `None`: grow until pure. Default None.
    pub max_depth: Option<usize>,
    /// Seed. Default 0.
    pub seed: u64,
}

impl Default for ForestParams {
    fn default() -> Self {
        ForestParams {
            n_trees: 100,
            max_features: None,
            max_depth: None,
            seed: 0,
        }
    }
}

/// A fitted forest.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Forest {
    /// Number of classes.
    pub n_classes: usize,
    /// The trees.
    pub trees: Vec<Node>,
}

impl Forest {
    /// Fit on (scaled) rows.
    pub fn fit(p: &ForestParams, x: &Array2<f64>, y: &[usize], n_classes: usize) -> Result<Forest> {
        if p.n_trees == 0 {
            return Err(LdhError::param("n_trees", 0, "at least one tree"));
        }
        let (n, f) = x.dim();
        if n == 0 || y.len() != n || y.iter().any(|&c| c >= n_classes) {
            return Err(LdhError::signal(
                "random forest",
                "rows, labels and classes do not match",
            ));
        }
        let tp = TreeParams {
            max_features: p
                .max_features
                .unwrap_or_else(|| ((f as f64).sqrt().floor() as usize).max(1))
                .clamp(1, f),
            max_depth: p.max_depth.unwrap_or(usize::MAX),
            min_samples_split: 2,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(p.seed);
        let trees = (0..p.n_trees)
            .map(|_| {
                let rows: Vec<usize> = (0..n).map(|_| rng.gen_range(0..n)).collect();
                grow(x, y, &rows, n_classes, &tp, 0, &mut rng)
            })
            .collect();
        Ok(Forest { n_classes, trees })
    }

    /// Mean class probabilities over the trees (scikit-learn's `predict_proba`).
    pub fn predict_proba(&self, x: &Array2<f64>) -> Array2<f64> {
        let mut p = Array2::<f64>::zeros((x.nrows(), self.n_classes));
        for t in &self.trees {
            for (i, row) in x.rows().into_iter().enumerate() {
                for (c, v) in t.proba(row).into_iter().enumerate() {
                    p[[i, c]] += v;
                }
            }
        }
        p / self.trees.len() as f64
    }
}
