//! `ldh agree`: an `ldh analyze` run ([`crate::output::LdhResults`]) against a laboratory's
//! reference ([`crate::reference`]: long-form files and per-step walkway exports, read and
//! checked): clock offsets, event matching, per-stride and per-recording agreement
//! ([`AgreementReport`], written by [`write_report`]; the page with the Bland–Altman plots and
//! timing histograms is `ldh_report::agreement_page`'s).
//!
//! The statistics live in [`crate::stats::agreement`] (Bland–Altman limits, ICC, test–retest
//! reliability), the event matching and the clock-offset search in [`crate::events::matching`]
//! and [`crate::events::offset`], the reliability table of `ldh stats --reliability` in
//! [`crate::cohort`], ldh's own results read back ([`crate::output::LdhResults`]) in
//! `output/results.rs`; every table is read through [`crate::io::table`]. They are re-exported
//! here under their former paths. Every formula and decision: `docs/agreement.md`.

pub mod calibrate;
mod outcome;
pub mod run;
mod run_events;
pub mod write;

#[cfg(test)]
pub(crate) mod tests;

pub use crate::events::matching::{
    match_events, match_groups, summarize, EventMatch, MatchSummary,
};
pub use crate::events::offset::{
    estimate_clock_offset, polish_offset, ClockOffset, OffsetCandidate,
};
pub use crate::reference::{
    read_reference, read_walkway, Reference, ReferenceError, WalkwayIds, WalkwayMap,
};
pub use crate::stats::agreement::{
    agreement, bland_altman, icc, limits_of_agreement, linregress, reliability, test_retest,
    AgreementError, AgreementParams, Icc, IccResult, LimitsOfAgreement, LinearFit,
    ParameterAgreement, Reliability, ValidAgreementParams, VarianceComponents,
    MAX_OFFSET_GRID_POINTS, MIN_PAIRS, MIN_SUBJECTS,
};
pub use calibrate::{calibrated_params, params_toml, MIN_CALIBRATION_EVENTS};
pub use run::{run, AgreementReport, OffsetMode};
pub use write::write_report;
