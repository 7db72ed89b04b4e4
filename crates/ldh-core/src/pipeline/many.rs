//! Many subjects at once: the read-inputs-and-analyse loop of `ldh analyze`, `stats`, `train`,
//! `predict` and `evaluate`, in parallel on the current rayon pool.
//!
//! [`analyze_to_folder`] streams: subjects are analysed a chunk at a time and their rows appended
//! to the output tables, so memory stays flat however many subjects there are; chunks keep the
//! input order, so the files are the same whatever the thread count.

use rayon::prelude::*;

use super::{
    analyze_subject, analyze_subject_checked, AnalysisParams, SubjectInput, SubjectResult,
};
use crate::error::Result;
use crate::io::{FormatSpec, ValidReadParams};
use crate::output::trace::{SubjectTraces, ValidTraceParams};
use crate::output::{self, OutputRun, RecordingRow, RenderedRows, TableSink};
use crate::timings::{Stage, StageTimings};

/// Analyse every subject (in parallel, results in input order).
pub fn analyze_many(
    subjects: &[SubjectInput],
    params: &AnalysisParams,
    format: Option<&FormatSpec>,
    read: &ValidReadParams,
) -> Vec<SubjectResult> {
    let checked = params.check().ok();
    subjects
        .par_iter()
        .map(|s| match &checked {
            Some(v) => analyze_subject_checked(s, v, format, read),
            None => analyze_subject(s, params, format, read),
        })
        .collect()
}

/// The per-recording rows of every subject (see [`analyze_many`]).
pub fn recording_rows_many(
    subjects: &[SubjectInput],
    params: &AnalysisParams,
    read: &ValidReadParams,
) -> Vec<RecordingRow> {
    recording_rows_many_with(subjects, params, read, &|| {})
}

/// [`recording_rows_many`], calling `done()` after each subject (progress).
pub fn recording_rows_many_with(
    subjects: &[SubjectInput],
    params: &AnalysisParams,
    read: &ValidReadParams,
    done: &(dyn Fn() + Sync),
) -> Vec<RecordingRow> {
    let checked = params.check().ok();
    let results: Vec<SubjectResult> = subjects
        .par_iter()
        .map(|s| {
            let r = match &checked {
                Some(v) => analyze_subject_checked(s, v, None, read),
                None => analyze_subject(s, params, None, read),
            };
            done();
            r
        })
        .collect();
    output::recording_rows(&results)
}

/// Options of [`analyze_to_folder`].
#[derive(Debug, Clone, Copy)]
pub struct FolderOptions<'a> {
    /// Subjects analysed between two writes of the output (memory grows with it, the output does
    /// not depend on it).
    pub chunk: usize,
    /// Also write each subject's signal traces to `<out>/traces/<subject>.json` (for reports).
    pub traces: Option<&'a ValidTraceParams>,
}

/// What [`analyze_to_folder`] wrote.
#[derive(Debug, Clone, Default)]
pub struct FolderSummary {
    /// Recordings (rows of `recordings.csv`).
    pub recordings: usize,
    /// Recordings whose analysis failed.
    pub failed: usize,
    /// Strides (rows of `strides.csv`).
    pub strides: usize,
    /// Valid strides.
    pub valid_strides: usize,
    /// Rows with something to say: failed or with warnings, in output order.
    pub flagged: Vec<RecordingRow>,
    /// Wall time per stage summed over the subjects (and threads); `write` is building and
    /// writing the tables (and traces).
    pub timings: StageTimings,
}

/// Refuse, before any work, subjects whose outputs would share a file: one report per subject
/// id, one trace per (subject, trial) (issues 19 and 37; see [`output::names`]).
pub fn check_output_names(subjects: &[SubjectInput]) -> Result<()> {
    output::names::check_unique_keys(
        subjects
            .iter()
            .map(|s| (s.subject_id.as_str(), s.trial_id.as_deref())),
    )
}

/// Analyse `subjects` and write `strides.csv/.json`, `events.csv` and `recordings.csv/.json`
/// into the folder of `run` (and traces, see [`FolderOptions`]); `done` is called once per
/// subject (progress). A recording that fails is a row with its error; only a write failure
/// stops the run. The caller begins the run ([`OutputRun::begin`], which clears an earlier
/// run's outputs) after [`check_output_names`], and finishes it (the marker) after its own files.
pub fn analyze_to_folder(
    subjects: &[SubjectInput],
    params: &AnalysisParams,
    format: Option<&FormatSpec>,
    read: &ValidReadParams,
    run: &OutputRun,
    opts: FolderOptions<'_>,
    done: &(dyn Fn() + Sync),
) -> Result<FolderSummary> {
    check_output_names(subjects)?;
    let mut strides = TableSink::create(run, "strides", &output::STRIDE_COLUMNS, true)?;
    let mut events = TableSink::create(run, "events", &output::EVENT_COLUMNS, false)?;
    let mut recordings = TableSink::create(run, "recordings", &[], true)?;
    let mut sum = FolderSummary::default();
    let checked = params.check().ok();
    let json = [strides.has_json(), events.has_json(), recordings.has_json()];
    for part in subjects.chunks(opts.chunk.max(1)) {
        // Each subject's rows are rendered to bytes on the thread that analysed it; the loop
        // below only copies them in input order.
        let tables: Vec<Result<(Rendered, StageTimings)>> = part
            .par_iter()
            .map(|s| {
                let r = match &checked {
                    Some(v) => analyze_subject_checked(s, v, format, read),
                    None => analyze_subject(s, params, format, read),
                };
                let mut spent = r.timings;
                let rendered = spent.time(Stage::Write, || -> Result<Rendered> {
                    if let Some(tp) = opts.traces {
                        write_traces(run, &r, tp)?;
                    }
                    Rendered::of(output::Tables::of(std::slice::from_ref(&r)), json)
                })?;
                done();
                Ok((rendered, spent))
            })
            .collect();
        for t in tables {
            let (t, spent) = t?;
            sum.timings.add(&spent);
            let clock = std::time::Instant::now();
            sum.valid_strides += t.valid_strides;
            strides.push_rendered(&t.strides)?;
            events.push_rendered(&t.events)?;
            recordings.push_rendered(&t.recordings)?;
            sum.recordings += t.rows.len();
            sum.failed += t.rows.iter().filter(|r| !r.is_ok()).count();
            sum.flagged.extend(
                t.rows
                    .into_iter()
                    .filter(|r| !r.is_ok() || !r.warnings.is_empty()),
            );
            sum.timings.write_s += clock.elapsed().as_secs_f64();
        }
    }
    sum.strides = strides.rows();
    let clock = std::time::Instant::now();
    output::finish_tables(vec![strides, events, recordings])?;
    sum.timings.write_s += clock.elapsed().as_secs_f64();
    Ok(sum)
}

/// One subject's three tables rendered for the sinks of [`analyze_to_folder`], with what the
/// summary needs.
struct Rendered {
    strides: RenderedRows,
    events: RenderedRows,
    recordings: RenderedRows,
    valid_strides: usize,
    rows: Vec<RecordingRow>,
}

impl Rendered {
    /// `json`: whether the strides, events and recordings tables have a JSON file.
    fn of(t: output::Tables, json: [bool; 3]) -> Result<Rendered> {
        Ok(Rendered {
            strides: RenderedRows::of(&t.strides, json[0])?,
            events: RenderedRows::of(&t.events, json[1])?,
            recordings: RenderedRows::of(&t.recordings, json[2])?,
            valid_strides: t.strides.iter().filter(|s| s.valid).count(),
            rows: t.recordings,
        })
    }
}

impl FolderSummary {
    /// Recordings with warnings, in output order.
    pub fn warned(&self) -> impl Iterator<Item = &RecordingRow> {
        self.flagged.iter().filter(|r| !r.warnings.is_empty())
    }
    /// Recordings whose analysis failed, in output order.
    pub fn failures(&self) -> impl Iterator<Item = &RecordingRow> {
        self.flagged.iter().filter(|r| !r.is_ok())
    }
}

fn write_traces(run: &OutputRun, r: &SubjectResult, p: &ValidTraceParams) -> Result<()> {
    let t = SubjectTraces::of(r, p);
    let json = serde_json::to_string(&t)?;
    let stem = output::names::key_stem(&r.subject_id, r.trial_id.as_deref());
    run.write(&format!("traces/{stem}.json"), json.as_bytes())
}

/// Worker threads for a requested count: at most the machine's cores (more threads than cores
/// only thrash: `n_jobs=10**6` would spawn a million threads). Returns the count to use and,
/// when the request was lowered, a warning saying so.
pub fn bounded_jobs(requested: usize) -> (usize, Option<String>) {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    if requested > cores {
        (
            cores,
            Some(format!(
                "{requested} worker threads requested, this machine has {cores} cores: using {cores}"
            )),
        )
    } else {
        (requested.max(1), None)
    }
}

#[cfg(test)]
mod jobs_tests {
    #[test]
    fn jobs_are_bounded_by_the_cores() {
        let cores = std::thread::available_parallelism().unwrap().get();
        assert_eq!(super::bounded_jobs(1), (1, None));
        let (n, w) = super::bounded_jobs(1_000_000);
        assert_eq!(n, cores);
        assert!(w.unwrap().contains("1000000 worker threads requested"));
    }
}
