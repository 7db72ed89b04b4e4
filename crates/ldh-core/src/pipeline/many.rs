//! Many subjects at once: the read-inputs-and-analyse loop of `ldh analyze`, `stats`, `train`,
//! `predict` and `evaluate`, in parallel on the current rayon pool.
//!
//! [`Many::to_folder`] streams: subjects are analysed a chunk at a time and their rows appended
//! to the output tables, so memory stays flat however many subjects there are; chunks keep the
//! input order, so the files are the same whatever the thread count.

use rayon::prelude::*;

use super::{Many, SubjectInput, SubjectResult};
use crate::error::Result;
use crate::output::trace::{SubjectTraces, ValidTraceParams};
use crate::output::{self, OutputRun, RecordingRow, RenderedRows, StrideRow, TableSink};
use crate::timings::{Stage, StageTimings};

/// Options of [`Many::to_folder`].
#[derive(Debug, Clone, Copy)]
pub struct FolderOptions<'a> {
    /// Subjects analysed between two writes of the output (memory grows with it, the output does
    /// not depend on it).
    pub chunk: usize,
    /// Also write each subject's signal traces to `<out>/traces/<subject>.json` (for reports).
    pub traces: Option<&'a ValidTraceParams>,
    /// Also keep the per-recording and per-stride rows and the traces in memory
    /// ([`FolderSummary::kept`]), for reports of this run without reading its tables back.
    /// The tables grow with the run; the signals are not kept.
    pub keep: bool,
}

/// The rows and traces of a run kept in memory ([`FolderOptions::keep`]): what its reports are
/// built from.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct KeptRun {
    /// Per-recording rows, in output order.
    pub recordings: Vec<RecordingRow>,
    /// Per-stride rows, in output order.
    pub strides: Vec<StrideRow>,
    /// Each subject's traces (when [`FolderOptions::traces`]), in output order.
    pub traces: Vec<SubjectTraces>,
}

/// What [`Many::to_folder`] wrote.
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
    /// The rows and traces, with [`FolderOptions::keep`].
    pub kept: Option<KeptRun>,
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

/// [`Many::to_folder`] (on the analysis' pool).
pub(super) fn to_folder(
    many: Many<'_, '_>,
    run: &OutputRun,
    opts: FolderOptions<'_>,
) -> Result<FolderSummary> {
    let (analysis, subjects) = (many.analysis, many.subjects);
    check_output_names(subjects)?;
    let mut strides = TableSink::create(run, "strides", &output::STRIDE_COLUMNS, true)?;
    let mut events = TableSink::create(run, "events", &output::EVENT_COLUMNS, false)?;
    let mut recordings = TableSink::create(run, "recordings", &[], true)?;
    let mut sum = FolderSummary {
        kept: opts.keep.then(KeptRun::default),
        ..FolderSummary::default()
    };
    let json = [strides.has_json(), events.has_json(), recordings.has_json()];
    for part in subjects.chunks(opts.chunk.max(1)) {
        // Each subject's rows are rendered to bytes on the thread that analysed it; the loop
        // below only copies them in input order.
        type Done = (Rendered, StageTimings, Option<SubjectTraces>);
        let tables: Vec<Result<Done>> = part
            .par_iter()
            .map(|s| {
                let r = analysis.subject(s);
                let mut spent = r.timings;
                let (rendered, trace) = spent.time(Stage::Write, || -> Result<_> {
                    let trace = match opts.traces {
                        Some(tp) => Some(write_traces(run, &r, tp)?),
                        None => None,
                    };
                    let t = output::Tables::of(std::slice::from_ref(&r));
                    Ok((Rendered::of(t, json, opts.keep)?, trace))
                })?;
                analysis.done();
                Ok((rendered, spent, trace.filter(|_| opts.keep)))
            })
            .collect();
        for t in tables {
            let (mut t, spent, trace) = t?;
            if let Some(k) = sum.kept.as_mut() {
                k.recordings.extend(t.rows.iter().cloned());
                k.strides.append(&mut t.kept_strides);
                k.traces.extend(trace);
            }
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

/// One subject's three tables rendered for the sinks of [`Many::to_folder`], with what the
/// summary needs.
struct Rendered {
    strides: RenderedRows,
    events: RenderedRows,
    recordings: RenderedRows,
    valid_strides: usize,
    rows: Vec<RecordingRow>,
    /// The stride rows, when the run keeps them.
    kept_strides: Vec<StrideRow>,
}

impl Rendered {
    /// `json`: whether the strides, events and recordings tables have a JSON file; `keep`:
    /// whether the stride rows are kept.
    fn of(t: output::Tables, json: [bool; 3], keep: bool) -> Result<Rendered> {
        Ok(Rendered {
            strides: RenderedRows::of(&t.strides, json[0])?,
            events: RenderedRows::of(&t.events, json[1])?,
            recordings: RenderedRows::of(&t.recordings, json[2])?,
            valid_strides: t.strides.iter().filter(|s| s.valid).count(),
            rows: t.recordings,
            kept_strides: if keep { t.strides } else { Vec::new() },
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

/// Write a subject's traces; they are returned (for a run that keeps them).
fn write_traces(run: &OutputRun, r: &SubjectResult, p: &ValidTraceParams) -> Result<SubjectTraces> {
    let t = SubjectTraces::of(r, p);
    let json = serde_json::to_string(&t)?;
    let stem = output::names::key_stem(&r.subject_id, r.trial_id.as_deref());
    run.write(&format!("traces/{stem}.json"), json.as_bytes())?;
    Ok(t)
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
mod tests {
    #[test]
    fn jobs_are_bounded_by_the_cores() {
        let cores = std::thread::available_parallelism().unwrap().get();
        assert_eq!(super::bounded_jobs(1), (1, None));
        let (n, w) = super::bounded_jobs(1_000_000);
        assert_eq!(n, cores);
        assert!(w.unwrap().contains("1000000 worker threads requested"));
    }
}
