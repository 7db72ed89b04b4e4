//! Outlier replacement (paper §3.1, eq. 1): the acceleration magnitude, the
//! `outlier_sd` rule (population SD, numpy's `ddof = 0`), clipped samples, and linear
//! interpolation over them with `numpy.interp` semantics.

use super::ValidPreprocessParams;
use crate::error::{LdhError, Result};
use crate::recording::Recording;

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

/// The checks of [`preprocess`](super::preprocess) and its outlier search, without the filtering: what
/// `preprocess(rec, params)` reports in `replaced`, `raw_norm_mean_g` and `raw_norm_sd_g`
/// (memory: one norm per sample).
pub fn outlier_summary(rec: &Recording, params: &ValidPreprocessParams) -> Result<OutlierSummary> {
    Ok(norm_and_outliers(rec, params)?.1)
}

/// The checks of [`preprocess`](super::preprocess), the raw acceleration norm and the outliers.
pub(super) fn norm_and_outliers(
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
