//! Classification datasets from the per-recording table, min–max scaling and folds.

use ndarray::{Array2, Axis};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::measured::Candidate;
pub use super::task::Task;
use crate::cohort::Parameter;
use crate::error::{LdhError, Result};
use crate::output::RecordingRow;

/// A labelled feature table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Dataset {
    /// Task.
    pub task: Task,
    /// Feature (column) names, with units in the names.
    pub feature_names: Vec<String>,
    /// Class names in label order.
    pub class_names: Vec<String>,
    /// Rows × features.
    pub x: Array2<f64>,
    /// Labels.
    pub y: Vec<usize>,
    /// Subject id of every row (the grouping for subject-grouped folds).
    pub groups: Vec<String>,
    /// A readable id per row (`L03/affected`…).
    pub row_ids: Vec<String>,
    /// Rows dropped (missing values), with the reason.
    pub dropped: Vec<String>,
}

/// The default features: the 13 parameters of Table 3 (with PBI) by their columns.
pub fn default_features() -> Vec<String> {
    default_parameters()
        .into_iter()
        .map(|p| p.column().to_string())
        .collect()
}

/// The default features as parameters: every parameter but double support (issue 49: added
/// to the tables and reports; the classifiers keep the paper's features, `--features` can add
/// it).
pub fn default_parameters() -> Vec<Parameter> {
    Parameter::ALL
        .into_iter()
        .filter(|&p| p != Parameter::DoubleSupport)
        .collect()
}

impl Dataset {
    /// Build from a per-recording table (one model). Rows with a missing feature are dropped and
    /// listed; groups with fewer than 3 complete subjects are refused (see
    /// [`crate::cohort::Cohort`]).
    pub fn from_recordings(
        rows: &[RecordingRow],
        task: Task,
        features: &[String],
    ) -> Result<Dataset> {
        // The names become parameters here, once.
        let features: Vec<Parameter> = features
            .iter()
            .map(|f| Parameter::from_column(f))
            .collect::<std::result::Result<_, _>>()?;
        let cands = super::measured::candidates(rows, task, &features)?;
        Dataset::from_candidates(task, &features, &cands)
    }

    /// Build from the task's rows ([`super::measured::candidates`]): rows with a missing
    /// feature are dropped and listed in `dropped`; a refusal after dropping rows says which
    /// features were not measured.
    pub fn from_candidates(
        task: Task,
        features: &[Parameter],
        cands: &[Candidate],
    ) -> Result<Dataset> {
        let mut x: Vec<f64> = Vec::new();
        let (mut y, mut groups, mut ids, mut dropped) = (vec![], vec![], vec![], vec![]);
        // how many dropped rows lack each feature, for the refusal's message
        let mut missing_count = vec![0usize; features.len()];
        for c in cands {
            match c.values.iter().copied().collect::<Option<Vec<f64>>>() {
                Some(v) => {
                    x.extend(v);
                    y.push(c.label);
                    groups.push(c.subject.clone());
                    ids.push(c.id());
                }
                None => {
                    let miss: Vec<usize> = (0..features.len())
                        .filter(|&f| c.values[f].is_none())
                        .collect();
                    let names: Vec<&str> = miss.iter().map(|&f| features[f].column()).collect();
                    for f in miss {
                        missing_count[f] += 1;
                    }
                    dropped.push(format!("{}: not measured: {}", c.id(), names.join(", ")));
                }
            }
        }
        let (n, p) = (y.len(), features.len());
        let x = Array2::from_shape_vec((n, p), x)
            .map_err(|e| LdhError::signal("dataset", e.to_string()))?;
        let ds = Dataset {
            task,
            feature_names: features.iter().map(|p| p.column().to_string()).collect(),
            class_names: task.class_names(),
            x,
            y,
            groups,
            row_ids: ids,
            dropped,
        };
        ds.validate()
            .map_err(|e| ds.refusal_after_drops(e, features, &missing_count))?;
        Ok(ds)
    }

    /// A refusal after dropping rows says which features were not measured.
    fn refusal_after_drops(
        &self,
        e: LdhError,
        features: &[Parameter],
        missing_count: &[usize],
    ) -> LdhError {
        let mut lacking: Vec<(usize, &str)> = missing_count
            .iter()
            .zip(features)
            .filter(|(&c, _)| c > 0)
            .map(|(&c, p)| (c, p.column()))
            .collect();
        if lacking.is_empty() {
            return e;
        }
        lacking.sort_by_key(|l| std::cmp::Reverse(l.0));
        let list: Vec<String> = lacking.iter().map(|(c, f)| format!("{f} on {c}")).collect();
        let e = e.to_string();
        let e = e.strip_prefix("dataset: ").unwrap_or(&e);
        LdhError::signal(
            "dataset",
            format!(
                "{e}; {} rows were left out for a feature not measured ({}): choose features that are measured (`ldh train --features`, Python `features=`)",
                self.dropped.len(),
                list.join(", ")
            ),
        )
    }

    /// Refuse datasets a classifier cannot learn from, saying why.
    pub fn validate(&self) -> Result<()> {
        let k = self.class_names.len();
        if self.x.ncols() == 0 {
            return Err(LdhError::signal(
                "dataset",
                "no features: at least one column is needed",
            ));
        }
        if self.x.nrows() != self.y.len() || self.groups.len() != self.y.len() {
            return Err(LdhError::signal(
                "dataset",
                format!(
                    "{} rows of features, {} labels, {} groups",
                    self.x.nrows(),
                    self.y.len(),
                    self.groups.len()
                ),
            ));
        }
        if let Some((i, &l)) = self.y.iter().enumerate().find(|(_, &l)| l >= k) {
            return Err(LdhError::signal(
                "dataset",
                format!(
                    "label {l} of row {i} is outside the {} classes {:?} (labels 0–{})",
                    k,
                    self.class_names,
                    k - 1
                ),
            ));
        }
        let counts = self.class_counts();
        if counts.iter().filter(|&&c| c > 0).count() < 2 {
            return Err(LdhError::signal(
                "dataset",
                format!("only one class present ({:?} rows per class {:?}); a classifier needs at least two", counts, self.class_names),
            ));
        }
        if counts.len() != k {
            return Err(LdhError::signal("dataset", "labels outside the class list"));
        }
        if let Some((i, j)) = self
            .x
            .indexed_iter()
            .find(|(_, v)| !v.is_finite())
            .map(|(ij, _)| ij)
        {
            return Err(LdhError::signal(
                "dataset",
                format!(
                    "non-finite value in row {} feature {}",
                    self.row_ids[i], self.feature_names[j]
                ),
            ));
        }
        Ok(())
    }

    /// The same rows with only the `k` features of largest |Pearson r| with the label (ranked on
    /// all rows; used for the saved model when cross-validation selected top-k per fold).
    pub fn select_top_k(&self, k: usize) -> Result<Dataset> {
        if k == 0 || k > self.feature_names.len() {
            return Err(LdhError::param(
                "top_k",
                k,
                format!("must lie in 1..={}", self.feature_names.len()),
            ));
        }
        let r = pearson_with_label(&self.x, &self.y);
        let mut idx: Vec<usize> = (0..r.len()).collect();
        idx.sort_by(|&a, &b| {
            r[b].abs()
                .partial_cmp(&r[a].abs())
                .unwrap_or(std::cmp::Ordering::Equal)
                .then(a.cmp(&b))
        });
        let mut keep: Vec<usize> = idx.into_iter().take(k).collect();
        keep.sort_unstable();
        Ok(Dataset {
            feature_names: keep
                .iter()
                .map(|&j| self.feature_names[j].clone())
                .collect(),
            x: self.x.select(Axis(1), &keep),
            ..self.clone()
        })
    }

    /// Rows per class.
    pub fn class_counts(&self) -> Vec<usize> {
        let mut c = vec![0; self.class_names.len()];
        for &l in &self.y {
            if l < c.len() {
                c[l] += 1;
            }
        }
        c
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.y.len()
    }

    /// No rows.
    pub fn is_empty(&self) -> bool {
        self.y.is_empty()
    }

    /// The rows `idx` (features, labels).
    pub fn take(&self, idx: &[usize]) -> (Array2<f64>, Vec<usize>) {
        (
            self.x.select(Axis(0), idx),
            idx.iter().map(|&i| self.y[i]).collect(),
        )
    }

    /// Read the CSV written by [`Dataset::to_csv`].
    pub fn from_csv(text: &str, task: Task, origin: &str) -> Result<Dataset> {
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
        if header.len() < 5 || header[..4] != ["row_id", "subject_id", "label", "class"] {
            return Err(LdhError::Format {
                name: origin.into(),
                reason: "expected columns row_id,subject_id,label,class,<features>".into(),
            });
        }
        let feature_names: Vec<String> = header[4..].iter().map(|s| s.to_string()).collect();
        let (mut xs, mut y, mut groups, mut ids) = (vec![], vec![], vec![], vec![]);
        for (i, line) in lines.enumerate() {
            let f: Vec<&str> = line.split(',').collect();
            let bad = |what: &str| LdhError::Format {
                name: origin.into(),
                reason: format!("line {}: {what}", i + 2),
            };
            if f.len() != header.len() {
                return Err(bad("wrong number of fields"));
            }
            ids.push(f[0].to_string());
            groups.push(f[1].to_string());
            y.push(
                f[2].parse::<usize>()
                    .map_err(|_| bad("label is not a number"))?,
            );
            for v in &f[4..] {
                xs.push(
                    v.parse::<f64>()
                        .map_err(|_| bad("feature is not a number"))?,
                );
            }
        }
        let n = y.len();
        let x = Array2::from_shape_vec((n, feature_names.len()), xs)
            .map_err(|e| LdhError::signal("dataset", e.to_string()))?;
        let ds = Dataset {
            task,
            feature_names,
            class_names: task.class_names(),
            x,
            y,
            groups,
            row_ids: ids,
            dropped: vec![],
        };
        ds.validate()?;
        Ok(ds)
    }

    /// As CSV: `row_id, subject_id, label, class, <features…>` (17 significant digits).
    pub fn to_csv(&self) -> String {
        let mut s = format!(
            "row_id,subject_id,label,class,{}\n",
            self.feature_names.join(",")
        );
        for i in 0..self.len() {
            s.push_str(&format!(
                "{},{},{},{}",
                self.row_ids[i], self.groups[i], self.y[i], self.class_names[self.y[i]]
            ));
            for v in self.x.row(i) {
                s.push_str(&format!(",{v:e}"));
            }
            s.push('\n');
        }
        s
    }
}

/// Min–max scaling to [0, 1] per feature (constant features map to 0), fitted on training rows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MinMax {
    /// Minimum per feature.
    pub min: Vec<f64>,
    /// Range per feature (1 for a constant feature).
    pub range: Vec<f64>,
}

impl MinMax {
    /// Fit on rows.
    pub fn fit(x: &Array2<f64>) -> MinMax {
        let (mut min, mut range) = (vec![], vec![]);
        for col in x.columns() {
            let lo = col.iter().cloned().fold(f64::INFINITY, f64::min);
            let hi = col.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            min.push(lo);
            range.push(if hi > lo { hi - lo } else { 1.0 });
        }
        MinMax { min, range }
    }
    /// Apply (values outside the training range map outside [0, 1], as scikit-learn does).
    pub fn transform(&self, x: &Array2<f64>) -> Array2<f64> {
        let mut out = x.clone();
        for (j, mut col) in out.columns_mut().into_iter().enumerate() {
            col.mapv_inplace(|v| (v - self.min[j]) / self.range[j]);
        }
        out
    }
}

/// Fold of every row for stratified k-fold: within each class, rows are shuffled by `seed` and
/// dealt to folds in turn, so every fold holds each class in proportion.
pub fn stratified_folds(y: &[usize], k: usize, seed: u64) -> Result<Vec<usize>> {
    check_k(y.len(), k, "rows")?;
    let classes = y.iter().max().map_or(0, |m| m + 1);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut fold = vec![0usize; y.len()];
    let mut next = 0usize;
    for c in 0..classes {
        let mut idx: Vec<usize> = (0..y.len()).filter(|&i| y[i] == c).collect();
        idx.shuffle(&mut rng);
        for i in idx {
            fold[i] = next % k;
            next += 1;
        }
    }
    Ok(fold)
}

/// Fold of every row for subject-grouped k-fold, stratified by class (scikit-learn's
/// StratifiedGroupKFold idea): subjects are grouped by the set of classes of their rows (an LDH
/// subject's two sides; a healthy subject), shuffled by `seed` within each set, and dealt to the
/// folds in turn across the sets, so every fold holds a share of every kind of subject and no
/// training fold loses a class while there are at least k subjects of it. All rows of a subject
/// share a fold.
pub fn grouped_folds(groups: &[String], y: &[usize], k: usize, seed: u64) -> Result<Vec<usize>> {
    let mut ids: Vec<&String> = groups.iter().collect();
    ids.sort();
    ids.dedup();
    check_k(ids.len(), k, "subjects")?;
    let signature = |g: &String| -> Vec<usize> {
        let mut c: Vec<usize> = groups
            .iter()
            .zip(y)
            .filter(|(x, _)| *x == g)
            .map(|(_, &l)| l)
            .collect();
        c.sort_unstable();
        c.dedup();
        c
    };
    let mut sigs: Vec<Vec<usize>> = ids.iter().map(|g| signature(g)).collect();
    sigs.sort();
    sigs.dedup();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut of_group = std::collections::HashMap::new();
    let mut next = 0usize;
    for sig in &sigs {
        let mut members: Vec<&String> = ids
            .iter()
            .copied()
            .filter(|g| &signature(g) == sig)
            .collect();
        members.shuffle(&mut rng);
        for g in members {
            of_group.insert(g.clone(), next % k);
            next += 1;
        }
    }
    Ok(groups.iter().map(|g| of_group[g]).collect())
}

fn check_k(n: usize, k: usize, what: &str) -> Result<()> {
    if k < 2 {
        return Err(LdhError::param("k", k, "at least 2 folds"));
    }
    if n < k {
        return Err(LdhError::param(
            "k",
            k,
            format!("there are fewer {what} ({n}) than folds ({k}): use k ≤ {n}"),
        ));
    }
    Ok(())
}

/// Pearson r of every feature with the label (ordinal codes; Table 5). NaN for a constant feature.
pub fn pearson_with_label(x: &Array2<f64>, y: &[usize]) -> Vec<f64> {
    let yf: Vec<f64> = y.iter().map(|&v| v as f64).collect();
    x.columns()
        .into_iter()
        .map(|c| {
            crate::stats::pearsonr(
                c.as_slice()
                    .map(|s| s.to_vec())
                    .unwrap_or_else(|| c.to_vec())
                    .as_slice(),
                &yf,
                crate::stats::Alternative::TwoSided,
            )
            .map(|r| r.statistic)
            .unwrap_or(f64::NAN)
        })
        .collect()
}
