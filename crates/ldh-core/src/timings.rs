//! Wall time per pipeline stage (issue 17): read, preprocess, align, attitude, events, strides,
//! STA and write, accumulated per leg by the pipeline ([`crate::pipeline::Analysis`]),
//! per subject ([`crate::pipeline::SubjectResult::timings`]) and summed over a run
//! ([`crate::pipeline::FolderSummary::timings`]), for `ldh analyze --timings` and the
//! `timings` of the Python result (docs/benchmarks.md).
//!
//! Timings describe the run, not the result: they are never written to the output tables, and
//! two [`StageTimings`] always compare equal, so results of different runs (or thread counts)
//! still compare equal.

use serde::{Deserialize, Serialize};
use std::time::Instant;

/// A stage of the per-recording pipeline (SPEC §3), plus reading and writing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// Reading and validating the file (CSV parse, rate, gaps, clipping, unit checks).
    Read,
    /// Outlier replacement and low-pass filtering.
    Preprocess,
    /// Sensor-to-segment alignment.
    Align,
    /// Attitude estimation (Kalman bank + smoother, or ACC-only).
    Attitude,
    /// Gait event detection.
    Events,
    /// Strides, stride length and per-side parameters.
    Strides,
    /// Local dynamic stability (AMI, FNN, Rosenstein).
    Sta,
    /// Building and writing the output tables.
    Write,
}

impl Stage {
    /// Every stage, in pipeline order.
    pub const ALL: [Stage; 8] = [
        Stage::Read,
        Stage::Preprocess,
        Stage::Align,
        Stage::Attitude,
        Stage::Events,
        Stage::Strides,
        Stage::Sta,
        Stage::Write,
    ];

    /// The stage's name as printed ("read", "preprocess", …, "sta", "write").
    pub fn as_str(self) -> &'static str {
        match self {
            Stage::Read => "read",
            Stage::Preprocess => "preprocess",
            Stage::Align => "align",
            Stage::Attitude => "attitude",
            Stage::Events => "events",
            Stage::Strides => "strides",
            Stage::Sta => "sta",
            Stage::Write => "write",
        }
    }
}

/// Wall time per stage in seconds, summed over the recordings (and threads) of a run. With
/// several threads the sum exceeds the run's wall time. Default: all zero.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize)]
pub struct StageTimings {
    /// Reading the files, s.
    pub read_s: f64,
    /// Preprocessing, s.
    pub preprocess_s: f64,
    /// Alignment, s.
    pub align_s: f64,
    /// Attitude estimation, s.
    pub attitude_s: f64,
    /// Event detection, s.
    pub events_s: f64,
    /// Strides, parameters, quality checks and the pairing of the legs, s.
    pub strides_s: f64,
    /// STA, s.
    pub sta_s: f64,
    /// Building and writing the output tables (and traces), s.
    pub write_s: f64,
    /// Recordings (legs) that entered the pipeline.
    pub recordings: usize,
}

/// Timings describe the run, not the result: always equal (see the module docs).
impl PartialEq for StageTimings {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl StageTimings {
    /// The seconds of one stage.
    pub fn get(&self, stage: Stage) -> f64 {
        match stage {
            Stage::Read => self.read_s,
            Stage::Preprocess => self.preprocess_s,
            Stage::Align => self.align_s,
            Stage::Attitude => self.attitude_s,
            Stage::Events => self.events_s,
            Stage::Strides => self.strides_s,
            Stage::Sta => self.sta_s,
            Stage::Write => self.write_s,
        }
    }

    fn slot(&mut self, stage: Stage) -> &mut f64 {
        match stage {
            Stage::Read => &mut self.read_s,
            Stage::Preprocess => &mut self.preprocess_s,
            Stage::Align => &mut self.align_s,
            Stage::Attitude => &mut self.attitude_s,
            Stage::Events => &mut self.events_s,
            Stage::Strides => &mut self.strides_s,
            Stage::Sta => &mut self.sta_s,
            Stage::Write => &mut self.write_s,
        }
    }

    /// Run `f`, adding its wall time to `stage`.
    pub fn time<T>(&mut self, stage: Stage, f: impl FnOnce() -> T) -> T {
        let start = Instant::now();
        let out = f();
        *self.slot(stage) += start.elapsed().as_secs_f64();
        out
    }

    /// Add the time since `clock` to `stage` and restart `clock`: for timing consecutive stages
    /// (`let mut clock = Instant::now(); …; t.lap(Stage::Align, &mut clock);`).
    pub fn lap(&mut self, stage: Stage, clock: &mut Instant) {
        let now = Instant::now();
        *self.slot(stage) += (now - *clock).as_secs_f64();
        *clock = now;
    }

    /// Add another run's (or leg's) timings to these.
    pub fn add(&mut self, other: &StageTimings) {
        for s in Stage::ALL {
            *self.slot(s) += other.get(s);
        }
        self.recordings += other.recordings;
    }

    /// The timings as JSON: `<stage>_s` for every stage, `total_s` (sum over the stages),
    /// `recordings` and, when given, the run's `wall_s`.
    pub fn to_json(&self, wall_s: Option<f64>) -> serde_json::Value {
        let mut m = serde_json::Map::new();
        for s in Stage::ALL {
            m.insert(format!("{}_s", s.as_str()), self.get(s).into());
        }
        m.insert("total_s".into(), self.total_s().into());
        m.insert("recordings".into(), self.recordings.into());
        if let Some(w) = wall_s {
            m.insert("wall_s".into(), w.into());
        }
        serde_json::Value::Object(m)
    }

    /// Sum over all stages, s.
    pub fn total_s(&self) -> f64 {
        Stage::ALL.iter().map(|&s| self.get(s)).sum()
    }

    /// The stages as a text table: seconds, milliseconds per recording and share of the total;
    /// with `wall_s`, a last line with the run's wall time.
    pub fn table(&self, wall_s: Option<f64>) -> String {
        let total = self.total_s();
        let per = |s: f64| {
            if self.recordings == 0 {
                f64::NAN
            } else {
                1e3 * s / self.recordings as f64
            }
        };
        let share = |s: f64| if total > 0.0 { 100.0 * s / total } else { 0.0 };
        let mut out = format!(
            "{:<12} {:>10} {:>16} {:>7}\n",
            "stage", "total s", "per recording ms", "share"
        );
        for s in Stage::ALL {
            let v = self.get(s);
            out.push_str(&format!(
                "{:<12} {:>10.4} {:>16.3} {:>6.1}%\n",
                s.as_str(),
                v,
                per(v),
                share(v)
            ));
        }
        out.push_str(&format!(
            "{:<12} {:>10.4} {:>16.3} {:>6.1}%\n",
            "all stages",
            total,
            per(total),
            100.0
        ));
        out.push_str(&format!("recordings: {}", self.recordings));
        if let Some(w) = wall_s {
            out.push_str(&format!(
                "; wall time of the run {w:.4} s (stage times are summed over threads)"
            ));
        }
        out.push('\n');
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_adds_to_its_stage_and_add_sums() {
        let mut t = StageTimings::default();
        let v = t.time(Stage::Sta, || {
            std::thread::sleep(std::time::Duration::from_millis(2));
            7
        });
        assert_eq!(v, 7);
        let mut clock = Instant::now();
        std::thread::sleep(std::time::Duration::from_millis(1));
        t.lap(Stage::Read, &mut clock);
        assert!(t.read_s >= 0.001);
        assert!(t.sta_s >= 0.002);
        t.recordings = 2;
        let mut sum = StageTimings::default();
        sum.add(&t);
        sum.add(&t);
        assert_eq!(sum.recordings, 4);
        assert!((sum.sta_s - 2.0 * t.sta_s).abs() < 1e-12);
        assert!((sum.total_s() - sum.sta_s - sum.read_s).abs() < 1e-12);
        let table = sum.table(Some(1.0));
        assert_eq!(table.lines().count(), 11, "{table}");
        assert!(table.contains("sta") && table.contains("recordings: 4"));
        // timings never make two results differ
        assert_eq!(sum, StageTimings::default());
        let j = sum.to_json(Some(1.5));
        assert_eq!(j["recordings"], 4);
        assert_eq!(j["wall_s"], 1.5);
        assert_eq!(j["sta_s"].as_f64(), Some(sum.sta_s));
        assert_eq!(j["total_s"].as_f64(), Some(sum.total_s()));
        assert_eq!(j.as_object().map(|m| m.len()), Some(11));
    }
}
