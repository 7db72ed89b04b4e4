//! `ldh train` as one call: rank features, cross-validate every classifier with subject-grouped
//! folds (the primary result) and the paper's stratified folds (for comparison), report the gap
//! between them, and train the models to save (paper §3.5, §4.2, Tables 5–7).

use serde::{Deserialize, Serialize};

use super::measured::{self, TrainNote};
use super::{cv, dataset, Classifier, CvKind, CvParams, CvReport, Dataset, ModelFile, Task};
use crate::error::{LdhError, Result};
use crate::output::RecordingRow;

/// A classifier by short name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum ClassifierKind {
    /// Random forest.
    #[cfg_attr(feature = "clap", value(alias = "random-forest"))]
    Rf,
    /// RBF support vector machine.
    Svm,
    /// Multi-layer perceptron.
    Mlp,
}

impl ClassifierKind {
    /// `rf`, `svm` or `mlp`.
    pub fn as_str(self) -> &'static str {
        match self {
            ClassifierKind::Rf => "rf",
            ClassifierKind::Svm => "svm",
            ClassifierKind::Mlp => "mlp",
        }
    }
    /// The default classifier of this kind with `seed`.
    pub fn classifier(self, seed: u64) -> Classifier {
        Classifier::from_name(self.as_str(), seed).expect("a known classifier name")
    }
}

impl std::str::FromStr for ClassifierKind {
    type Err = LdhError;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "rf" | "random-forest" => Ok(ClassifierKind::Rf),
            "svm" => Ok(ClassifierKind::Svm),
            "mlp" => Ok(ClassifierKind::Mlp),
            o => Err(LdhError::param("classifier", o, "expected rf, svm or mlp")),
        }
    }
}

/// Parameters of [`train`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrainParams {
    /// Task. Default three-class.
    pub task: Task,
    /// Classifiers, in report order. Default rf, svm, mlp.
    pub classifiers: Vec<ClassifierKind>,
    /// Folds. Default 10.
    pub k: usize,
    /// Repeats of the k-fold split. Default 10.
    pub repeats: usize,
    /// Seed of folds and models. Default 1.
    pub seed: u64,
    /// Keep the k features with the largest |Pearson r| inside each training fold. Default none.
    pub top_k: Option<usize>,
    /// Features (columns of recordings.csv); `None`: the 13 parameters, those measured in at
    /// least `min_feature_coverage` of the rows ([`super::measured::select_measured`]).
    pub features: Option<Vec<String>>,
    /// The share of rows (those with anything measured) a default feature must be measured in
    /// to be kept, in (0, 1]. Default 0.9. Not used with `features`.
    #[serde(default = "default_coverage")]
    pub min_feature_coverage: f64,
}

fn default_coverage() -> f64 {
    0.9
}

impl TrainParams {
    /// Refuse parameters no training can use (checked once, at the start of [`train`]).
    pub fn check(&self) -> Result<()> {
        let c = self.min_feature_coverage;
        if !(c > 0.0 && c <= 1.0) {
            return Err(LdhError::param(
                "min_feature_coverage",
                c,
                "a share of the rows in (0, 1]",
            ));
        }
        if self.k < 2 {
            return Err(LdhError::param("k", self.k, "at least 2 folds"));
        }
        if self.repeats == 0 {
            return Err(LdhError::param("repeats", 0, "at least 1"));
        }
        if self.classifiers.is_empty() {
            return Err(LdhError::param(
                "classifiers",
                "none",
                "at least one classifier",
            ));
        }
        Ok(())
    }
}

impl Default for TrainParams {
    fn default() -> Self {
        TrainParams {
            task: Task::ThreeClass,
            classifiers: vec![ClassifierKind::Rf, ClassifierKind::Svm, ClassifierKind::Mlp],
            k: 10,
            repeats: 10,
            seed: 1,
            top_k: None,
            features: None,
            min_feature_coverage: default_coverage(),
        }
    }
}

/// What [`train`] produced: the report and every file of `ldh train`'s output folder.
#[derive(Debug, Clone)]
pub struct TrainOutcome {
    /// The Markdown report (`report.md`).
    pub markdown: String,
    /// Cross-validation reports: grouped then stratified, classifiers in order.
    pub reports: Vec<CvReport>,
    /// `(file name, content)` of every output file but the figures, in writing order (the
    /// confusion matrices are `ldh_report::figures::train_figures`').
    pub files: Vec<(String, String)>,
    /// What was changed from what was asked (features or rows left out, fewer folds), in order;
    /// also at the top of the report.
    pub notes: Vec<TrainNote>,
    /// The folds used (`k`, or fewer: see `notes`).
    pub k: usize,
}

/// Cross-validate and train on the per-recording rows (one attitude model). Runs in parallel on
/// the current rayon pool; the result does not depend on the thread count.
pub fn train(rows: &[RecordingRow], p: &TrainParams) -> Result<TrainOutcome> {
    train_with_progress(rows, p, &|_| {})
}

/// [`train`], calling `done(steps)` after each step (a classifier's cross-validation of one fold
/// kind, or a saved model) with the number of steps.
pub fn train_with_progress(
    rows: &[RecordingRow],
    p: &TrainParams,
    done: &(dyn Fn(usize) + Sync),
) -> Result<TrainOutcome> {
    p.check()?;
    let (ds, mut notes) = dataset_of(rows, p)?;
    let (k, lowered) = measured::folds_for(&ds.class_counts(), &ds.class_names, p.k)
        .map_err(|e| refusal(e, &notes))?;
    notes.extend(lowered);
    let p = &TrainParams { k, ..p.clone() };
    let attitude_model = rows
        .first()
        .map(|r| r.model.to_string())
        .unwrap_or_default();
    let clfs: Vec<Classifier> = p.classifiers.iter().map(|c| c.classifier(p.seed)).collect();
    let steps = clfs.len() * 3;
    let mut reports = Vec::new();
    for kind in [CvKind::Grouped, CvKind::Stratified] {
        let cp = CvParams {
            kind,
            permutation_importance: true,
            ..cv_params(p)
        };
        for c in &clfs {
            reports.push(super::cross_validate(&ds, c, &cp)?);
            done(steps);
        }
    }
    let mut files = vec![
        ("dataset.csv".to_string(), ds.to_csv()),
        ("folds.csv".to_string(), folds_csv(&ds, p)?),
    ];
    let markdown = markdown(&ds, p, &attitude_model, &clfs, &reports, &notes);
    // The saved model is the cross-validated pipeline: with top_k, the top features ranked on
    // all rows.
    let final_ds = match p.top_k {
        Some(k) => ds.select_top_k(k)?,
        None => ds.clone(),
    };
    for c in &clfs {
        let m = ModelFile::train(&final_ds, c, &attitude_model)?;
        let json = m.to_json()?;
        files.push((format!("model_{}.json", c.name()), json));
        done(steps);
    }
    let cv_json = serde_json::to_string_pretty(&reports)?;
    files.push(("cv_results.json".into(), cv_json));
    files.push(("report.md".into(), markdown.clone()));
    Ok(TrainOutcome {
        markdown,
        reports,
        files,
        notes,
        k,
    })
}

/// The dataset and the notes on what it left out: the features asked for (rows lacking one
/// dropped, as always), or else the default features the cohort measured.
fn dataset_of(rows: &[RecordingRow], p: &TrainParams) -> Result<(Dataset, Vec<TrainNote>)> {
    let (ds, mut notes) = match &p.features {
        Some(f) => (Dataset::from_recordings(rows, p.task, f)?, Vec::new()),
        None => {
            let all = dataset::default_parameters();
            let cands = measured::candidates(rows, p.task, &all)?;
            let (kept, cands, notes) =
                measured::select_measured(cands, &all, p.min_feature_coverage)?;
            let ds =
                Dataset::from_candidates(p.task, &kept, &cands).map_err(|e| refusal(e, &notes))?;
            (ds, notes)
        }
    };
    if !ds.dropped.is_empty() {
        notes.push(TrainNote::RowsLeftOut {
            rows: ds.dropped.clone(),
        });
    }
    Ok((ds, notes))
}

/// A refusal once rows or features were left out: one error saying why and what was left out.
fn refusal(e: LdhError, notes: &[TrainNote]) -> LdhError {
    if notes.is_empty() {
        return e;
    }
    let why = match &e {
        LdhError::Signal { reason, .. } => reason.clone(),
        LdhError::Param { reason, .. } => reason.clone(),
        other => other.to_string(),
    };
    measured::nothing_to_train(why, notes)
}

fn cv_params(p: &TrainParams) -> CvParams {
    CvParams {
        k: p.k,
        repeats: p.repeats,
        seed: p.seed,
        top_k: p.top_k,
        ..CvParams::default()
    }
}

/// The folds as used, one column per kind and repeat (for the scikit-learn comparison script).
fn folds_csv(ds: &Dataset, p: &TrainParams) -> Result<String> {
    let mut out = String::from("row_id");
    let mut cols: Vec<Vec<usize>> = Vec::new();
    for kind in [CvKind::Grouped, CvKind::Stratified] {
        let cp = CvParams {
            kind,
            top_k: None,
            ..cv_params(p)
        };
        for r in 0..p.repeats {
            out.push_str(&format!(",{}_r{r}", kind.as_str()));
            cols.push(cv::folds(ds, &cp, r)?);
        }
    }
    out.push('\n');
    for i in 0..ds.len() {
        out.push_str(&ds.row_ids[i]);
        for c in &cols {
            out.push_str(&format!(",{}", c[i]));
        }
        out.push('\n');
    }
    Ok(out)
}

fn mean_accuracy(reports: &[CvReport], clf: &str, kind: CvKind) -> f64 {
    reports
        .iter()
        .find(|r| r.classifier == clf && r.kind == kind)
        .map(|r| r.accuracy.mean)
        .unwrap_or(f64::NAN)
}

fn markdown(
    ds: &Dataset,
    p: &TrainParams,
    attitude_model: &str,
    clfs: &[Classifier],
    reports: &[CvReport],
    notes: &[TrainNote],
) -> String {
    let counts: Vec<String> = ds
        .class_names
        .iter()
        .zip(ds.class_counts())
        .map(|(n, c)| format!("{c} {n}"))
        .collect();
    let mut md = format!(
        "# Classification ({}, {} rows: {})\n\nFeatures from the `{attitude_model}` attitude model. Min–max scaling{} is fitted on each training fold only.\n\n",
        p.task.as_str(),
        ds.len(),
        counts.join(", "),
        if p.top_k.is_some() { " and the top-k feature selection" } else { "" }
    );
    if p.features.is_none() {
        md.push_str(&format!(
            "Features: the {} of the 13 parameters measured in at least {:.0} % of the rows with anything measured.\n\n",
            ds.feature_names.len(),
            p.min_feature_coverage * 100.0,
        ));
    }
    if !notes.is_empty() {
        md.push_str("Notes:\n\n");
        for n in notes {
            md.push_str(&format!("- {n}.\n"));
        }
        md.push('\n');
    }
    md.push_str("## Cross-validation\n\n**Subject-grouped folds are the primary result**: both sides of a subject always fall on the same side of a split. The paper's stratified folds, beside them, let one side of a subject train the model that tests the other side.\n\n");
    md.push_str(&cv::markdown(reports));
    md.push_str("\n| classifier | grouped − stratified accuracy |\n|---|---:|\n");
    for c in clfs {
        let g = mean_accuracy(reports, c.name(), CvKind::Grouped);
        let s = mean_accuracy(reports, c.name(), CvKind::Stratified);
        md.push_str(&format!("| {} | {:+.3} |\n", c.name(), g - s));
    }
    md.push_str(
        "\n## Feature ranking (Table 5): Pearson r with the label\n\n| feature | r |\n|---|---:|\n",
    );
    for (f, r) in cv::ranking(ds) {
        md.push_str(&format!("| {f} | {r:+.3} |\n"));
    }
    md.push_str("\n## Permutation importance (grouped CV, mean accuracy drop)\n\n| feature |");
    let grouped: Vec<&CvReport> = reports
        .iter()
        .filter(|r| r.kind == CvKind::Grouped)
        .collect();
    for r in &grouped {
        md.push_str(&format!(" {} |", r.classifier));
    }
    md.push_str("\n|---|");
    for _ in &grouped {
        md.push_str("---:|");
    }
    md.push('\n');
    for (j, f) in ds.feature_names.iter().enumerate() {
        md.push_str(&format!("| {f} |"));
        for r in &grouped {
            md.push_str(&format!(" {:+.3} |", r.permutation_importance[j].1));
        }
        md.push('\n');
    }
    md
}
