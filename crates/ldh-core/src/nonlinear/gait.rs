//! Gait use: short-term local divergence exponent λs (Dingwell & Cusumano
//! 2000; Bruijn et al. 2013 review) of a single gait signal, e.g. the sagittal
//! angular velocity of the shank.

use serde::{Deserialize, Serialize};

use super::embed::{lag_acf, lag_ami};
use super::fnn::{emb_dim_fnn_index, FnnParams, FnnResult};
use super::rosenstein::{lyap_r_with, RosensteinParams, RosensteinResult};
use super::{check_series, invalid, NonlinearError};

/// How the embedding delay is chosen in [`gait_sta`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LagRule {
    /// First minimum of the average mutual information ([`super::lag_ami`]),
    /// searched up to one mean stride; `bins: None` = Sturges' rule.
    Ami {
        /// histogram bins (`None`: `⌈log2 n⌉ + 1`)
        bins: Option<usize>,
    },
    /// First lag where the autocorrelation drops to 1/e ([`super::lag_acf`]),
    /// searched up to one mean stride.
    Acf,
    /// A fixed delay in samples (of the possibly time-normalised series).
    Fixed(usize),
}

/// Optional time normalisation of the series before the analysis.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TimeNormalisation {
    /// Analyse the series as recorded (default).
    #[default]
    None,
    /// Resample the whole series by linear interpolation so that one *mean*
    /// stride spans `samples_per_stride` samples (new sampling interval
    /// `mean_stride_s / samples_per_stride`).
    MeanStride {
        /// samples per mean stride after resampling (e.g. 100)
        samples_per_stride: usize,
    },
    /// Resample every stride between consecutive boundaries (sample indices
    /// of e.g. heel strikes, strictly increasing) to exactly
    /// `samples_per_stride` samples by linear interpolation, and concatenate;
    /// samples before the first and after the last boundary are dropped. One
    /// sample then stands for `mean_stride_s / samples_per_stride` seconds.
    StrideBoundaries {
        /// stride boundaries, sample indices into the signal
        boundaries: Vec<usize>,
        /// samples per stride after resampling (e.g. 100)
        samples_per_stride: usize,
    },
}

/// Parameters of [`gait_sta`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct GaitStaParams {
    /// Delay rule (default: AMI first minimum).
    pub lag: LagRule,
    /// Embedding dimension; `None` (default): false nearest neighbours with
    /// [`GaitStaParams::fnn`].
    pub emb_dim: Option<usize>,
    /// FNN settings when `emb_dim` is `None` (default [`FnnParams::default`]).
    pub fnn: FnnParams,
    /// Theiler window in strides (default 1.0 = one mean stride).
    pub theiler_strides: f64,
    /// Fit range of the divergence curve in strides from k = 0 (default 0.5 =
    /// first half stride, the "short-term" exponent λs).
    pub fit_strides: f64,
    /// Time normalisation (default none).
    pub time_normalisation: TimeNormalisation,
}

impl Default for GaitStaParams {
    fn default() -> Self {
        Self {
            lag: LagRule::Ami { bins: None },
            emb_dim: None,
            fnn: FnnParams::default(),
            theiler_strides: 1.0,
            fit_strides: 0.5,
            time_normalisation: TimeNormalisation::None,
        }
    }
}

impl GaitStaParams {
    /// Sets the delay rule.
    pub fn lag(mut self, lag: LagRule) -> Self {
        self.lag = lag;
        self
    }
    /// Sets (or with `None` lets FNN choose) the embedding dimension.
    pub fn emb_dim(mut self, emb_dim: Option<usize>) -> Self {
        self.emb_dim = emb_dim;
        self
    }
    /// Sets the FNN settings.
    pub fn fnn(mut self, fnn: FnnParams) -> Self {
        self.fnn = fnn;
        self
    }
    /// Sets the Theiler window in strides.
    pub fn theiler_strides(mut self, strides: f64) -> Self {
        self.theiler_strides = strides;
        self
    }
    /// Sets the fit range in strides.
    pub fn fit_strides(mut self, strides: f64) -> Self {
        self.fit_strides = strides;
        self
    }
    /// Sets the time normalisation.
    pub fn time_normalisation(mut self, tn: TimeNormalisation) -> Self {
        self.time_normalisation = tn;
        self
    }
    /// Check what can be checked without a series: the Theiler window and the fit range are
    /// finite and positive (in strides). [`gait_sta`] runs the same check, and
    /// [`crate::pipeline::AnalysisParams::check`] runs it once per analysis, so a bad value is
    /// refused before any leg instead of being reported as every leg's STA status.
    pub fn check(&self) -> Result<(), NonlinearError> {
        for (name, v) in [
            ("theiler_strides", self.theiler_strides),
            ("fit_strides", self.fit_strides),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(invalid(name, v, "must be finite and positive (in strides)"));
            }
        }
        Ok(())
    }
}

/// Result of [`gait_sta`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GaitSta {
    /// λs in 1/s.
    pub lambda_per_s: f64,
    /// λs per stride: `lambda_per_s · mean_stride_s`.
    pub lambda_per_stride: f64,
    /// Delay used, in samples of the analysed series.
    pub lag: usize,
    /// Embedding dimension used.
    pub emb_dim: usize,
    /// FNN outcome when the dimension was estimated.
    pub fnn: Option<FnnResult>,
    /// Samples per mean stride in the analysed series.
    pub samples_per_stride: f64,
    /// Sampling rate of the analysed series in Hz.
    pub fs_hz: f64,
    /// Full Rosenstein result (divergence curve, fitted line, Theiler window).
    pub rosenstein: RosensteinResult,
}

/// Upper bound on the length of a time-normalised series (guards against
/// absurd `samples_per_stride` values exhausting memory).
const MAX_RESAMPLED: usize = 100_000_000;

fn interp(signal: &[f64], pos: f64) -> f64 {
    let i = pos.floor() as usize;
    if i + 1 >= signal.len() {
        return signal[signal.len() - 1];
    }
    let f = pos - i as f64;
    signal[i] * (1.0 - f) + signal[i + 1] * f
}

fn normalise(
    signal: &[f64],
    fs_hz: f64,
    mean_stride_s: f64,
    tn: &TimeNormalisation,
) -> Result<(Vec<f64>, f64), NonlinearError> {
    match tn {
        TimeNormalisation::None => Ok((signal.to_vec(), fs_hz)),
        TimeNormalisation::MeanStride { samples_per_stride } => {
            let p = *samples_per_stride;
            if p < 4 {
                return Err(invalid("samples_per_stride", p, "must be at least 4"));
            }
            let fs_new = p as f64 / mean_stride_s;
            let step = fs_hz / fs_new; // input samples per output sample
            let count = ((signal.len() - 1) as f64 / step).floor() + 1.0;
            if count > MAX_RESAMPLED as f64 {
                return Err(invalid(
                    "samples_per_stride",
                    p,
                    format!("would resample to {count} samples (limit {MAX_RESAMPLED})"),
                ));
            }
            let count = count as usize;
            Ok((
                (0..count)
                    .map(|k| interp(signal, k as f64 * step))
                    .collect(),
                fs_new,
            ))
        }
        TimeNormalisation::StrideBoundaries {
            boundaries,
            samples_per_stride,
        } => {
            let p = *samples_per_stride;
            if p < 4 {
                return Err(invalid("samples_per_stride", p, "must be at least 4"));
            }
            if boundaries.len() < 2 {
                return Err(invalid(
                    "boundaries",
                    boundaries.len(),
                    "need at least 2 stride boundaries",
                ));
            }
            for w in boundaries.windows(2) {
                if w[1] <= w[0] || w[1] >= signal.len() {
                    return Err(invalid(
                        "boundaries",
                        format!("{:?}", &w),
                        format!(
                            "must be strictly increasing sample indices below the signal length {}",
                            signal.len()
                        ),
                    ));
                }
            }
            let total = (boundaries.len() - 1).saturating_mul(p);
            if total > MAX_RESAMPLED {
                return Err(invalid(
                    "samples_per_stride",
                    p,
                    format!("would resample to {total} samples (limit {MAX_RESAMPLED})"),
                ));
            }
            let mut out = Vec::with_capacity(total);
            for w in boundaries.windows(2) {
                let (a, b) = (w[0] as f64, w[1] as f64);
                for k in 0..p {
                    out.push(interp(signal, a + (b - a) * k as f64 / p as f64));
                }
            }
            Ok((out, p as f64 / mean_stride_s))
        }
    }
}

/// Short-term local divergence exponent λs of a gait signal (e.g. sagittal
/// angular velocity in rad/s, sampled at `fs_hz`, mean stride time
/// `mean_stride_s` in seconds).
///
/// 1. Optional time normalisation ([`TimeNormalisation`]).
/// 2. Delay by AMI (default) / ACF / fixed; dimension by FNN unless given.
/// 3. Rosenstein's method ([`super::lyap_r`]) with Theiler window
///    `⌈theiler_strides · samples_per_stride⌉` samples, divergence followed
///    and fitted over `k = 0..=round(fit_strides · samples_per_stride)`.
/// 4. λs in 1/s (`tau = 1/fs` of the analysed series) and per stride.
pub fn gait_sta(
    signal: &[f64],
    fs_hz: f64,
    mean_stride_s: f64,
    params: &GaitStaParams,
) -> Result<GaitSta, NonlinearError> {
    check_series(signal)?;
    if !(fs_hz.is_finite() && fs_hz > 0.0) {
        return Err(invalid(
            "fs_hz",
            fs_hz,
            "must be a finite, positive sampling rate",
        ));
    }
    if !(mean_stride_s.is_finite() && mean_stride_s > 0.0) {
        return Err(invalid(
            "mean_stride_s",
            mean_stride_s,
            "must be a finite, positive stride time in seconds",
        ));
    }
    params.check()?;
    let (x, fs) = normalise(signal, fs_hz, mean_stride_s, &params.time_normalisation)?;
    check_series(&x)?;
    let sps = mean_stride_s * fs;
    if sps < 4.0 {
        return Err(invalid(
            "mean_stride_s",
            mean_stride_s,
            format!("gives only {sps:.2} samples per stride at {fs} Hz"),
        ));
    }
    let max_lag = (sps.round() as usize).max(2);
    let lag = match &params.lag {
        LagRule::Ami { bins } => lag_ami(&x, max_lag, *bins)?,
        LagRule::Acf => lag_acf(&x, max_lag.min(x.len().saturating_sub(1)).max(1))?,
        LagRule::Fixed(l) => *l,
    };
    if lag == 0 {
        return Err(invalid("lag", lag, "must be at least 1 sample"));
    }
    // FNN's neighbour index (a delay embedding of x with this lag) serves Rosenstein's search
    let (emb_dim, fnn, index) = match params.emb_dim {
        Some(d) => (d, None, None),
        None => {
            let (r, index) = emb_dim_fnn_index(&x, lag, &params.fnn)?;
            (r.emb_dim, Some(r), index)
        }
    };
    let min_tsep = (params.theiler_strides * sps).ceil() as usize;
    let fit_len = ((params.fit_strides * sps).round() as usize).max(1);
    let rp = RosensteinParams::default()
        .emb_dim(emb_dim)
        .lag(Some(lag))
        .min_tsep(Some(min_tsep))
        .tau(1.0 / fs)
        .trajectory_len(fit_len.saturating_add(1));
    let ros = lyap_r_with(&x, &rp.check()?, index.as_ref().map(|s| (s, lag)))?;
    Ok(GaitSta {
        lambda_per_s: ros.exponent,
        lambda_per_stride: ros.exponent * mean_stride_s,
        lag,
        emb_dim,
        fnn,
        samples_per_stride: sps,
        fs_hz: fs,
        rosenstein: ros,
    })
}
