//! Local dynamic stability: the maximum Lyapunov exponent (paper §3.3).
//!
//! The paper quantifies gait stability with the largest Lyapunov exponent of
//! the reconstructed state space. This module provides:
//!
//! * **Phase-space reconstruction** ([`delay_embed`], [`state_embed`]): the
//!   delay is chosen at the first minimum of the average mutual information
//!   (Fraser & Swinney 1986, [`lag_ami`]) or, optionally, where the
//!   autocorrelation falls below 1/e ([`lag_acf`]); the embedding dimension by
//!   false nearest neighbours (Kennel, Brown & Abarbanel 1992, [`emb_dim_fnn`]).
//!   The paper "randomly selects" both; we do not, and the values used are
//!   returned with every result.
//! * **Rosenstein's method** ([`lyap_r`]; Rosenstein, Collins & De Luca 1993,
//!   Physica D 65:117–134) and **Eckmann's method** ([`lyap_e`]; Eckmann,
//!   Kamphorst, Ruelle & Ciliberto 1986, Phys. Rev. A 34:4971–4979), with the
//!   parameters and the exact semantics of `nolds.lyap_r(..., fit="poly")` and
//!   `nolds.lyap_e` (nolds 0.6.2), checked against nolds to 1e-6 relative.
//! * **Gait use** ([`gait_sta`]): the short-term local divergence exponent λs
//!   of a gait signal (Theiler window of one stride, fit over the first half
//!   stride), in 1/s and per stride.
//!
//! Nearest neighbours are exact, found through a k-d tree that skips the
//! Theiler window (Euclidean: Rosenstein, FNN) or a `kiddo` k-d tree
//! (Chebyshev: Eckmann); no O(N²) distance matrix; see `docs/lyapunov.md` for
//! the algorithms, defaults, differences from nolds and measured speed.

mod divergence;
mod eckmann;
mod embed;
mod fft;
mod fnn;
mod gait;
mod linalg;
mod neighbours;
mod npsum;
mod ransac;
mod rosenstein;
mod window_tree;

#[cfg(test)]
mod tests;

pub use eckmann::{lyap_e, lyap_e_len, EckmannParams, EckmannResult, ValidEckmannParams};
pub use embed::{delay_embed, lag_acf, lag_ami, state_embed};
pub use fnn::{emb_dim_fnn, FnnParams, FnnResult, FnnRows};
pub use gait::{gait_sta, GaitSta, GaitStaParams, LagRule, TimeNormalisation};
pub use rosenstein::{
    check_orbit_size, lyap_r, lyap_r_len, lyap_r_orbit, Fit, RosensteinParams, RosensteinResult,
    ValidRosensteinParams, MAX_ORBIT_VALUES,
};

/// Errors of the nonlinear (Lyapunov exponent) module. Every variant carries the
/// offending values; no function of this module panics on user input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NonlinearError {
    /// The input series is empty.
    #[error("input series is empty")]
    Empty,
    /// The input contains a NaN or infinite sample.
    #[error("input contains a non-finite value ({value}) at index {index}")]
    NonFinite {
        /// index of the first non-finite sample
        index: usize,
        /// the offending value
        value: f64,
    },
    /// The input series is constant: no dynamics to reconstruct.
    #[error("input series of {len} samples is constant (value {value}): no dynamics to analyse")]
    Constant {
        /// number of samples
        len: usize,
        /// the constant value
        value: f64,
    },
    /// A parameter is out of its valid range.
    #[error("invalid parameter {name} = {value}: {reason}")]
    InvalidParameter {
        /// parameter name
        name: &'static str,
        /// offending value, formatted
        value: String,
        /// what is required
        reason: String,
    },
    /// Rosenstein: the series is shorter than nolds' `lyap_r_len`.
    #[error(
        "series of {len} samples is too short for emb_dim={emb_dim}, lag={lag}, \
         min_tsep={min_tsep}, trajectory_len={trajectory_len}: Rosenstein needs at least \
         {needed} samples (nolds lyap_r_len)"
    )]
    TooShortRosenstein {
        /// number of samples (orbit rows + (emb_dim−1)·lag for an orbit input)
        len: usize,
        /// embedding dimension
        emb_dim: usize,
        /// embedding lag in samples
        lag: usize,
        /// Theiler window in samples
        min_tsep: usize,
        /// divergence trajectory length in samples
        trajectory_len: usize,
        /// required number of samples
        needed: usize,
    },
    /// Eckmann: the series is shorter than nolds' `lyap_e_len`.
    #[error(
        "series of {len} samples is too short for emb_dim={emb_dim}, matrix_dim={matrix_dim}, \
         min_nb={min_nb}, min_tsep={min_tsep}: Eckmann needs at least {needed} samples \
         (nolds lyap_e_len)"
    )]
    TooShortEckmann {
        /// number of samples
        len: usize,
        /// embedding dimension
        emb_dim: usize,
        /// Jacobian matrix dimension
        matrix_dim: usize,
        /// minimal number of neighbours
        min_nb: usize,
        /// Theiler window in samples
        min_tsep: usize,
        /// required number of samples
        needed: usize,
    },
    /// A series too short for an embedding or estimation step other than the
    /// two Lyapunov methods (delay embedding, AMI, FNN, resampling).
    #[error("series of {len} samples is too short for {what}: needs at least {needed}")]
    TooShort {
        /// number of samples
        len: usize,
        /// which step
        what: String,
        /// required number of samples
        needed: usize,
    },
    /// Channels of a multi-dimensional state have different lengths.
    #[error("state channel {channel} has {len} samples, channel 0 has {expected}")]
    ChannelLength {
        /// channel index
        channel: usize,
        /// its length
        len: usize,
        /// length of channel 0
        expected: usize,
    },
    /// The line fit of the divergence curve is impossible (fewer than two
    /// finite points after `fit_offset`).
    #[error("divergence curve has {finite} finite points after fit_offset={fit_offset}: a line needs at least 2")]
    DegenerateFit {
        /// finite points available to the fit
        finite: usize,
        /// points skipped at the start
        fit_offset: usize,
    },
}

/// Returns an error for an empty, non-finite or constant series.
pub(crate) fn check_series(x: &[f64]) -> Result<(), NonlinearError> {
    if x.is_empty() {
        return Err(NonlinearError::Empty);
    }
    if let Some((index, &value)) = x.iter().enumerate().find(|(_, v)| !v.is_finite()) {
        return Err(NonlinearError::NonFinite { index, value });
    }
    if x.iter().all(|&v| v == x[0]) {
        return Err(NonlinearError::Constant {
            len: x.len(),
            value: x[0],
        });
    }
    Ok(())
}

pub(crate) fn invalid(
    name: &'static str,
    value: impl ToString,
    reason: impl ToString,
) -> NonlinearError {
    NonlinearError::InvalidParameter {
        name,
        value: value.to_string(),
        reason: reason.to_string(),
    }
}
