//! The analysis of `ldh-core` on simulated walks with exact ground truth: the tests of the stages that need the simulator (reading, quality checks, events,
//! attitude, the pipeline, agreement). They live in `ldh-sim` because `ldh-core` must not depend
//! on its simulator; they use `ldh-core`'s public API only.

mod agreement_retest;
mod agreement_run;
mod clocks;
mod clocks_observables;
mod events_accuracy;
mod events_to_hugadb;
mod events_to_legs;
mod events_to_pitch;
mod events_to_rules;
mod fusion;
mod height_estimate;
mod io_columns;
mod io_read;
mod io_start;
mod io_stream;
mod io_units;
mod io_vendors;
mod pipeline;
mod pipeline_inputs;
mod pipeline_steady;
mod quality;
mod quality_faults;
mod real_data;
mod real_walks;
mod stairs;
