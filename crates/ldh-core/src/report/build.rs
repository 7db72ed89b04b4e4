//! Writing the reports of an `ldh analyze` output folder: one page per subject (with its strides
//! regrouped from the streamed `strides.csv`, its traces when kept, and a classifier's output
//! when given) and the cohort page.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use rayon::prelude::*;

use super::cycle::{pitch_cycle, CycleReference};
use super::reference::passes_every_check;
use super::{
    cohort_html, file_stem, subject_html, CohortReport, Reference, SubjectReport, SubjectTraces,
    ValidReportParams,
};
use crate::error::{LdhError, Result};
use crate::io::write_atomic;
use crate::ml::{ModelFile, Prediction};
use crate::output::{self, RecordingRow};

/// What goes into the reports besides the analysis folder.
#[derive(Debug, Clone, Copy, Default)]
pub struct BuildSources<'a> {
    /// A model saved by `ldh train`: its output goes into each subject's report.
    pub model: Option<&'a ModelFile>,
    /// Output folder of `ldh stats` (`table4.json`) for the cohort report.
    pub stats: Option<&'a Path>,
    /// Output folder of `ldh train` (`cv_results.json`) for the cohort report.
    pub train: Option<&'a Path>,
}

/// A table of an output folder, read back whole (at most [`crate::io::MAX_TABLE_MB`] MB).
fn read_text(path: &Path) -> Result<String> {
    crate::io::read_text_limited(path, crate::io::MAX_TABLE_MB, "an output table")
}

fn read_json<T: serde::de::DeserializeOwned>(path: &Path, what: &str) -> Result<T> {
    serde_json::from_str(&read_text(path)?).map_err(|e| LdhError::Format {
        name: path.display().to_string(),
        reason: format!("not {what}: {e}"),
    })
}

/// The per-recording table (`recordings.json`) of an `ldh analyze` output folder.
pub fn read_recordings(results: &Path) -> Result<Vec<RecordingRow>> {
    read_json(&results.join("recordings.json"), "an ldh recordings table")
}

/// Write `<out>/subjects/<subject>.html` for every subject of the `ldh analyze` folder `results`
/// and the cohort report `<out>/index.html`; returns the number of subject reports. Pages are
/// rendered in parallel on the current rayon pool, a chunk of subjects at a time (memory stays
/// flat); `done(total)` is called once per subject page with the number of pages (progress).
pub fn build(
    results: &Path,
    out: &Path,
    src: BuildSources<'_>,
    params: &ValidReportParams,
    done: &(dyn Fn(usize) + Sync),
) -> Result<usize> {
    let rows = read_recordings(results)?;
    let mut reference = Reference::from_rows(&rows, params);
    reference.cycle = cycle_reference(results, &rows, params)?;
    let mut preds_by = predictions_by_subject(src.model, &rows)?;
    let model_desc = src.model.map(|m| m.describe()).unwrap_or_default();
    let subjects = output::rows_by_subject(&rows);
    let ids: Vec<String> = subjects.iter().map(|(id, _)| id.to_string()).collect();
    output::names::check_unique(ids.iter().map(String::as_str))?;
    let _lock = crate::io::OutputLock::acquire(out)?;
    let mut groups = output::stride_groups(&results.join("strides.csv"))?.peekable();
    let chunk = (rayon::current_num_threads() * 32).max(32);
    for part in subjects.chunks(chunk) {
        // Strides of this chunk's subjects (the file has each subject's rows together, in the
        // order of recordings.json).
        let mut jobs: Vec<SubjectReport> = Vec::with_capacity(part.len());
        for (id, recs) in part {
            let mut strides = Vec::new();
            if let Some(Ok((gid, _))) = groups.peek() {
                if gid == id {
                    strides = groups.next().expect("peeked")?.1;
                }
            } else if let Some(Err(_)) = groups.peek() {
                groups.next().expect("peeked")?;
            }
            jobs.push(SubjectReport {
                subject_id: id.to_string(),
                recordings: recs.iter().map(|r| (*r).clone()).collect(),
                strides,
                traces: None,
                predictions: src.model.map(|m| {
                    (
                        preds_by.remove(*id).unwrap_or_default(),
                        m.class_names.clone(),
                        model_desc.clone(),
                    )
                }),
            });
        }
        let written: Vec<Result<()>> = jobs
            .into_par_iter()
            .map(|job| {
                write_subject(results, out, job, &reference, params)?;
                done(ids.len());
                Ok(())
            })
            .collect();
        written.into_iter().collect::<Result<()>>()?;
    }
    let cohort = CohortReport {
        offsets: match src.stats {
            Some(d) => read_json(&d.join("table4.json"), "an ldh stats Table 4")?,
            None => Vec::new(),
        },
        cv: match src.train {
            Some(d) => read_json(&d.join("cv_results.json"), "an ldh train result")?,
            None => Vec::new(),
        },
        subject_links: ids
            .iter()
            .map(|id| (id.clone(), format!("subjects/{}.html", file_stem(id))))
            .collect(),
        recordings: rows,
        reference: Some(reference),
    };
    write_atomic(out.join("index.html"), cohort_html(&cohort)?.as_bytes())?;
    Ok(ids.len())
}

fn predictions_by_subject(
    model: Option<&ModelFile>,
    rows: &[RecordingRow],
) -> Result<HashMap<String, Vec<Prediction>>> {
    let mut by: HashMap<String, Vec<Prediction>> = HashMap::new();
    if let Some(m) = model {
        for p in m.predict_rows(rows)? {
            by.entry(p.subject_id.clone()).or_default().push(p);
        }
    }
    Ok(by)
}

/// The trace file of a subject (of its first trial when it has several), and that trial.
fn trace_file(
    results: &Path,
    subject_id: &str,
    recs: &[RecordingRow],
) -> (PathBuf, Option<String>) {
    let first_trial = recs.first().map(|r| r.trial_id.clone());
    match first_trial.filter(|t| !t.is_empty()) {
        Some(t) => {
            let key = format!("{subject_id}__trial_{t}");
            let tf = results
                .join("traces")
                .join(format!("{}.json", file_stem(&key)));
            let several = recs.iter().any(|r| r.trial_id != t);
            (tf, several.then_some(t))
        }
        None => (
            results
                .join("traces")
                .join(format!("{}.json", file_stem(subject_id))),
            None,
        ),
    }
}

/// The healthy reference band of the shank-pitch cycle: the mean curve of every healthy leg
/// that passes every quality check and has a trace (from `ldh analyze --report`).
fn cycle_reference(
    results: &Path,
    rows: &[RecordingRow],
    params: &ValidReportParams,
) -> Result<CycleReference> {
    let legs: HashSet<(&str, &str)> = rows
        .iter()
        .filter(|r| {
            matches!(r.group, Some(crate::pipeline::GroupLabel::Healthy))
                && r.is_ok()
                && passes_every_check(r)
        })
        .map(|r| (r.subject_id.as_str(), r.side.as_str()))
        .collect();
    let subjects: HashSet<&str> = legs.iter().map(|l| l.0).collect();
    let mut curves = Vec::new();
    if subjects.is_empty() || !results.join("traces").is_dir() {
        return Ok(CycleReference::default());
    }
    let mut strides: HashMap<String, Vec<crate::output::StrideRow>> = HashMap::new();
    for g in output::stride_groups(&results.join("strides.csv"))? {
        let (id, v) = g?;
        if subjects.contains(id.as_str()) {
            strides.insert(id, v);
        }
    }
    for (id, recs) in output::rows_by_subject(rows) {
        if !subjects.contains(id) {
            continue;
        }
        let recs: Vec<RecordingRow> = recs.into_iter().cloned().collect();
        let (tf, trial) = trace_file(results, id, &recs);
        if !tf.exists() {
            continue;
        }
        let t = SubjectTraces::from_json(&read_text(&tf)?, &tf.display().to_string())?;
        let st: Vec<crate::output::StrideRow> = strides
            .remove(id)
            .unwrap_or_default()
            .into_iter()
            .filter(|r| trial.as_ref().is_none_or(|t| &r.trial_id == t))
            .collect();
        for leg in &t.legs {
            if legs.contains(&(id, leg.side.as_str())) {
                curves.extend(pitch_cycle(leg, &st));
            }
        }
    }
    Ok(CycleReference::from_legs(
        &curves,
        params.0.min_healthy_subjects,
    ))
}

fn write_subject(
    results: &Path,
    out: &Path,
    mut job: SubjectReport,
    reference: &Reference,
    params: &ValidReportParams,
) -> Result<()> {
    let stem = file_stem(&job.subject_id);
    // A person's several trials: the plots show the first trial (its traces and strides); the
    // parameter table averages them all.
    let (tf, trial) = trace_file(results, &job.subject_id, &job.recordings);
    if let Some(t) = trial {
        job.strides.retain(|r| r.trial_id == t);
    }
    if tf.exists() {
        job.traces = Some(SubjectTraces::from_json(
            &read_text(&tf)?,
            &tf.display().to_string(),
        )?);
    }
    let html = subject_html(&job, reference, params)?;
    write_atomic(
        out.join("subjects").join(format!("{stem}.html")),
        html.as_bytes(),
    )
}
