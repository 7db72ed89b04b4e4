//! How much a leg's stride length depends on a sensor height that was assumed, not given
//! (issue 20).
//!
//! The stride integration starts and ends at the sensor's velocity ω × r at mid-stance, r =
//! the sensor's height along the shank above the resting ankle ([`super::stride_length`]; the
//! inverted-pendulum velocity update of Sci Rep 2021, doi 10.1038/s41598-021-81009-w). A
//! wrong r is a constant velocity error ω Δr over the stride, which de-drifting cannot see (it
//! is there at both ends), so the length is off by ≈ ω Δr T: nothing in the recording checks
//! it. Where the ankle rests with the shank almost still (simulator family A: 2–12 deg/s) the
//! height hardly matters (the leg's median moves by 0.1–7.3 % over the range below); where the
//! shank turns over the ankle at mid-stance at 40–80 deg/s (HuGaDB) the length moves by
//! 0.4–0.9 m per m of height, 16–27 % over the range (family B: 17–38 %; docs/accuracy.md
//! "Sensor height not given (issue 20)").
//!
//! So when no height is given, the leg's median reported stride length is recomputed with the
//! sensor at both ends of the range a shank sensor can sit at ([`SENSOR_HEIGHT_RANGE_M`]),
//! through the same per-stride checks, and the length at the assumed height is vouched for only
//! when the median moves by at most [`MAX_HEIGHT_SPREAD_SHARE`] of itself across that range
//! ([`HeightSensitivity::vouched`]; the finding is `sensor_height_unknown` in
//! [`crate::pipeline::quality`]: a note when vouched, a warning withholding the length when not).

use super::segment::{lengths_at_heights, LengthsAtHeights};
use super::{Stride, ValidStrideParams};
use crate::align::Aligned;
use crate::attitude::{Attitude, AttitudeModel};
use crate::events::Events;
use crate::recording::Side;

/// The heights above the ankle joint a shank sensor can sit at, m: 0.05 (strapped just above
/// the malleoli, the lowest place on the shank a strap holds, its centre ≈ 5 cm above the
/// joint) to 0.35 (just below the knee: the shank, knee to ankle joint, is 0.246 × body height
/// (Winter, Biomechanics and Motor Control of Human Movement, 4th ed. 2009, Fig. 4.1: knee
/// 0.285 H, ankle 0.039 H above the floor), 0.39 m at 1.60 m, and a sensor below the tibial
/// plateau sits ≥ 4 cm under the knee joint). The
/// same bound as [`super::MAX_TILT_DEG`]'s. Anthropometry, not fitted.
pub const SENSOR_HEIGHT_RANGE_M: [f64; 2] = [0.05, 0.35];

/// Largest movement of a leg's median stride length across [`SENSOR_HEIGHT_RANGE_M`] accepted
/// when the height was assumed, as a share of the median at the assumed height (0.15).
///
/// 15 % is the largest per-stride error the team accepts (issue 20; the same bound as
/// [`super::MAX_VERTICAL_SHARE`] and [`super::MAX_CLIP_STEP_SHARE`]). The movement across the
/// range bounds the error the assumed height can leave whatever the true height in the range
/// (the length is monotone in the height: ≈ ω h T), so a leg whose median moves by more is
/// not vouched for to that tolerance. Derived from that tolerance, not fitted; on the tuning
/// cohort (simulator family A, seed 100, 15 + 15 subjects) every leg moves by 0.1–7.3 %
/// (docs/accuracy.md "Sensor height not given (issue 20)"), so no value near 15 % changes
/// anything there.
pub const MAX_HEIGHT_SPREAD_SHARE: f64 = 0.15;

/// A leg's median stride length at the assumed sensor height and at both ends of
/// [`SENSOR_HEIGHT_RANGE_M`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeightSensitivity {
    /// The height assumed, m.
    pub assumed_m: f64,
    /// The leg's median reported stride length at the assumed height, m.
    pub median_m: f64,
    /// The heights of the range's ends, m ([`SENSOR_HEIGHT_RANGE_M`]).
    pub range_m: [f64; 2],
    /// The median stride length of the valid strides passing the per-stride checks with the
    /// sensor at each end, m (`None`: none passes there).
    pub at_ends_m: [Option<f64>; 2],
}

impl HeightSensitivity {
    /// How far the leg's median stride length moves across the range of heights (its largest
    /// minus its smallest value at the assumed height and at both ends), as a share of the
    /// median at the assumed height (`None` when an end has no length: the movement cannot be
    /// bounded).
    pub fn spread_share(&self) -> Option<f64> {
        let [a, b] = self.at_ends_m;
        let (a, b) = (a?, b?);
        let hi = self.median_m.max(a).max(b);
        let lo = self.median_m.min(a).min(b);
        Some((hi - lo) / self.median_m)
    }

    /// Whether the length at the assumed height is vouched for: it moves by at most
    /// [`MAX_HEIGHT_SPREAD_SHARE`] across the range of heights.
    pub fn vouched(&self) -> bool {
        self.spread_share()
            .is_some_and(|e| e <= MAX_HEIGHT_SPREAD_SHARE)
    }
}

/// Median (the upper one for an even count) of the valid strides' finite values (`None`
/// when there is none: a leg may report its length from 2 strides, [`super::MIN_LENGTH_STRIDES`]).
fn median_of(strides: &[Stride], lengths: impl Iterator<Item = f64>) -> Option<f64> {
    let mut v: Vec<f64> = strides
        .iter()
        .zip(lengths)
        .filter(|(s, l)| s.valid && l.is_finite())
        .map(|(_, l)| l)
        .collect();
    crate::stats::median(&mut v, crate::stats::EvenMedian::Upper)
}

/// How much the leg's stride length depends on the sensor height, when the height was assumed
/// (`params` has none: [`ValidStrideParams::sensor_height_given`]) and the leg reports a stride
/// length: `strides` are the leg's final strides at the assumed height (after its quality
/// checks). `None` when the height was given, the attitude model reports no length (ACC-only),
/// or no valid stride has a length (nothing to qualify). Costs two more length integrations
/// per valid stride (not the attitude); the pipeline measures them during the segmentation
/// instead ([`height_sensitivity_measured`]).
pub fn height_sensitivity(
    side: Side,
    al: &Aligned,
    att: &Attitude,
    ev: &Events,
    params: &ValidStrideParams,
    strides: &[Stride],
) -> Option<HeightSensitivity> {
    if heights_to_measure(params, att.model).is_empty() {
        return None;
    }
    // the median first: no integration when no valid stride has a length
    median_of(strides, strides.iter().map(|s| s.stride_length_m))?;
    let ends = lengths_at_heights(side, al, att, ev, params, strides, &SENSOR_HEIGHT_RANGE_M);
    sensitivity(params, strides, &ends)
}

/// The sensor heights, m, at which the segmentation has to measure the strides
/// ([`super::strides_at_heights`]) for [`height_sensitivity_measured`]:
/// [`SENSOR_HEIGHT_RANGE_M`] when the height was assumed and the attitude model reports a
/// length, none otherwise.
pub fn heights_to_measure(params: &ValidStrideParams, model: AttitudeModel) -> &'static [f64] {
    if params.sensor_height_given() || model == AttitudeModel::Acc {
        &[]
    } else {
        &SENSOR_HEIGHT_RANGE_M
    }
}

/// [`height_sensitivity`] from the lengths the segmentation measured (`measured`: from
/// [`super::strides_at_heights`] at [`heights_to_measure`]'s heights; `strides`: the same
/// strides after the leg's checks): the same value, without finding the strides'
/// zero-velocity spans and rotating their acceleration again. `None` also when `measured`
/// does not hold [`SENSOR_HEIGHT_RANGE_M`] for these strides.
pub fn height_sensitivity_measured(
    params: &ValidStrideParams,
    model: AttitudeModel,
    strides: &[Stride],
    measured: &LengthsAtHeights,
) -> Option<HeightSensitivity> {
    let complete = measured.heights_m == SENSOR_HEIGHT_RANGE_M
        && measured.lengths_m.iter().all(|l| l.len() == strides.len());
    if heights_to_measure(params, model).is_empty() || !complete {
        return None;
    }
    let ends = measured.checked(strides, params.0.max_length_deviation);
    sensitivity(params, strides, &ends)
}

/// The sensitivity from the lengths of `strides` at the ends of [`SENSOR_HEIGHT_RANGE_M`]
/// (`ends`: per end, per stride, through the same checks).
fn sensitivity(
    params: &ValidStrideParams,
    strides: &[Stride],
    ends: &[Vec<f64>],
) -> Option<HeightSensitivity> {
    let median_m = median_of(strides, strides.iter().map(|s| s.stride_length_m))?;
    Some(HeightSensitivity {
        assumed_m: params.sensor_height_m(),
        median_m,
        range_m: SENSOR_HEIGHT_RANGE_M,
        at_ends_m: [0, 1].map(|k| median_of(strides, ends[k].iter().copied())),
    })
}
