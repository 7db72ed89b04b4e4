//! Preprocessing parameters (paper §3.1 defaults) and their check into
//! [`ValidPreprocessParams`], which holds the designed Butterworth sections.

use serde::{Deserialize, Serialize};

use super::filter::butterworth_lowpass_sos;
use crate::error::{LdhError, Result};
use sci_rs::signal::filter::design::Sos;

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
    pub(super) params: PreprocessParams,
    pub(super) fs_hz: f64,
    pub(super) sos: Vec<Sos<f64>>,
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
