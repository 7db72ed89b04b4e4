//! Writing the reports of an `ldh analyze` output folder: one page per subject (with its strides
//! regrouped from the streamed `strides.csv`, its traces when kept, and a classifier's output
//! when given) and the cohort page.

use std::collections::{HashMap, HashSet};
use std::path::Path;

use rayon::prelude::*;

use super::cycle::{pitch_cycle, CycleReference};
use super::reference::passes_every_check;
use super::{
    cohort_html, file_stem, subject_html, CohortReport, Reference, RunContext, SubjectReport,
    SubjectTraces, ValidReportParams,
};
use ldh_core::error::{LdhError, Result};
use ldh_core::events::EventCalibration;
use ldh_core::ml::{ModelFile, Prediction};
use ldh_core::output::names::key_stem;
use ldh_core::output::{self, read_marker, OutputRun, RecordingRow, RunKind, RunMarker};

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

/// A table of an output folder, read back whole (at most [`ldh_core::io::MAX_TABLE_MB`] MB).
fn read_text(path: &Path) -> Result<String> {
    ldh_core::io::read_text_limited(path, ldh_core::io::MAX_TABLE_MB, "an output table")
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

/// The run marker of an `ldh analyze` folder, checked: a folder whose run did not finish, or
/// that another command wrote, is refused; a folder without a marker (an older ldh, or made
/// by hand) is read with a warning and its traces are not used.
fn results_run(results: &Path, warnings: &mut Vec<String>) -> Result<Option<RunMarker>> {
    let where_ = results.display().to_string();
    match read_marker(results)? {
        None => {
            warnings.push(format!(
                "{where_}: no {} (an older ldh, or files put together by hand): nothing shows that its files come from one run, so no signal traces are drawn; re-run `ldh analyze --report` to have them",
                output::MARKER
            ));
            Ok(None)
        }
        Some(m) if !m.complete => Err(LdhError::signal(
            where_,
            format!(
                "the ldh analyze run writing this folder did not finish ({} says complete: false: it was interrupted, or is still running); re-run ldh analyze",
                output::MARKER
            ),
        )),
        Some(m) if m.command != RunKind::Analyze => Err(LdhError::signal(
            where_,
            "not an ldh analyze folder (its run marker was written by ldh report)",
        )),
        Some(m) => Ok(Some(m)),
    }
}

/// The tables of `results` its marker lists (same content): `recordings.json` read and
/// checked, `strides.csv` checked by size (it is streamed later).
fn checked_rows(results: &Path, marker: Option<&RunMarker>) -> Result<Vec<RecordingRow>> {
    let Some(m) = marker else {
        return ldh_core::output::read_recordings(results);
    };
    let path = results.join("recordings.json");
    let text = read_text(&path)?;
    let strides = std::fs::metadata(results.join("strides.csv"))
        .map(|x| x.len())
        .ok();
    let strides_ok = m.file("strides.csv").map(|f| f.bytes) == strides;
    if !m.lists("recordings.json", text.as_bytes()) || !strides_ok {
        return Err(LdhError::signal(
            results.display().to_string(),
            format!(
                "{} is not the file its run wrote (changed after the run: the tables would not match the traces); re-run ldh analyze",
                if strides_ok { "recordings.json" } else { "strides.csv" }
            ),
        ));
    }
    serde_json::from_str(&text).map_err(|e| LdhError::Format {
        name: path.display().to_string(),
        reason: format!("not an ldh recordings table: {e}"),
    })
}

/// Write `<out>/subjects/<subject>.html` for every subject of the `ldh analyze` folder `results`
/// and the cohort report `<out>/index.html`. `out` is one run's folder ([`OutputRun`]): an
/// earlier report there is replaced whole, other files refuse the run, links are never
/// followed. Only files `results`' run marker lists are used (a trace from another run is
/// never drawn beside these tables). Pages are rendered in parallel on the current rayon pool,
/// a chunk of subjects at a time (memory stays flat); `done(total)` is called once per subject
/// page with the number of pages (progress).
pub fn build(
    results: &Path,
    out: &Path,
    src: BuildSources<'_>,
    params: &ValidReportParams,
    done: &(dyn Fn(usize) + Sync),
) -> Result<BuildSummary> {
    let mut warnings = Vec::new();
    let marker = results_run(results, &mut warnings)?;
    let rows = checked_rows(results, marker.as_ref())?;
    let ctx = Ctx {
        results,
        marker: marker.as_ref(),
        warnings: std::sync::Mutex::new(warnings),
    };
    let mut reference = Reference::from_rows(&rows, params);
    reference.cycle = cycle_reference(&ctx, &rows, params)?;
    let mut preds_by = predictions_by_subject(src.model, &rows)?;
    let context = RunContext {
        calibration: run_calibration(results, &ctx)?,
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
    let subjects = output::rows_by_subject(&rows);
    let ids: Vec<String> = subjects.iter().map(|(id, _)| id.to_string()).collect();
    output::names::check_unique(ids.iter().map(String::as_str))?;
    output::run::refuse_links_below(results, out)?;
    let mut run = OutputRun::begin(out, RunKind::Report)?;
    run.set_results_run(marker.as_ref().map(|m| m.run_id.clone()));
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
                write_subject(&ctx, &run, job, &reference, params)?;
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
        asymmetry_flag_pct: Some(params.0.asymmetry_flag_pct),
        context,
    };
    run.write("index.html", cohort_html(&cohort)?.as_bytes())?;
    run.finish()?;
    Ok(BuildSummary {
        subjects: ids.len(),
        warnings: {
            // Traces are looked at twice (the healthy cycle band, then the page): once each.
            let mut seen = HashSet::new();
            let mut w = ctx.warnings.into_inner().expect("no panic holds it");
            w.retain(|x| seen.insert(x.clone()));
            w
        },
    })
}

/// The event calibration of the run (`events.calibration` of its `params.json`), when it had
/// one. Only that entry is read, so the parameters of an older ldh (other fields) still
/// report; a calibration that does not read is a warning, and the pages then say nothing of
/// one (an unreadable `params.json` is not this function's to judge).
fn run_calibration(results: &Path, ctx: &Ctx) -> Result<Option<EventCalibration>> {
    let path = results.join("params.json");
    if !path.is_file() {
        return Ok(None);
    }
    let value: serde_json::Value = match serde_json::from_str(&read_text(&path)?) {
        Ok(v) => v,
        Err(_) => return Ok(None),
    };
    let Some(c) = value
        .pointer("/events/calibration")
        .filter(|c| !c.is_null())
    else {
        return Ok(None);
    };
    match serde_json::from_value::<EventCalibration>(c.clone()) {
        Ok(c) => Ok(Some(c)),
        Err(e) => {
            ctx.warnings.lock().expect("no panic holds it").push(format!(
                "{}: events.calibration does not read ({e}); the pages do not say the events were calibrated",
                path.display()
            ));
            Ok(None)
        }
    }
}

/// The `ldh analyze` folder being reported and what its traces raised.
struct Ctx<'a> {
    results: &'a Path,
    /// Its complete run marker (`None`: no marker, traces are not used).
    marker: Option<&'a RunMarker>,
    warnings: std::sync::Mutex<Vec<String>>,
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

/// The traces of a subject (of its first trial when it has several) and that trial when it has
/// several. A trace is used only when the results' run marker lists it with this content and
/// it names this subject and trial; otherwise it is left out with a warning.
fn load_trace(
    ctx: &Ctx<'_>,
    subject_id: &str,
    recs: &[RecordingRow],
) -> Result<(Option<SubjectTraces>, Option<String>)> {
    let first = recs
        .first()
        .map(|r| r.trial_id.clone())
        .filter(|t| !t.is_empty());
    let several = first
        .as_ref()
        .is_some_and(|t| recs.iter().any(|r| &r.trial_id != t));
    let trial = first.clone().filter(|_| several);
    let rel = format!("traces/{}.json", key_stem(subject_id, first.as_deref()));
    let path = ctx.results.join(&rel);
    let Some(marker) = ctx.marker else {
        return Ok((None, trial));
    };
    let warn = |why: String| {
        ctx.warnings
            .lock()
            .expect("no panic holds it")
            .push(format!(
                "{}: {why}: its signals are not drawn",
                path.display()
            ));
    };
    match std::fs::symlink_metadata(&path) {
        Err(_) => return Ok((None, trial)),
        Ok(m) if !m.is_file() => {
            warn("not a regular file (a link?)".into());
            return Ok((None, trial));
        }
        Ok(_) => {}
    }
    let bytes = std::fs::read(&path).map_err(|source| LdhError::Io {
        path: path.clone(),
        source,
    })?;
    if !marker.lists(&rel, &bytes) {
        warn(format!(
            "not the trace the run of these tables wrote (not listed with this content in {})",
            output::MARKER
        ));
        return Ok((None, trial));
    }
    let t = SubjectTraces::from_json(
        &String::from_utf8_lossy(&bytes),
        &path.display().to_string(),
    )?;
    if t.subject_id != subject_id || t.trial_id != first {
        warn(format!(
            "holds subject {:?} trial {:?}, not subject {subject_id:?} trial {first:?}",
            t.subject_id, t.trial_id
        ));
        return Ok((None, trial));
    }
    Ok((Some(t), trial))
}

/// The healthy reference band of the shank-pitch cycle: the mean curve of every healthy leg
/// that passes every quality check and has a trace (from `ldh analyze --report`).
fn cycle_reference(
    ctx: &Ctx<'_>,
    rows: &[RecordingRow],
    params: &ValidReportParams,
) -> Result<CycleReference> {
    let results = ctx.results;
    let legs: HashSet<(&str, &str)> = rows
        .iter()
        .filter(|r| {
            matches!(r.group, Some(ldh_core::pipeline::GroupLabel::Healthy))
                && r.is_ok()
                && passes_every_check(r)
        })
        .map(|r| (r.subject_id.as_str(), r.side.as_str()))
        .collect();
    let subjects: HashSet<&str> = legs.iter().map(|l| l.0).collect();
    let mut curves = Vec::new();
    if subjects.is_empty() || ctx.marker.is_none() || !results.join("traces").is_dir() {
        return Ok(CycleReference::default());
    }
    let mut strides: HashMap<String, Vec<ldh_core::output::StrideRow>> = HashMap::new();
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
        let (Some(t), trial) = load_trace(ctx, id, &recs)? else {
            continue;
        };
        let st: Vec<ldh_core::output::StrideRow> = strides
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
    ctx: &Ctx<'_>,
    run: &OutputRun,
    mut job: SubjectReport,
    reference: &Reference,
    params: &ValidReportParams,
) -> Result<()> {
    let stem = file_stem(&job.subject_id);
    // A person's several trials: the plots show the first trial (its traces and strides); the
    // parameter table averages them all.
    let (traces, trial) = load_trace(ctx, &job.subject_id, &job.recordings)?;
    if let Some(t) = trial {
        job.strides.retain(|r| r.trial_id == t);
    }
    job.traces = traces;
    let html = subject_html(&job, reference, params)?;
    run.write(&format!("subjects/{stem}.html"), html.as_bytes())
}
