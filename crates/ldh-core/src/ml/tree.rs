//! A CART classification tree (Gini impurity), deterministic, with a random subset of features
//! drawn at every split as scikit-learn's random forest does.
//!
//! Hand-written rather than linfa-trees: linfa-trees 0.8 keeps class frequencies in a
//! `std::collections::HashMap` with random hashing, so its Gini sums and its modal-class tie
//! breaks change from run to run (same seed, different trees), and it cannot draw features per
//! split. Here class counts are plain vectors and every tie goes to the lowest threshold,
//! threshold and class, or, between features, to the seeded random feature order.

use ndarray::Array2;
use rand::seq::index::sample;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// A node of a fitted tree.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Node {
    /// A leaf with the class counts of its training rows.
    Leaf(Vec<f64>),
    /// A split: rows with `x[feature] <= threshold` go left.
    Split {
        /// Feature index.
        feature: usize,
        /// Threshold (midpoint between two training values).
        threshold: f64,
        /// Left child.
        left: Box<Node>,
        /// Right child.
        right: Box<Node>,
    },
}

/// Tree growth parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TreeParams {
    /// Features tried at each split.
    pub max_features: usize,
    /// Maximum depth (`usize::MAX`: until pure).
    pub max_depth: usize,
    /// Fewest rows to split a node.
    pub min_samples_split: usize,
}

fn gini(counts: &[f64], n: f64) -> f64 {
    1.0 - counts.iter().map(|c| (c / n) * (c / n)).sum::<f64>()
}

/// Grow a tree on rows `idx` of `x` (labels `y` < `n_classes`).
pub fn grow(
    x: &Array2<f64>,
    y: &[usize],
    idx: &[usize],
    n_classes: usize,
    p: &TreeParams,
    depth: usize,
    rng: &mut ChaCha8Rng,
) -> Node {
    let mut counts = vec![0.0; n_classes];
    for &i in idx {
        counts[y[i]] += 1.0;
    }
    let n = idx.len() as f64;
    let pure = counts.iter().filter(|&&c| c > 0.0).count() <= 1;
    if pure || idx.len() < p.min_samples_split || depth >= p.max_depth {
        return Node::Leaf(counts);
    }
    let parent = gini(&counts, n);
    let nf = x.ncols();
    // Features in a random order; those constant in this node are skipped without counting, and
    // the first `max_features` others are searched (scikit-learn's splitter). Ties keep the
    // first found, so they are broken by the random order, reproducibly for a seed.
    let perm: Vec<usize> = sample(rng, nf, nf).into_vec();
    let want = p.max_features.clamp(1, nf);
    let mut searched = 0usize;
    let mut best: Option<(f64, usize, f64)> = None; // (impurity decrease, feature, threshold)
    let mut order: Vec<usize> = idx.to_vec();
    for &f in &perm {
        if searched == want {
            break;
        }
        let first = x[[idx[0], f]];
        if idx.iter().all(|&i| x[[i, f]] == first) {
            continue;
        }
        searched += 1;
        order.sort_by(|&a, &b| {
            x[[a, f]]
                .partial_cmp(&x[[b, f]])
                .unwrap_or(std::cmp::Ordering::Equal)
                .then(a.cmp(&b))
        });
        let mut left = vec![0.0; n_classes];
        let mut right = counts.clone();
        for w in 0..order.len() - 1 {
            let c = y[order[w]];
            left[c] += 1.0;
            right[c] -= 1.0;
            let (v0, v1) = (x[[order[w], f]], x[[order[w + 1], f]]);
            if v1 <= v0 {
                continue;
            }
            let nl = (w + 1) as f64;
            let nr = n - nl;
            let dec = parent - (nl / n) * gini(&left, nl) - (nr / n) * gini(&right, nr);
            if best.is_none_or(|(b, _, _)| dec > b + 1e-12) {
                best = Some((dec, f, 0.5 * (v0 + v1)));
            }
        }
    }
    match best {
        Some((dec, f, t)) if dec > 0.0 => {
            let (l, r): (Vec<usize>, Vec<usize>) = idx.iter().partition(|&&i| x[[i, f]] <= t);
            Node::Split {
                feature: f,
                threshold: t,
                left: Box::new(grow(x, y, &l, n_classes, p, depth + 1, rng)),
                right: Box::new(grow(x, y, &r, n_classes, p, depth + 1, rng)),
            }
        }
        _ => Node::Leaf(counts),
    }
}

impl Node {
    /// Class probabilities of one row (the leaf's class shares).
    pub fn proba(&self, row: ndarray::ArrayView1<f64>) -> Vec<f64> {
        match self {
            Node::Leaf(c) => {
                let s: f64 = c.iter().sum();
                c.iter().map(|v| v / s.max(1e-300)).collect()
            }
            Node::Split {
                feature,
                threshold,
                left,
                right,
            } => {
                if row[*feature] <= *threshold {
                    left.proba(row)
                } else {
                    right.proba(row)
                }
            }
        }
    }
}
