//! Writing the reports of an `ldh analyze` run's results ([`RunResults`], in memory from the
//! run or read once from its folder): one page per subject (with its strides, its traces when
//! kept, and a classifier's output when given) and the cohort page.

use std::collections::{HashMap, HashSet};
use std::path::Path;

use rayon::prelude::*;

use super::cycle::{pitch_cycle, CycleReference};
use super::reference::passes_every_check;
use super::results::{first_trial, read_text, RunResults};
use super::{
    cohort_html, file_stem, subject_html, CohortReport, Reference, RunContext, SubjectReport,
    ValidReportParams,
};
use ldh_core::error::{LdhError, Result};
use ldh_core::ml::{ModelFile, Prediction};
use ldh_core::output::{self, OutputRun, RecordingRow, RunKind};

/// What goes into the reports besides the analysis folder.
#[derive(Debug, Clone, Copy, Default)]
pub struct BuildSources<'a> {
    /// A model saved by `ldh train`: its output goes into each subject's report.
    pub model: Option<&'a ModelFile>,
    /// Output folder of `ldh stats` (`table4.json`) for the cohort report.
    pub stats: Option<&'a Path>,
    /// Output folder of `ldh train` (`cv_results.json`) for the cohort report.
    pub train: Option<&'a Path>,
    /// A test–retest reliability table (`reliability.csv` of `ldh stats --reliability`): changes
    /// between visits beyond its MDC95 are marked on the subject pages.
    pub reliability: Option<&'a Path>,
}

fn read_json<T: serde::de::DeserializeOwned>(path: &Path, what: &str) -> Result<T> {
    serde_json::from_str(&read_text(path)?).map_err(|e| LdhError::Format {
        name: path.display().to_string(),
        reason: format!("not {what}: {e}"),
    })
}

/// What [`build`] did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BuildSummary {
    /// Subject reports written.
    pub subjects: usize,
    /// What the reports could not use and why (a folder without a run marker, a trace that is
    /// not its run's), one sentence each.
    pub warnings: Vec<String>,
}

/// Write `<out>/subjects/<subject>.html` for every subject of an `ldh analyze` run's `results`
/// and the cohort report `<out>/index.html`. `out` is one run's folder ([`OutputRun`]): an
/// earlier report there is replaced whole, other files refuse the run, links are never
/// followed. Pages are rendered in parallel on the current rayon pool, a chunk of subjects at a
/// time; `done(total)` is called once per subject page with the number of pages (progress).
pub fn build(
    results: &RunResults,
    out: &Path,
    src: BuildSources<'_>,
    params: &ValidReportParams,
    done: &(dyn Fn(usize) + Sync),
) -> Result<BuildSummary> {
    let rows = &results.recordings;
    let mut reference = Reference::from_rows(rows, params);
    reference.cycle = cycle_reference(results, params);
    let mut preds_by = predictions_by_subject(src.model, rows)?;
    let context = RunContext {
        calibration: results.calibration.clone(),
        reliability: src
            .reliability
            .map(ldh_core::cohort::ReliabilityTable::read)
            .transpose()?,
        reliability_source: src.reliability.map(|p| {
            p.file_name().map_or(p.display().to_string(), |n| {
                n.to_string_lossy().into_owned()
            })
        }),
    };
    let model_desc = src.model.map(|m| m.describe()).unwrap_or_default();
    let subjects = output::rows_by_subject(rows);
    let ids: Vec<String> = subjects.iter().map(|(id, _)| id.to_string()).collect();
    output::names::check_unique(ids.iter().map(String::as_str))?;
    output::run::refuse_links_below(&results.dir, out)?;
    let mut run = OutputRun::begin(out, RunKind::Report)?;
    run.set_results_run(results.run_id.clone());
    let mut groups = results.strides.iter().peekable();
    let chunk = (rayon::current_num_threads() * 32).max(32);
    for part in subjects.chunks(chunk) {
        // Strides of this chunk's subjects (the table has each subject's rows together, in the
        // order of the recordings).
        let mut jobs: Vec<SubjectReport> = Vec::with_capacity(part.len());
        for (id, recs) in part {
            let mut strides = Vec::new();
            if let Some((gid, _)) = groups.peek() {
                if gid == id {
                    strides = groups.next().expect("peeked").1.clone();
                }
            }
            jobs.push(SubjectReport {
                subject_id: id.to_string(),
                recordings: recs.iter().map(|r| (*r).clone()).collect(),
                strides,
                traces: None,
                context: context.clone(),
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
                write_subject(results, &run, job, &reference, params)?;
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
        recordings: rows.clone(),
        reference: Some(reference),
        asymmetry_flag_pct: Some(params.0.asymmetry_flag_pct),
        context,
    };
    run.write("index.html", cohort_html(&cohort)?.as_bytes())?;
    run.finish()?;
    Ok(BuildSummary {
        subjects: ids.len(),
        warnings: {
            let mut seen = HashSet::new();
            let mut w = results.warnings.clone();
            w.retain(|x| seen.insert(x.clone()));
            w
        },
    })
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

/// The healthy reference band of the shank-pitch cycle: the mean curve of every healthy leg
/// that passes every quality check and has a trace (from `ldh analyze --report`).
fn cycle_reference(results: &RunResults, params: &ValidReportParams) -> CycleReference {
    let rows = &results.recordings;
    let legs: HashSet<(&str, &str)> = rows
        .iter()
        .filter(|r| {
            matches!(r.group, Some(ldh_core::pipeline::Group::Healthy))
                && r.is_ok()
                && passes_every_check(r)
        })
        .map(|r| (r.subject_id.as_str(), r.side.as_str()))
        .collect();
    let subjects: HashSet<&str> = legs.iter().map(|l| l.0).collect();
    let mut curves = Vec::new();
    if subjects.is_empty() || results.traces.is_empty() {
        return CycleReference::default();
    }
    // A subject's last run of rows wins (as a table read group by group into a map).
    let strides: HashMap<&str, &Vec<ldh_core::output::StrideRow>> = results
        .strides
        .iter()
        .filter(|(id, _)| subjects.contains(id.as_str()))
        .map(|(id, v)| (id.as_str(), v))
        .collect();
    for (id, recs) in output::rows_by_subject(rows) {
        if !subjects.contains(id) {
            continue;
        }
        let recs: Vec<RecordingRow> = recs.into_iter().cloned().collect();
        let Some(t) = results.traces.get(id) else {
            continue;
        };
        let (_, trial) = first_trial(&recs);
        let st: Vec<ldh_core::output::StrideRow> = strides
            .get(id)
            .map(|v| v.to_vec())
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
    CycleReference::from_legs(&curves, params.0.min_healthy_subjects)
}

fn write_subject(
    results: &RunResults,
    run: &OutputRun,
    mut job: SubjectReport,
    reference: &Reference,
    params: &ValidReportParams,
) -> Result<()> {
    let stem = file_stem(&job.subject_id);
    // A person's several trials: the page keeps every trial's strides (its tables count them
    // all) and plots the first trial's (`subject_html`).
    job.traces = results.traces.get(&job.subject_id).cloned();
    let html = subject_html(&job, reference, params)?;
    run.write(&format!("subjects/{stem}.html"), html.as_bytes())
}
