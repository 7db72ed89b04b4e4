//! Agreement of two measurements of one quantity and test–retest reliability (issue 38): the
//! statistics of `ldh agree` and `ldh stats --reliability`, with pingouin / scipy parity.
//!
//! - [`agreement`]: one parameter's paired values (ldh, reference) → bias, SD of the
//!   differences, 95 % limits of agreement and their confidence intervals (Bland & Altman
//!   1986, 1999; [`bland_altman`]), proportional bias (regression of the difference on the
//!   mean), MAE and relative MAE, ICC(2,1) and ICC(3,1) with confidence intervals (Shrout &
//!   Fleiss 1979; McGraw & Wong 1996; [`icc`]) and Pearson's r. NaN pairs are dropped and
//!   counted.
//! - [`test_retest`]: a subjects × trials table → ICC(2,1), ICC(3,1), SEM, MDC95 (Weir 2005),
//!   within-subject CV and the variance components ([`reliability`]).
//!
//! Every formula, the pingouin / scipy function it reproduces, and the decisions where they are
//! silent: `docs/agreement.md`, "Statistics". The goldens (`data-fixtures/golden/agreement/`,
//! written by `data-fixtures/scripts/gen_agreement_golden.py` with pingouin 0.7.0, scipy 1.17.1)
//! are matched to 1e-9 (absolute or relative) in `tests.rs`.
//!
//! All functions take [`ValidAgreementParams`] (from [`AgreementParams::check`]; the same
//! parameters serve the event matching of [`crate::events::matching`]) and return an
//! [`AgreementError`] where pingouin or scipy would give NaN or raise; none returns a NaN.

pub mod bland_altman;
mod error;
pub mod icc;
mod paired;
mod params;
pub mod reliability;

#[cfg(test)]
mod tests;

pub use bland_altman::{limits_of_agreement, linregress, LimitsOfAgreement, LinearFit};
pub use error::AgreementError;
pub use icc::{icc, Icc, IccResult};
pub use paired::{agreement, ParameterAgreement, MIN_PAIRS};
pub use params::{AgreementParams, ValidAgreementParams, MAX_OFFSET_GRID_POINTS};
pub use reliability::{test_retest, Reliability, VarianceComponents, MIN_SUBJECTS};
