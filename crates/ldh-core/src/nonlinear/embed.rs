//! Phase-space reconstruction: delay and state embeddings, and the delay from the average
//! mutual information (Fraser & Swinney 1986) or the autocorrelation; the embedding dimension
//! from false nearest neighbours is in [`super::fnn`].

use ndarray::Array2;

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
pub(super) fn delay_embed_into(x: &[f64], emb_dim: usize, lag: usize, out: &mut Vec<f64>) {
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
