//! What the reports are built from: one `ldh analyze` run's per-recording rows, per-stride
//! rows, signal traces and event calibration ([`RunResults`]). `ldh analyze --report` hands
//! over its own results in memory ([`RunResults::of_run`]); `ldh report` reads an output folder
//! once into the same type ([`RunResults::read`]), checking that every file is the one its run
//! wrote (the run marker, docs/robustness.md).
//!
//! The two are the same values: the rows are rounded before they are written, and CSV and JSON
//! (serde_json's `float_roundtrip`) read back the float written, so a report from memory and a
//! report from the folder are the same bytes (`tests/pins`).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use ldh_core::error::{LdhError, Result};
use ldh_core::events::EventCalibration;
use ldh_core::output::names::key_stem;
use ldh_core::output::{self, read_marker, RecordingRow, RunKind, RunMarker, StrideRow};
use ldh_core::pipeline::{AnalysisParams, KeptRun};

use super::SubjectTraces;

/// One `ldh analyze` run's results, as the reports use them.
#[derive(Debug, Clone, Default)]
pub struct RunResults {
    /// The run's output folder (messages name it; reports may not be written through a link
    /// inside it).
    pub dir: PathBuf,
    /// The run's id (its marker's `run_id`; `None`: a folder without a marker, whose traces are
    /// not used).
    pub run_id: Option<String>,
    /// The per-recording rows (`recordings.json`).
    pub recordings: Vec<RecordingRow>,
    /// The per-stride rows (`strides.csv`) as runs of consecutive rows of one subject, in table
    /// order (the run writes each subject's rows together).
    pub strides: Vec<(String, Vec<StrideRow>)>,
    /// Each subject's signal traces (of its first trial), when the run kept them and they are
    /// the run's own.
    pub traces: HashMap<String, SubjectTraces>,
    /// The event calibration the run applied (`params.json`'s `events.calibration`).
    pub calibration: Option<EventCalibration>,
    /// What could not be used and why, one sentence each.
    pub warnings: Vec<String>,
}

/// A subject's first trial and, when it has several, the trial the plots show (the first).
pub(crate) fn first_trial(recs: &[RecordingRow]) -> (Option<String>, Option<String>) {
    let first = recs
        .first()
        .map(|r| r.trial_id.clone())
        .filter(|t| !t.is_empty());
    let several = first
        .as_ref()
        .is_some_and(|t| recs.iter().any(|r| &r.trial_id != t));
    let trial = first.clone().filter(|_| several);
    (first, trial)
}

/// Stride rows as runs of consecutive rows of one subject (as [`output::stride_groups`]).
fn group_strides(rows: Vec<StrideRow>) -> Vec<(String, Vec<StrideRow>)> {
    let mut out: Vec<(String, Vec<StrideRow>)> = Vec::new();
    for r in rows {
        match out.last_mut() {
            Some((id, v)) if *id == r.subject_id => v.push(r),
            _ => out.push((r.subject_id.clone(), vec![r])),
        }
    }
    out
}

impl RunResults {
    /// The results of the run that just wrote `dir` (`ldh analyze --report`): its rows and
    /// traces as kept in memory ([`ldh_core::pipeline::FolderOptions::keep`]), its marker and
    /// its parameters. Nothing is read back.
    pub fn of_run(
        dir: &Path,
        kept: KeptRun,
        marker: &RunMarker,
        params: &AnalysisParams,
    ) -> RunResults {
        let mut traces: HashMap<(String, Option<String>), SubjectTraces> = kept
            .traces
            .into_iter()
            .map(|t| ((t.subject_id.clone(), t.trial_id.clone()), t))
            .collect();
        let mut own = HashMap::new();
        for (id, recs) in output::rows_by_subject(&kept.recordings) {
            let recs: Vec<RecordingRow> = recs.into_iter().cloned().collect();
            let (first, _) = first_trial(&recs);
            if let Some(t) = traces.remove(&(id.to_string(), first)) {
                own.insert(id.to_string(), t);
            }
        }
        RunResults {
            dir: dir.to_path_buf(),
            run_id: Some(marker.run_id.clone()),
            strides: group_strides(kept.strides),
            recordings: kept.recordings,
            traces: own,
            calibration: params.events.calibration.clone(),
            warnings: Vec::new(),
        }
    }

    /// Read the `ldh analyze` folder `dir` once: its marker (a run that did not finish, or a
    /// folder another command wrote, is refused; a folder without one is read with a warning
    /// and its traces are not used), `recordings.json` and `strides.csv` (checked against the
    /// marker), each subject's trace (used only when the marker lists it with this content and
    /// it names its subject and trial; otherwise left out with a warning) and the calibration
    /// of `params.json`.
    pub fn read(dir: &Path) -> Result<RunResults> {
        let mut warnings = Vec::new();
        let marker = results_run(dir, &mut warnings)?;
        let recordings = checked_rows(dir, marker.as_ref())?;
        let strides = output::stride_groups(&dir.join("strides.csv"))?.collect::<Result<_>>()?;
        let mut traces = HashMap::new();
        if let Some(m) = &marker {
            for (id, recs) in output::rows_by_subject(&recordings) {
                let recs: Vec<RecordingRow> = recs.into_iter().cloned().collect();
                if let Some(t) = load_trace(dir, m, id, &recs, &mut warnings)? {
                    traces.insert(id.to_string(), t);
                }
            }
        }
        let calibration = run_calibration(dir, &mut warnings)?;
        Ok(RunResults {
            dir: dir.to_path_buf(),
            run_id: marker.map(|m| m.run_id),
            recordings,
            strides,
            traces,
            calibration,
            warnings,
        })
    }
}

/// A table of an output folder, read back whole (at most [`ldh_core::io::MAX_TABLE_MB`] MB).
pub(crate) fn read_text(path: &Path) -> Result<String> {
    ldh_core::io::read_text_limited(path, ldh_core::io::MAX_TABLE_MB, "an output table")
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
/// checked, `strides.csv` checked by size.
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

/// The trace of a subject (of its first trial when it has several), when `marker` lists it
/// with this content and it names this subject and trial; otherwise `None`, with a warning
/// when there was a file.
fn load_trace(
    results: &Path,
    marker: &RunMarker,
    subject_id: &str,
    recs: &[RecordingRow],
    warnings: &mut Vec<String>,
) -> Result<Option<SubjectTraces>> {
    let (first, _) = first_trial(recs);
    let rel = format!("traces/{}.json", key_stem(subject_id, first.as_deref()));
    let path = results.join(&rel);
    let mut warn = |why: String| {
        warnings.push(format!(
            "{}: {why}: its signals are not drawn",
            path.display()
        ));
    };
    match std::fs::symlink_metadata(&path) {
        Err(_) => return Ok(None),
        Ok(m) if !m.is_file() => {
            warn("not a regular file (a link?)".into());
            return Ok(None);
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
        return Ok(None);
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
        return Ok(None);
    }
    Ok(Some(t))
}

/// The event calibration of the run (`events.calibration` of its `params.json`), when it had
/// one. Only that entry is read, so the parameters of an older ldh (other fields) still
/// report; a calibration that does not read is a warning, and the pages then say nothing of
/// one (an unreadable `params.json` is not this function's to judge).
fn run_calibration(results: &Path, warnings: &mut Vec<String>) -> Result<Option<EventCalibration>> {
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
            warnings.push(format!(
                "{}: events.calibration does not read ({e}); the pages do not say the events were calibrated",
                path.display()
            ));
            Ok(None)
        }
    }
}
