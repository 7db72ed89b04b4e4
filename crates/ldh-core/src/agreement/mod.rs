//! Agreement of ldh with a laboratory reference system, and test–retest reliability
//! (issue 38): the numeric core, with pingouin / scipy parity.
//!
//! - [`agreement`]: one parameter's paired values (ldh, reference) → bias, SD of the
//!   differences, 95 % limits of agreement and their confidence intervals (Bland & Altman
//!   1986, 1999; [`bland_altman`]), proportional bias (regression of the difference on the
//!   mean), MAE and relative MAE, ICC(2,1) and ICC(3,1) with confidence intervals (Shrout &
//!   Fleiss 1979; McGraw & Wong 1996; [`icc`]) and Pearson's r. NaN pairs are dropped and
//!   counted.
//! - [`test_retest`]: a subjects × trials table → ICC(2,1), ICC(3,1), SEM, MDC95 (Weir 2005),
//!   within-subject CV and the variance components ([`reliability`]); [`ReliabilityTable`],
//!   one row per parameter, is `reliability.csv` ([`reliability_table`](mod@reliability_table)),
//!   computed from a cohort's repeated trials by [`fn@reliability_table`] ([`retest`]).
//! - [`match_events`]: two sorted event trains → one-to-one matches within a tolerance (the
//!   rule of gaitmap's `match_stride_lists`), recall, precision, F1 and timing errors
//!   ([`events`]); [`estimate_clock_offset`] finds the offset between the two clocks
//!   ([`offset`]).
//!
//! - [`run`]: `ldh agree` — an `ldh analyze` run ([`LdhResults`]) against a laboratory's
//!   reference files ([`read_reference`]): clock offsets, event matching, per-stride and
//!   per-recording agreement ([`AgreementReport`], written by [`write_report`]; the page
//!   with the Bland–Altman plots and timing histograms is `ldh_report::agreement_page`'s); per-step walkway exports
//!   (GAITRite-like) read through a column map ([`walkway`]).
//!
//! Every formula, the pingouin / scipy function it reproduces, and the decisions where they are
//! silent: `docs/agreement.md`, "Statistics". The goldens (`data-fixtures/golden/agreement/`,
//! written by `data-fixtures/scripts/gen_agreement_golden.py` with pingouin 0.7.0, scipy 1.17.1)
//! are matched to 1e-9 (absolute or relative) in `tests.rs`.
//!
//! All functions take [`ValidAgreementParams`] (from [`AgreementParams::check`]) and return an
//! [`AgreementError`] where pingouin or scipy would give NaN or raise; none returns a NaN.

pub mod bland_altman;
pub mod calibrate;
mod dist;
mod error;
pub mod events;
pub mod icc;
pub mod offset;
mod outcome;
mod paired;
mod params;
pub mod reference;
mod reference_error;
pub mod reliability;
pub mod reliability_table;
pub mod results;
pub mod retest;
pub mod run;
mod run_events;
pub mod walkway;
mod walkway_map;
pub mod write;

#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_events;
#[cfg(test)]
mod tests_run;
#[cfg(test)]
mod tests_walkway;

pub use bland_altman::{limits_of_agreement, linregress, LimitsOfAgreement, LinearFit};
pub use calibrate::{calibrated_params, params_toml, MIN_CALIBRATION_EVENTS};
pub use error::AgreementError;
pub use events::{match_events, match_groups, summarize, EventMatch, MatchSummary};
pub use icc::{icc, Icc, IccResult};
pub use offset::{estimate_clock_offset, polish_offset, ClockOffset, OffsetCandidate};
pub use paired::{agreement, ParameterAgreement, MIN_PAIRS};
pub use params::{AgreementParams, ValidAgreementParams, MAX_OFFSET_GRID_POINTS};
pub use reference::{read_reference, Reference};
pub use reference_error::ReferenceError;
pub use reliability::{test_retest, Reliability, VarianceComponents, MIN_SUBJECTS};
pub use reliability_table::{ReliabilityRow, ReliabilityTable};
pub use results::LdhResults;
pub use retest::{reliability_table, require_repeated_trials};
pub use run::{run, AgreementReport, OffsetMode};
pub use walkway::{read_walkway, WalkwayIds, WalkwayMap};
pub use write::write_report;
