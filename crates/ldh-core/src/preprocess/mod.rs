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
//!    and initial conditions (sci-rs `butter_dyn` + `sosfiltfilt_dyn`, equal to scipy to ~1e-14;
//!    the latter written out bit for bit, a sensor's three axes side by side: [`sosfiltfilt_each`]).
//! 4. For the stride length only, a second acceleration (`Preprocessed::acc_motion_g`): the
//!    magnitude outliers kept and the clipped samples reconstructed on the axis that clipped by
//!    a local quadratic ([`declip`], `declip.rs`), then the same low-pass.
//!
//! The golden test (`data-fixtures/golden/preprocess/`) checks each step against numpy/scipy to
//! 1e-9 relative.

mod declip;
mod filter;
mod outliers;
mod params;

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};
use crate::recording::Recording;
pub(crate) use declip::runs;
pub use declip::{clipped_axes, declip, DECLIP_NEIGHBOURS};
pub use filter::{
    butter_filtfilt, butterworth_lowpass_sos, sosfiltfilt, sosfiltfilt_each, BUTTERWORTH_WN_RANGE,
};
use outliers::norm_and_outliers;
pub use outliers::{
    interpolate_over, magnitude, mean_sd, outlier_summary, outliers_sd, OutlierSummary,
};
pub use params::{OutlierChannels, PreprocessParams, ValidPreprocessParams};

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
    /// did). `acc_motion_g` reconstructs them; a stride length integrated over them has its own
    /// check ([`crate::gait::LengthEstimate::implausible`]).
    #[serde(default)]
    pub acc_clipped: Vec<usize>,
    /// Filtered acceleration with the magnitude outliers **kept** and the clipped samples
    /// **reconstructed** on the axis that clipped ([`declip`]), g; `None` when it equals
    /// `acc_g` (nothing clipped, and no outlier replaced or `replace_outliers` off). The
    /// outlier rule of step 2 (|a| beyond `outlier_sd` SDs of its mean) flags the shank's
    /// genuine heel-strike decelerations wherever the magnitude varies little, as in slow gait
    /// (SD 0.12-0.2 g: 7-11 samples around every heel strike); interpolating them removes their
    /// area from a strapdown integral, which made slow walkers' stride lengths 10-29 % short,
    /// and interpolating clipped runs made ±2 g strides up to 40 % short (docs/accuracy.md).
    /// The stride length integrates this one ([`crate::gait::stride_length`]); everything else
    /// keeps the paper's signals.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub acc_motion_g: Option<[Vec<f64>; 3]>,
    /// Mean of the raw magnitude, g.
    pub raw_norm_mean_g: f64,
    /// SD (ddof = 0) of the raw magnitude, g.
    pub raw_norm_sd_g: f64,
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
    // the three axes of a sensor side by side (`sosfiltfilt_each`)
    let filt = |ch: &[Vec<f64>; 3]| {
        sosfiltfilt_each(&params.sos, [&ch[0][..], &ch[1], &ch[2]])
            .map_err(|e| LdhError::signal(ctx(), e.to_string()))
    };
    let acc_f = filt(&acc)?;
    let gyro_f = filt(&gyro)?;
    let acc_norm_g = magnitude(&acc_f[0], &acc_f[1], &acc_f[2]);
    let acc_clipped: Vec<usize> = (0..rec.len())
        .filter(|&i| rec.acc_saturated_at(i))
        .collect();
    // The acceleration the stride length integrates: magnitude outliers kept (they are the
    // shank's real heel-strike decelerations), clipped samples reconstructed on the axis that
    // clipped (`declip`). Stored only when it differs from `acc_f`.
    let differs =
        !acc_clipped.is_empty() || (params.params.replace_outliers && !replaced.is_empty());
    let acc_motion_g = if differs {
        let mut acc = rec.acc_g.clone();
        let (axes, unknown) = clipped_axes(&acc, &acc_clipped);
        for (ch, bad) in acc.iter_mut().zip(&axes) {
            declip(ch, bad);
            interpolate_over(ch, &unknown);
        }
        Some(filt(&acc)?)
    } else {
        None
    };
    Ok(Preprocessed {
        fs_hz: rec.fs_hz,
        acc_g: acc_f,
        gyro_dps: gyro_f,
        acc_norm_g,
        replaced,
        acc_clipped,
        acc_motion_g,
        raw_norm_mean_g: m,
        raw_norm_sd_g: sd,
    })
}

#[cfg(test)]
mod tests;
