//! # ldh-core
//!
//! All computation of **ldh**, a gait assessment for lumbar disc herniation (LDH) from two
//! shank-worn IMUs, after Wang et al., "A wearable gait assessment method for lumbar disc
//! herniation based on adaptive Kalman filtering" (the paper; see `shared/paper`), and the
//! project's specification (SPEC.md).
//!
//! Pipeline stages are modules with a data type between them:
//! recording ([`recording::Recording`], read by [`io`]) → preprocessed
//! ([`preprocess::Preprocessed`]) → attitude → events → strides → features.
//! [`simulate`] is the deterministic two-shank gait simulator that produces the demo data and
//! the ground truth the accuracy tests score against.
//!
//! Every algorithm takes a parameter type with serde, `Default` and setters, validated once
//! into the type the algorithm accepts (`params.check(...)`). All errors are [`LdhError`].

pub mod agreement;
pub mod align;
pub mod attitude;
pub mod cohort;
pub mod demo;
pub mod error;
pub mod evaluate;
pub mod events;
#[doc(hidden)]
pub mod fuzz_targets;
pub mod gait;
pub mod io;
pub mod ml;
pub mod nonlinear;
pub mod output;
pub mod pipeline;
pub mod plots;
pub mod preprocess;
pub mod recording;
pub mod report;
pub mod simulate;
pub mod stats;
pub mod timings;

pub use error::{ErrorKind, LdhError, Location, Result};
pub use recording::{Recording, Setting, Side};
