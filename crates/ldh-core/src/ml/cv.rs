//! Repeated k-fold cross-validation with scaling (and optional feature selection) fitted inside
//! each training fold, metrics as scikit-learn computes them, permutation importance.

use ndarray::{Array2, Axis};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::dataset::{grouped_folds, pearson_with_label, stratified_folds, Dataset, MinMax};
use super::model::Classifier;
use crate::error::{LdhError, Result};

/// How rows are split into folds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CvKind {
    /// Subject-grouped: all rows of a subject in one fold (default; no subject straddles train
    /// and test).
    Grouped,
    /// Stratified by class, ignoring subjects (the paper's design).
    Stratified,
}

impl CvKind {
    /// `grouped` or `stratified` (file names and tables).
    pub fn as_str(&self) -> &'static str {
        match self {
            CvKind::Grouped => "grouped",
            CvKind::Stratified => "stratified",
        }
    }
}

/// Cross-validation parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CvParams {
    /// Folds. Default 10.
    pub k: usize,
    /// Repeats (each with new folds). Default 10.
    pub repeats: usize,
    /// Seed of fold assignment and models. Default 1.
    pub seed: u64,
    /// Fold kind. Default grouped.
    pub kind: CvKind,
    /// Keep the k features with the largest |Pearson r| on each training fold. Default all.
    pub top_k: Option<usize>,
    /// Compute permutation importance. Default true.
    pub permutation_importance: bool,
}

impl Default for CvParams {
    fn default() -> Self {
        CvParams {
            k: 10,
            repeats: 10,
            seed: 1,
            kind: CvKind::Grouped,
            top_k: None,
            permutation_importance: true,
        }
    }
}

/// Mean and SD over repeats.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeanSd {
    /// Mean.
    pub mean: f64,
    /// SD (ddof = 1; 0 for one repeat).
    pub sd: f64,
}

fn mean_sd(v: &[f64]) -> MeanSd {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let sd = if v.len() > 1 {
        (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
    } else {
        0.0
    };
    MeanSd { mean: m, sd }
}

/// Results of one classifier's cross-validation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CvReport {
    /// Classifier name.
    pub classifier: String,
    /// Fold kind.
    pub kind: CvKind,
    /// Folds.
    pub k: usize,
    /// Repeats.
    pub repeats: usize,
    /// Class names.
    pub class_names: Vec<String>,
    /// Accuracy over repeats.
    pub accuracy: MeanSd,
    /// Macro precision over repeats.
    pub precision_macro: MeanSd,
    /// Macro recall over repeats.
    pub recall_macro: MeanSd,
    /// Macro F1 over repeats.
    pub f1_macro: MeanSd,
    /// Per class (pooled over repeats): precision, recall, F1.
    pub per_class: Vec<(String, f64, f64, f64)>,
    /// Confusion matrix summed over repeats: rows true, columns predicted.
    pub confusion: Vec<Vec<usize>>,
    /// Mean accuracy drop when a feature is permuted in the test folds (by feature).
    pub permutation_importance: Vec<(String, f64)>,
    /// Accuracy of each repeat.
    pub accuracy_per_repeat: Vec<f64>,
}

/// Precision, recall, F1 per class from a confusion matrix (0 when undefined, as scikit-learn's
/// `zero_division=0`).
pub fn prf(conf: &[Vec<usize>]) -> Vec<(f64, f64, f64)> {
    let k = conf.len();
    (0..k)
        .map(|c| {
            let tp = conf[c][c] as f64;
            let pred: f64 = (0..k).map(|r| conf[r][c] as f64).sum();
            let actual: f64 = conf[c].iter().sum::<usize>() as f64;
            let p = if pred > 0.0 { tp / pred } else { 0.0 };
            let r = if actual > 0.0 { tp / actual } else { 0.0 };
            let f = if p + r > 0.0 {
                2.0 * p * r / (p + r)
            } else {
                0.0
            };
            (p, r, f)
        })
        .collect()
}

/// The fold assignment of one repeat. A refusal (too few rows or subjects for the folds) after
/// rows were dropped for features not measured says so, and how to choose other features.
pub fn folds(ds: &Dataset, p: &CvParams, repeat: usize) -> Result<Vec<usize>> {
    fold_assignment(ds, p, repeat).map_err(|e| match (e, ds.dropped.first()) {
        // Only a count refusal (too few rows or subjects) can be helped by other features.
        (LdhError::Param { name, value, reason }, Some(first)) if p.k >= 2 => LdhError::Param {
            name,
            value,
            reason: format!(
                "{reason}; {} rows were left out for a feature not measured (the first: {first}): choose features that are measured (`ldh train --features`, Python `features=`)",
                ds.dropped.len()
            ),
        },
        (e, _) => e,
    })
}

fn fold_assignment(ds: &Dataset, p: &CvParams, repeat: usize) -> Result<Vec<usize>> {
    let seed = p.seed.wrapping_add(repeat as u64 * 7919);
    match p.kind {
        CvKind::Stratified => {
            let min = ds
                .class_counts()
                .into_iter()
                .filter(|&c| c > 0)
                .min()
                .unwrap_or(0);
            if min < p.k {
                return Err(LdhError::param(
                    "k",
                    p.k,
                    format!("the smallest class has {min} rows: stratified k-fold needs k ≤ {min}"),
                ));
            }
            stratified_folds(&ds.y, p.k, seed)
        }
        CvKind::Grouped => grouped_folds(&ds.groups, &ds.y, p.k, seed),
    }
}

/// Cross-validate one classifier (folds drawn from `p.seed`).
pub fn cross_validate(ds: &Dataset, clf: &Classifier, p: &CvParams) -> Result<CvReport> {
    ds.validate()?;
    if p.repeats == 0 {
        return Err(LdhError::param("repeats", 0, "at least 1"));
    }
    let folds: Vec<Vec<usize>> = (0..p.repeats)
        .map(|r| folds(ds, p, r))
        .collect::<Result<_>>()?;
    cross_validate_with_folds(ds, clf, p, &folds)
}

/// Cross-validate with given fold assignments (one vector of fold ids per repeat), e.g. the
/// folds a scikit-learn comparison used.
pub fn cross_validate_with_folds(
    ds: &Dataset,
    clf: &Classifier,
    p: &CvParams,
    fold_sets: &[Vec<usize>],
) -> Result<CvReport> {
    ds.validate()?;
    let p = &checked_fold_params(ds, p, fold_sets)?;
    // Every (repeat, fold) is independent: run them in parallel, then reduce in order.
    let jobs: Vec<(usize, usize, &Vec<usize>)> = fold_sets
        .iter()
        .enumerate()
        .flat_map(|(r, f)| (0..p.k).map(move |k| (r, k, f)))
        .collect();
    let outs: Vec<FoldOut> = jobs
        .par_iter()
        .map(|&(r, k, fold)| run_fold(ds, clf, p, r, k, fold))
        .collect::<Result<Vec<_>>>()?;
    Ok(reduce_folds(ds, clf, p, &outs))
}

/// The CV params with `k` and `repeats` taken from the fold table, after checking that every
/// row has a fold id in every repeat, every repeat uses every fold and `top_k` fits.
fn checked_fold_params(ds: &Dataset, p: &CvParams, fold_sets: &[Vec<usize>]) -> Result<CvParams> {
    if fold_sets.is_empty() || fold_sets.iter().any(|f| f.len() != ds.len()) {
        return Err(LdhError::param(
            "folds",
            fold_sets.len(),
            "one fold id per row for every repeat",
        ));
    }
    let k = fold_sets.iter().flatten().max().map_or(0, |m| m + 1);
    if k < 2 {
        return Err(LdhError::param("folds", k, "at least 2 folds"));
    }
    if let Some(r) = fold_sets
        .iter()
        .position(|f| (0..k).any(|q| !f.contains(&q)))
    {
        return Err(LdhError::param(
            "folds",
            r,
            format!(
                "repeat {r} leaves a fold of 0..{k} empty: every repeat must use every fold id"
            ),
        ));
    }
    if let Some(t) = p.top_k {
        if t == 0 || t > ds.feature_names.len() {
            return Err(LdhError::param(
                "top_k",
                t,
                format!("must lie in 1..={}", ds.feature_names.len()),
            ));
        }
    }
    Ok(CvParams {
        repeats: fold_sets.len(),
        k,
        ..p.clone()
    })
}

/// One fold's outcome: repeat, (true, predicted) pairs, accuracy drop per feature, test rows.
type FoldOut = (usize, Vec<(usize, usize)>, Vec<f64>, usize);

/// Trains on every row outside fold `k` of repeat `r` and tests on the fold (feature selection
/// and min-max scaling fitted on the training rows only).
fn run_fold(
    ds: &Dataset,
    clf: &Classifier,
    p: &CvParams,
    r: usize,
    k: usize,
    fold: &[usize],
) -> Result<FoldOut> {
    let nf = ds.feature_names.len();
    let train: Vec<usize> = (0..ds.len()).filter(|&i| fold[i] != k).collect();
    let test: Vec<usize> = (0..ds.len()).filter(|&i| fold[i] == k).collect();
    if test.is_empty() {
        return Ok((r, vec![], vec![0.0; nf], 0));
    }
    let (xtr, ytr) = ds.take(&train);
    let (xte, yte) = ds.take(&test);
    let cols: Vec<usize> = match p.top_k {
        None => (0..nf).collect(),
        Some(t) => top_k_columns(&xtr, &ytr, t),
    };
    let xtr = xtr.select(Axis(1), &cols);
    let xte = xte.select(Axis(1), &cols);
    let sc = MinMax::fit(&xtr);
    let (xtr, xte) = (sc.transform(&xtr), sc.transform(&xte));
    let seed = p
        .seed
        .wrapping_mul(1_000_003)
        .wrapping_add((r * 1000 + k) as u64);
    let model = clf
        .reseeded(seed)
        .fit(&xtr, &ytr, ds.class_names.len())
        .map_err(|e| LdhError::signal("cross-validation", format!("repeat {r}, fold {k}: {e}")))?;
    let pred = model.predict(&xte)?;
    let pairs: Vec<(usize, usize)> = yte.iter().copied().zip(pred.iter().copied()).collect();
    let base = pairs.iter().filter(|(a, b)| a == b).count() as f64;
    let mut imp = vec![0.0; nf];
    if p.permutation_importance {
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5eed);
        for (jj, &j) in cols.iter().enumerate() {
            let mut xp = xte.clone();
            let mut col: Vec<f64> = xp.column(jj).to_vec();
            col.shuffle(&mut rng);
            for (i, v) in col.into_iter().enumerate() {
                xp[[i, jj]] = v;
            }
            let pp = model.predict(&xp)?;
            let acc = yte.iter().zip(&pp).filter(|(a, b)| a == b).count() as f64;
            imp[j] = base - acc;
        }
    }
    Ok((r, pairs, imp, test.len()))
}

/// The `t` columns most correlated (|Pearson r|) with the label, in column order; ties keep
/// the lower index.
fn top_k_columns(x: &Array2<f64>, y: &[usize], t: usize) -> Vec<usize> {
    let rr = pearson_with_label(x, y);
    let mut idx: Vec<usize> = (0..rr.len()).collect();
    idx.sort_by(|&a, &b| {
        rr[b]
            .abs()
            .partial_cmp(&rr[a].abs())
            .unwrap_or(std::cmp::Ordering::Equal)
            .then(a.cmp(&b))
    });
    let mut keep: Vec<usize> = idx.into_iter().take(t).collect();
    keep.sort_unstable();
    keep
}

/// Confusion matrices and macro scores per repeat, pooled per-class scores and importances.
fn reduce_folds(ds: &Dataset, clf: &Classifier, p: &CvParams, outs: &[FoldOut]) -> CvReport {
    let nc = ds.class_names.len();
    let nf = ds.feature_names.len();
    let mut conf_total = vec![vec![0usize; nc]; nc];
    let (mut acc, mut pm, mut rm, mut fm) = (vec![], vec![], vec![], vec![]);
    let mut imp_total = vec![0.0; nf];
    let mut n_test = 0usize;
    for r in 0..p.repeats {
        let mut conf = vec![vec![0usize; nc]; nc];
        for (_, pairs, imp, nt) in outs.iter().filter(|o| o.0 == r) {
            for &(t, q) in pairs {
                conf[t][q] += 1;
            }
            for (a, b) in imp_total.iter_mut().zip(imp) {
                *a += b;
            }
            n_test += nt;
        }
        let total: usize = conf.iter().flatten().sum();
        let correct: usize = (0..nc).map(|c| conf[c][c]).sum();
        let m = prf(&conf);
        acc.push(correct as f64 / total.max(1) as f64);
        let present: Vec<usize> = (0..nc)
            .filter(|&c| conf[c].iter().sum::<usize>() > 0)
            .collect();
        let avg = |f: fn(&(f64, f64, f64)) -> f64| {
            present.iter().map(|&c| f(&m[c])).sum::<f64>() / present.len().max(1) as f64
        };
        pm.push(avg(|x| x.0));
        rm.push(avg(|x| x.1));
        fm.push(avg(|x| x.2));
        for (a, row) in conf_total.iter_mut().zip(&conf) {
            for (x, y) in a.iter_mut().zip(row) {
                *x += y;
            }
        }
    }
    let pc = prf(&conf_total);
    CvReport {
        classifier: clf.name().into(),
        kind: p.kind,
        k: p.k,
        repeats: p.repeats,
        class_names: ds.class_names.clone(),
        accuracy: mean_sd(&acc),
        precision_macro: mean_sd(&pm),
        recall_macro: mean_sd(&rm),
        f1_macro: mean_sd(&fm),
        per_class: ds
            .class_names
            .iter()
            .zip(&pc)
            .map(|(n, (p, r, f))| (n.clone(), *p, *r, *f))
            .collect(),
        confusion: conf_total,
        permutation_importance: ds
            .feature_names
            .iter()
            .zip(&imp_total)
            .map(|(n, v)| (n.clone(), v / n_test.max(1) as f64))
            .collect(),
        accuracy_per_repeat: acc,
    }
}

/// The feature ranking of Table 5: Pearson r with the label, and its absolute rank.
pub fn ranking(ds: &Dataset) -> Vec<(String, f64)> {
    let r = pearson_with_label(&ds.x, &ds.y);
    let mut v: Vec<(String, f64)> = ds.feature_names.iter().cloned().zip(r).collect();
    v.sort_by(|a, b| {
        b.1.abs()
            .partial_cmp(&a.1.abs())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    v
}

/// Table 6/7-like Markdown of several reports.
pub fn markdown(reports: &[CvReport]) -> String {
    let mut s = String::from("| classifier | CV | accuracy | precision (macro) | recall (macro) | F1 (macro) |\n|---|---|---|---|---|---|\n");
    for r in reports {
        let f = |m: &MeanSd| format!("{:.3} ± {:.3}", m.mean, m.sd);
        s.push_str(&format!(
            "| {} | {} {}-fold × {} | {} | {} | {} | {} |\n",
            r.classifier,
            match r.kind {
                CvKind::Grouped => "subject-grouped",
                CvKind::Stratified => "stratified",
            },
            r.k,
            r.repeats,
            f(&r.accuracy),
            f(&r.precision_macro),
            f(&r.recall_macro),
            f(&r.f1_macro)
        ));
    }
    s
}
