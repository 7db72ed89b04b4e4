//! Preprocessing (paper §3.1, SPEC §3.1): acceleration magnitude (eq. 1), outlier replacement,
//! zero-phase Butterworth low-pass on all six channels.
//!
//! 1. Magnitude ‖a‖ = √(a_x² + a_y² + a_z²) per sample (eq. 1).
//! 2. Outliers: samples whose acceleration magnitude lies more than `outlier_sd` standard
//!    deviations (population SD, numpy's default `ddof = 0`) from the mean magnitude are
//!    replaced by linear interpolation between the nearest good samples (`numpy.interp`
//!    semantics: held constant at the ends). By default only the three acceleration channels
//!    are replaced ([`OutlierChannels::Acc`]): an acceleration-magnitude outlier says nothing
//!    about the gyroscope, and interpolating the angular velocity over such samples removes
//!    area from its integral — on simulated walking the 3-SD rule flags genuine swing peaks, and
//!    replacing the gyroscope there raised the gyro-only pitch error from 0.7° to 1.7° RMS
//!    (docs/accuracy.md). [`OutlierChannels::All`] is the literal reading of the paper.
//!    Samples the reader flagged as clipped are replaced in both modes, on the channels of the
//!    sensor that clipped (`Recording::acc_saturated`, `Recording::gyro_saturated`; both
//!    sensors when the recording does not say which): an accelerometer at its ±2 g range at
//!    heel strike says nothing about the angular velocity of the same sample, and replacing
//!    the gyroscope there (HuGaDB: 13-21 % of the samples) took 5-10° out of the pitch
//!    integral around every heel strike, so the mid-stance pitch spread over 23-27° instead of
//!    the 4-8° of the untouched gyroscope (docs/quality.md).
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
    /// Which channels an acceleration-magnitude outlier is replaced on. Default acc.
    pub outlier_channels: OutlierChannels,
}

/// Channels on which an acceleration-magnitude outlier is replaced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum OutlierChannels {
    /// The three acceleration channels (default).
    #[default]
    Acc,
    /// All six channels (the paper read literally).
    All,
}

impl Default for PreprocessParams {
    fn default() -> Self {
        PreprocessParams {
            cutoff_hz: 10.0,
            filter_order: 4,
            outlier_sd: 3.0,
            replace_outliers: true,
            outlier_channels: OutlierChannels::Acc,
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
    /// Choose the channels outliers are replaced on.
    pub fn outlier_channels(mut self, v: OutlierChannels) -> Self {
        self.outlier_channels = v;
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
        if self.filter_order < 2 || self.filter_order > 10 || !self.filter_order.is_multiple_of(2) {
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
        let sos = butterworth_lowpass_sos(self.filter_order, self.cutoff_hz, fs_hz)?;
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
    /// Indices of the samples replaced by interpolation on the acceleration channels (outliers
    /// and samples where the accelerometer clipped); the gyroscope channels are replaced where
    /// the gyroscope clipped, and at the outliers too with [`OutlierChannels::All`].
    pub replaced: Vec<usize>,
    /// Indices of the samples where the accelerometer clipped (sorted; empty when it never
    /// did). Their acceleration is unknown whatever replaced it, so no velocity or stride length
    /// integrated over them is reported ([`crate::gait::stride_length`]).
    #[serde(default)]
    pub acc_clipped: Vec<usize>,
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

/// What preprocessing finds in a recording before filtering it (`ldh inspect` reports this
/// without the filtered copies of the channels).
#[derive(Debug, Clone, PartialEq)]
pub struct OutlierSummary {
    /// Samples whose acceleration is replaced (outliers and clipped samples).
    pub replaced: Vec<usize>,
    /// Mean of the raw acceleration norm, g.
    pub raw_norm_mean_g: f64,
    /// SD of the raw acceleration norm, g.
    pub raw_norm_sd_g: f64,
}

/// The checks of [`preprocess`] and its outlier search, without the filtering: what
/// `preprocess(rec, params)` reports in `replaced`, `raw_norm_mean_g` and `raw_norm_sd_g`
/// (memory: one norm per sample).
pub fn outlier_summary(rec: &Recording, params: &ValidPreprocessParams) -> Result<OutlierSummary> {
    Ok(norm_and_outliers(rec, params)?.1)
}

/// The checks of [`preprocess`], the raw acceleration norm and the outliers.
fn norm_and_outliers(
    rec: &Recording,
    params: &ValidPreprocessParams,
) -> Result<(Vec<f64>, OutlierSummary)> {
    rec.validate()?;
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
    let mut replaced = Vec::new();
    if params.params.replace_outliers {
        let k = params.params.outlier_sd;
        replaced = (0..rec.len())
            .filter(|&i| (raw_norm[i] - m).abs() > k * sd || rec.acc_saturated_at(i))
            .collect();
    }
    let summary = OutlierSummary {
        replaced,
        raw_norm_mean_g: m,
        raw_norm_sd_g: sd,
    };
    Ok((raw_norm, summary))
}

/// Run the preprocessing stage on a recording.
pub fn preprocess(rec: &Recording, params: &ValidPreprocessParams) -> Result<Preprocessed> {
    let ctx = || format!("preprocess {}", rec.label());
    let (raw_norm, found) = norm_and_outliers(rec, params)?;
    let (m, sd) = (found.raw_norm_mean_g, found.raw_norm_sd_g);
    let replaced = found.replaced;
    let mut acc = rec.acc_g.clone();
    let mut gyro = rec.gyro_dps.clone();
    if params.params.replace_outliers {
        let k = params.params.outlier_sd;
        for ch in acc.iter_mut() {
            interpolate_over(ch, &replaced);
        }
        let outlier = |i: usize| match params.params.outlier_channels {
            OutlierChannels::All => (raw_norm[i] - m).abs() > k * sd,
            OutlierChannels::Acc => false,
        };
        let gyro_bad: Vec<usize> = (0..rec.len())
            .filter(|&i| rec.gyro_saturated_at(i) || outlier(i))
            .collect();
        for ch in gyro.iter_mut() {
            interpolate_over(ch, &gyro_bad);
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
        acc_clipped: (0..rec.len())
            .filter(|&i| rec.acc_saturated_at(i))
            .collect(),
        raw_norm_mean_g: m,
        raw_norm_sd_g: sd,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::{read_recording, ReadParams};
    use proptest::prelude::*;
    use serde_json::Value;

    const EXPECTED: &str = include_str!("../../../data-fixtures/golden/preprocess/expected.json");

    fn golden() -> Value {
        serde_json::from_str(EXPECTED).unwrap()
    }

    fn vec_of(v: &Value) -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    }

    /// Largest |a − b| / (|b| + 1e-3 · max|b|): relative, with a floor at the channel's scale
    /// so zero crossings do not divide by ~0.
    fn max_rel_err(a: &[f64], b: &[f64]) -> f64 {
        assert_eq!(a.len(), b.len());
        let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs() / (y.abs() + 1e-3 * scale))
            .fold(0.0, f64::max)
    }

    #[test]
    fn preprocessing_equals_numpy_and_scipy() {
        let g = golden();
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../data-fixtures/golden/preprocess/input.csv"
        );
        let (rec, _) = read_recording(path, None, &ReadParams::default().check().unwrap()).unwrap();
        assert!((rec.fs_hz - g["fs_hz"].as_f64().unwrap()).abs() < 1e-9);
        let p = PreprocessParams::default()
            .outlier_channels(OutlierChannels::All)
            .check(rec.fs_hz)
            .unwrap();
        // The filter design equals scipy.signal.butter(…, output="sos").
        let sos_ref = g["sos"].as_array().unwrap();
        for (s, r) in p.sos.iter().zip(sos_ref) {
            let r = vec_of(r);
            let ours = [s.b[0], s.b[1], s.b[2], s.a[0], s.a[1], s.a[2]];
            assert!(max_rel_err(&ours, &r) < 1e-12, "{ours:?} vs {r:?}");
        }
        let out = preprocess(&rec, &p).unwrap();
        let outliers: Vec<usize> = g["outliers"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_u64().unwrap() as usize)
            .collect();
        assert_eq!(out.replaced, outliers);
        assert!((out.raw_norm_mean_g - g["norm_mean_g"].as_f64().unwrap()).abs() < 1e-12);
        assert!((out.raw_norm_sd_g - g["norm_sd_g"].as_f64().unwrap()).abs() < 1e-12);
        let names = ["acc_x", "acc_y", "acc_z", "gyro_x", "gyro_y", "gyro_z"];
        for (k, name) in names.iter().enumerate() {
            let ours = if k < 3 {
                &out.acc_g[k]
            } else {
                &out.gyro_dps[k - 3]
            };
            let err = max_rel_err(ours, &vec_of(&g["filtered"][name]));
            eprintln!("{name}: max relative error vs scipy {err:e}");
            assert!(err < 1e-9, "{name}: relative error {err:e}");
        }
        let err = max_rel_err(&out.acc_norm_g, &vec_of(&g["filtered_norm_g"]));
        assert!(err < 1e-9, "norm: {err:e}");
        // The default replaces acceleration-magnitude outliers on the acceleration channels only.
        let acc_only =
            preprocess(&rec, &PreprocessParams::default().check(rec.fs_hz).unwrap()).unwrap();
        for (k, name) in names.iter().enumerate() {
            let ours = if k < 3 {
                &acc_only.acc_g[k]
            } else {
                &acc_only.gyro_dps[k - 3]
            };
            let err = max_rel_err(ours, &vec_of(&g["filtered_acc_outliers_only"][name]));
            assert!(
                err < 1e-9,
                "{name} (acc-only replacement): relative error {err:e}"
            );
        }
    }

    #[test]
    fn sosfiltfilt_equals_scipy_for_several_designs() {
        let g = golden();
        let noise = vec_of(&g["noise"]);
        for case in g["sosfiltfilt_cases"].as_array().unwrap() {
            let order = case["order"].as_u64().unwrap() as usize;
            let (fc, fs) = (
                case["cutoff_hz"].as_f64().unwrap(),
                case["fs_hz"].as_f64().unwrap(),
            );
            let y = butter_filtfilt(&noise, order, fc, fs).unwrap();
            let err = max_rel_err(&y, &vec_of(&case["y"]));
            assert!(err < 1e-9, "order {order} fc {fc} fs {fs}: {err:e}");
        }
    }

    #[test]
    fn bad_parameters_and_short_signals_are_errors() {
        let e = PreprocessParams::default()
            .cutoff_hz(60.0)
            .check(100.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("cutoff_hz") && e.contains("(0, 50)"), "{e}");
        assert!(PreprocessParams::default()
            .filter_order(3)
            .check(100.0)
            .is_err());
        assert!(PreprocessParams::default()
            .outlier_sd(0.0)
            .check(100.0)
            .is_err());
        let e = butter_filtfilt(&[1.0; 15], 4, 10.0, 100.0)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("too short") && e.contains("15 samples") && e.contains("at least 16"),
            "{e}"
        );
        assert!(butter_filtfilt(&[f64::NAN; 40], 4, 10.0, 100.0).is_err());
        // Found by fuzzing: a recording claiming 9.3e74 Hz made sci-rs's design panic
        // (fuzz/regressions/pipeline/butterworth-huge-rate). Now a parameter error.
        for (fs, fc) in [(9.3e74, 10.0), (1e300, 10.0), (100.0, 49.999_999_999_9)] {
            let e = PreprocessParams::default()
                .cutoff_hz(fc)
                .check(fs)
                .unwrap_err()
                .to_string();
            assert!(e.contains("cutoff_hz") && e.contains("Nyquist"), "{e}");
            assert!(butterworth_lowpass_sos(4, fc, fs).is_err());
        }
        assert!(butterworth_lowpass_sos(4, 10.0, 100.0).is_ok());
        assert!(butterworth_lowpass_sos(0, 10.0, 100.0).is_err());
        let rec = Recording::new(
            100.0,
            [vec![1.0; 10], vec![0.0; 10], vec![0.0; 10]],
            [vec![0.0; 10], vec![0.0; 10], vec![0.0; 10]],
            vec![],
        )
        .unwrap();
        let p = PreprocessParams::default().check(100.0).unwrap();
        assert!(preprocess(&rec, &p)
            .unwrap_err()
            .to_string()
            .contains("at least 16"));
        let p50 = PreprocessParams::default().check(50.0).unwrap();
        assert!(preprocess(&rec, &p50).is_err());
    }

    #[test]
    fn interpolation_handles_edges_and_runs() {
        let mut v = vec![0.0, 10.0, 10.0, 3.0, 4.0, 10.0];
        interpolate_over(&mut v, &[1, 2, 5]);
        assert_eq!(v, vec![0.0, 1.0, 2.0, 3.0, 4.0, 4.0]);
        let mut w = vec![9.0, 9.0, 2.0];
        interpolate_over(&mut w, &[0, 1]);
        assert_eq!(w, vec![2.0, 2.0, 2.0]);
    }

    proptest! {
        /// A zero-phase low-pass keeps a constant signal constant.
        #[test]
        fn filtfilt_keeps_constants(c in -1e3f64..1e3, n in 22usize..400, order in prop::sample::select(vec![2usize, 4, 6]), fc in 1.0f64..40.0) {
            let y = butter_filtfilt(&vec![c; n], order, fc, 100.0).unwrap();
            for v in y {
                prop_assert!((v - c).abs() <= 1e-9 * c.abs().max(1.0));
            }
        }

        /// Filtering is linear: filt(a·x + b) = a·filt(x) + b.
        #[test]
        fn filtfilt_is_linear(x in prop::collection::vec(-10.0f64..10.0, 20..200), a in -5.0f64..5.0, b in -5.0f64..5.0) {
            let fx = butter_filtfilt(&x, 4, 10.0, 100.0).unwrap();
            let ax: Vec<f64> = x.iter().map(|v| a * v + b).collect();
            let fax = butter_filtfilt(&ax, 4, 10.0, 100.0).unwrap();
            for (p, q) in fax.iter().zip(&fx) {
                prop_assert!((p - (a * q + b)).abs() < 1e-9 * (1.0 + a.abs() * 10.0 + b.abs()));
            }
        }
    }
}
