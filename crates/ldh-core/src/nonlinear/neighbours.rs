//! Exact nearest-neighbour searches with a Theiler window.
//!
//! Points are rows of a row-major `n × dim` slice. For `dim` in `1..=10` the
//! Euclidean searches go through a [`WindowTree`] that skips the Theiler window,
//! the Chebyshev ones through a `kiddo` 6 k-d tree (the dimension is a const
//! generic, dispatched by [`dispatch_dim!`]); for larger dimensions an exact brute-force
//! scan is used (O(n²) time but O(n) memory: one row of distances is never
//! materialised, each query keeps only its running best).
//!
//! Parity with nolds matters more than raw speed, so the distance that decides
//! the neighbour is recomputed in numpy's summation order ([`np_euclidean`]) and
//! ties are broken by the lowest index, exactly like `np.argmin` over a row of
//! nolds' distance matrix.

use std::num::NonZeroUsize;
use std::ops::Range;

use kiddo::{Chebyshev, ImmutableKdTree};

pub(crate) use super::npsum::{np_sum, np_sum_rows};
pub(crate) use super::window_tree::total_order;
use super::window_tree::{delay_orders, WindowTree};
use rayon::prelude::*;

/// Dispatches a const-generic function over dimensions 1..=10; `None` for
/// larger dimensions (the caller then uses the brute-force path).
macro_rules! dispatch_dim {
    ($dim:expr, $f:ident, $($arg:expr),* $(,)?) => {
        match $dim {
            1 => Some($f::<1>($($arg),*)),
            2 => Some($f::<2>($($arg),*)),
            3 => Some($f::<3>($($arg),*)),
            4 => Some($f::<4>($($arg),*)),
            5 => Some($f::<5>($($arg),*)),
            6 => Some($f::<6>($($arg),*)),
            7 => Some($f::<7>($($arg),*)),
            8 => Some($f::<8>($($arg),*)),
            9 => Some($f::<9>($($arg),*)),
            10 => Some($f::<10>($($arg),*)),
            _ => None,
        }
    };
}
pub(crate) use dispatch_dim;

/// Euclidean distance as nolds computes it: `np.sqrt(np.sum((x - y)**2))`.
pub(crate) fn np_euclidean(a: &[f64], b: &[f64]) -> f64 {
    if a.len() < 8 {
        // np_sum's plain loop, without the buffer
        let mut res = 0.0;
        for (x, y) in a.iter().zip(b) {
            let d = x - y;
            res += d * d;
        }
        return res.sqrt();
    }
    let mut sq = [0.0f64; 128];
    if a.len() <= 128 {
        for ((s, x), y) in sq.iter_mut().zip(a).zip(b) {
            let d = x - y;
            *s = d * d;
        }
        np_sum(&sq[..a.len()]).sqrt()
    } else {
        let v: Vec<f64> = a
            .iter()
            .zip(b)
            .map(|(x, y)| {
                let d = x - y;
                d * d
            })
            .collect();
        np_sum(&v).sqrt()
    }
}

/// Squared Euclidean distance summed as `np.sum((x - y)**2)` sums it (the square of
/// [`np_euclidean`] before its root, bit for bit), for a fixed dimension.
#[inline(always)]
pub(crate) fn np_sq_sum<const K: usize>(a: &[f64; K], b: &[f64; K]) -> f64 {
    if K < 8 {
        // np_sum's plain loop
        let mut res = 0.0;
        for k in 0..K {
            let d = a[k] - b[k];
            res += d * d;
        }
        res
    } else {
        let mut sq = [0.0; K];
        for k in 0..K {
            let d = a[k] - b[k];
            sq[k] = d * d;
        }
        np_sum(&sq)
    }
}

/// Chebyshev (max-norm) distance; exact in floating point (no rounding).
pub(crate) fn chebyshev(a: &[f64], b: &[f64]) -> f64 {
    let mut m = 0.0f64;
    for (x, y) in a.iter().zip(b) {
        let d = (x - y).abs();
        if d > m || d.is_nan() {
            m = d;
        }
    }
    m
}

#[inline]
fn outside_window(i: usize, j: usize, min_tsep: usize) -> bool {
    i.abs_diff(j) > min_tsep
}

fn to_arrays<const K: usize>(points: &[f64]) -> Vec<[f64; K]> {
    points
        .chunks_exact(K)
        .map(|c| {
            let mut a = [0.0; K];
            a.copy_from_slice(c);
            a
        })
        .collect()
}

/// For every row `i` of `points` (`n × dim`), the index `j` minimising the
/// Euclidean distance over all rows with `|i − j| > min_tsep` (nolds' mask
/// `dists[i, i-min_tsep : i+min_tsep+1] = inf`), lowest `j` among ties.
///
/// Precondition (checked by callers): `n ≥ 2·min_tsep + 2`, so every row has a
/// candidate outside its window.
///
/// `hint`, when given, holds for each row a row to measure first (e.g. its neighbour in a lower
/// embedding dimension); it speeds the search up and never changes the result.
pub(crate) fn nearest_outside_window(
    points: &[f64],
    dim: usize,
    min_tsep: usize,
    hint: Option<&[usize]>,
) -> Vec<usize> {
    if dim == 1 && min_tsep == 0 && points.len() <= u32::MAX as usize {
        return nn_sorted_1d(points, &total_order(points));
    }
    match orbit_index(points, dim) {
        Some(index) => index.nearest_all(dim, min_tsep, points.len() / dim, hint, None),
        None => nn_brute(points, dim, min_tsep),
    }
}

/// One dimension, only the row itself excluded (FNN's first dimension): the nearest value is
/// next to the row's own in sorted order. The computed distance `√((x − y)²)` does not
/// decrease as `y` moves away from `x` in sorted order (rounding is monotone), so each side is
/// walked while the distance is at most the best (rows as near as the best, with a lower
/// index, may follow) and then stops: the answer is the brute-force one, ties included, in
/// whatever order `order` (the positions of `points` sorted by [`f64::total_cmp`], e.g. from
/// [`total_order`]) holds them.
pub(crate) fn nn_sorted_1d(points: &[f64], order: &[u32]) -> Vec<usize> {
    let sorted = Sorted1d::new(points, order);
    (0..points.len()).map(|i| sorted.nearest(i)).collect()
}

/// The values of [`nn_sorted_1d`] in sorted order and each row's place among them, so that any
/// row's nearest row is found on its own (false nearest neighbours' first dimension searches
/// only the rows it needs before rejecting the dimension).
pub(crate) struct Sorted1d {
    /// `(value, row)` in `order`'s order.
    sorted: Vec<(f64, usize)>,
    /// Row `i`'s place in `sorted`.
    place: Vec<u32>,
}

impl Sorted1d {
    /// `order`: the positions of `points` sorted by [`f64::total_cmp`] (fewer than `u32::MAX`).
    pub(crate) fn new(points: &[f64], order: &[u32]) -> Self {
        let sorted: Vec<(f64, usize)> = order
            .iter()
            .map(|&t| (points[t as usize], t as usize))
            .collect();
        let mut place = vec![0u32; points.len()];
        for (p, &t) in order.iter().enumerate() {
            place[t as usize] = p as u32;
        }
        Sorted1d { sorted, place }
    }

    /// Row `i`'s nearest other row, lowest index among ties (`usize::MAX` if there is none).
    pub(crate) fn nearest(&self, i: usize) -> usize {
        let p = self.place[i] as usize;
        let (x, _) = self.sorted[p];
        let dist = |x: f64, y: f64| {
            let d = x - y;
            (d * d).sqrt()
        };
        let mut best = (f64::INFINITY, usize::MAX);
        let sides = [&self.sorted[..p], &self.sorted[p + 1..]];
        for (side, rows) in sides.into_iter().enumerate() {
            let mut walk = |&(y, j): &(f64, usize)| {
                let d = dist(x, y);
                if d > best.0 {
                    return false;
                }
                if d < best.0 || j < best.1 {
                    best = (d, j);
                }
                true
            };
            if side == 0 {
                rows.iter().rev().take_while(|r| walk(r)).for_each(drop);
            } else {
                rows.iter().take_while(|r| walk(r)).for_each(drop);
            }
        }
        best.1
    }
}

/// Exact brute force (reference for tests, and the path for `dim > 10`).
pub(crate) fn nn_brute(points: &[f64], dim: usize, min_tsep: usize) -> Vec<usize> {
    let n = points.len() / dim;
    (0..n)
        .into_par_iter()
        .map(|i| {
            let p = &points[i * dim..(i + 1) * dim];
            let mut best = (f64::INFINITY, usize::MAX);
            for j in 0..n {
                if !outside_window(i, j, min_tsep) {
                    continue;
                }
                let d = np_euclidean(p, &points[j * dim..(j + 1) * dim]);
                // strict `<` keeps the lowest index among ties (np.argmin)
                if d < best.0 || best.1 == usize::MAX {
                    best = (d, j);
                }
            }
            best.1
        })
        .collect()
}

/// Rows searched in order on one thread; chunks of this many rows run in parallel.
const CHUNK: usize = 1024;

/// Fewer rows than this are searched on the calling thread: a 30 s leg's ≈ 3 000 queries take
/// about a millisecond, and handing them to the rayon pool costs a thread hand-over per call
/// and the worker's idle spinning; `Analysis::many` already runs legs in parallel.
const PAR_ROWS: usize = 1 << 14;

/// A built neighbour search over rows of [`NeighbourIndex::dims`] coordinates (a
/// [`WindowTree`], whose dimension is a const generic, behind one object-safe interface). One
/// build serves queries over the first `dims` coordinates and the first `limit` rows, so false
/// nearest neighbours searches dimensions 2, 3, 4 of one delay embedding with one tree, and
/// Rosenstein's method reuses it.
pub(crate) trait NeighbourIndex: Send + Sync {
    /// Number of coordinates of every row.
    fn dims(&self) -> usize;
    /// Number of rows.
    fn len(&self) -> usize;
    /// For every row `i < limit`, the row `j < limit` with `|i − j| > min_tsep` nearest over
    /// the first `dims` coordinates (numpy-order Euclidean distance, lowest `j` among ties;
    /// `usize::MAX` if there is none). `hint[i]`, when given, is measured first; it speeds the
    /// search up and never changes the result. `limit ≤ len()`, `dims ≤ self.dims()`, and the
    /// first `dims` coordinates of the first `limit` rows are finite (callers guarantee).
    ///
    /// `known[i]`, when given, is row i's neighbour over the same `dims` coordinates among more
    /// rows: a Theiler window no wider and a limit no lower (e.g. false nearest neighbours'
    /// last search, for Rosenstein's method; callers guarantee). Wherever it is admitted here
    /// it is the answer, without a search: the nearest row of a set, lowest index among ties,
    /// is the nearest row of any subset that holds it, lowest index among ties.
    fn nearest_all(
        &self,
        dims: usize,
        min_tsep: usize,
        limit: usize,
        hint: Option<&[usize]>,
        known: Option<&[usize]>,
    ) -> Vec<usize> {
        let limit = limit.min(self.len());
        self.nearest_rows((dims, min_tsep, limit), 0..limit, None, hint, known)
    }
    /// [`NeighbourIndex::nearest_all`]'s answers for the rows `rows` only (`rows.end ≤ limit ≤
    /// len()`), in order; `prev`, row `rows.start − 1`'s neighbour, seeds the first query. False
    /// nearest neighbours searches a dimension's rows block by block and stops once the
    /// dimension is rejected.
    fn nearest_rows(
        &self,
        search: (usize, usize, usize),
        rows: Range<usize>,
        prev: Option<usize>,
        hint: Option<&[usize]>,
        known: Option<&[usize]>,
    ) -> Vec<usize>;
}

impl<const K: usize> NeighbourIndex for WindowTree<K> {
    fn dims(&self) -> usize {
        K
    }

    fn len(&self) -> usize {
        WindowTree::len(self)
    }

    /// Rows in order (in chunks, in parallel, from [`PAR_ROWS`] rows on). Every query is
    /// seeded with the previous row's neighbour shifted by one (trajectories are continuous)
    /// and the caller's hint for the row.
    fn nearest_rows(
        &self,
        (dims, min_tsep, limit): (usize, usize, usize),
        rows: Range<usize>,
        prev: Option<usize>,
        hint: Option<&[usize]>,
        known: Option<&[usize]>,
    ) -> Vec<usize> {
        let limit = limit.min(self.len());
        let rows = rows.start.min(limit)..rows.end.min(limit);
        let mut out = vec![usize::MAX; rows.len()];
        let run = |c: usize, chunk: &mut [usize]| {
            let mut stack = Vec::with_capacity(64);
            // the first chunk continues the caller's rows; the others start unseeded
            let mut prev = if c == 0 { prev } else { None };
            for (o, slot) in chunk.iter_mut().enumerate() {
                let i = rows.start + c * CHUNK + o;
                let admitted = |j: &usize| *j < limit && i.abs_diff(*j) > min_tsep;
                if let Some(j) = known.and_then(|k| k.get(i).copied()).filter(admitted) {
                    *slot = j;
                    prev = Some(j);
                    continue;
                }
                let seeds = [prev.map(|j| j + 1), hint.and_then(|h| h.get(i).copied())];
                let query = (min_tsep, limit, dims);
                // None only when no row is admitted (excluded by the callers' preconditions)
                *slot = self
                    .nearest_outside(i, query, &seeds, &mut stack)
                    .unwrap_or(usize::MAX);
                prev = Some(*slot);
            }
        };
        if rows.len() < PAR_ROWS {
            run(0, &mut out);
        } else {
            out.par_chunks_mut(CHUNK)
                .enumerate()
                .for_each(|(c, chunk)| run(c, chunk));
        }
        out
    }
}

fn orbit_index_k<const K: usize>(points: &[f64]) -> Box<dyn NeighbourIndex> {
    Box::new(WindowTree::new(to_arrays::<K>(points)))
}

/// A [`NeighbourIndex`] over the rows of a row-major `n × dim` slice; `None` above 10
/// dimensions or `u32::MAX` rows (the callers then scan exactly by brute force).
pub(crate) fn orbit_index(points: &[f64], dim: usize) -> Option<Box<dyn NeighbourIndex>> {
    if dim == 0 || points.len() / dim > u32::MAX as usize {
        return None;
    }
    dispatch_dim!(dim, orbit_index_k, points)
}

fn delay_index_k<const K: usize>(
    x: &[f64],
    lag: usize,
    rows: usize,
    x_order: &[u32],
) -> Box<dyn NeighbourIndex> {
    let at = |t: usize| x.get(t).copied().unwrap_or(f64::NAN);
    let pts = (0..rows)
        .map(|i| std::array::from_fn(|a| at(i + a * lag)))
        .collect();
    let orders = delay_orders::<K>(x.len(), x_order, lag, rows);
    Box::new(WindowTree::<K>::with_orders(pts, orders))
}

/// A [`NeighbourIndex`] over the first `rows` rows of the delay embedding of `x` in `dims`
/// dimensions: row `i` is `[x_i, x_{i+lag}, …, x_{i+(dims−1)·lag}]`, NaN past the end of `x`
/// (such rows must lie beyond the limit of every query measuring that coordinate). `x_order`
/// is [`total_order`] of `x` (one sort serves every dimension's index). `None` above 10
/// dimensions or `u32::MAX` samples.
pub(crate) fn delay_index(
    x: &[f64],
    lag: usize,
    dims: usize,
    rows: usize,
    x_order: &[u32],
) -> Option<Box<dyn NeighbourIndex>> {
    if x.len() > u32::MAX as usize || x_order.len() != x.len() {
        return None;
    }
    dispatch_dim!(dims, delay_index_k, x, lag, rows, x_order)
}

/// Eckmann neighbourhoods: for every row `i` of `points` (`n × dim`), the
/// `min_nb`-th smallest Chebyshev distance `r_i` over rows `j ≠ i` with
/// `|i − j| > min_tsep`, and all such rows with distance `≤ r_i` (ascending
/// index, as `np.where(diffs <= r)` returns them). `None` for a row with fewer
/// than `min_nb` candidates (nolds' "r is inf" error).
///
/// Chebyshev distances are exact in floating point, so ties are exact and
/// independent of the search order: kiddo 6's `Chebyshev` metric is used
/// directly.
pub(crate) fn chebyshev_neighbourhoods(
    points: &[f64],
    dim: usize,
    min_tsep: usize,
    min_nb: usize,
) -> Vec<Option<Vec<usize>>> {
    dispatch_dim!(dim, cheb_kdtree, points, min_tsep, min_nb)
        .unwrap_or_else(|| cheb_brute(points, dim, min_tsep, min_nb))
}

/// Exact brute-force Chebyshev neighbourhoods (reference and `dim > 10`): one
/// query at a time, O(n) memory per query.
pub(crate) fn cheb_brute(
    points: &[f64],
    dim: usize,
    min_tsep: usize,
    min_nb: usize,
) -> Vec<Option<Vec<usize>>> {
    let n = points.len() / dim;
    (0..n)
        .into_par_iter()
        .map(|i| {
            let p = &points[i * dim..(i + 1) * dim];
            let mut cand: Vec<(f64, usize)> = (0..n)
                .filter(|&j| outside_window(i, j, min_tsep) && j != i)
                .map(|j| (chebyshev(p, &points[j * dim..(j + 1) * dim]), j))
                .collect();
            if cand.len() < min_nb || min_nb == 0 {
                return None;
            }
            let mut ds: Vec<f64> = cand.iter().map(|c| c.0).collect();
            let (_, r, _) = ds.select_nth_unstable_by(min_nb - 1, |a, b| a.total_cmp(b));
            let r = *r;
            cand.retain(|c| c.0 <= r);
            Some(cand.into_iter().map(|c| c.1).collect())
        })
        .collect()
}

fn cheb_kdtree<const K: usize>(
    points: &[f64],
    min_tsep: usize,
    min_nb: usize,
) -> Vec<Option<Vec<usize>>> {
    let pts = to_arrays::<K>(points);
    let n = pts.len();
    let Ok(tree) = ImmutableKdTree::<f64, K>::new_from_slice(&pts) else {
        // construction only fails for > u32::MAX points: stay exact, no panic
        return cheb_brute(points, K, min_tsep, min_nb);
    };
    // the window (self included) holds at most 2·min_tsep + 1 rows
    let start_k = (min_nb + 2 * min_tsep + 2).max(8).min(n).max(1);
    (0..n)
        .into_par_iter()
        .map(|i| {
            if min_nb == 0 {
                return None;
            }
            let q = &pts[i];
            let mut k = start_k;
            loop {
                let res = tree
                    .query(q)
                    .nearest_n::<Chebyshev<f64>>(NonZeroUsize::new(k).unwrap_or(NonZeroUsize::MIN))
                    .execute();
                let all_returned = res.len() < k || k >= n;
                let mut valid: Vec<(f64, usize)> = res
                    .iter()
                    .filter(|r| {
                        outside_window(i, r.item as usize, min_tsep) && r.item as usize != i
                    })
                    .map(|r| (r.distance, r.item as usize))
                    .collect();
                if valid.len() >= min_nb {
                    let mut ds: Vec<f64> = valid.iter().map(|c| c.0).collect();
                    let (_, r, _) = ds.select_nth_unstable_by(min_nb - 1, |a, b| a.total_cmp(b));
                    let r = *r;
                    let last = res.last().map(|x| x.distance).unwrap_or(f64::INFINITY);
                    // every row with distance ≤ r is in `res` once the largest
                    // returned distance exceeds r (or everything was returned)
                    if all_returned || last > r {
                        valid.retain(|c| c.0 <= r);
                        let mut idx: Vec<usize> = valid.into_iter().map(|c| c.1).collect();
                        idx.sort_unstable();
                        return Some(idx);
                    }
                } else if all_returned {
                    return None;
                }
                k = (k * 2).min(n);
            }
        })
        .collect()
}
