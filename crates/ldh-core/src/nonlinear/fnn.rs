//! Embedding dimension by false nearest neighbours (Kennel, Brown & Abarbanel 1992, Phys. Rev.
//! A 45:3403): for each dimension, every delay vector's exact nearest neighbour (a
//! [`super::window_tree::WindowTree`] per dimension), and the fraction of those neighbours that
//! separate when the next delay coordinate is added.

use serde::{Deserialize, Serialize};

use super::embed::delay_embed_into;
use super::neighbours::{
    delay_index, nearest_outside_window, nn_brute, nn_sorted_1d, np_euclidean, total_order,
    NeighbourIndex,
};
use super::{check_series, invalid, NonlinearError};

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
