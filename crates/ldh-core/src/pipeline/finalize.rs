//! Compute, then decide once (issue 48): the one step that applies a subject's findings to
//! each leg's strides and parameters, in this order (mobgap's "stride selection is one step,
//! aggregation once", `mobgap/pipeline/_mobilised_pipeline.py`):
//!
//! 1. [`finalize_strides`], per leg: the leg's own findings, then the pair's
//!    ([`quality::apply_to_strides`]: a span's strides invalid, withheld angles and lengths
//!    blanked); the survivors of a leg whose lengths are not vouched for
//!    ([`withhold_unvouched_lengths`]); steady walking only ([`quality::apply_steady`]).
//! 2. Between the legs (in [`crate::pipeline::Analysis::pair`]): the stride lengths the other
//!    leg contradicts ([`quality::withhold_disagreeing_lengths`]), when the pair is one walk.
//! 3. [`finalize_parameters`], per leg: the survivors again (fewer may be left), the
//!    parameters from the final strides and the other leg's heel strikes, STA kept as the leg
//!    computed it (on its own strides), then the parameters every finding withholds, the
//!    leg's first, then the pair's ([`quality::withhold`]: the first reason stays, a fault's
//!    replaces it).
//! 4. Then the stride length variability against the walk's noise, from both final legs
//!    ([`quality::check_length_variability`]).
//!
//! Every step decides on typed codes ([`crate::gait::StrideCode`], [`crate::domain::Reason`],
//! [`Warning::affects`]); none reads a message. The leg alone ([`crate::pipeline::leg_back`])
//! applies its own findings in the same order before a subject pairs it.

use super::quality::{self, Warning};
use super::LegResult;
use crate::domain::Parameter;
use crate::gait::{side_parameters, withhold_unvouched_lengths, ValidSteadyParams};

/// Step 1 for one leg: the findings about strides, the survivors, steady walking.
pub(crate) fn finalize_strides(
    leg: &mut LegResult,
    pair: &[Warning],
    steady: Option<&ValidSteadyParams>,
) {
    quality::apply_to_strides(&mut leg.strides, &leg.warnings);
    quality::apply_to_strides(&mut leg.strides, pair);
    withhold_unvouched_lengths(&mut leg.strides);
    if let Some(p) = steady {
        leg.steady = quality::apply_steady(&mut leg.strides, &mut leg.warnings, p);
    }
}

/// Step 3 for one leg: its parameters from its final strides (`other_hs`: the other leg's heel
/// strikes on this leg's clock), then what the leg's and the pair's findings withhold.
pub(crate) fn finalize_parameters(leg: &mut LegResult, pair: &[Warning], other_hs: Option<&[f64]>) {
    let p = &leg.parameters;
    let sta = (p[Parameter::Sta], p.sta_per_stride, p.sta_status.clone());
    // Fewer survivors after the pair's check may leave the leg's lengths unvouched.
    withhold_unvouched_lengths(&mut leg.strides);
    leg.parameters = side_parameters(&leg.strides, other_hs);
    let p = &mut leg.parameters;
    (p[Parameter::Sta], p.sta_per_stride, p.sta_status) = sta;
    quality::withhold(&mut leg.parameters, &leg.warnings);
    quality::withhold(&mut leg.parameters, pair);
}
