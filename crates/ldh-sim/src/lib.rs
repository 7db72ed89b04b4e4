#![doc = include_str!("../README.md")]
//!
//! ## The model (SPEC §8)
//!
//! The paper's data are private, so ldh ships a physically derived model of two shank IMUs
//! ([`model`] explains the kinematics and frames): sagittal segment kinematics from published
//! normal-gait curves, feet that roll over heel and forefoot without slipping, the sensor on the
//! lateral shank above the ankle, acceleration from the exact second derivative of its position
//! plus gravity rotated into the sensor frame, angular velocity from the segment's body rate;
//! then sensor noise, bias, mounting misalignment (mirrored on the right leg), quantisation and
//! saturation. Subjects stand quietly at start and end and have stride-to-stride variability.
//! LDH subjects get an affected side with less swing knee flexion, a longer stance, slower and
//! more variable gait, and circumduction (SPEC §2, issue 2).
//!
//! Over a straight walk both feet travel the same distance, so the two sides' mean stride
//! lengths are equal; asymmetry is in step length, stance and angles.
//!
//! Everything is drawn from a ChaCha8 stream seeded by the cohort seed with one stream per
//! subject, so a cohort is byte-identical for a seed whatever the thread count. A retest
//! cohort ([`retest`], `--trials N`) walks each person N times with a known day-to-day
//! variation, each trial from a stream of its own.

mod analyze;
pub use analyze::{analyze_cohort, analyze_simulated, analyze_simulated_with, simulated_input};
mod cohort;
pub mod curves;
pub mod demo;
mod draw;
pub mod evaluate;
pub mod family_b;
pub mod free_living;
pub mod jet;
pub mod model;
mod params;
pub mod retest;
mod sensor;
mod truth;
mod write;

pub use cohort::CohortParams;
use ldh_core::error::{LdhError, Result};
pub use model::simulate_subject;
pub use params::{LegParams, SubjectParams, RAMP_STRIDE_EXTRA};
pub use sensor::SensorModel;
pub use truth::{
    read_truth, DenseTruth, LegTruth, SensorTruth, SimLeg, SimSubject, StrideTruth, SubjectTruth,
    TRUTH_SCHEMA,
};
pub use write::{manifest_csv, write_cohort, Cohort, ManifestRow};

/// The most samples one simulated leg may have (`duration_s × fs_hz`): 1 000 000, e.g. 2.7 h
/// at 100 Hz or 500 s at 2000 Hz. The simulator holds about 0.8 kB per output sample of a
/// subject (the 10× oversampled integration grid of both legs), so this bounds one subject in
/// flight to about 0.8 GB; longer recordings are made by concatenating simulated ones
/// (tests/tests/bad_inputs.rs `two_hour`).
pub const MAX_SAMPLES_PER_LEG: u64 = 1_000_000;

/// The most subjects one simulated cohort may have (`healthy + ldh`): 100 000.
pub const MAX_SUBJECTS: u64 = 100_000;

/// The declared size limits of a simulation, checked with exact arithmetic before any work:
/// `healthy + ldh` (which must not overflow) at most [`MAX_SUBJECTS`], `duration_s × fs_hz`
/// at most [`MAX_SAMPLES_PER_LEG`]. The error says which limit and what to do.
pub fn check_size(healthy: usize, ldh: usize, duration_s: f64, fs_hz: f64) -> Result<()> {
    let n = (healthy as u64).checked_add(ldh as u64);
    if n.is_none_or(|n| n > MAX_SUBJECTS) {
        return Err(LdhError::param(
            "healthy + ldh",
            format!("{healthy} + {ldh}"),
            format!("a simulated cohort holds at most {MAX_SUBJECTS} subjects"),
        ));
    }
    check_samples(duration_s, fs_hz)
}

/// `duration_s × fs_hz` at most [`MAX_SAMPLES_PER_LEG`] (both finite and positive; the range of
/// each is checked by the caller).
pub fn check_samples(duration_s: f64, fs_hz: f64) -> Result<()> {
    let samples = duration_s * fs_hz;
    if duration_s.is_finite() && fs_hz.is_finite() && samples <= MAX_SAMPLES_PER_LEG as f64 {
        return Ok(());
    }
    let longest_s = MAX_SAMPLES_PER_LEG as f64 / fs_hz.max(1.0);
    let longest = if longest_s >= 3600.0 {
        format!("{:.1} h", longest_s / 3600.0)
    } else {
        format!("{longest_s:.0} s")
    };
    Err(LdhError::param(
        "duration_s × fs_hz",
        format!("{duration_s:?} s × {fs_hz:?} Hz"),
        format!(
            "a simulated leg holds at most {MAX_SAMPLES_PER_LEG} samples ({longest} at {fs_hz:?} Hz); \
             simulate shorter recordings (or a lower rate) and concatenate them"
        ),
    ))
}

/// Subject group (defined with the recordings' other labels: the analysis reads it too).
pub use ldh_core::domain::Group;

#[cfg(test)]
mod tests;
