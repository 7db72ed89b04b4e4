//! ldh's own results read back (issue 48: through the one table reader, `io/table.rs`): what
//! `ldh agree` compares with the reference, the events, strides and per-recording values
//! of one `ldh analyze` run, read back from its output folder ([`LdhResults::read`]) or taken
//! from results in memory ([`LdhResults::from_results`], unrounded).

use std::path::Path;

use crate::error::{LdhError, Location, Result};
use crate::io::table::{Table, TableFormat};
use crate::output::{Parameter, RecordingRow, StrideRow};
use crate::pipeline::{EventKind, SubjectResult};
use crate::Side;

/// Whether `ldh agree` compares parameter `p` stride by stride: every parameter with a
/// per-stride value ([`Parameter::PER_STRIDE`], the columns of `strides.csv`) but double
/// support (issue 49 added it to strides.csv; `ldh agree` does not compare it yet). A parameter
/// given a per-stride value is compared without being listed anywhere else.
pub const fn compared_per_stride(p: Parameter) -> bool {
    p.definition().per_stride.is_some() && !matches!(p, Parameter::DoubleSupport)
}

/// How many parameters [`STRIDE_PARAMETERS`] holds.
pub const STRIDE_PARAMETER_COUNT: usize = {
    let mut n = 0;
    let mut i = 0;
    while i < Parameter::PER_STRIDE_COUNT {
        n += compared_per_stride(Parameter::PER_STRIDE[i]) as usize;
        i += 1;
    }
    n
};

/// The parameters of a stride `ldh agree` compares with a reference's
/// ([`compared_per_stride`]), in the order of [`Parameter::PER_STRIDE`].
pub const STRIDE_PARAMETERS: [Parameter; STRIDE_PARAMETER_COUNT] = {
    let mut out = [Parameter::StrideTime; STRIDE_PARAMETER_COUNT];
    let (mut i, mut k) = (0, 0);
    while i < Parameter::PER_STRIDE_COUNT {
        let p = Parameter::PER_STRIDE[i];
        if compared_per_stride(p) {
            out[k] = p;
            k += 1;
        }
        i += 1;
    }
    out
};

/// One gait event (ldh's, or a reference's on its own clock).
#[derive(Debug, Clone, PartialEq)]
pub struct GaitEvent {
    /// Subject.
    pub subject_id: String,
    /// Trial (empty without one).
    pub trial_id: String,
    /// Leg.
    pub side: Side,
    /// HS or TO.
    pub event: EventKind,
    /// Time, s (ldh's: from the recordings' first sample).
    pub time_s: f64,
}

/// One stride ldh segmented (valid or not).
#[derive(Debug, Clone, PartialEq)]
pub struct LdhStride {
    /// Subject.
    pub subject_id: String,
    /// Trial (empty without one).
    pub trial_id: String,
    /// Leg.
    pub side: Side,
    /// Stride number within the leg.
    pub stride_index: usize,
    /// Heel strike starting the stride, s (NaN when not known).
    pub hs_time_s: f64,
    /// Heel strike ending it, s (NaN when not known).
    pub next_hs_time_s: f64,
    /// Used for the per-side means.
    pub valid: bool,
    /// Values in the order of [`STRIDE_PARAMETERS`] (NaN: withheld).
    pub values: [f64; STRIDE_PARAMETER_COUNT],
}

/// One `ldh analyze` run's results as `ldh agree` uses them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LdhResults {
    /// Bilateral events.
    pub events: Vec<GaitEvent>,
    /// Strides.
    pub strides: Vec<LdhStride>,
    /// Per-recording rows (one per subject, trial and side).
    pub recordings: Vec<RecordingRow>,
    /// The analysis parameters of the run (`params.json` of its folder), when known: what
    /// `ldh agree --write-params` starts from ([`crate::agreement::calibrated_params`]).
    pub analysis_params: Option<crate::pipeline::AnalysisParams>,
}

fn opt(x: Option<f64>) -> f64 {
    x.unwrap_or(f64::NAN)
}

impl LdhResults {
    /// Results in memory, with their times and per-stride values unrounded (the tables round
    /// times to 0.1 ms); per-recording values as `recordings.csv` holds them.
    pub fn from_results(results: &[SubjectResult]) -> LdhResults {
        let mut out = LdhResults {
            recordings: crate::output::recording_rows(results),
            ..Default::default()
        };
        for r in results {
            let trial_id = r.trial_id.clone().unwrap_or_default();
            for e in r.bilateral_events() {
                out.events.push(GaitEvent {
                    subject_id: r.subject_id.clone(),
                    trial_id: trial_id.clone(),
                    side: e.side,
                    event: e.event,
                    time_s: e.time_s,
                });
            }
            for (side, leg) in r.legs() {
                let Ok(leg) = leg else { continue };
                for s in &leg.strides {
                    out.strides.push(LdhStride {
                        subject_id: r.subject_id.clone(),
                        trial_id: trial_id.clone(),
                        side,
                        stride_index: s.stride_index,
                        hs_time_s: s.hs_time_s,
                        next_hs_time_s: s.next_hs_time_s,
                        valid: s.valid,
                        values: STRIDE_PARAMETERS.map(|p| opt(s.value(p))),
                    });
                }
            }
        }
        out
    }

    /// Read `recordings.json`, `strides.csv` and `events.csv` of an `ldh analyze` output
    /// folder. Errors: a run that did not finish or that another command wrote (its
    /// `ldh-run.json`), a missing or unreadable table, a row that is not an ldh row, the
    /// results of several attitude models.
    pub fn read(dir: &Path) -> Result<LdhResults> {
        if let Some(m) = crate::output::read_marker(dir)? {
            if !m.complete || m.command != crate::output::RunKind::Analyze {
                return Err(LdhError::signal(
                    dir.display().to_string(),
                    "not a finished ldh analyze run (its ldh-run.json says it did not finish, or another command wrote it); re-run ldh analyze",
                ));
            }
        }
        let recordings = crate::output::read_recordings(dir)?;
        let mut models: Vec<String> = recordings.iter().map(|r| r.model.to_string()).collect();
        models.sort();
        models.dedup();
        if models.len() > 1 {
            return Err(LdhError::signal(
                dir.join("recordings.json").display().to_string(),
                format!(
                    "the results hold several attitude models ({}); agree one model's results at a time",
                    models.join(", ")
                ),
            ));
        }
        let strides = read_rows::<StrideRow>(&dir.join("strides.csv"), "strides.csv")?
            .into_iter()
            .map(|(line, r)| stride_from_row(r, &dir.join("strides.csv"), line))
            .collect::<Result<Vec<_>>>()?;
        let events = read_rows::<crate::output::EventRow>(&dir.join("events.csv"), "events.csv")?
            .into_iter()
            .map(|(line, r)| event_from_row(r, &dir.join("events.csv"), line))
            .collect::<Result<Vec<_>>>()?;
        let params_file = dir.join("params.json");
        let analysis_params = if params_file.is_file() {
            let text = crate::io::read_text_limited(
                &params_file,
                crate::io::MAX_PARAMS_MB,
                "a parameter file",
            )?;
            Some(serde_json::from_str(&text).map_err(|e| LdhError::Format {
                name: params_file.display().to_string(),
                reason: format!("not the parameters of an ldh analyze run: {e}"),
            })?)
        } else {
            None
        };
        Ok(LdhResults {
            events,
            strides,
            recordings,
            analysis_params,
        })
    }

    /// Duration of a trial, s: the longest of its legs' (`None` when no leg has one).
    pub fn duration_s(&self, subject_id: &str, trial_id: &str) -> Option<f64> {
        self.recordings
            .iter()
            .filter(|r| r.subject_id == subject_id && r.trial_id == trial_id)
            .filter_map(|r| r.duration_s)
            .reduce(f64::max)
    }

    /// The trials of a subject in the results, in order of first appearance.
    pub fn trials_of(&self, subject_id: &str) -> Vec<&str> {
        let mut v: Vec<&str> = Vec::new();
        for r in self
            .recordings
            .iter()
            .filter(|r| r.subject_id == subject_id)
        {
            if !v.contains(&r.trial_id.as_str()) {
                v.push(&r.trial_id);
            }
        }
        v
    }

    /// Every (subject, trial) of the results, in order of first appearance.
    pub fn trials(&self) -> Vec<(&str, &str)> {
        let mut v: Vec<(&str, &str)> = Vec::new();
        for r in &self.recordings {
            let k = (r.subject_id.as_str(), r.trial_id.as_str());
            if !v.contains(&k) {
                v.push(k);
            }
        }
        v
    }
}

/// A row of an output table that is not an ldh row (`reason` cut as a message echoes a value).
fn not_a_row(loc: Location, table: &str, reason: &str) -> LdhError {
    LdhError::signal(
        loc.to_string(),
        format!("not an ldh {table} row: {}", crate::error::clip(reason)),
    )
}

/// The rows of an output table with their line numbers.
fn read_rows<T: serde::de::DeserializeOwned>(
    path: &Path,
    table: &'static str,
) -> Result<Vec<(u64, T)>> {
    let t = Table::read(path, "an output table", &TableFormat::default())?;
    t.rows()
        .map(|row| {
            let row = row.map_err(|f| f.into_error(""))?;
            let r = row
                .deserialize()
                .map_err(|e| not_a_row(row.loc_line(), table, &e.to_string()))?;
            Ok((row.line, r))
        })
        .collect()
}

fn known_side(
    side: &crate::output::Label<Side>,
    path: &Path,
    line: u64,
    table: &'static str,
) -> Result<Side> {
    side.known().ok_or_else(|| {
        not_a_row(
            Location::line(path, line),
            table,
            &format!("side '{side}' is not left or right"),
        )
    })
}

fn stride_from_row(r: StrideRow, path: &Path, line: u64) -> Result<LdhStride> {
    Ok(LdhStride {
        side: known_side(&r.side, path, line, "strides.csv")?,
        stride_index: r.stride_index,
        hs_time_s: opt(r.hs_time_s),
        next_hs_time_s: opt(r.next_hs_time_s),
        valid: r.valid,
        values: STRIDE_PARAMETERS.map(|p| opt(r.value(p))),
        subject_id: r.subject_id,
        trial_id: r.trial_id,
    })
}

fn event_from_row(r: crate::output::EventRow, path: &Path, line: u64) -> Result<GaitEvent> {
    let event = r.event.parse::<EventKind>().map_err(|_| {
        not_a_row(
            Location::line(path, line),
            "events.csv",
            &format!("event '{}' is not HS or TO", r.event),
        )
    })?;
    Ok(GaitEvent {
        side: known_side(&r.side, path, line, "events.csv")?,
        event,
        time_s: r.time_s,
        subject_id: r.subject_id,
        trial_id: r.trial_id,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The list `ldh agree` compares is the per-stride vocabulary, double support left out, in
    /// the vocabulary's order: a parameter given a per-stride value joins it.
    #[test]
    fn agree_compares_the_per_stride_parameters_but_double_support() {
        let expected: Vec<Parameter> = Parameter::PER_STRIDE
            .into_iter()
            .filter(|p| *p != Parameter::DoubleSupport)
            .collect();
        assert_eq!(STRIDE_PARAMETERS.to_vec(), expected);
        for p in Parameter::ALL {
            assert_eq!(
                STRIDE_PARAMETERS.contains(&p),
                p.definition().per_stride.is_some() && p != Parameter::DoubleSupport,
                "{p:?}"
            );
        }
    }
}
