//! Free-living days (issue 52): a day or a week of two shank sensors at home, with ground
//! truth, for the tests and benchmarks of `ldh monitor` (`ldh simulate --free-living`).
//!
//! A subject's recording is a sequence of activity segments ([`plan`]): nights lying (bed time
//! ≈ 23:00 and wake time ≈ 07:00, each ± 40 min, posture changes every 30–120 min), one or two
//! non-wear periods a day (the sensors still on a table, off the body), and in the day rest
//! episodes (sitting, standing, lying) separated by movement: level walking (most), stairs,
//! running and cycling, with fidgeting inside sitting. Walking bout durations are log-normal
//! (median 15 s, σ = 1.0, 5–600 s): many short bouts and a few long ones, as daily-life walking
//! is (Orendurff et al., J Rehabil Res Dev 2008: 40 % of daily walking bouts are under 12
//! steps; Del Din et al., J Gerontol 2016: most bouts ≤ 30 s).
//!
//! Walking, stairs and running come from the family A gait model ([`crate::simulate_subject`])
//! with an ideal sensor; rest postures, cycling, fidgeting and non-wear from the models in
//! [`render`]. One fixed device mounting, bias and noise stream per leg then measures them
//! all ([`stream`]), so a week is one continuous recording from one pair of devices.
//!
//! Clocks: the left sensor's clock is true time; the right sensor's clock runs fast by
//! `drift_ppm` (its time t_r = offset + t·(1 + drift_ppm·10⁻⁶)) and samples at its nominal rate
//! on its own clock, so its samples are the right leg's signal resampled (linear
//! interpolation) at the true times of its clock ticks. Ground truth (`truth_bouts.csv`) is on
//! the left clock.
//!
//! Everything is streamed in chunks of at most one minute of signal (one gait bout, at most
//! ten minutes, is simulated whole): memory does not grow with the recording's length.
//! Deterministic by seed: one ChaCha8 stream per subject for the plan and the gait, one per
//! leg for the sensor noise.

mod plan;
mod render;
mod score;
mod stream;
mod truth;

#[cfg(test)]
mod tests;

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::{Group, SensorModel};
use ldh_core::error::{LdhError, Result};
use ldh_core::io::DateTime;

pub use plan::Activity;
pub use score::{drift_error_s_per_day, score, FoundBout, Score, ScoreTargets};
pub use truth::{read_truth_bouts, FreeLivingTruth, TruthBout, TRUTH_BOUTS_HEADER};

/// The output file format of the long recordings.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "snake_case")]
pub enum LongFormat {
    /// ldh's CSV (`time_s, acc_x … gyro_z` in s, g, deg/s; `# start:` comment): `left.csv`,
    /// `right.csv`.
    #[default]
    Csv,
}

impl LongFormat {
    /// The file extension: `csv` or `cwa`.
    pub fn extension(self) -> &'static str {
        match self {
            LongFormat::Csv => "csv",
        }
    }
}

/// Parameters of a free-living simulation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FreeLivingParams {
    /// Healthy subjects (`H01`, …). Default 1.
    pub healthy: usize,
    /// LDH subjects (`L01`, …), slower and asymmetric gait. Default 0.
    pub ldh: usize,
    /// Recording length, h (1 day = 24, a week = 168). Default 24.
    pub duration_h: f64,
    /// Sampling rate of both sensors on their own clocks, Hz. Default 100.
    pub fs_hz: f64,
    /// Random seed. Default 1.
    pub seed: u64,
    /// Date and time of the first sample (left clock). Default 2026-03-02T08:00:00.
    pub start: DateTime,
    /// Right clock drift, ppm (positive: the right clock runs fast). Default `None`: drawn per
    /// subject, uniform in ±[20, 50] ppm.
    pub drift_ppm: Option<f64>,
    /// Right clock time at the left's first sample, s (its file's time column then starts
    /// there). Default 0.
    pub right_clock_offset_s: f64,
    /// The devices' error model (mounting misalignment, bias, noise, range). Default: the
    /// family A sensor ([`SensorModel::default`]) with a ±16 g accelerometer (AX6).
    pub sensor: SensorModel,
    /// File format. Default CSV.
    pub format: LongFormat,
    /// Every subject's stride time multiplied by this factor, stride length kept (cadence and
    /// speed divided by it): a later monitoring period's slower (> 1) or faster (< 1) walking,
    /// the change a visit comparison should find. Default 1.
    pub stride_time_factor: f64,
    /// The seed of the subjects' own gait (their draw from their group), when it is not
    /// `seed`: the same people on other days (one `subject_seed`, a `seed` per day). Default
    /// `None`: `seed`'s draw.
    pub subject_seed: Option<u64>,
}

impl Default for FreeLivingParams {
    fn default() -> Self {
        FreeLivingParams {
            healthy: 1,
            ldh: 0,
            duration_h: 24.0,
            fs_hz: 100.0,
            seed: 1,
            start: DateTime::new((2026, 3, 2), (8, 0, 0), false).expect("valid date"),
            drift_ppm: None,
            right_clock_offset_s: 0.0,
            sensor: SensorModel::default().acc_range_g(16.0),
            format: LongFormat::Csv,
            stride_time_factor: 1.0,
            subject_seed: None,
        }
    }
}

/// The longest free-living recording simulated: 14 days (336 h).
pub const MAX_DURATION_H: f64 = 336.0;

impl FreeLivingParams {
    /// Check the parameters: at least one subject, 0.01–336 h, 20–500 Hz, |drift| ≤ 500 ppm,
    /// |offset| ≤ 3600 s, a stride-time factor in 0.5–2, a valid sensor model.
    pub fn validate(&self) -> Result<()> {
        let range = |name: &'static str, v: f64, lo: f64, hi: f64| {
            if v.is_finite() && (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(LdhError::param(
                    name,
                    v,
                    format!("must lie in [{lo}, {hi}]"),
                ))
            }
        };
        if self.healthy + self.ldh == 0 || self.healthy + self.ldh > 1000 {
            return Err(LdhError::param(
                "healthy + ldh",
                self.healthy + self.ldh,
                "a free-living simulation has 1–1000 subjects",
            ));
        }
        range("duration_h", self.duration_h, 0.01, MAX_DURATION_H)?;
        range("fs_hz", self.fs_hz, 20.0, 500.0)?;
        if let Some(d) = self.drift_ppm {
            range("drift_ppm", d, -500.0, 500.0)?;
        }
        range("stride_time_factor", self.stride_time_factor, 0.5, 2.0)?;
        range(
            "right_clock_offset_s",
            self.right_clock_offset_s,
            -3600.0,
            3600.0,
        )?;
        self.sensor.validate()
    }

    /// Number of subjects.
    pub fn len(&self) -> usize {
        self.healthy + self.ldh
    }

    /// True when there are no subjects.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Subject `i`'s identifier and group (`H01`…, then `L01`…).
    pub fn subject(&self, i: usize) -> (String, Group) {
        let width = if self.len() >= 100 { 3 } else { 2 };
        if i < self.healthy {
            (format!("H{:0width$}", i + 1), Group::Healthy)
        } else {
            (format!("L{:0width$}", i - self.healthy + 1), Group::Ldh)
        }
    }
}

/// What was written for one subject.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeLivingSubject {
    /// Subject identifier (folder name).
    pub subject_id: String,
    /// The subject's folder.
    pub dir: PathBuf,
    /// `truth.json`'s content.
    pub truth: FreeLivingTruth,
}

/// Simulate every subject of `params` into `out_dir/<subject>/` (`left.csv`, `right.csv` or
/// `.cwa`, `truth_bouts.csv`, `truth.json`), then `out_dir/manifest.csv` and
/// `out_dir/free_living.json` (the parameters). Subjects run in parallel on the current rayon
/// pool; each streams its files, so memory is bounded whatever the duration. `done` is called
/// once per subject written.
pub fn simulate_free_living(
    params: &FreeLivingParams,
    out_dir: &Path,
    done: &(dyn Fn() + Sync),
) -> Result<Vec<FreeLivingSubject>> {
    params.validate()?;
    std::fs::create_dir_all(out_dir).map_err(|source| LdhError::Io {
        path: out_dir.to_path_buf(),
        source,
    })?;
    let subjects: Vec<FreeLivingSubject> = (0..params.len())
        .into_par_iter()
        .map(|i| {
            let s = stream::simulate_subject_to(params, i, out_dir)?;
            done();
            Ok(s)
        })
        .collect::<Result<_>>()?;
    let ext = params.format.extension();
    let mut manifest = String::from("subject_id,group,affected_side,left,right\n");
    for s in &subjects {
        manifest.push_str(&format!(
            "{id},{},{},{id}/left.{ext},{id}/right.{ext}\n",
            s.truth.group.as_str(),
            s.truth.affected_side.as_deref().unwrap_or("none"),
            id = s.subject_id,
        ));
    }
    ldh_core::io::write_atomic(out_dir.join("manifest.csv"), manifest.as_bytes())?;
    let json = serde_json::to_string_pretty(params).map_err(|e| LdhError::Write {
        path: out_dir.join("free_living.json"),
        reason: e.to_string(),
    })?;
    ldh_core::io::write_atomic(out_dir.join("free_living.json"), json.as_bytes())?;
    Ok(subjects)
}
