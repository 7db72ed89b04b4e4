//! Rosenstein, Collins & De Luca (1993): largest Lyapunov exponent from the
//! mean logarithmic divergence of nearest neighbours, with the exact semantics
//! of `nolds.lyap_r(..., fit="poly")` (nolds 0.6.2).

use serde::{Deserialize, Serialize};

use super::divergence::divergence;
use super::embed::delay_embed_flat;
use super::fnn::FnnSearch;
use super::linalg::line_fit;
use super::neighbours::nearest_outside_window;
use super::{check_series, fft, invalid, NonlinearError};

/// Line-fitting method for the divergence curve (nolds' `fit`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Fit {
    /// Least-squares straight line, `np.polyfit(ks, div, 1)` (`"poly"`; the pipeline's STA).
    #[default]
    #[serde(rename = "poly")]
    Poly,
    /// RANSAC line as scikit-learn fits it for nolds (`"RANSAC"`, nolds' default), made
    /// deterministic by trying every triple of points: see [`super::ransac`].
    #[serde(rename = "RANSAC", alias = "ransac")]
    Ransac,
}

/// Parameters of [`lyap_r`], mirroring `nolds.lyap_r` one to one.
///
/// All lengths are in samples. Defaults equal nolds' except `fit` (least squares here, for the
/// pipeline's STA; nolds defaults to RANSAC: [`RosensteinParams::nolds`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct RosensteinParams {
    /// Embedding dimension (default 10).
    pub emb_dim: usize,
    /// Embedding lag in samples. `None` (default): nolds' rule, the first lag
    /// at which the (unnormalised, mean-not-removed) autocorrelation drops
    /// below `(1 − 1/e)` of its value at lag 0, stopped early when fewer than
    /// `min_neighbors` orbit vectors would remain.
    pub lag: Option<usize>,
    /// Theiler window in samples: neighbours must satisfy `|i − j| > min_tsep`.
    /// `None` (default): nolds' rule, `ceil(1 / mean frequency)` of the
    /// power spectrum of the whole series, capped at `⌊0.25·n⌋`.
    pub min_tsep: Option<usize>,
    /// Sampling interval in seconds (default 1.0): the slope per sample is
    /// divided by `tau`, so the exponent is in 1/s (or 1/sample when 1.0).
    pub tau: f64,
    /// Only used when `lag` is `None`: the lag search stops once fewer than
    /// this many orbit vectors would remain (default 20).
    pub min_neighbors: usize,
    /// Number of steps (samples) over which each neighbour pair is followed;
    /// the line is fitted over `k = 0..trajectory_len` (default 20).
    pub trajectory_len: usize,
    /// Line-fitting method (default [`Fit::Poly`]).
    pub fit: Fit,
    /// Number of initial steps of the divergence curve left out of the fit
    /// (default 0).
    pub fit_offset: usize,
}

impl RosensteinParams {
    /// nolds 0.6.2's defaults exactly, including `fit="RANSAC"` (what `ldh.lyap_r` uses, so
    /// a nolds call gives the same value after `import ldh as nolds`).
    pub fn nolds() -> Self {
        Self {
            fit: Fit::Ransac,
            ..Self::default()
        }
    }
}

impl Default for RosensteinParams {
    fn default() -> Self {
        Self {
            emb_dim: 10,
            lag: None,
            min_tsep: None,
            tau: 1.0,
            min_neighbors: 20,
            trajectory_len: 20,
            fit: Fit::Poly,
            fit_offset: 0,
        }
    }
}

impl RosensteinParams {
    /// Sets the embedding dimension.
    pub fn emb_dim(mut self, emb_dim: usize) -> Self {
        self.emb_dim = emb_dim;
        self
    }
    /// Sets the embedding lag in samples (`None`: nolds' autocorrelation rule).
    pub fn lag(mut self, lag: Option<usize>) -> Self {
        self.lag = lag;
        self
    }
    /// Sets the Theiler window in samples (`None`: nolds' mean-period rule).
    pub fn min_tsep(mut self, min_tsep: Option<usize>) -> Self {
        self.min_tsep = min_tsep;
        self
    }
    /// Sets the sampling interval in seconds.
    pub fn tau(mut self, tau_s: f64) -> Self {
        self.tau = tau_s;
        self
    }
    /// Sets the minimal number of orbit vectors for the automatic lag search.
    pub fn min_neighbors(mut self, min_neighbors: usize) -> Self {
        self.min_neighbors = min_neighbors;
        self
    }
    /// Sets the divergence trajectory length in samples.
    pub fn trajectory_len(mut self, trajectory_len: usize) -> Self {
        self.trajectory_len = trajectory_len;
        self
    }
    /// Sets the fitting method.
    pub fn fit(mut self, fit: Fit) -> Self {
        self.fit = fit;
        self
    }
    /// Sets the number of initial divergence steps left out of the fit.
    pub fn fit_offset(mut self, fit_offset: usize) -> Self {
        self.fit_offset = fit_offset;
        self
    }

    /// Validates the parameters that do not depend on the data (`emb_dim ≥ 1`,
    /// `lag ≥ 1` when given, finite `tau > 0`, at least two fitted points
    /// `trajectory_len ≥ fit_offset + 2`) into the type [`lyap_r`] accepts.
    /// Length checks against the series happen in [`lyap_r`].
    pub fn check(&self) -> Result<ValidRosensteinParams, NonlinearError> {
        if self.emb_dim == 0 {
            return Err(invalid("emb_dim", self.emb_dim, "must be at least 1"));
        }
        if self.lag == Some(0) {
            return Err(invalid("lag", 0, "must be at least 1 sample"));
        }
        if !(self.tau.is_finite() && self.tau > 0.0) {
            return Err(invalid(
                "tau",
                self.tau,
                "must be a finite, positive sampling interval in seconds",
            ));
        }
        if self.trajectory_len < 2 || self.fit_offset.saturating_add(2) > self.trajectory_len {
            return Err(invalid(
                "trajectory_len",
                self.trajectory_len,
                format!(
                    "must leave at least 2 points for the line fit after fit_offset={}",
                    self.fit_offset
                ),
            ));
        }
        Ok(ValidRosensteinParams(self.clone()))
    }
}

/// [`RosensteinParams`] validated by [`RosensteinParams::check`]: the type
/// [`lyap_r`] accepts. Dereferences to the parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct ValidRosensteinParams(RosensteinParams);

impl std::ops::Deref for ValidRosensteinParams {
    type Target = RosensteinParams;
    fn deref(&self) -> &RosensteinParams {
        &self.0
    }
}

/// Result of [`lyap_r`] / [`lyap_r_orbit`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RosensteinResult {
    /// Largest Lyapunov exponent: `slope / tau` (1/s if `tau` is in s).
    pub exponent: f64,
    /// Embedding dimension used (number of channels for a state orbit).
    pub emb_dim: usize,
    /// Embedding lag used in samples (`None` for a multi-channel state orbit).
    pub lag: Option<usize>,
    /// Theiler window used in samples (`|i − j| > min_tsep`).
    pub min_tsep: usize,
    /// Divergence trajectory length in samples.
    pub trajectory_len: usize,
    /// Sampling interval in seconds.
    pub tau: f64,
    /// Steps `k` (samples) of the finite points of the divergence curve
    /// (nolds' `ks`).
    pub ks: Vec<usize>,
    /// Mean log divergence `⟨ln d_i(k)⟩` at each `ks` (nolds' `div_traj`).
    pub divergence: Vec<f64>,
    /// Fitted slope per sample (nolds' `poly[0]`).
    pub slope: f64,
    /// Fitted intercept (nolds' `poly[1]`).
    pub intercept: f64,
}

/// Minimum series length for [`lyap_r`] (nolds `lyap_r_len`):
/// `(emb_dim − 1)·lag + 1 + (trajectory_len − 1) + 2·min_tsep + 1`.
pub fn lyap_r_len(emb_dim: usize, lag: usize, trajectory_len: usize, min_tsep: usize) -> usize {
    emb_dim
        .saturating_sub(1)
        .saturating_mul(lag)
        .saturating_add(1)
        .saturating_add(trajectory_len.saturating_sub(1))
        .saturating_add(min_tsep.saturating_mul(2))
        .saturating_add(1)
}

/// nolds' default Theiler window: `ceil(1 / mean frequency)`, capped at
/// `⌊0.25·n⌋`.
fn default_min_tsep(x: &[f64]) -> usize {
    let n = x.len();
    let mf = fft::mean_frequency(x);
    let mut min_tsep = (1.0 / mf).ceil();
    if !min_tsep.is_finite() || min_tsep < 0.0 {
        min_tsep = f64::MAX;
    }
    let cap = (0.25 * n as f64).floor();
    if min_tsep > 0.25 * n as f64 {
        cap as usize
    } else {
        min_tsep as usize
    }
}

/// nolds' default lag (autocorrelation falls below `(1 − 1/e)·r(0)`).
fn default_lag(x: &[f64], p: &RosensteinParams, min_tsep: usize) -> usize {
    let n = x.len();
    let acorr = fft::autocorrelation(x);
    let eps = acorr[0] * (1.0 - 1.0 / std::f64::consts::E);
    let mut lag = 1;
    for (i, &r) in acorr.iter().enumerate().take(n).skip(1) {
        lag = i;
        if r < eps {
            break;
        }
        let min_len = lyap_r_len(p.emb_dim, i, p.trajectory_len, min_tsep);
        if n.saturating_sub(min_len) < p.min_neighbors {
            break;
        }
    }
    lag
}

/// Largest Lyapunov exponent by Rosenstein's method, equal to
/// `nolds.lyap_r(x, emb_dim, lag, min_tsep, tau, min_neighbors,
/// trajectory_len, fit="poly", fit_offset=fit_offset)` (nolds 0.6.2).
///
/// Steps: delay embedding `X_i = [x_i, x_{i+lag}, …]`; for every
/// `i < ntraj = m − trajectory_len + 1` the Euclidean nearest `X_j`,
/// `j < ntraj`, `|i − j| > min_tsep` (lowest `j` among ties); divergence
/// `d(k) = mean_i ln ‖X_{i+k} − X_{j+k}‖` over non-zero distances for
/// `k = 0..trajectory_len`; least-squares line over the finite `d(k)` after
/// `fit_offset`; exponent = slope / tau.
///
/// Errors: empty, non-finite or constant input; series shorter than
/// [`lyap_r_len`]; fewer than 2 finite divergence points (nolds returns
/// `-inf` there). Parameters are validated by [`RosensteinParams::check`].
pub fn lyap_r(
    x: &[f64],
    params: &ValidRosensteinParams,
) -> Result<RosensteinResult, NonlinearError> {
    check_orbit_size(x.len(), params.emb_dim)?;
    lyap_r_with(x, params, None)
}

/// Most values of the delay embedding [`lyap_r`] builds, samples × `emb_dim`: 10⁷ (10⁶ samples
/// at nolds' default `emb_dim` = 10). Memory and time grow with it: 10⁷ samples at
/// `emb_dim` 10 took 3.4 GB and more than 60 s (issue 37); at the limit the peak stays under
/// 1 GB. A gait series is far smaller (150 strides at 100 Hz: 15 000 samples); a longer series
/// is refused with the sizes rather than exhausting the machine.
pub const MAX_ORBIT_VALUES: usize = 10_000_000;

/// Refuse a series whose delay embedding would exceed [`MAX_ORBIT_VALUES`].
pub fn check_orbit_size(n: usize, emb_dim: usize) -> Result<(), NonlinearError> {
    let values = n.saturating_mul(emb_dim);
    if values > MAX_ORBIT_VALUES {
        return Err(invalid(
            "data",
            format!("{n} samples"),
            format!(
                "{n} samples x emb_dim {emb_dim} = {values} embedded values exceed the limit of {MAX_ORBIT_VALUES} (at most {} samples at this emb_dim; memory and time grow with the size)",
                MAX_ORBIT_VALUES / emb_dim.max(1)
            ),
        ));
    }
    Ok(())
}

/// [`lyap_r`], searching the neighbours in `delay`, when given: false nearest neighbours' last
/// search over the delay embedding of `x` with the lag given alongside (see
/// [`super::fnn::emb_dim_fnn_index`]), used when that lag is the one used here and its index
/// has at least `emb_dim` coordinates and enough rows (its neighbours are taken where they are
/// admitted, see [`super::neighbours::NeighbourIndex::nearest_all`]); the result is the same
/// either way.
pub(crate) fn lyap_r_with(
    x: &[f64],
    params: &ValidRosensteinParams,
    delay: Option<(&FnnSearch, usize)>,
) -> Result<RosensteinResult, NonlinearError> {
    check_series(x)?;
    let n = x.len();
    let min_tsep = match params.min_tsep {
        Some(t) => t,
        None => default_min_tsep(x),
    };
    let lag = match params.lag {
        Some(l) => l,
        None => default_lag(x, params, min_tsep),
    };
    let needed = lyap_r_len(params.emb_dim, lag, params.trajectory_len, min_tsep);
    if n < needed {
        return Err(NonlinearError::TooShortRosenstein {
            len: n,
            emb_dim: params.emb_dim,
            lag,
            min_tsep,
            trajectory_len: params.trajectory_len,
            needed,
        });
    }
    let orbit = delay_embed_flat(x, params.emb_dim, lag)?;
    let index = delay.and_then(|(ix, ix_lag)| (ix_lag == lag).then_some(ix));
    let mut res = rosenstein_core(
        &orbit,
        params.emb_dim,
        min_tsep,
        params.trajectory_len,
        params.tau,
        params.fit_offset,
        index,
    )?;
    if params.fit == Fit::Ransac {
        let xs: Vec<f64> = res.ks[params.fit_offset..]
            .iter()
            .map(|&k| k as f64)
            .collect();
        let (slope, intercept) =
            super::ransac::ransac_line_fit(&xs, &res.divergence[params.fit_offset..]);
        res.slope = slope;
        res.intercept = intercept;
        res.exponent = slope / params.tau;
    }
    res.lag = Some(lag);
    Ok(res)
}

/// Rosenstein's method on an already reconstructed orbit, e.g. a
/// multi-channel state from [`super::state_embed`] (rows = time, columns =
/// state variables) or a delay embedding from [`super::delay_embed`].
///
/// `min_tsep`, `trajectory_len` are in samples, `tau_s` in seconds; the
/// divergence is followed for `trajectory_len` rows and the line fitted after
/// `fit_offset` steps, exactly as in [`lyap_r`] (which calls this after the
/// embedding). The result reports `lag: None`.
pub fn lyap_r_orbit(
    orbit: ndarray::ArrayView2<'_, f64>,
    min_tsep: usize,
    trajectory_len: usize,
    tau_s: f64,
    fit_offset: usize,
) -> Result<RosensteinResult, NonlinearError> {
    let (m, dim) = orbit.dim();
    if m == 0 || dim == 0 {
        return Err(NonlinearError::Empty);
    }
    let flat: Vec<f64> = orbit.iter().copied().collect();
    if let Some((index, &value)) = flat.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(NonlinearError::NonFinite { index, value });
    }
    if flat.iter().all(|&v| v == flat[0]) {
        return Err(NonlinearError::Constant {
            len: m,
            value: flat[0],
        });
    }
    RosensteinParams::default()
        .emb_dim(dim)
        .tau(tau_s)
        .trajectory_len(trajectory_len)
        .fit_offset(fit_offset)
        .check()?;
    let needed = lyap_r_len(1, 1, trajectory_len, min_tsep);
    if m < needed {
        return Err(NonlinearError::TooShortRosenstein {
            len: m,
            emb_dim: dim,
            lag: 0,
            min_tsep,
            trajectory_len,
            needed,
        });
    }
    rosenstein_core(
        &flat,
        dim,
        min_tsep,
        trajectory_len,
        tau_s,
        fit_offset,
        None,
    )
}

/// Core of Rosenstein's method on a row-major orbit (`m × dim`). Callers have
/// checked `m ≥ trajectory_len + 2·min_tsep + 1` (nolds' `ntraj ≥ min_traj`). `index`, when
/// given, is a search whose index holds the orbit's rows as the prefixes of its own (the
/// neighbours are searched there if it has `dim` coordinates and enough rows).
pub(crate) fn rosenstein_core(
    orbit: &[f64],
    dim: usize,
    min_tsep: usize,
    trajectory_len: usize,
    tau: f64,
    fit_offset: usize,
    index: Option<&FnnSearch>,
) -> Result<RosensteinResult, NonlinearError> {
    let m = orbit.len() / dim;
    let ntraj = m + 1 - trajectory_len;
    let nb = match index {
        Some(s) if s.index.dims() >= dim && s.index.len() >= ntraj => {
            // false nearest neighbours' answers over the same coordinates, with a window no
            // wider and all the index's rows, are the answers wherever admitted here (on a gait
            // leg two rows in three: the nearest row is usually on another stride)
            let known =
                (s.index.dims() == dim && s.min_tsep <= min_tsep).then_some(&s.neighbours[..]);
            s.index.nearest_all(dim, min_tsep, ntraj, None, known)
        }
        _ => nearest_outside_window(&orbit[..ntraj * dim], dim, min_tsep, None),
    };
    let div = divergence(orbit, dim, &nb, trajectory_len);
    let (ks, divergence): (Vec<usize>, Vec<f64>) = div
        .iter()
        .enumerate()
        .filter(|(_, v)| v.is_finite())
        .map(|(k, &v)| (k, v))
        .unzip();
    if ks.len() < fit_offset.saturating_add(2) {
        return Err(NonlinearError::DegenerateFit {
            finite: ks.len(),
            fit_offset,
        });
    }
    let xs: Vec<f64> = ks[fit_offset..].iter().map(|&k| k as f64).collect();
    let (slope, intercept) = line_fit(&xs, &divergence[fit_offset..]);
    Ok(RosensteinResult {
        exponent: slope / tau,
        emb_dim: dim,
        lag: None,
        min_tsep,
        trajectory_len,
        tau,
        ks,
        divergence,
        slope,
        intercept,
    })
}
