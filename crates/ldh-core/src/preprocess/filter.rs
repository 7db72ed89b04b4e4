//! The Butterworth low-pass as second-order sections and zero-phase filtering with
//! `scipy.signal.sosfiltfilt`'s padding (sci-rs `butter_dyn` + `sosfiltfilt_dyn`).

use super::PreprocessParams;
use crate::error::{LdhError, Result};
use sci_rs::signal::filter::design::{
    butter_dyn, DigitalFilter, FilterBandType, FilterOutputType, Sos,
};
use sci_rs::signal::filter::sosfiltfilt_dyn;

/// Smallest and largest cut-off as a fraction of the Nyquist frequency `fs/2` that
/// [`butterworth_lowpass_sos`] accepts. Beyond about 1e-13 from either end sci-rs's design
/// panics (found by fuzzing: a recording claiming 1e74 Hz); well before that the sections lose
/// their precision, and no IMU analysis filters that close to 0 or to Nyquist.
pub const BUTTERWORTH_WN_RANGE: (f64, f64) = (1e-6, 1.0 - 1e-6);

/// Second-order sections of a Butterworth low-pass (scipy `butter(order, cutoff_hz,
/// output='sos', fs=fs_hz)`).
///
/// Errors unless `fs_hz` and `cutoff_hz` are finite and positive, `order` is 1–20 and the
/// normalised cut-off `cutoff_hz / (fs_hz / 2)` lies in [`BUTTERWORTH_WN_RANGE`].
pub fn butterworth_lowpass_sos(order: usize, cutoff_hz: f64, fs_hz: f64) -> Result<Vec<Sos<f64>>> {
    if !(fs_hz.is_finite() && fs_hz > 0.0) {
        return Err(LdhError::param("fs_hz", fs_hz, "must be finite and > 0"));
    }
    if !(1..=20).contains(&order) {
        return Err(LdhError::param("filter_order", order, "must be 1–20"));
    }
    let wn = cutoff_hz / (fs_hz / 2.0);
    let (lo, hi) = BUTTERWORTH_WN_RANGE;
    if !(cutoff_hz.is_finite() && wn >= lo && wn <= hi) {
        return Err(LdhError::param(
            "cutoff_hz",
            cutoff_hz,
            format!(
                "is {wn:e} of the Nyquist frequency fs/2 = {} Hz; the Butterworth design needs {lo:e}–{hi} of it (is the sampling rate right?)",
                fs_hz / 2.0
            ),
        ));
    }
    match butter_dyn(
        order,
        vec![cutoff_hz],
        Some(FilterBandType::Lowpass),
        Some(false),
        Some(FilterOutputType::Sos),
        Some(fs_hz),
    ) {
        DigitalFilter::Sos(s) => Ok(s.sos),
        _ => unreachable!("butter_dyn returns SOS when asked for SOS"),
    }
}

/// Zero-phase filtering with `sos`, as `scipy.signal.sosfiltfilt(sos, x)` (odd padding of
/// `3 · (2 · sections + 1)` samples). Errors when `x` is not longer than the padding (scipy
/// raises; sci-rs would panic).
pub fn sosfiltfilt(sos: &[Sos<f64>], x: &[f64]) -> Result<Vec<f64>> {
    let padlen = 3 * (2 * sos.len() + 1);
    if x.len() <= padlen {
        return Err(LdhError::signal(
            "sosfiltfilt",
            format!(
                "signal of {} samples is too short: at least {} are needed",
                x.len(),
                padlen + 1
            ),
        ));
    }
    if let Some(i) = x.iter().position(|v| !v.is_finite()) {
        return Err(LdhError::signal(
            "sosfiltfilt",
            format!("non-finite value at sample {i}"),
        ));
    }
    Ok(sosfiltfilt_dyn(x.iter(), sos))
}

/// Butterworth low-pass, zero phase: `sosfiltfilt(butter(order, cutoff_hz, fs=fs_hz,
/// output='sos'), x)`.
pub fn butter_filtfilt(x: &[f64], order: usize, cutoff_hz: f64, fs_hz: f64) -> Result<Vec<f64>> {
    let p = PreprocessParams::default()
        .filter_order(order)
        .cutoff_hz(cutoff_hz)
        .check(fs_hz)?;
    sosfiltfilt(&p.sos, x)
}
