//! The domain layer (issue 48): the vocabulary every stage shares, defined once at the bottom
//! of ldh-core. It imports nothing above it (only `crate::error`), and every module may use it.
//!
//! - [`labels`]: [`Side`], [`Legs`], [`Setting`], [`Group`] (the one group type of manifests, tables,
//!   statistics and the simulator), [`AffectedSide`], [`EventKind`];
//! - [`parameter`]: [`Parameter`], every gait parameter once with its code, column, plain
//!   name, unit and meaning (the model is gaitmap's one vocabulary, `gaitmap/utils/consts.py`);
//! - [`measured`]: [`Reason`] (a typed code with its message), [`Measured`], [`PerParameter`],
//!   [`Withheld`] (the withheld parameters and why, keyed by [`Parameter`]);
//! - [`block`]: every parameter's value written (and read back) by one loop over
//!   [`Parameter::TABLE_ORDER`], for a leg's parameters and the per-recording row;
//! - [`walk`]: [`WalkValue`], the values of a walk rather than a leg (its cadence and steady
//!   window, one value on both legs' rows), each with its column, unit and meaning.
//! - [`warning_code`]: [`WarningCode`], the stable code of every quality finding.

pub mod block;
pub mod labels;
pub mod measured;
pub mod parameter;
mod unsure;
pub mod walk;
pub mod warning_code;

pub use block::ParameterBlock;
pub use labels::{AffectedSide, EventKind, Group, Legs, Setting, Side};
pub use measured::{Measured, PerParameter, Reason, ReasonCode, Withheld};
pub use parameter::{Definition, Parameter, UnknownParameter};
pub use unsure::UnsureEvent;
pub use walk::{walk_cadence_steps_per_min, WalkValue};
pub use warning_code::{codes, UnknownWarningCode, WarningCode};
