//! Random forest: bagged linfa-trees decision trees, each on a bootstrap sample of the rows and
//! a random subset of ⌈√p⌉ features (the random-subspace forest of linfa-ensemble, written as our
//! own bagging so the forest can be saved and can give vote probabilities).

use linfa::prelude::*;
use linfa_trees::{DecisionTree, SplitQuality};
use ndarray::{Array1, Array2, Axis};
use rand::seq::index::sample;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};

/// Forest parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ForestParams {
    /// Number of trees. Default 100.
    pub n_trees: usize,
    /// Features per tree; `None`: ⌈√p⌉. Default None.
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
    /// Per tree: the feature columns it uses and the tree.
    pub trees: Vec<(Vec<usize>, DecisionTree<f64, usize>)>,
}

impl Forest {
    /// Fit on (scaled) rows.
    pub fn fit(p: &ForestParams, x: &Array2<f64>, y: &[usize], n_classes: usize) -> Result<Forest> {
        if p.n_trees == 0 {
            return Err(LdhError::param("n_trees", 0, "at least one tree"));
        }
        let (n, f) = x.dim();
        let m = p
            .max_features
            .unwrap_or_else(|| (f as f64).sqrt().ceil() as usize)
            .clamp(1, f);
        let mut rng = ChaCha8Rng::seed_from_u64(p.seed);
        let mut trees = Vec::with_capacity(p.n_trees);
        for _ in 0..p.n_trees {
            let rows: Vec<usize> = (0..n).map(|_| rng.gen_range(0..n)).collect();
            let mut cols: Vec<usize> = sample(&mut rng, f, m).into_vec();
            cols.sort_unstable();
            let xs = x.select(Axis(0), &rows).select(Axis(1), &cols);
            let ys = Array1::from(rows.iter().map(|&i| y[i]).collect::<Vec<_>>());
            let ds = Dataset::new(xs, ys);
            let tree = DecisionTree::params()
                .split_quality(SplitQuality::Gini)
                .max_depth(p.max_depth)
                .min_weight_split(2.0)
                .min_weight_leaf(1.0)
                .fit(&ds)
                .map_err(|e| LdhError::signal("random forest", e.to_string()))?;
            trees.push((cols, tree));
        }
        Ok(Forest { n_classes, trees })
    }

    /// Vote shares per class.
    pub fn predict_proba(&self, x: &Array2<f64>) -> Array2<f64> {
        let mut votes = Array2::<f64>::zeros((x.nrows(), self.n_classes));
        for (cols, tree) in &self.trees {
            let pred: Array1<usize> = tree.predict(&x.select(Axis(1), cols));
            for (i, &c) in pred.iter().enumerate() {
                if c < self.n_classes {
                    votes[[i, c]] += 1.0;
                }
            }
        }
        votes / self.trees.len() as f64
    }
}
