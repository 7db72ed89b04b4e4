//! Test helpers shared by ldh's crates, so a fixture is written once (issue 48): a temporary
//! folder to write test files into, a small simulated cohort analysed from its files with its
//! truth, `ldh agree` of results against reference texts, and a monitoring period built from
//! its daily steps. A dev-dependency of the crates whose tests need them (ldh-report's unit
//! tests, ldh-sim's `tests/analysis/`, ldh-core's integration tests); ldh-core's own unit tests
//! cannot use it (it depends on ldh-core), so their fixtures stay beside them or move to
//! `crates/ldh-core/tests/`.

use std::path::{Path, PathBuf};

use ldh_core::agreement::{run, AgreementParams, AgreementReport, OffsetMode, Reference};
use ldh_core::monitor::{DayRow, MonitorResult};
use ldh_core::output::LdhResults;
use ldh_core::pipeline::{AnalysisParams, SubjectResult};
use ldh_core::reference::parse_reference;

/// A temporary folder for a test's files, removed when dropped.
#[derive(Debug)]
pub struct TempFolder {
    dir: tempfile::TempDir,
}

impl TempFolder {
    /// A new empty folder.
    ///
    /// # Panics
    /// When the folder cannot be made (a test's fixture).
    pub fn new() -> TempFolder {
        TempFolder {
            dir: tempfile::tempdir().unwrap(),
        }
    }
    /// The folder.
    pub fn path(&self) -> &Path {
        self.dir.path()
    }
    /// Write `bytes` to the file `name` in the folder; its path.
    ///
    /// # Panics
    /// When the file cannot be written (a test's fixture).
    pub fn write(&self, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
        let p = self.dir.path().join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    }
}

impl Default for TempFolder {
    fn default() -> Self {
        TempFolder::new()
    }
}

/// A small simulated cohort (2 healthy, 2 LDH, seed 38) written to a temporary folder and
/// analysed from its files without STA, and its truth.
///
/// # Panics
/// When the simulation or the analysis fails (a test's fixture).
pub fn simulated() -> (Vec<SubjectResult>, Vec<ldh_sim::SubjectTruth>) {
    let dir = tempfile::tempdir().unwrap();
    let c = ldh_sim::CohortParams {
        healthy: 2,
        ldh: 2,
        seed: 38,
        ..Default::default()
    };
    let params = AnalysisParams::default()
        .with_options(None, None, None, Some(false))
        .unwrap();
    ldh_sim::analyze_cohort(&c, dir.path(), &params).unwrap()
}

/// `ldh agree` of `results` against the reference texts `events` and `strides` (read as
/// `ev.csv` and `st.csv`), matched within the evaluation's window.
///
/// # Panics
/// When a reference text does not read or the run fails (a test's fixture).
pub fn agree_with(
    results: &LdhResults,
    events: &str,
    strides: &str,
    mode: OffsetMode,
) -> AgreementReport {
    let p = AgreementParams {
        tolerance_s: ldh_sim::evaluate::MATCH_WINDOW_S,
        ..Default::default()
    }
    .check()
    .unwrap();
    let mut reference = Reference::default();
    parse_reference(events, Path::new("ev.csv"), results, &p, &mut reference).unwrap();
    parse_reference(strides, Path::new("st.csv"), results, &p, &mut reference).unwrap();
    run(results, &reference, &p, mode).unwrap()
}

/// One person's monitoring period of valid days with `daily_steps` steps each, walking
/// `steps / 100` minutes in 10 bouts a day, and no cadence measured (no bout over 30 s): the
/// fixture of the visit change and the week page.
pub fn monitor_period(subject_id: &str, visit: &str, daily_steps: &[f64]) -> MonitorResult {
    MonitorResult {
        subject_id: subject_id.into(),
        visit: Some(visit.into()),
        days: daily_steps
            .iter()
            .enumerate()
            .map(|(i, &s)| DayRow {
                day: i + 1,
                valid: true,
                steps: s,
                walking_min: s / 100.0,
                bouts: 10.0,
                gait_median: [f64::NAN; 6],
                ..DayRow::default()
            })
            .collect(),
        ..MonitorResult::default()
    }
}
