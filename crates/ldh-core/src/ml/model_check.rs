//! Integrity of saved model files (issue 19): a schema version, a checksum over the content,
//! and a structural check of everything prediction will index or multiply, so a truncated,
//! edited or damaged file is refused with a [`ModelError`] instead of panicking or predicting
//! silently wrong classes.
//!
//! **Checksum.** `checksum = "crc32:xxxxxxxx"`: CRC-32 (IEEE) of a canonical text of every other
//! field: object keys sorted, numbers as integers (`i12`) or as the 16 hex digits of the
//! float's IEEE-754 bits (`f3ff0000000000000`). The JSON is written with the shortest digits
//! that read back to the same float and read with serde_json's `float_roundtrip`, so every float
//! reads back bit-identical and the writer's and the reader's canonical texts agree (before issue
//! 37 floats were rounded to 12 digits, and a float the parser read one ulp off that sat on a
//! rounding boundary broke the checksum of a freshly trained model). It detects damage and hand
//! edits (a shuffled feature list, a changed weight); it is not a signature against someone who
//! recomputes it, which the structural checks below and the plausibility rules of
//! [`super::model_plausible`] are for.
//!
//! **Structure.** Feature names: non-empty, distinct, as many as the scaler's columns (finite
//! minimum, finite positive range). Class names: those of the task, in label order, as many as
//! the rows-per-class counts. Random forest: one count per class in every leaf (finite, ≥ 0,
//! not all zero), split features inside the feature list, finite thresholds. SVM: one machine
//! (binary) or one per class, finite γ, ρ and multipliers, support vectors as wide as the
//! feature list and as many as the non-zero multipliers. MLP: layer shapes (checked when it
//! is read), input width = features, output classes inside the class list, finite weights.

use serde_json::Value;

pub use super::model_types::ModelError;
use super::model_types::{FittedModel, ModelFile};
use super::tree::Node;

/// The CRC-32 checksum text (`crc32:xxxxxxxx`) of a model file's JSON value, `checksum` field
/// excluded.
pub fn checksum(v: &Value) -> String {
    let mut h = crc32fast::Hasher::new();
    canon(v, &mut h, true, &mut String::new());
    format!("crc32:{:08x}", h.finalize())
}

/// Feed the canonical text of `v` to `h` (`buf`: scratch space, so that the numbers of a large
/// file are not each a new allocation).
fn canon(v: &Value, h: &mut crc32fast::Hasher, top: bool, buf: &mut String) {
    use std::fmt::Write;
    buf.clear();
    match v {
        Value::Null => h.update(b"n"),
        Value::Bool(b) => h.update(if *b { b"t" } else { b"f" }),
        Value::Number(n) => {
            let _ = if let Some(i) = n.as_i64() {
                write!(buf, "i{i}")
            } else if let Some(u) = n.as_u64() {
                write!(buf, "i{u}")
            } else {
                // The exact bits: serde_json's `float_roundtrip` reads back the float written,
                // so the writer's and the reader's canonical texts are the same.
                write!(buf, "f{:016x}", n.as_f64().unwrap_or(f64::NAN).to_bits())
            };
            h.update(buf.as_bytes());
        }
        Value::String(s) => {
            let _ = write!(buf, "s{}:", s.len());
            h.update(buf.as_bytes());
            h.update(s.as_bytes());
        }
        Value::Array(a) => {
            let _ = write!(buf, "[{}", a.len());
            h.update(buf.as_bytes());
            for x in a {
                canon(x, h, false, buf);
            }
            h.update(b"]");
        }
        Value::Object(m) => {
            let mut keys: Vec<&String> = m.keys().filter(|k| !(top && *k == "checksum")).collect();
            keys.sort();
            let _ = write!(buf, "{{{}", keys.len());
            h.update(buf.as_bytes());
            for k in keys {
                buf.clear();
                let _ = write!(buf, "{}:", k.len());
                h.update(buf.as_bytes());
                h.update(k.as_bytes());
                canon(&m[k], h, false, buf);
            }
            h.update(b"}");
        }
    }
}

fn bad(origin: &str, what: impl Into<String>) -> ModelError {
    ModelError::Inconsistent {
        origin: origin.into(),
        what: what.into(),
    }
}

fn finite(origin: &str, what: &str, xs: impl IntoIterator<Item = f64>) -> Result<(), ModelError> {
    match xs.into_iter().enumerate().find(|(_, x)| !x.is_finite()) {
        Some((i, x)) => Err(bad(origin, format!("{what}[{i}] = {x} is not finite"))),
        None => Ok(()),
    }
}

/// Check that every array of a parsed model fits the declared sizes (see the module docs).
pub fn validate(m: &ModelFile, origin: &str) -> Result<(), ModelError> {
    let nf = m.feature_names.len();
    if nf == 0 {
        return Err(bad(origin, "no feature names"));
    }
    let mut seen = std::collections::HashSet::new();
    for f in &m.feature_names {
        if f.trim().is_empty() || !seen.insert(f.as_str()) {
            return Err(bad(
                origin,
                format!("feature name {f:?} is empty or repeated"),
            ));
        }
    }
    if m.class_names != m.task.class_names() {
        return Err(bad(
            origin,
            format!(
                "class names {:?} are not those of the task {} ({:?})",
                m.class_names,
                m.task.as_str(),
                m.task.class_names()
            ),
        ));
    }
    let nc = m.class_names.len();
    if m.trained_rows_per_class.len() != nc {
        return Err(bad(
            origin,
            format!(
                "{} rows-per-class counts for {nc} classes",
                m.trained_rows_per_class.len()
            ),
        ));
    }
    if m.scaling.min.len() != nf || m.scaling.range.len() != nf {
        return Err(bad(
            origin,
            format!(
                "the scaler has {} minima and {} ranges for {nf} features",
                m.scaling.min.len(),
                m.scaling.range.len()
            ),
        ));
    }
    finite(origin, "scaling.min", m.scaling.min.iter().copied())?;
    finite(origin, "scaling.range", m.scaling.range.iter().copied())?;
    if let Some(j) = m.scaling.range.iter().position(|r| *r <= 0.0) {
        return Err(bad(
            origin,
            format!(
                "scaling.range[{j}] = {} is not positive",
                m.scaling.range[j]
            ),
        ));
    }
    match &m.model {
        FittedModel::RandomForest(f) => {
            if f.n_classes != nc || f.trees.is_empty() {
                return Err(bad(
                    origin,
                    format!(
                        "forest of {} trees for {} classes, the file has {nc} classes",
                        f.trees.len(),
                        f.n_classes
                    ),
                ));
            }
            for (t, tree) in f.trees.iter().enumerate() {
                check_node(tree, nf, nc, origin, t)?;
            }
        }
        FittedModel::Svm(s) => check_svm(s, nf, nc, origin)?,
        FittedModel::Mlp(p) => {
            if p.n_features() != nf {
                return Err(bad(
                    origin,
                    format!("MLP input layer of {} for {nf} features", p.n_features()),
                ));
            }
            if let Some(c) = p.classes().iter().find(|&&c| c >= nc) {
                return Err(bad(
                    origin,
                    format!("MLP class label {c} outside the {nc} classes"),
                ));
            }
            for (l, (w, b)) in p.coefs().iter().zip(p.intercepts()).enumerate() {
                finite(origin, &format!("mlp.coefs[{l}]"), w.iter().copied())?;
                finite(origin, &format!("mlp.intercepts[{l}]"), b.iter().copied())?;
            }
        }
    }
    Ok(())
}

fn check_node(n: &Node, nf: usize, nc: usize, origin: &str, t: usize) -> Result<(), ModelError> {
    let mut stack = vec![n];
    while let Some(n) = stack.pop() {
        match n {
            Node::Leaf(c) => {
                if c.len() != nc {
                    return Err(bad(
                        origin,
                        format!(
                            "tree {t}: a leaf has {} class counts for {nc} classes",
                            c.len()
                        ),
                    ));
                }
                finite(origin, &format!("tree {t} leaf"), c.iter().copied())?;
                if c.iter().any(|v| *v < 0.0) || c.iter().sum::<f64>() <= 0.0 {
                    return Err(bad(origin, format!("tree {t}: a leaf has counts {c:?}")));
                }
            }
            Node::Split {
                feature,
                threshold,
                left,
                right,
            } => {
                if *feature >= nf {
                    return Err(bad(
                        origin,
                        format!("tree {t}: split on feature {feature} of {nf}"),
                    ));
                }
                if !threshold.is_finite() {
                    return Err(bad(
                        origin,
                        format!("tree {t}: split threshold {threshold}"),
                    ));
                }
                stack.push(left);
                stack.push(right);
            }
        }
    }
    Ok(())
}

/// Number of an f64 in a JSON value (ndarray's `{"v","dim","data"}` arrays included).
fn nums(v: &Value) -> Option<Vec<f64>> {
    let a = v.get("data").unwrap_or(v).as_array()?;
    a.iter().map(Value::as_f64).collect()
}

fn check_svm(
    s: &super::svm::SvmModel,
    nf: usize,
    nc: usize,
    origin: &str,
) -> Result<(), ModelError> {
    let want = if nc == 2 { 1 } else { nc };
    if s.n_classes != nc || s.machines.len() != want {
        return Err(bad(
            origin,
            format!(
                "SVM of {} machines for {} classes, expected {want} for {nc}",
                s.machines.len(),
                s.n_classes
            ),
        ));
    }
    finite(origin, "svm.gamma", [s.gamma])?;
    for (k, m) in s.machines.iter().enumerate() {
        finite(
            origin,
            &format!("svm machine {k} alpha"),
            m.alpha.iter().copied(),
        )?;
        finite(origin, &format!("svm machine {k} rho"), [m.rho])?;
        // The kernel and the support vectors are private in linfa-svm: read them from its
        // serialised form.
        let v = serde_json::to_value(m).map_err(|e| bad(origin, e.to_string()))?;
        if let Some(g) = v.get("kernel_method").and_then(|k| k.get("Gaussian")) {
            let g = g.as_f64().unwrap_or(f64::NAN);
            if !(g.is_finite() && g > 0.0) {
                return Err(bad(
                    origin,
                    format!("svm machine {k}: Gaussian kernel width {g}"),
                ));
            }
        }
        let hp = v.get("sep_hyperplane");
        let (rows, cols, data) = if let Some(w) = hp.and_then(|h| h.get("Linear")) {
            let d = nums(w).unwrap_or_default();
            (1, d.len(), d)
        } else if let Some(w) = hp.and_then(|h| h.get("WeightedCombination")) {
            let dim: Vec<usize> = w
                .get("dim")
                .and_then(Value::as_array)
                .map(|d| {
                    d.iter()
                        .filter_map(|x| x.as_u64().map(|x| x as usize))
                        .collect()
                })
                .unwrap_or_default();
            let d = nums(w).unwrap_or_default();
            match dim.as_slice() {
                [r, c] => {
                    let used = m
                        .alpha
                        .iter()
                        .filter(|a| a.abs() > 100.0 * f64::EPSILON)
                        .count();
                    if *r != used {
                        return Err(bad(origin, format!("svm machine {k}: {r} support vectors for {used} non-zero multipliers")));
                    }
                    (*r, *c, d)
                }
                _ => {
                    return Err(bad(
                        origin,
                        format!("svm machine {k}: support vectors without a 2-d shape"),
                    ))
                }
            }
        } else {
            return Err(bad(
                origin,
                format!("svm machine {k}: no separating hyperplane"),
            ));
        };
        if cols != nf || data.len() != rows * cols {
            return Err(bad(
                origin,
                format!("svm machine {k}: support vectors of {cols} values for {nf} features"),
            ));
        }
        finite(origin, &format!("svm machine {k} support vectors"), data)?;
    }
    Ok(())
}
