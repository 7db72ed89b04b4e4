//! The ground truth of a free-living recording: `truth_bouts.csv` (one row per activity
//! bout on the left clock, [`TruthBout`]) and `truth.json` ([`FreeLivingTruth`]).

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::plan::Activity;
use super::FreeLivingParams;
use crate::{Group, SubjectParams};
use ldh_core::error::{LdhError, Result};
use ldh_core::io::{write_atomic, DateTime};

/// The header of `truth_bouts.csv`.
pub const TRUTH_BOUTS_HEADER: &str = "bout,start_s,end_s,activity,steps_left,steps_right";

/// One bout of one activity, on the left sensor's clock (s from its first sample).
/// A gait bout (walking, stairs, running) runs from its first heel strike (either leg) to its
/// last; its steps are each leg's heel strikes in it. Other activities have 0 steps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TruthBout {
    /// Bout number, from 1, in time order.
    pub bout: usize,
    /// Start, s.
    pub start_s: f64,
    /// End, s.
    pub end_s: f64,
    /// What the subject does.
    pub activity: Activity,
    /// Left heel strikes.
    pub steps_left: usize,
    /// Right heel strikes.
    pub steps_right: usize,
}

impl TruthBout {
    /// Length, s.
    pub fn duration_s(&self) -> f64 {
        self.end_s - self.start_s
    }
    /// Steps of both legs.
    pub fn steps(&self) -> usize {
        self.steps_left + self.steps_right
    }
}

/// Write `truth_bouts.csv`.
pub(super) fn write_truth_bouts(path: &Path, bouts: &[TruthBout]) -> Result<()> {
    let mut s = String::with_capacity(bouts.len() * 48 + 64);
    s.push_str(TRUTH_BOUTS_HEADER);
    s.push('\n');
    for b in bouts {
        s.push_str(&format!(
            "{},{:.3},{:.3},{},{},{}\n",
            b.bout, b.start_s, b.end_s, b.activity, b.steps_left, b.steps_right
        ));
    }
    write_atomic(path, s.as_bytes())
}

/// Read a `truth_bouts.csv`.
pub fn read_truth_bouts(path: &Path) -> Result<Vec<TruthBout>> {
    let text = std::fs::read_to_string(path).map_err(|source| LdhError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let bad = |line: usize, reason: String| LdhError::Format {
        name: path.display().to_string(),
        reason: format!("line {line}: {reason}"),
    };
    let mut lines = text.lines();
    if lines.next().map(str::trim) != Some(TRUTH_BOUTS_HEADER) {
        return Err(bad(1, format!("the header must be {TRUTH_BOUTS_HEADER}")));
    }
    let mut out = Vec::new();
    for (i, l) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        let c: Vec<&str> = l.split(',').collect();
        let line = i + 2;
        if c.len() != 6 {
            return Err(bad(line, format!("{} cells, 6 expected", c.len())));
        }
        let num = |s: &str| {
            s.trim()
                .parse::<f64>()
                .map_err(|e| bad(line, format!("'{s}': {e}")))
        };
        let int = |s: &str| {
            s.trim()
                .parse::<usize>()
                .map_err(|e| bad(line, format!("'{s}': {e}")))
        };
        out.push(TruthBout {
            bout: int(c[0])?,
            start_s: num(c[1])?,
            end_s: num(c[2])?,
            activity: c[3].parse().map_err(|e| bad(line, e))?,
            steps_left: int(c[4])?,
            steps_right: int(c[5])?,
        });
    }
    Ok(out)
}

/// `truth.json` of a free-living subject.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FreeLivingTruth {
    /// Subject.
    pub subject_id: String,
    /// Group.
    pub group: Group,
    /// Affected side of an LDH subject (`left`, `right`).
    pub affected_side: Option<String>,
    /// Right clock drift, ppm (right time = offset + left time · (1 + drift_ppm·10⁻⁶)).
    pub drift_ppm: f64,
    /// Right clock time at the left's first sample, s.
    pub right_clock_offset_s: f64,
    /// Nominal rate of both sensors on their own clocks, Hz.
    pub rate_hz: f64,
    /// Recording length (left clock), h.
    pub duration_h: f64,
    /// Recording length, days.
    pub days: f64,
    /// Date and time of the first left sample.
    pub start: DateTime,
    /// Samples written to the left file.
    pub samples_left: u64,
    /// Samples written to the right file.
    pub samples_right: u64,
    /// Total time per activity, s.
    pub activity_s: BTreeMap<String, f64>,
    /// Walking bouts (level walking).
    pub walking_bouts: usize,
    /// Steps (both legs) in walking bouts.
    pub walking_steps: usize,
    /// The subject's usual gait (each bout varies stride time and length by 4 %).
    pub gait: SubjectParams,
}

impl FreeLivingTruth {
    pub(super) fn new(
        params: &FreeLivingParams,
        id: &str,
        gait: &SubjectParams,
        drift_ppm: f64,
        samples: [u64; 2],
        bouts: &[TruthBout],
    ) -> FreeLivingTruth {
        let mut activity_s = BTreeMap::new();
        for b in bouts {
            *activity_s
                .entry(b.activity.as_str().to_string())
                .or_insert(0.0) += b.duration_s();
        }
        let walking: Vec<&TruthBout> = bouts
            .iter()
            .filter(|b| b.activity == Activity::Walking)
            .collect();
        FreeLivingTruth {
            subject_id: id.to_string(),
            group: gait.group.clone(),
            affected_side: gait.affected_side.map(|s| s.as_str().to_string()),
            drift_ppm,
            right_clock_offset_s: params.right_clock_offset_s,
            rate_hz: params.fs_hz,
            duration_h: params.duration_h,
            days: params.duration_h / 24.0,
            start: params.start,
            samples_left: samples[0],
            samples_right: samples[1],
            activity_s,
            walking_bouts: walking.len(),
            walking_steps: walking.iter().map(|b| b.steps()).sum(),
            gait: gait.clone(),
        }
    }

    pub(super) fn write(&self, path: &Path) -> Result<()> {
        let json = serde_json::to_string_pretty(self).map_err(|e| LdhError::Write {
            path: path.to_path_buf(),
            reason: e.to_string(),
        })?;
        write_atomic(path, json.as_bytes())
    }

    /// Read a `truth.json`.
    pub fn read(path: &Path) -> Result<FreeLivingTruth> {
        let text = std::fs::read_to_string(path).map_err(|source| LdhError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        serde_json::from_str(&text).map_err(|e| LdhError::Format {
            name: path.display().to_string(),
            reason: format!("not a free-living truth.json: {e}"),
        })
    }
}
