//! Phase-space reconstruction: delay and state embeddings, the delay from the
//! average mutual information (Fraser & Swinney 1986) or the autocorrelation,
//! and the embedding dimension from false nearest neighbours (Kennel, Brown &
//! Abarbanel 1992).

use ndarray::Array2;
use serde::{Deserialize, Serialize};

use super::neighbours::{
    delay_index, nearest_outside_window, nn_brute, nn_sorted_1d, np_euclidean, total_order,
    NeighbourIndex,
};
use super::{check_series, invalid, NonlinearError};

/// Row-major delay embedding (`m × emb_dim`, `m = n − (emb_dim − 1)·lag`),
/// as nolds' `delay_embedding`.
pub(crate) fn delay_embed_flat(
    x: &[f64],
    emb_dim: usize,
    lag: usize,
) -> Result<Vec<f64>, NonlinearError> {
    if emb_dim == 0 {
        return Err(invalid("emb_dim", emb_dim, "must be at least 1"));
    }
    if lag == 0 {
        return Err(invalid("lag", lag, "must be at least 1 sample"));
    }
    let span = (emb_dim - 1).saturating_mul(lag).saturating_add(1);
    if x.len() < span {
        return Err(NonlinearError::TooShort {
            len: x.len(),
            what: format!("a delay embedding with emb_dim={emb_dim}, lag={lag}"),
            needed: span,
        });
    }
    let mut out = Vec::new();
    delay_embed_into(x, emb_dim, lag, &mut out);
    Ok(out)
}

/// [`delay_embed_flat`] into a reused buffer (cleared first); the caller has checked
/// `emb_dim ≥ 1`, `lag ≥ 1` and `x.len() ≥ (emb_dim − 1)·lag + 1`.
fn delay_embed_into(x: &[f64], emb_dim: usize, lag: usize, out: &mut Vec<f64>) {
    let m = x.len() + 1 - ((emb_dim - 1) * lag + 1);
    out.clear();
    out.reserve(m * emb_dim);
    for i in 0..m {
        for d in 0..emb_dim {
            out.push(x[i + d * lag]);
        }
    }
}

/// Delay embedding of a 1-D series: row `i` is
/// `[x_i, x_{i+lag}, …, x_{i+(emb_dim−1)·lag}]`, `n − (emb_dim − 1)·lag` rows
/// (nolds `delay_embedding`). `lag` in samples.
pub fn delay_embed(x: &[f64], emb_dim: usize, lag: usize) -> Result<Array2<f64>, NonlinearError> {
    let flat = delay_embed_flat(x, emb_dim, lag)?;
    let m = flat.len() / emb_dim;
    Array2::from_shape_vec((m, emb_dim), flat).map_err(|e| invalid("emb_dim", emb_dim, e))
}

/// Embedding of a multi-dimensional state without delay: row `t` is
/// `[c_0[t], c_1[t], …]` (one column per channel, e.g. the three gyroscope
/// axes). All channels must have the same, non-zero length and finite values.
pub fn state_embed(channels: &[&[f64]]) -> Result<Array2<f64>, NonlinearError> {
    let first = channels.first().ok_or(NonlinearError::Empty)?;
    let n = first.len();
    if n == 0 {
        return Err(NonlinearError::Empty);
    }
    for (c, ch) in channels.iter().enumerate() {
        if ch.len() != n {
            return Err(NonlinearError::ChannelLength {
                channel: c,
                len: ch.len(),
                expected: n,
            });
        }
        if let Some((i, &v)) = ch.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(NonlinearError::NonFinite { index: i, value: v });
        }
    }
    Ok(Array2::from_shape_fn((n, channels.len()), |(t, c)| {
        channels[c][t]
    }))
}

/// Reused buffers of [`lag_ami`]: the bin of every sample (computed once), the joint histogram,
/// and the two marginals, kept for the current lag and updated from lag to lag.
struct AmiBuffers {
    bins: usize,
    bin: Vec<usize>,
    joint: Vec<u32>,
    pa: Vec<u32>,
    pb: Vec<u32>,
    /// The lag the marginals are for (0: the histogram of all samples).
    tau: usize,
}

impl AmiBuffers {
    fn new(x: &[f64], bins: usize, lo: f64, width: f64) -> Self {
        let bin = |v: f64| (((v - lo) / width) as usize).min(bins - 1);
        let bin: Vec<usize> = x.iter().map(|&v| bin(v)).collect();
        let mut all = vec![0u32; bins];
        for &b in &bin {
            all[b] += 1;
        }
        AmiBuffers {
            bins,
            bin,
            joint: vec![0; bins * bins],
            pa: all.clone(),
            pb: all,
            tau: 0,
        }
    }

    /// Average mutual information `I(τ)` (nats) between `x_t` and `x_{t+τ}`, for increasing `τ`.
    fn ami(&mut self, tau: usize) -> f64 {
        let bins = self.bins;
        let n = self.bin.len();
        let m = n - tau;
        // marginals of the m pairs: samples 0..m and tau..n; from the previous lag's, one
        // sample fewer at each end per step (the same counts as counting again)
        for t in self.tau..tau {
            self.pa[self.bin[n - 1 - t]] -= 1;
            self.pb[self.bin[t]] -= 1;
        }
        self.tau = tau;
        self.joint.fill(0);
        for (&a, &b) in self.bin[..m].iter().zip(&self.bin[tau..]) {
            self.joint[a * bins + b] += 1;
        }
        let mf = m as f64;
        let mut s = 0.0;
        for a in 0..bins {
            for b in 0..bins {
                let c = self.joint[a * bins + b];
                if c > 0 {
                    let pab = c as f64 / mf;
                    s += pab * (pab / (self.pa[a] as f64 / mf * self.pb[b] as f64 / mf)).ln();
                }
            }
        }
        s
    }
}

/// Delay (samples) at the first local minimum of the average mutual
/// information (Fraser & Swinney 1986), the first `τ ≥ 1` with
/// `I(τ) ≤ I(τ+1)`, searched up to `max_lag`.
///
/// Histogram estimator: `bins` equal-width bins over `[min x, max x]`
/// (`None`: Sturges' rule `⌈log2 n⌉ + 1`); the marginals are the histograms
/// of the `n − τ` paired samples. Errors if no minimum exists up to `max_lag`
/// or the series is too short (`n < max_lag + 2·bins`).
pub fn lag_ami(x: &[f64], max_lag: usize, bins: Option<usize>) -> Result<usize, NonlinearError> {
    check_series(x)?;
    let n = x.len();
    let bins = bins.unwrap_or_else(|| (n as f64).log2().ceil() as usize + 1);
    if bins < 2 {
        return Err(invalid("bins", bins, "must be at least 2"));
    }
    if max_lag == 0 {
        return Err(invalid("max_lag", max_lag, "must be at least 1"));
    }
    if bins > 4096 {
        return Err(invalid("bins", bins, "at most 4096 histogram bins"));
    }
    let needed = max_lag.saturating_add(1).saturating_add(2 * bins);
    if n < needed {
        return Err(NonlinearError::TooShort {
            len: n,
            what: format!("the average mutual information up to lag {max_lag} with {bins} bins"),
            needed,
        });
    }
    let lo = x.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = x.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let width = (hi - lo) / bins as f64;
    let mut buf = AmiBuffers::new(x, bins, lo, width);
    let mut prev = buf.ami(1);
    for tau in 1..max_lag {
        let next = buf.ami(tau + 1);
        if prev <= next {
            return Ok(tau);
        }
        prev = next;
    }
    Err(invalid(
        "max_lag",
        max_lag,
        "the average mutual information has no local minimum up to this lag",
    ))
}

/// Delay (samples) at which the autocorrelation (mean removed, normalised to
/// 1 at lag 0) first drops to `1/e` or below, searched up to `max_lag`.
pub fn lag_acf(x: &[f64], max_lag: usize) -> Result<usize, NonlinearError> {
    check_series(x)?;
    let n = x.len();
    if max_lag == 0 || max_lag >= n {
        return Err(invalid("max_lag", max_lag, format!("must be in 1..{n}")));
    }
    let mean = x.iter().sum::<f64>() / n as f64;
    let c: Vec<f64> = x.iter().map(|v| v - mean).collect();
    let c0: f64 = c.iter().map(|v| v * v).sum();
    let thr = c0 / std::f64::consts::E;
    for tau in 1..=max_lag {
        let r: f64 = c[..n - tau].iter().zip(&c[tau..]).map(|(a, b)| a * b).sum();
        if r <= thr {
            return Ok(tau);
        }
    }
    Err(invalid(
        "max_lag",
        max_lag,
        "the autocorrelation does not fall to 1/e up to this lag",
    ))
}

/// Parameters of the false-nearest-neighbour test ([`emb_dim_fnn`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct FnnParams {
    /// Largest embedding dimension tried (default 10).
    pub max_dim: usize,
    /// Kennel's first criterion `R_tol`: a neighbour is false when the added
    /// coordinate's distance exceeds `r_tol` times the distance in `d`
    /// dimensions (default 15).
    pub r_tol: f64,
    /// Kennel's second criterion `A_tol`: a neighbour is false when its
    /// distance in `d + 1` dimensions exceeds `a_tol` times the standard
    /// deviation of the series (default 2).
    pub a_tol: f64,
    /// The chosen dimension is the first with a false-neighbour fraction
    /// below this value (default 0.01 = 1 %).
    pub threshold: f64,
    /// Theiler window in samples for the neighbour search (`|i − j| >
    /// min_tsep`; default 0 = only the point itself is excluded, as Kennel).
    pub min_tsep: usize,
}

impl Default for FnnParams {
    fn default() -> Self {
        Self {
            max_dim: 10,
            r_tol: 15.0,
            a_tol: 2.0,
            threshold: 0.01,
            min_tsep: 0,
        }
    }
}

/// Result of [`emb_dim_fnn`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FnnResult {
    /// Chosen embedding dimension: the first `d` whose false-neighbour
    /// fraction is below the threshold, or the `d` with the smallest fraction
    /// if none is (then `converged` is false).
    pub emb_dim: usize,
    /// False-neighbour fraction for `d = 1..=fractions.len()`.
    pub fractions: Vec<f64>,
    /// Whether a fraction fell below the threshold.
    pub converged: bool,
}

/// Embedding dimension by false nearest neighbours (Kennel, Brown & Abarbanel
/// 1992, Phys. Rev. A 45:3403). For each `d = 1..=max_dim`, every vector of
/// the `d`-dimensional delay embedding (rows `0..n − d·lag`) gets its exact
/// Euclidean nearest neighbour (k-d tree, Theiler window `min_tsep`); the pair
/// is false when `|x_{i+d·lag} − x_{j+d·lag}| / R_d > r_tol` or
/// `R_{d+1} / σ_x > a_tol`. Pairs at distance 0 are skipped. `lag` in samples.
pub fn emb_dim_fnn(x: &[f64], lag: usize, params: &FnnParams) -> Result<FnnResult, NonlinearError> {
    emb_dim_fnn_index(x, lag, params).map(|(r, _)| r)
}

/// [`emb_dim_fnn`], and the last dimension's search (its neighbour index, a delay embedding of
/// `x` with `lag` (see [`delay_index`]), and the neighbours found) for Rosenstein's method to
/// reuse.
pub(crate) fn emb_dim_fnn_index(
    x: &[f64],
    lag: usize,
    params: &FnnParams,
) -> Result<(FnnResult, Option<FnnSearch>), NonlinearError> {
    check_series(x)?;
    if lag == 0 {
        return Err(invalid("lag", lag, "must be at least 1 sample"));
    }
    if params.max_dim == 0 {
        return Err(invalid("max_dim", params.max_dim, "must be at least 1"));
    }
    for (name, v) in [
        ("r_tol", params.r_tol),
        ("a_tol", params.a_tol),
        ("threshold", params.threshold),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(invalid(name, v, "must be finite and positive"));
        }
    }
    let n = x.len();
    let needed = params
        .max_dim
        .saturating_mul(lag)
        .saturating_add(params.min_tsep.saturating_mul(2))
        .saturating_add(2);
    if n < needed {
        return Err(NonlinearError::TooShort {
            len: n,
            what: format!(
                "false nearest neighbours up to dimension {} with lag {lag}, min_tsep {}",
                params.max_dim, params.min_tsep
            ),
            needed,
        });
    }
    let mean = x.iter().sum::<f64>() / n as f64;
    let sd = (x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n as f64).sqrt();
    let mut fractions = Vec::with_capacity(params.max_dim);
    // one index per dimension, over exactly its coordinates (a tree split on coordinates a
    // query does not measure cannot end its searches early); the loop stops at the first
    // dimension that meets the criterion, and its index serves Rosenstein's search
    let mut index: Option<Box<dyn NeighbourIndex>> = None;
    // each dimension's neighbours seed the next dimension's search (a true neighbour stays near)
    let mut prev_nb: Vec<usize> = Vec::new();
    // one sort of the series gives every dimension's order on every axis (empty, and the
    // searches exact scans, beyond u32::MAX samples)
    let x_order = if n <= u32::MAX as usize {
        total_order(x)
    } else {
        Vec::new()
    };
    for d in 1..=params.max_dim {
        let rows = n - d * lag;
        // rows ≥ 2·min_tsep + 2 ≥ 2 by the length check above
        let nb = fnn_neighbours((x, &x_order), lag, d, rows, params, &mut index, &prev_nb);
        let mut false_nb = 0usize;
        let mut counted = 0usize;
        for (i, &j) in nb.iter().enumerate() {
            // the distance of the d-dimensional rows, as the embedding's np_euclidean
            let rd = delay_dist(x, lag, d, i, j);
            if rd == 0.0 {
                continue;
            }
            counted += 1;
            let extra = (x[i + d * lag] - x[j + d * lag]).abs();
            let rd1 = (rd * rd + extra * extra).sqrt();
            if extra / rd > params.r_tol || rd1 / sd > params.a_tol {
                false_nb += 1;
            }
        }
        prev_nb = nb;
        fractions.push(if counted == 0 {
            1.0
        } else {
            false_nb as f64 / counted as f64
        });
        if fractions[d - 1] < params.threshold {
            let result = FnnResult {
                emb_dim: d,
                fractions,
                converged: true,
            };
            return Ok((result, FnnSearch::of(index, prev_nb, params.min_tsep)));
        }
    }
    let best = fractions
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .map(|(i, _)| i + 1)
        .unwrap_or(params.max_dim);
    let result = FnnResult {
        emb_dim: best,
        fractions,
        converged: false,
    };
    Ok((result, FnnSearch::of(index, prev_nb, params.min_tsep)))
}

/// The last search of [`emb_dim_fnn_index`], for Rosenstein's method to reuse: the neighbour
/// index over the delay embedding (its `dims()` coordinates, the lag of the call), and every
/// row's neighbour over all those coordinates and all the index's rows, with Theiler window
/// `min_tsep`.
pub(crate) struct FnnSearch {
    pub(crate) index: Box<dyn NeighbourIndex>,
    pub(crate) neighbours: Vec<usize>,
    pub(crate) min_tsep: usize,
}

impl FnnSearch {
    fn of(
        index: Option<Box<dyn NeighbourIndex>>,
        neighbours: Vec<usize>,
        min_tsep: usize,
    ) -> Option<Self> {
        let index = index?;
        // the index was built for the dimension whose neighbours these are, over its rows
        (neighbours.len() == index.len()).then_some(FnnSearch {
            index,
            neighbours,
            min_tsep,
        })
    }
}

/// [`np_euclidean`] of rows `i` and `j` of the `d`-dimensional delay embedding of `x`, read in
/// place below eight dimensions (numpy's plain loop), gathered from eight on.
fn delay_dist(x: &[f64], lag: usize, d: usize, i: usize, j: usize) -> f64 {
    if d < 8 {
        let mut s = 0.0;
        for c in 0..d {
            let t = x[i + c * lag] - x[j + c * lag];
            s += t * t;
        }
        s.sqrt()
    } else {
        let a: Vec<f64> = (0..d).map(|c| x[i + c * lag]).collect();
        let b: Vec<f64> = (0..d).map(|c| x[j + c * lag]).collect();
        np_euclidean(&a, &b)
    }
}

/// The nearest neighbour of each of the first `rows` rows of the `d`-dimensional delay
/// embedding (Theiler window `params.min_tsep`): sorted values in one dimension, else a new
/// `index` over the `d` coordinates (left in `index`); an exact scan above 10 dimensions.
fn fnn_neighbours(
    (x, x_order): (&[f64], &[u32]),
    lag: usize,
    d: usize,
    rows: usize,
    params: &FnnParams,
    index: &mut Option<Box<dyn NeighbourIndex>>,
    prev_nb: &[usize],
) -> Vec<usize> {
    if d == 1 && params.min_tsep == 0 {
        if x_order.len() != x.len() {
            return nearest_outside_window(&x[..rows], 1, 0, None);
        }
        // the series' order, restricted to the rows, is the rows' order
        let order: Vec<u32> = x_order
            .iter()
            .copied()
            .filter(|&t| (t as usize) < rows)
            .collect();
        return nn_sorted_1d(&x[..rows], &order);
    }
    *index = delay_index(x, lag, d, rows, x_order);
    match index {
        Some(ix) => ix.nearest_all(d, params.min_tsep, rows, Some(prev_nb), None),
        None => {
            let mut pts = Vec::new();
            delay_embed_into(&x[..rows + (d - 1) * lag], d, lag, &mut pts);
            nn_brute(&pts, d, params.min_tsep)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The marginals carried from lag to lag are the counts of the pairs of each lag: every
    /// AMI value equals the one from histograms counted afresh, bit for bit.
    #[test]
    fn ami_with_carried_marginals_equals_fresh_counts() {
        let x: Vec<f64> = (0..2_000)
            .map(|i| (i as f64 * 0.071).sin() + 0.3 * (i as f64 * 0.29).cos())
            .collect();
        let (lo, hi) = (-1.3, 1.3);
        let bins = 12;
        let width = (hi - lo) / bins as f64;
        let mut carried = AmiBuffers::new(&x, bins, lo, width);
        for tau in 1..60 {
            let mut fresh = AmiBuffers::new(&x, bins, lo, width);
            let counted = {
                // the marginals of lag tau counted directly
                fresh.pa.fill(0);
                fresh.pb.fill(0);
                let m = x.len() - tau;
                for t in 0..m {
                    fresh.pa[fresh.bin[t]] += 1;
                    fresh.pb[fresh.bin[t + tau]] += 1;
                }
                fresh.tau = tau;
                fresh.ami(tau)
            };
            assert_eq!(carried.ami(tau).to_bits(), counted.to_bits(), "lag {tau}");
        }
    }
}
