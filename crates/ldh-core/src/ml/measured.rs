//! Training on what was measured (docs/classification.md, "What is trained on"): the task's
//! rows before any is dropped ([`candidates`]), the default features a cohort measured
//! ([`select_measured`]), the folds its smallest class allows ([`folds_for`]), and the typed
//! notes ([`TrainNote`]) that say what was left out and why.

use serde::{Deserialize, Serialize};

use super::task::Task;
use crate::cohort::{Cohort, Parameter};
use crate::error::{LdhError, Result};
use crate::output::RecordingRow;

/// One row of a task before incomplete rows are dropped: an LDH side, or a healthy subject's
/// mean of both legs (a feature is missing in the mean when either leg lacks it).
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// One value per feature, `None` where it was not measured.
    pub values: Vec<Option<f64>>,
    /// Label (class index of the task).
    pub label: usize,
    /// Subject id (the group of subject-grouped folds).
    pub subject: String,
    /// `unaffected`, `affected` or `healthy`.
    pub what: String,
}

impl Candidate {
    /// `subject/what`, as rows are named everywhere.
    pub fn id(&self) -> String {
        format!("{}/{}", self.subject, self.what)
    }
    /// No feature was measured (a walk without a valid stride).
    pub fn nothing_measured(&self) -> bool {
        self.values.iter().all(Option::is_none)
    }
}

/// The task's rows of a per-recording table (one attitude model), with their missing values.
pub fn candidates(
    rows: &[RecordingRow],
    task: Task,
    features: &[Parameter],
) -> Result<Vec<Candidate>> {
    let cohort = Cohort::from_rows(rows)?;
    let get =
        |r: &RecordingRow| -> Vec<Option<f64>> { features.iter().map(|&p| r.value(p)).collect() };
    let row = |values, label, subject: &str, what: &str| Candidate {
        values,
        label,
        subject: subject.to_string(),
        what: what.to_string(),
    };
    let mut out = Vec::new();
    for s in &cohort.ldh {
        if task == Task::ThreeClass {
            out.push(row(get(&s.a), 0, &s.subject_id, "unaffected"));
        }
        out.push(row(get(&s.b), 1, &s.subject_id, "affected")); // 1 in both tasks
    }
    let healthy = if task == Task::ThreeClass { 2 } else { 0 };
    for s in &cohort.healthy {
        let mean = get(&s.a)
            .into_iter()
            .zip(get(&s.b))
            .map(|(a, b)| Some((a? + b?) / 2.0))
            .collect();
        out.push(row(mean, healthy, &s.subject_id, "healthy"));
    }
    Ok(out)
}

/// How many of the rows measured a feature.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FeatureCoverage {
    /// Column name.
    pub feature: String,
    /// Rows with a value.
    pub measured: usize,
    /// Rows considered (those with any measurement).
    pub rows: usize,
}

/// What `ldh train` changed from what was asked, and why: one sentence each (`Display`), shown
/// on stderr and in the training report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "note", rename_all = "snake_case")]
pub enum TrainNote {
    /// Rows with no feature measured (no valid stride on the walk), left out first.
    NothingMeasured {
        /// The rows (`subject/what`).
        rows: Vec<String>,
    },
    /// Default features measured in too few rows, left out.
    FeaturesDropped {
        /// The features and how many rows measured each.
        features: Vec<FeatureCoverage>,
        /// The share of rows a feature needs.
        min_coverage: f64,
    },
    /// Rows left out because a feature used was not measured in them.
    RowsLeftOut {
        /// The rows with what they lack.
        rows: Vec<String>,
    },
    /// Fewer folds than asked: the smallest class has fewer rows than `asked`.
    FoldsLowered {
        /// Folds asked.
        asked: usize,
        /// Folds used.
        used: usize,
        /// The smallest class.
        class: String,
    },
}

impl std::fmt::Display for TrainNote {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TrainNote::NothingMeasured { rows } => write!(
                f,
                "{} row(s) left out with nothing measured (no valid stride): {}",
                rows.len(),
                rows.join(", ")
            ),
            TrainNote::FeaturesDropped {
                features,
                min_coverage,
            } => {
                let list: Vec<String> = features
                    .iter()
                    .map(|c| {
                        format!(
                            "{} (measured in {} of {} rows)",
                            c.feature, c.measured, c.rows
                        )
                    })
                    .collect();
                write!(
                    f,
                    "{} feature(s) left out, measured in fewer than {:.0} % of the rows: {}",
                    features.len(),
                    min_coverage * 100.0,
                    list.join(", ")
                )
            }
            TrainNote::RowsLeftOut { rows } => write!(
                f,
                "{} row(s) left out for a feature not measured: {}",
                rows.len(),
                rows.join("; ")
            ),
            TrainNote::FoldsLowered { asked, used, class } => write!(
                f,
                "k lowered from {asked} to {used}: the smallest class ({class}) has {used} rows"
            ),
        }
    }
}

/// The default features a cohort measured: rows with nothing measured are set aside, then a
/// feature is kept when it is measured in at least `min_coverage` of the remaining rows
/// (rows lacking a kept feature are left out later, by the dataset). Returns the features
/// kept, the rows that measured something, and the notes. Refuses, saying why, when no row
/// measured anything or no feature reaches the coverage.
pub fn select_measured(
    cands: Vec<Candidate>,
    features: &[Parameter],
    min_coverage: f64,
) -> Result<(Vec<Parameter>, Vec<Candidate>, Vec<TrainNote>)> {
    let total = cands.len();
    let (usable, empty): (Vec<Candidate>, Vec<Candidate>) =
        cands.into_iter().partition(|c| !c.nothing_measured());
    let mut notes = Vec::new();
    if !empty.is_empty() {
        notes.push(TrainNote::NothingMeasured {
            rows: empty.iter().map(Candidate::id).collect(),
        });
    }
    if usable.is_empty() {
        return Err(nothing_to_train(
            format!("none of the {total} rows has a measured feature (no valid stride on any walk: record longer walks)"),
            &notes,
        ));
    }
    let n = usable.len();
    let (mut kept, mut dropped) = (Vec::new(), Vec::new());
    for (j, &p) in features.iter().enumerate() {
        let measured = usable.iter().filter(|c| c.values[j].is_some()).count();
        if measured > 0 && measured as f64 >= min_coverage * n as f64 {
            kept.push(j);
        } else {
            dropped.push(FeatureCoverage {
                feature: p.column().to_string(),
                measured,
                rows: n,
            });
        }
    }
    if !dropped.is_empty() {
        notes.push(TrainNote::FeaturesDropped {
            features: dropped,
            min_coverage,
        });
    }
    if kept.is_empty() {
        return Err(nothing_to_train(
            "no feature is measured in enough rows".to_string(),
            &notes,
        ));
    }
    let usable = usable
        .into_iter()
        .map(|c| Candidate {
            values: kept.iter().map(|&j| c.values[j]).collect(),
            ..c
        })
        .collect();
    Ok((kept.iter().map(|&j| features[j]).collect(), usable, notes))
}

/// The folds to use: `k`, or the size of the smallest class present when it is smaller (with a
/// note). Refuses when the smallest class has fewer than 2 rows.
pub fn folds_for(
    counts: &[usize],
    class_names: &[String],
    k: usize,
) -> Result<(usize, Option<TrainNote>)> {
    let Some((i, &m)) = counts
        .iter()
        .enumerate()
        .filter(|(_, &c)| c > 0)
        .min_by_key(|(_, &c)| c)
    else {
        return Err(LdhError::signal("train", "no rows"));
    };
    if m >= k {
        return Ok((k, None));
    }
    if m < 2 {
        return Err(LdhError::param(
            "k",
            k,
            format!(
                "the smallest class ({}) has {m} row: cross-validation needs at least 2 rows of every class ({})",
                class_names[i],
                per_class(counts, class_names)
            ),
        ));
    }
    let note = TrainNote::FoldsLowered {
        asked: k,
        used: m,
        class: class_names[i].clone(),
    };
    Ok((m, Some(note)))
}

/// `3 LDHH, 3 LDHE, 6 H`.
pub fn per_class(counts: &[usize], class_names: &[String]) -> String {
    let parts: Vec<String> = counts
        .iter()
        .zip(class_names)
        .map(|(c, n)| format!("{c} {n}"))
        .collect();
    format!("rows per class: {}", parts.join(", "))
}

/// The one refusal when nothing is left to train on: why, then what was left out.
pub fn nothing_to_train(why: String, notes: &[TrainNote]) -> LdhError {
    let mut reason = format!("nothing to train on: {why}");
    for n in notes {
        reason.push_str("; ");
        reason.push_str(&n.to_string());
    }
    LdhError::signal("train", reason)
}

#[cfg(test)]
mod tests;
