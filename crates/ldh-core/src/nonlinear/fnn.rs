//! Embedding dimension by false nearest neighbours (Kennel, Brown & Abarbanel 1992, Phys. Rev.
//! A 45:3403): for each dimension, every delay vector's exact nearest neighbour (a
//! [`super::window_tree::WindowTree`] per dimension), and the fraction of those neighbours that
//! separate when the next delay coordinate is added.

use serde::{Deserialize, Serialize};

use super::embed::delay_embed_into;
use super::neighbours::{
    delay_index, nearest_outside_window, nn_brute, np_euclidean, total_order, NeighbourIndex,
    Sorted1d,
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
    /// How many rows of each dimension are searched (default
    /// [`FnnRows::UntilRejected`]: the chosen dimension is the same as with
    /// [`FnnRows::All`], the rejected dimensions' fractions are lower bounds).
    pub rows: FnnRows,
}

/// How many rows of each dimension [`emb_dim_fnn`] searches.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FnnRows {
    /// Search a dimension's rows block by block and stop once more than
    /// `threshold` of *all* its rows are known to be false neighbours: the
    /// dimension is then rejected whatever the other rows hold. Its fraction
    /// is that lower bound (false neighbours found ÷ all rows, above the
    /// threshold). The chosen dimension, `converged` and the neighbours
    /// handed to Rosenstein's method are those of [`FnnRows::All`]; when no
    /// dimension meets the threshold, every fraction is recomputed over all
    /// rows to pick the smallest. On a 30 s gait leg this searches ≈ 3 % of
    /// dimension 2's rows and ≈ 10 % of dimension 3's (docs/benchmarks.md).
    #[default]
    UntilRejected,
    /// Search every row of every dimension tried: every fraction is exact.
    All,
}

impl Default for FnnParams {
    fn default() -> Self {
        Self {
            max_dim: 10,
            r_tol: 15.0,
            a_tol: 2.0,
            threshold: 0.01,
            min_tsep: 0,
            rows: FnnRows::UntilRejected,
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
    /// False-neighbour fraction for `d = 1..=fractions.len()` (with
    /// [`FnnRows::UntilRejected`], a lower bound above the threshold for a
    /// dimension rejected before all its rows were searched).
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
    // one sort of the series gives every dimension's order on every axis (empty, and the
    // searches exact scans, beyond u32::MAX samples)
    let order = if n <= u32::MAX as usize {
        total_order(x)
    } else {
        Vec::new()
    };
    let series = FnnSeries {
        x,
        order: &order,
        lag,
        sd,
    };
    let (result, search, cut_short) = fnn_dims(&series, params);
    if cut_short && !result.converged {
        // the smallest fraction is chosen: every fraction must be exact
        let all = FnnParams {
            rows: FnnRows::All,
            ..params.clone()
        };
        let (result, search, _) = fnn_dims(&series, &all);
        return Ok((result, search));
    }
    Ok((result, search))
}

/// The series of [`emb_dim_fnn_index`]: its values, their [`total_order`] (empty beyond
/// `u32::MAX` samples), the delay, and the standard deviation of Kennel's second criterion.
struct FnnSeries<'a> {
    x: &'a [f64],
    order: &'a [u32],
    lag: usize,
    sd: f64,
}

/// Dimensions `1..=max_dim` until one meets the criterion: the result, the last dimension's
/// search, and whether a dimension was rejected before all its rows were searched.
fn fnn_dims(s: &FnnSeries, params: &FnnParams) -> (FnnResult, Option<FnnSearch>, bool) {
    let mut fractions = Vec::with_capacity(params.max_dim);
    // one index per dimension, over exactly its coordinates (a tree split on coordinates a
    // query does not measure cannot end its searches early); the loop stops at the first
    // dimension that meets the criterion, and its index serves Rosenstein's search
    let mut index: Option<Box<dyn NeighbourIndex>> = None;
    // each dimension's neighbours seed the next dimension's search (a true neighbour stays near)
    let mut prev_nb: Vec<usize> = Vec::new();
    let mut cut_short = false;
    for d in 1..=params.max_dim {
        let (nb, fraction, complete) = fnn_dimension(s, d, params, &mut index, &prev_nb);
        cut_short |= !complete;
        prev_nb = nb;
        fractions.push(fraction);
        // a dimension cut short has a fraction above the threshold: this one is complete
        if fraction < params.threshold {
            let result = FnnResult {
                emb_dim: d,
                fractions,
                converged: true,
            };
            return (
                result,
                FnnSearch::of(index, prev_nb, params.min_tsep),
                cut_short,
            );
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
    (
        result,
        FnnSearch::of(index, prev_nb, params.min_tsep),
        cut_short,
    )
}

/// Rows searched before dimension `d` may first be rejected; later blocks grow by a quarter of
/// the rows searched, so a rejection searches at most ≈ 25 % more rows than it needed.
const FNN_BLOCK: usize = 64;

/// Dimension `d`'s nearest neighbours (rows `0..n − d·lag`) and false-neighbour fraction, and
/// whether every row was searched. With [`FnnRows::UntilRejected`] the rows are searched block
/// by block and the search stops once more than `threshold` of all the rows are known false
/// (the fraction is then that lower bound and the neighbours cover the rows searched).
fn fnn_dimension(
    s: &FnnSeries,
    d: usize,
    params: &FnnParams,
    index: &mut Option<Box<dyn NeighbourIndex>>,
    prev_nb: &[usize],
) -> (Vec<usize>, f64, bool) {
    let (x, lag) = (s.x, s.lag);
    // rows ≥ 2·min_tsep + 2 ≥ 2 by the length check of emb_dim_fnn_index
    let rows = x.len() - d * lag;
    let search = dim_search(s, d, rows, params, index);
    let (mut nb, ix, sorted) = match search {
        DimSearch::Scanned(nb) => (nb, None, None),
        DimSearch::Sorted(sorted) => (Vec::with_capacity(rows), None, Some(sorted)),
        DimSearch::Index => (Vec::with_capacity(rows), index.as_deref(), None),
    };
    let early = params.rows == FnnRows::UntilRejected;
    let (mut false_nb, mut counted, mut done) = (0usize, 0usize, 0usize);
    while done < rows {
        let block = if early {
            (done / 4).max(FNN_BLOCK).min(rows - done)
        } else {
            rows - done
        };
        if let Some(ix) = ix {
            let search = (d, params.min_tsep, rows);
            let prev = nb.last().copied();
            nb.extend(ix.nearest_rows(search, done..done + block, prev, Some(prev_nb), None));
        } else if let Some(sorted) = &sorted {
            nb.extend((done..done + block).map(|i| sorted.nearest(i)));
        }
        for (i, &j) in nb.iter().enumerate().take(done + block).skip(done) {
            // the distance of the d-dimensional rows, as the embedding's np_euclidean
            let rd = delay_dist(x, lag, d, i, j);
            if rd == 0.0 {
                continue;
            }
            counted += 1;
            let extra = (x[i + d * lag] - x[j + d * lag]).abs();
            let rd1 = (rd * rd + extra * extra).sqrt();
            if extra / rd > params.r_tol || rd1 / s.sd > params.a_tol {
                false_nb += 1;
            }
        }
        done += block;
        // false/rows > threshold (strictly, so the rounding of the division cannot decide)
        // gives false_final/counted_final > threshold: rejected whatever the other rows hold
        let bound = false_nb as f64 / rows as f64;
        if early && done < rows && bound > params.threshold {
            return (nb, bound, false);
        }
    }
    let fraction = if counted == 0 {
        1.0
    } else {
        false_nb as f64 / counted as f64
    };
    (nb, fraction, true)
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

/// How [`fnn_dimension`] finds the nearest neighbours of dimension `d`.
enum DimSearch {
    /// Every row's neighbour, found at once by an exact scan (above 10 dimensions or
    /// `u32::MAX` samples).
    Scanned(Vec<usize>),
    /// One dimension, only the row itself excluded: row by row along the sorted values.
    Sorted(Sorted1d),
    /// Row by row through the new index over the `d` coordinates (left in `index`).
    Index,
}

/// The search for the first `rows` rows of the `d`-dimensional delay embedding (Theiler window
/// `params.min_tsep`).
fn dim_search(
    s: &FnnSeries,
    d: usize,
    rows: usize,
    params: &FnnParams,
    index: &mut Option<Box<dyn NeighbourIndex>>,
) -> DimSearch {
    let (x, x_order, lag) = (s.x, s.order, s.lag);
    if d == 1 && params.min_tsep == 0 {
        if x_order.len() != x.len() {
            return DimSearch::Scanned(nearest_outside_window(&x[..rows], 1, 0, None));
        }
        // the series' order, restricted to the rows, is the rows' order
        let order: Vec<u32> = x_order
            .iter()
            .copied()
            .filter(|&t| (t as usize) < rows)
            .collect();
        return DimSearch::Sorted(Sorted1d::new(&x[..rows], &order));
    }
    *index = delay_index(x, lag, d, rows, x_order);
    if index.is_some() {
        return DimSearch::Index;
    }
    let mut pts = Vec::new();
    delay_embed_into(&x[..rows + (d - 1) * lag], d, lag, &mut pts);
    DimSearch::Scanned(nn_brute(&pts, d, params.min_tsep))
}
