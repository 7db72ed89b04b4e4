//! A laboratory's reference for `ldh agree` (`docs/agreement.md`, "Command line and Python"):
//! long-form reference files of events or parameters ([`read_reference`], `long_form.rs`) and
//! per-step walkway exports read through a TOML column map ([`read_walkway`], `walkway.rs`,
//! `walkway_map.rs`), each row checked against an `ldh analyze` run's results
//! ([`crate::output::LdhResults`]) before anything is compared. Every table is split by the one
//! CSV reader, [`crate::io::table`]; every refusal is a [`ReferenceError`] naming the file, the
//! line and the column. The comparison itself is [`crate::agreement`]'s.

mod error;
mod long_form;
mod walkway;
mod walkway_map;

#[cfg(test)]
mod tests;

pub(crate) use error::boxed;
pub use error::ReferenceError;
pub use long_form::{parse_reference, read_reference, Reference, ReferenceOffset, ReferenceValues};
pub use walkway::{parse_walkway, read_walkway, WalkwayIds};
pub use walkway_map::{MappedColumn, SideColumn, StrideAnchor, WalkwayMap, WalkwayUnit};
