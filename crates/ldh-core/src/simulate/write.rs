//! Writing a whole simulated cohort to a folder: the one loop behind `ldh simulate`,
//! `ldh.simulate_cohort` in Python and the demo cohort's regeneration test.

use std::path::Path;

use rayon::prelude::*;

use super::family_b::CohortParamsB;
use super::{manifest_csv, CohortParams, ManifestRow, SimSubject};
use crate::error::{LdhError, Result};
use crate::io::{write_atomic, FormatSpec};

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
/// parameters). Subjects are simulated in parallel on the current rayon pool; the files are the
/// same whatever the thread count. `done` is called once per subject written (progress).
/// Returns the manifest rows in subject order; the first failing subject's error otherwise.
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
    let results: Vec<Result<ManifestRow>> = (0..params.len())
        .into_par_iter()
        .map(|i| {
            let s = params.simulate(i)?;
            s.write(&out.join(&s.params.subject_id), format)?;
            done();
            Ok(ManifestRow::of(&s))
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
