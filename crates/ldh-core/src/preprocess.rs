//! Preprocessing (paper §3.1, SPEC §3.1): acceleration magnitude (eq. 1), outlier replacement,
//! zero-phase Butterworth low-pass on all six channels.
//!
//! 1. Magnitude ‖a‖ = √(a_x² + a_y² + a_z²) per sample (eq. 1).
//! 2. Outliers: samples whose magnitude lies more than `outlier_sd` standard deviations
//!    (population SD, numpy's default `ddof = 0`) from the mean magnitude, and samples the
//!    reader flagged as clipped, are replaced on all six channels by linear interpolation
//!    between the nearest good samples (`numpy.interp` semantics: held constant at the ends).
//! 3. A `filter_order`-th order Butterworth low-pass at `cutoff_hz`, designed as second-order
//!    sections and applied forward and backward with `scipy.signal.sosfiltfilt`'s odd padding
//!    and initial conditions (sci-rs `butter_dyn` + `sosfiltfilt_dyn`, equal to scipy to ~1e-14).
//!
//! The golden test (`data-fixtures/golden/preprocess/`) checks each step against numpy/scipy to
//! 1e-9 relative.

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};
use crate::recording::Recording;
use sci_rs::signal::filter::design::{
    butter_dyn, DigitalFilter, FilterBandType, FilterOutputType, Sos,
};
use sci_rs::signal::filter::sosfiltfilt_dyn;

/// Preprocessing parameters (unchecked). Defaults are the paper's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PreprocessParams {
    /// Low-pass cut-off in Hz. Default 10.
    pub cutoff_hz: f64,
    /// Butterworth order (even, 2–10). Default 4.
    pub filter_order: usize,
    /// Outlier threshold in standard deviations of the magnitude. Default 3.
    pub outlier_sd: f64,
    /// Replace outliers (and clipped samples) by interpolation. Default true.
    pub replace_outliers: bool,
}

impl Default for PreprocessParams {
    fn default() -> Self {
        PreprocessParams {
            cutoff_hz: 10.0,
            filter_order: 4,
            outlier_sd: 3.0,
            replace_outliers: true,
        }
    }
}

impl PreprocessParams {
    /// Set the cut-off frequency in Hz.
    pub fn cutoff_hz(mut self, v: f64) -> Self {
        self.cutoff_hz = v;
        self
    }
    /// Set the filter order.
    pub fn filter_order(mut self, v: usize) -> Self {
        self.filter_order = v;
        self
    }
    /// Set the outlier threshold in SD.
    pub fn outlier_sd(mut self, v: f64) -> Self {
        self.outlier_sd = v;
        self
    }
    /// Switch outlier replacement on or off.
    pub fn replace_outliers(mut self, v: bool) -> Self {
        self.replace_outliers = v;
        self
    }

    /// Validate for a recording sampled at `fs_hz` (the cut-off must lie below Nyquist).
    pub fn check(&self, fs_hz: f64) -> Result<ValidPreprocessParams> {
        if !(fs_hz.is_finite() && fs_hz > 0.0) {
            return Err(LdhError::param("fs_hz", fs_hz, "must be > 0"));
        }
        if !(self.cutoff_hz.is_finite() && self.cutoff_hz > 0.0 && self.cutoff_hz < fs_hz / 2.0) {
            return Err(LdhError::param(
                "cutoff_hz",
                self.cutoff_hz,
                format!(
                    "must lie in (0, fs/2) = (0, {}) Hz for this recording",
                    fs_hz / 2.0
                ),
            ));
        }
        if self.filter_order < 2 || self.filter_order > 10 || self.filter_order % 2 != 0 {
            return Err(LdhError::param(
                "filter_order",
                self.filter_order,
                "must be even, 2–10",
            ));
        }
        if !(self.outlier_sd.is_finite() && self.outlier_sd > 0.0) {
            return Err(LdhError::param(
                "outlier_sd",
                self.outlier_sd,
                "must be > 0",
            ));
        }
        let sos = butterworth_lowpass_sos(self.filter_order, self.cutoff_hz, fs_hz);
        Ok(ValidPreprocessParams {
            params: self.clone(),
            fs_hz,
            sos,
        })
    }
}

/// Checked preprocessing parameters with the designed filter.
#[derive(Debug, Clone)]
pub struct ValidPreprocessParams {
    params: PreprocessParams,
    fs_hz: f64,
    sos: Vec<Sos<f64>>,
}

impl ValidPreprocessParams {
    /// The parameters.
    pub fn params(&self) -> &PreprocessParams {
        &self.params
    }
    /// The rate they were checked for.
    pub fn fs_hz(&self) -> f64 {
        self.fs_hz
    }
    /// Minimum signal length for the zero-phase filter: scipy's `padlen + 1`.
    pub fn min_len(&self) -> usize {
        3 * (2 * self.sos.len() + 1) + 1
    }
}

/// The output of preprocessing: filtered channels plus what was replaced.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Preprocessed {
    /// Sampling rate, Hz (from the recording).
    pub fs_hz: f64,
    /// Filtered acceleration, g.
    pub acc_g: [Vec<f64>; 3],
    /// Filtered angular velocity, deg/s.
    pub gyro_dps: [Vec<f64>; 3],
    /// Magnitude of the filtered acceleration, g.
    pub acc_norm_g: Vec<f64>,
    /// Indices of the samples replaced by interpolation (outliers and clipped samples).
    pub replaced: Vec<usize>,
    /// Mean of the raw magnitude, g.
    pub raw_norm_mean_g: f64,
    /// SD (ddof = 0) of the raw magnitude, g.
    pub raw_norm_sd_g: f64,
}

/// ‖a‖ per sample (eq. 1).
pub fn magnitude(x: &[f64], y: &[f64], z: &[f64]) -> Vec<f64> {
    x.iter()
        .zip(y)
        .zip(z)
        .map(|((a, b), c)| (a * a + b * b + c * c).sqrt())
        .collect()
}

/// Mean and population SD (ddof = 0).
pub fn mean_sd(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n;
    (mean, var.sqrt())
}

/// Indices where |v − mean| > `k` · SD (SD with ddof = 0).
pub fn outliers_sd(v: &[f64], k: f64) -> Vec<usize> {
    let (mean, sd) = mean_sd(v);
    v.iter()
        .enumerate()
        .filter(|(_, x)| (*x - mean).abs() > k * sd)
        .map(|(i, _)| i)
        .collect()
}

/// Replace `bad` samples (sorted indices) of `v` by linear interpolation between the nearest
/// good samples; ends are held at the nearest good value (`numpy.interp`). If every sample is
/// bad, `v` is left unchanged.
pub fn interpolate_over(v: &mut [f64], bad: &[usize]) {
    if bad.is_empty() || bad.len() >= v.len() {
        return;
    }
    let mut is_bad = vec![false; v.len()];
    for &i in bad {
        is_bad[i] = true;
    }
    let mut i = 0;
    while i < v.len() {
        if !is_bad[i] {
            i += 1;
            continue;
        }
        let start = i;
        while i < v.len() && is_bad[i] {
            i += 1;
        }
        let left = start.checked_sub(1);
        let right = (i < v.len()).then_some(i);
        match (left, right) {
            (Some(l), Some(r)) => {
                let (yl, yr) = (v[l], v[r]);
                for (k, item) in v.iter_mut().enumerate().take(r).skip(start) {
                    let w = (k - l) as f64 / (r - l) as f64;
                    *item = yl + w * (yr - yl);
                }
            }
            (Some(l), None) => {
                let y = v[l];
                v[start..].iter_mut().for_each(|x| *x = y);
            }
            (None, Some(r)) => {
                let y = v[r];
                v[..r].iter_mut().for_each(|x| *x = y);
            }
            (None, None) => {}
        }
    }
}

/// Second-order sections of a Butterworth low-pass (scipy `butter(order, cutoff_hz,
/// output='sos', fs=fs_hz)`).
pub fn butterworth_lowpass_sos(order: usize, cutoff_hz: f64, fs_hz: f64) -> Vec<Sos<f64>> {
    match butter_dyn(
        order,
        vec![cutoff_hz],
        Some(FilterBandType::Lowpass),
        Some(false),
        Some(FilterOutputType::Sos),
        Some(fs_hz),
    ) {
        DigitalFilter::Sos(s) => s.sos,
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
                "signal of {} samples is too short: more than {padlen} are needed",
                x.len()
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

/// Run the preprocessing stage on a recording.
pub fn preprocess(rec: &Recording, params: &ValidPreprocessParams) -> Result<Preprocessed> {
    if (params.fs_hz - rec.fs_hz).abs() > 1e-9 * rec.fs_hz {
        return Err(LdhError::param(
            "fs_hz",
            params.fs_hz,
            format!(
                "parameters were checked for {} Hz but the recording is at {} Hz",
                params.fs_hz, rec.fs_hz
            ),
        ));
    }
    let ctx = || format!("preprocess {}", rec.label());
    if rec.len() < params.min_len() {
        return Err(LdhError::signal(
            ctx(),
            format!(
                "{} samples: the zero-phase filter needs at least {}",
                rec.len(),
                params.min_len()
            ),
        ));
    }
    let raw_norm = magnitude(&rec.acc_g[0], &rec.acc_g[1], &rec.acc_g[2]);
    let (m, sd) = mean_sd(&raw_norm);
    let mut acc = rec.acc_g.clone();
    let mut gyro = rec.gyro_dps.clone();
    let mut replaced = Vec::new();
    if params.params.replace_outliers {
        let k = params.params.outlier_sd;
        replaced = (0..rec.len())
            .filter(|&i| (raw_norm[i] - m).abs() > k * sd || rec.saturated[i])
            .collect();
        for ch in acc.iter_mut().chain(gyro.iter_mut()) {
            interpolate_over(ch, &replaced);
        }
    }
    let filt = |ch: &Vec<f64>| {
        sosfiltfilt(&params.sos, ch).map_err(|e| LdhError::signal(ctx(), e.to_string()))
    };
    let acc_f = [filt(&acc[0])?, filt(&acc[1])?, filt(&acc[2])?];
    let gyro_f = [filt(&gyro[0])?, filt(&gyro[1])?, filt(&gyro[2])?];
    let acc_norm_g = magnitude(&acc_f[0], &acc_f[1], &acc_f[2]);
    Ok(Preprocessed {
        fs_hz: rec.fs_hz,
        acc_g: acc_f,
        gyro_dps: gyro_f,
        acc_norm_g,
        replaced,
        raw_norm_mean_g: m,
        raw_norm_sd_g: sd,
    })
}
