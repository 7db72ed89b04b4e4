#![doc = include_str!("../README.md")]
//!
//! ## Pages (SPEC §6)
//!
//! Self-contained HTML reports a clinician opens offline: one per subject and one per cohort;
//! the agreement page of `ldh agree` ([`agreement_page`]); the SVG figures ([`plots`]) and the
//! figure files of `ldh stats` and `ldh train` ([`figures`]).
//!
//! A report is one HTML file: inline CSS and inline SVG figures (drawn by [`crate::plots`]),
//! no scripts, no network, no fonts to fetch; A4 print CSS (`@page`, figures kept whole). The
//! markup is also well-formed XML (every element closed, only the five XML entities), so it can
//! be checked by any XML parser.
//!
//! The **per-subject report** shows the recording facts (duration, rate, alignment, outlier
//! replacement, clipping, gaps), the strides used and excluded with their reasons, the 12
//! parameters (+PBI) per side beside a healthy reference range ([`reference`]), values outside
//! it marked, the side-to-side symmetry index (Robinson et al. 1987), the signal figures of the
//! paper (Fig. 3: preprocessed acceleration and angular velocity; Fig. 4: attitude with HS/TO
//! marks and stance shading) from a [`trace::SubjectTraces`], stride-by-stride parameters, a
//! radar chart of the subject's z-scores, and — given a model — the classifier's output worded
//! as decision support. A side that failed is named with its error; the rest still renders.
//!
//! The **cohort report** has Table 3 (group statistics), Table 4 (model comparison) when an
//! `ldh stats --compare acc` output is given, the radar and box plots (Figs. 5–7), the
//! cross-validation results (Tables 6–7) and confusion matrices when an `ldh train` output is
//! given, and the list of recordings with their status.
//!
//! The markup is written with the `maud` template macros ([`maud::html`]): every value spliced into
//! a page is escaped by construction. One file per page ([`subject`], [`cohort`]), one function
//! per section.

pub mod agreement_page;
mod build;
mod cohort;
pub mod cycle;
pub mod figures;
mod headline;
pub(crate) mod html;
mod measured;
pub mod plots;
pub mod reference;
mod results;
mod subject;
mod summary;
mod todo;
/// The signal traces `ldh analyze --report` keeps (written by the analysis, read by the pages).
pub use ldh_core::output::trace;
mod trials;
mod verdict;
mod visits;
mod week;

use serde::{Deserialize, Serialize};

pub use build::{build, BuildSources, BuildSummary};
pub use cohort::cohort_html;
use ldh_core::cohort::ModelOffsets;
use ldh_core::error::{LdhError, Result};
use ldh_core::ml::{CvReport, Prediction};
pub use ldh_core::output::read_recordings;
use ldh_core::output::{RecordingRow, StrideRow};
pub use reference::{Reference, ReferenceRange, ReferenceSource};
pub use results::RunResults;
pub use subject::subject_html;
pub use trace::{LegTrace, SubjectTraces, TraceParams, ValidTraceParams};
pub use week::{week_html, write_week_pages};

/// Parameters of the reports.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ReportParams {
    /// Healthy subjects a cohort needs before its own reference range is used (else published
    /// values). Default 10.
    pub min_healthy_subjects: usize,
    /// Half-width of the reference range in SDs (mean ± z·SD). Default 1.96 (95 % of a normal
    /// healthy population).
    pub reference_z: f64,
    /// |symmetry index| above which a parameter is flagged, %. Default 10 %.
    pub asymmetry_flag_pct: f64,
    /// The plotted signal window.
    pub trace: TraceParams,
}

impl Default for ReportParams {
    fn default() -> Self {
        ReportParams {
            min_healthy_subjects: 10,
            reference_z: 1.96,
            asymmetry_flag_pct: 10.0,
            trace: TraceParams::default(),
        }
    }
}

impl ReportParams {
    /// Set [`ReportParams::min_healthy_subjects`].
    pub fn min_healthy_subjects(mut self, v: usize) -> Self {
        self.min_healthy_subjects = v;
        self
    }
    /// Validate.
    pub fn check(&self) -> Result<ValidReportParams> {
        if self.min_healthy_subjects < 3 {
            return Err(LdhError::param(
                "min_healthy_subjects",
                self.min_healthy_subjects,
                "must be at least 3 (an SD from fewer subjects is meaningless)",
            ));
        }
        if !(self.reference_z.is_finite() && self.reference_z > 0.0) {
            return Err(LdhError::param(
                "reference_z",
                self.reference_z,
                "must be > 0",
            ));
        }
        if !(self.asymmetry_flag_pct.is_finite() && self.asymmetry_flag_pct > 0.0) {
            return Err(LdhError::param(
                "asymmetry_flag_pct",
                self.asymmetry_flag_pct,
                "must be > 0",
            ));
        }
        Ok(ValidReportParams(self.clone(), self.trace.check()?))
    }
}

/// Checked [`ReportParams`] (with the checked trace window).
#[derive(Debug, Clone, PartialEq)]
pub struct ValidReportParams(pub(crate) ReportParams, pub(crate) ValidTraceParams);

impl ValidReportParams {
    /// The checked trace window.
    pub fn trace(&self) -> &ValidTraceParams {
        &self.1
    }
}

/// A file name for a subject's report and trace: see [`ldh_core::output::names`] (sanitised and,
/// when the id had to change, disambiguated by a stable suffix).
pub use ldh_core::output::names::file_stem;

/// Everything the per-subject report shows.
#[derive(Debug, Clone, Default)]
pub struct SubjectReport {
    /// Subject.
    pub subject_id: String,
    /// The subject's per-recording rows (left and right, failed ones with their error).
    pub recordings: Vec<RecordingRow>,
    /// The subject's strides.
    pub strides: Vec<StrideRow>,
    /// Signal excerpts, when `ldh analyze --report` kept them.
    pub traces: Option<SubjectTraces>,
    /// Classifier output per side, with the model's class names and a description.
    pub predictions: Option<(Vec<Prediction>, Vec<String>, String)>,
    /// What the run says about every page.
    pub context: RunContext,
}

/// What one analysis run says about all its pages, besides its tables.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RunContext {
    /// The event calibration the run applied (`params.json`'s `events.calibration`, written by
    /// `ldh agree --write-params`): every page says the events are calibrated and against what.
    pub calibration: Option<ldh_core::events::EventCalibration>,
    /// The test–retest reliability table given with `--reliability` (`ldh stats
    /// --reliability`'s `reliability.csv`): its MDC95 decide which changes between visits are
    /// marked (`visits.rs`); `None`: no change is marked.
    pub reliability: Option<ldh_core::cohort::ReliabilityTable>,
    /// Where that table comes from (its file name), for the pages.
    pub reliability_source: Option<String>,
}

/// The symmetry index of two values, % (Robinson et al. 1987): 100·(L − R) / ((L + R) / 2).
pub fn symmetry_index_pct(left: f64, right: f64) -> Option<f64> {
    let m = 0.5 * (left + right);
    (left.is_finite() && right.is_finite() && m.abs() > 1e-12).then(|| 100.0 * (left - right) / m)
}

/// What the cohort report shows.
#[derive(Debug, Clone, Default)]
pub struct CohortReport {
    /// Per-recording rows of the analysis (one attitude model).
    pub recordings: Vec<RecordingRow>,
    /// Table 4 offsets per model, from `ldh stats --compare acc` (`table4.json`).
    pub offsets: Vec<ModelOffsets>,
    /// Cross-validation results from `ldh train` (`cv_results.json`).
    pub cv: Vec<CvReport>,
    /// Links to the per-subject reports (subject, relative href).
    pub subject_links: Vec<(String, String)>,
    /// The reference the subject pages were judged against (the triage table counts values
    /// outside it); `None`: made from `recordings` with the default parameters.
    pub reference: Option<Reference>,
    /// The asymmetry threshold the subject pages used (%); `None`: the default
    /// ([`ReportParams::asymmetry_flag_pct`]).
    pub asymmetry_flag_pct: Option<f64>,
    /// What the run says about every page.
    pub context: RunContext,
}

#[cfg(test)]
pub(crate) mod tests;
