//! The per-classifier plausibility rules of [`super::model_plausible`] (see its module docs):
//! sizes and values of a fitted forest, SVM and MLP against the training summary.

use serde_json::Value;

use super::forest::Forest;
use super::mlp::Mlp;
use super::model_types::{
    Classifier, ModelError, ModelFile, MAX_HIDDEN_UNITS, MAX_TREES, MAX_WEIGHT,
};
use super::svm::SvmModel;
use super::tree::Node;

fn bad(origin: &str, what: impl Into<String>) -> ModelError {
    ModelError::Implausible {
        origin: origin.into(),
        what: what.into(),
    }
}

/// Tolerance of a scaled value outside [0, 1] (the scaler's rounding).
const UNIT_TOL: f64 = 1e-9;

/// Forest: tree count, nodes, leaf counts, thresholds, splits of pure nodes, class totals.
pub(super) fn check_forest(m: &ModelFile, f: &Forest, origin: &str) -> Result<(), ModelError> {
    let rows = m.training.rows;
    let want = match &m.classifier {
        Classifier::RandomForest(p) => p.n_trees,
        c => {
            return Err(bad(
                origin,
                format!("a random forest under {} parameters", c.name()),
            ))
        }
    };
    if f.trees.len() != want || want > MAX_TREES {
        return Err(bad(
            origin,
            format!(
                "{} trees, the parameters say {want} (at most {MAX_TREES})",
                f.trees.len()
            ),
        ));
    }
    let nc = m.class_names.len();
    let mut totals = vec![0.0; nc];
    for (t, tree) in f.trees.iter().enumerate() {
        let mut s = TreeStats {
            nodes: 0,
            counts: vec![0.0; nc],
        };
        walk(tree, &mut s, rows, t, origin)?;
        if s.nodes > 2 * rows - 1 {
            return Err(bad(
                origin,
                format!(
                    "tree {t} has {} nodes, more than 2 × {rows} training rows − 1",
                    s.nodes
                ),
            ));
        }
        let n: f64 = s.counts.iter().sum();
        if n != rows as f64 {
            return Err(bad(
                origin,
                format!("the leaves of tree {t} count {n} rows, its bootstrap sample has {rows}"),
            ));
        }
        for c in 0..nc {
            totals[c] += s.counts[c];
        }
    }
    // Every tree's class counts are a bootstrap draw: Binomial(rows, share) per class.
    let trees = f.trees.len() as f64;
    for c in 0..nc {
        let share = m.trained_rows_per_class[c] as f64 / rows as f64;
        let expect = trees * rows as f64 * share;
        let sd = (trees * rows as f64 * share * (1.0 - share)).sqrt();
        if (totals[c] - expect).abs() > 8.0 * sd + 1e-9 {
            return Err(bad(
                origin,
                format!(
                    "the leaves count {} rows of class {} over the trees, the training rows give {expect:.0} ± {sd:.0}: leaf counts edited",
                    totals[c], m.class_names[c]
                ),
            ));
        }
    }
    Ok(())
}

struct TreeStats {
    nodes: usize,
    counts: Vec<f64>,
}

/// Visit a tree (depth is bounded by the JSON reader's nesting limit); returns the bit set of
/// the classes present in its leaves.
fn walk(
    n: &Node,
    s: &mut TreeStats,
    rows: usize,
    t: usize,
    origin: &str,
) -> Result<u64, ModelError> {
    s.nodes += 1;
    if s.nodes > 2 * rows {
        return Err(bad(
            origin,
            format!("tree {t} has more than 2 × {rows} training rows − 1 nodes"),
        ));
    }
    match n {
        Node::Leaf(c) => {
            let mut present = 0u64;
            for (k, &v) in c.iter().enumerate() {
                if v.fract() != 0.0 || v > rows as f64 {
                    return Err(bad(
                        origin,
                        format!("tree {t}: a leaf counts {v} rows (whole numbers up to {rows} expected)"),
                    ));
                }
                if v > 0.0 {
                    present |= 1 << k.min(63);
                }
                s.counts[k] += v;
            }
            Ok(present)
        }
        Node::Split {
            threshold,
            left,
            right,
            ..
        } => {
            if !(-UNIT_TOL..=1.0 + UNIT_TOL).contains(threshold) {
                return Err(bad(
                    origin,
                    format!("tree {t}: split threshold {threshold:e} outside the scaled training range [0, 1]"),
                ));
            }
            let l = walk(left, s, rows, t, origin)?;
            let r = walk(right, s, rows, t, origin)?;
            if (l | r).count_ones() < 2 {
                return Err(bad(
                    origin,
                    format!("tree {t}: a split of rows that are all of one class (ldh train never splits a pure node): leaf counts edited"),
                ));
            }
            Ok(l | r)
        }
    }
}

/// SVM: γ, kernel width, multipliers, offsets, support vectors.
pub(super) fn check_svm(m: &ModelFile, s: &SvmModel, origin: &str) -> Result<(), ModelError> {
    let (rows, nf) = (m.training.rows as f64, m.feature_names.len() as f64);
    let (c, fixed) = match &m.classifier {
        Classifier::Svm(p) => (p.c, p.gamma),
        o => return Err(bad(origin, format!("an SVM under {} parameters", o.name()))),
    };
    if !(c.is_finite() && c > 0.0 && c <= 1e6) {
        return Err(bad(origin, format!("SVM C = {c:e}, expected in (0, 1e6]")));
    }
    let ok = match fixed {
        Some(g) => s.gamma == g,
        None => (1.0 / nf..=2.0 * rows).contains(&s.gamma),
    };
    if !ok {
        return Err(bad(
            origin,
            format!(
                "SVM gamma = {:e}, expected {} for scaled training rows",
                s.gamma,
                match fixed {
                    Some(g) => format!("the stored {g:e}"),
                    None => format!("1/p = {:e} to 2 × rows = {:e}", 1.0 / nf, 2.0 * rows),
                }
            ),
        ));
    }
    for (k, machine) in s.machines.iter().enumerate() {
        if let Some(a) = machine.alpha.iter().find(|a| a.abs() > c * (1.0 + 1e-9)) {
            return Err(bad(
                origin,
                format!("svm machine {k}: multiplier {a:e} beyond C = {c}"),
            ));
        }
        if machine.rho.abs() > rows * c + 1.0 {
            return Err(bad(
                origin,
                format!(
                    "svm machine {k}: offset rho = {:e} beyond rows × C + 1",
                    machine.rho
                ),
            ));
        }
        let v = serde_json::to_value(machine).map_err(|e| bad(origin, e.to_string()))?;
        if let Some(w) = v
            .get("kernel_method")
            .and_then(|k| k.get("Gaussian"))
            .and_then(Value::as_f64)
        {
            if (w * s.gamma - 1.0).abs() > 1e-9 {
                return Err(bad(
                    origin,
                    format!(
                        "svm machine {k}: kernel width {w:e} is not 1/gamma = {:e}",
                        1.0 / s.gamma
                    ),
                ));
            }
        }
        let sv = v.pointer("/sep_hyperplane/WeightedCombination");
        let n_sv = sv
            .and_then(|w| w.pointer("/dim/0"))
            .and_then(Value::as_u64)
            .unwrap_or(0);
        if n_sv as f64 > rows {
            return Err(bad(
                origin,
                format!("svm machine {k}: {n_sv} support vectors for {rows} training rows"),
            ));
        }
        let data = sv.and_then(|w| w.get("data")).and_then(Value::as_array);
        if let Some(x) = data
            .into_iter()
            .flatten()
            .filter_map(Value::as_f64)
            .find(|x| !(-UNIT_TOL..=1.0 + UNIT_TOL).contains(x))
        {
            return Err(bad(
                origin,
                format!("svm machine {k}: support vector value {x:e} outside the scaled training range [0, 1]"),
            ));
        }
    }
    Ok(())
}

/// MLP: layers as the parameters say, bounded weights, classes with rows, epochs.
pub(super) fn check_mlp(m: &ModelFile, p: &Mlp, origin: &str) -> Result<(), ModelError> {
    let params = match &m.classifier {
        Classifier::Mlp(q) => q
            .clone()
            .check()
            .map_err(|e| bad(origin, format!("MLP parameters: {e}")))?,
        o => return Err(bad(origin, format!("an MLP under {} parameters", o.name()))),
    };
    let hidden: Vec<usize> = p.coefs().iter().skip(1).map(|w| w.nrows()).collect();
    if hidden != params.hidden_layer_sizes() || hidden.iter().any(|&h| h > MAX_HIDDEN_UNITS) {
        return Err(bad(
            origin,
            format!(
                "MLP hidden layers {hidden:?}, the parameters say {:?} (at most 2 of {MAX_HIDDEN_UNITS} units)",
                params.hidden_layer_sizes()
            ),
        ));
    }
    for (l, (w, b)) in p.coefs().iter().zip(p.intercepts()).enumerate() {
        if let Some(x) = w.iter().chain(b.iter()).find(|x| !(x.abs() <= MAX_WEIGHT)) {
            return Err(bad(
                origin,
                format!("MLP layer {l}: weight {x:e} beyond ±{MAX_WEIGHT:e}"),
            ));
        }
    }
    let cls = p.classes();
    if cls.windows(2).any(|w| w[0] >= w[1])
        || cls
            .iter()
            .any(|&c| m.trained_rows_per_class.get(c).is_none_or(|&n| n == 0))
    {
        return Err(bad(
            origin,
            format!("MLP classes {cls:?} are not the classes with training rows, in order"),
        ));
    }
    if p.n_epochs() > params.max_iter() || p.loss_curve().len() != p.n_epochs() {
        return Err(bad(
            origin,
            format!(
                "MLP trained {} epochs with {} losses, at most max_iter = {}",
                p.n_epochs(),
                p.loss_curve().len(),
                params.max_iter()
            ),
        ));
    }
    Ok(())
}
