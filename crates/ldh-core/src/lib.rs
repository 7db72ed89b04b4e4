#![doc = include_str!("../README.md")]
//!
//! ## Stages
//!
//! Pipeline stages are modules with a data type between them:
//! recording ([`recording::Recording`], read by [`io`]) → preprocessed
//! ([`preprocess::Preprocessed`]) → attitude → events → strides → features.
//! The specification is the project's SPEC.md; the paper is in `shared/paper`.
//!
//! Every algorithm takes a parameter type with serde, `Default` and setters, validated once
//! into the type the algorithm accepts (`params.check(...)`). All errors are [`LdhError`].

pub mod agreement;
pub mod align;
pub mod attitude;
pub mod cohort;
pub mod demo;
pub mod error;
pub mod events;
pub mod gait;
pub mod io;
pub mod ml;
pub mod nonlinear;
pub mod output;
pub mod pipeline;
pub mod preprocess;
pub mod recording;
pub mod reference;
pub mod stats;
pub mod timings;

pub use error::{ErrorKind, LdhError, Location, Result};
pub use recording::{Recording, Setting, Side};
