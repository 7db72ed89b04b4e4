//! Writing a whole simulated cohort to a folder: the one loop behind `ldh simulate`,
//! `ldh.simulate_cohort` in Python and the demo cohort's regeneration test; one subject's
//! files ([`SimSubject::write`]) and the cohort manifest ([`ManifestRow`], [`manifest_csv`]).

use std::path::Path;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::family_b::CohortParamsB;
use super::{CohortParams, Group, SimSubject};
use ldh_core::error::{LdhError, Result};
use ldh_core::io::{write_atomic, FormatSpec, WriteOptions};

/// A cohort description either simulator family can write ([`CohortParams`] for family A,
/// [`CohortParamsB`] for family B).
pub trait Cohort: serde::Serialize + Sync {
    /// Check the parameters.
    fn validate(&self) -> Result<()>;
    /// Number of subjects.
    fn len(&self) -> usize;
    /// True when there are no subjects.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Draw and simulate subject `i` (independent of the other subjects and of threads).
    fn simulate(&self, i: usize) -> Result<SimSubject>;
    /// Trials per subject (a retest cohort when ≥ 2). Default 1.
    fn trials(&self) -> usize {
        1
    }
    /// Trial `t` of subject `i`. Default: [`Cohort::simulate`] (one trial).
    fn simulate_trial(&self, i: usize, _t: usize) -> Result<SimSubject> {
        self.simulate(i)
    }
}

impl Cohort for CohortParams {
    fn validate(&self) -> Result<()> {
        CohortParams::validate(self)
    }
    fn len(&self) -> usize {
        CohortParams::len(self)
    }
    fn simulate(&self, i: usize) -> Result<SimSubject> {
        CohortParams::simulate(self, i)
    }
    fn trials(&self) -> usize {
        self.trials
    }
    fn simulate_trial(&self, i: usize, t: usize) -> Result<SimSubject> {
        CohortParams::simulate_trial(self, i, t)
    }
}

impl Cohort for CohortParamsB {
    fn validate(&self) -> Result<()> {
        CohortParamsB::validate(self)
    }
    fn len(&self) -> usize {
        CohortParamsB::len(self)
    }
    fn simulate(&self, i: usize) -> Result<SimSubject> {
        CohortParamsB::simulate(self, i)
    }
}

/// Simulate every subject of `params` and write `<out>/<subject>/left.csv`, `right.csv`,
/// `truth.json` (in `format`), then `<out>/manifest.csv` and `<out>/cohort.json` (the
/// parameters). With several trials per subject ([`Cohort::trials`]) each trial is written to
/// `<out>/<subject>/<trial>/` and the manifest has a `trial_id` column (`T1`, `T2`, …;
/// [`super::retest::trial_id`]). Recordings are simulated in parallel on the current rayon
/// pool; the files are the same whatever the thread count. `done` is called once per
/// recording pair written (progress). Returns the manifest rows in subject (then trial)
/// order; the first failing recording's error otherwise.
pub fn write_cohort<C: Cohort>(
    params: &C,
    out: &Path,
    format: &FormatSpec,
    done: &(dyn Fn() + Sync),
) -> Result<Vec<ManifestRow>> {
    params.validate()?;
    std::fs::create_dir_all(out).map_err(|source| LdhError::Io {
        path: out.to_path_buf(),
        source,
    })?;
    let trials = params.trials().max(1);
    let results: Vec<Result<ManifestRow>> = (0..params.len().saturating_mul(trials))
        .into_par_iter()
        .map(|j| {
            if trials == 1 {
                let s = params.simulate(j)?;
                s.write(&out.join(&s.params.subject_id), format)?;
                done();
                return Ok(ManifestRow::of(&s));
            }
            let (i, t) = (j / trials, j % trials);
            let s = params.simulate_trial(i, t)?;
            let trial = super::retest::trial_id(t, trials);
            s.write(&out.join(&s.params.subject_id).join(&trial), format)?;
            done();
            Ok(ManifestRow::of(&s).in_trial(trial))
        })
        .collect();
    let rows: Vec<ManifestRow> = results.into_iter().collect::<Result<_>>()?;
    write_atomic(out.join("manifest.csv"), manifest_csv(&rows).as_bytes())?;
    let cohort = serde_json::to_string_pretty(params).map_err(|e| LdhError::Write {
        path: out.join("cohort.json"),
        reason: e.to_string(),
    })?;
    write_atomic(out.join("cohort.json"), cohort.as_bytes())?;
    Ok(rows)
}

/// A cohort manifest row (SPEC §2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ManifestRow {
    /// Subject.
    pub subject_id: String,
    /// Trial of a retest cohort (`T1`, …), its files in `<subject>/<trial>/`; `None` for one
    /// trial per subject (then the manifest has no `trial_id` column).
    #[serde(default)]
    pub trial_id: Option<String>,
    /// `healthy` or `ldh`.
    pub group: Group,
    /// `left`, `right` or `none`.
    pub affected_side: String,
    /// Left recording, relative to the manifest.
    pub left: String,
    /// Right recording, relative to the manifest.
    pub right: String,
    /// Sensor height above the ankle, m (optional column).
    pub sensor_height_m: Option<f64>,
    /// Overground or treadmill (optional column `setting`; written for family B, and for family
    /// A with a belt start-up, `ramp_s` > 0).
    #[serde(default)]
    pub setting: Option<ldh_core::recording::Setting>,
}

impl ManifestRow {
    /// The row of a simulated subject stored in `<subject_id>/`.
    pub fn of(s: &SimSubject) -> ManifestRow {
        let id = &s.params.subject_id;
        ManifestRow {
            subject_id: id.clone(),
            trial_id: None,
            group: s.params.group.clone(),
            affected_side: s
                .params
                .affected_side
                .map(|x| x.as_str().to_string())
                .unwrap_or_else(|| "none".into()),
            left: format!("{id}/left.csv"),
            right: format!("{id}/right.csv"),
            sensor_height_m: Some(
                ((s.left.truth.sensor_height_m + s.right.truth.sensor_height_m) / 2.0 * 1000.0)
                    .round()
                    / 1000.0,
            ),
            setting: s.family_b.as_ref().map(|p| p.setting).or(
                // Family A with a belt start-up walks on a treadmill.
                (s.params.ramp_s > 0.0).then_some(ldh_core::recording::Setting::Treadmill),
            ),
        }
    }
}

impl ManifestRow {
    /// This row as trial `trial` of its subject: files in `<subject>/<trial>/`.
    pub fn in_trial(mut self, trial: String) -> ManifestRow {
        let id = &self.subject_id;
        self.left = format!("{id}/{trial}/left.csv");
        self.right = format!("{id}/{trial}/right.csv");
        self.trial_id = Some(trial);
        self
    }
}

/// Render manifest rows as CSV text.
/// The `setting` column is written only when a row has a setting (family B), so family A
/// manifests keep their columns. The last column, `clocks`, says `one` on every row: both
/// legs are simulated on one clock although written as two files (the manifest's `clocks`,
/// docs/input.md), so the timings between the legs are vouched for.
pub fn manifest_csv(rows: &[ManifestRow]) -> String {
    let with_setting = rows.iter().any(|r| r.setting.is_some());
    let with_trial = rows.iter().any(|r| r.trial_id.is_some());
    let mut out = String::from(if with_trial {
        "subject_id,trial_id,group,affected_side,left,right,sensor_height_m"
    } else {
        "subject_id,group,affected_side,left,right,sensor_height_m"
    });
    out.push_str(if with_setting { ",setting" } else { "" });
    out.push_str(",clocks\n");
    let clocks = ldh_core::pipeline::Clocks::One.as_str();
    for r in rows {
        out.push_str(&r.subject_id);
        if with_trial {
            out.push(',');
            out.push_str(r.trial_id.as_deref().unwrap_or(""));
        }
        out.push_str(&format!(
            ",{},{},{},{},{}",
            r.group.as_str(),
            r.affected_side,
            r.left,
            r.right,
            r.sensor_height_m.map(|h| h.to_string()).unwrap_or_default()
        ));
        if with_setting {
            out.push(',');
            out.push_str(r.setting.map(|s| s.as_str()).unwrap_or(""));
        }
        out.push(',');
        out.push_str(clocks);
        out.push('\n');
    }
    out
}

impl SimSubject {
    /// Write `left.csv`, `right.csv` (in `format`) and `truth.json` into `dir`.
    /// Formats without timestamps (a sample counter or no time) are written with the simulated
    /// rate as their stated rate.
    pub fn write(&self, dir: &Path, format: &FormatSpec) -> Result<()> {
        let opts = WriteOptions::default();
        let format = &match format.time.unit {
            ldh_core::io::format::TimeUnit::Counter | ldh_core::io::format::TimeUnit::None => {
                format.clone().with_rate_hz(self.params.fs_hz)
            }
            _ => format.clone(),
        };
        for leg in [&self.left, &self.right] {
            let side = leg.truth.side.as_str();
            ldh_core::io::write_recording(
                dir.join(format!("{side}.csv")),
                &leg.recording,
                format,
                &opts,
            )?;
        }
        let json = serde_json::to_string(&self.truth()).map_err(|e| LdhError::Write {
            path: dir.join("truth.json"),
            reason: e.to_string(),
        })?;
        write_atomic(dir.join("truth.json"), json.as_bytes())
    }
}
