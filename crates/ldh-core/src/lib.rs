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
//! into the type the algorithm accepts ([`ParamGuard::check`]; what needs the recording's rate
//! or the subject's sensor height is checked with it at the call). All errors are [`LdhError`].
//!
//! ## The calls of an analysis
//!
//! 1. [`pipeline::AnalysisParams`] (defaults, a TOML/JSON file, or
//!    [`pipeline::AnalysisParams::with_options`]) → `.check()` →
//!    [`pipeline::ValidAnalysisParams`].
//! 2. [`pipeline::Analysis::new`]`(checked)`, with options: `.read(limits)`, `.format(spec)`,
//!    `.jobs(n)`, `.progress(&done)`, `.one_leg()`.
//! 3. One verb per scale: [`pipeline::Analysis::leg`] (one [`Recording`]),
//!    [`pipeline::Analysis::pair`] (two legs already read, e.g.
//!    [`pipeline::leg_from_arrays`]), [`pipeline::Analysis::subject`] (a
//!    [`pipeline::SubjectInput`] read from its files), [`pipeline::Analysis::many`] (subjects
//!    from [`pipeline::discover`] → [`pipeline::Many::results`] in memory, or
//!    [`pipeline::Many::to_folder`] into an output folder).
//! 4. Tables of the results: [`output::Tables::of`].

pub mod agreement;
pub mod align;
pub mod attitude;
pub mod cohort;
pub mod demo;
pub mod domain;
pub mod error;
pub mod events;
pub mod gait;
pub mod guard;
pub mod io;
pub mod ml;
pub mod monitor;
pub mod nonlinear;
pub mod output;
pub mod pipeline;
pub mod preprocess;
pub mod recording;
pub mod reference;
pub mod stats;
pub mod timings;

pub use error::{ErrorKind, LdhError, Location, Result};
pub use guard::ParamGuard;
pub use recording::{Recording, Setting, Side};
