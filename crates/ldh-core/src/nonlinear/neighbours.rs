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

use kiddo::{Chebyshev, ImmutableKdTree};

use super::window_tree::WindowTree;
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

/// Sum in numpy's order (`pairwise_sum` of `numpy/_core/src/umath/loops_utils.h`):
/// plain loop below 8 elements, eight interleaved accumulators up to 128, and a
/// recursive split above. Used so that sums match numpy bit for bit (hand
/// written: no crate reproduces numpy's summation order).
pub(crate) fn np_sum(a: &[f64]) -> f64 {
    let n = a.len();
    if n < 8 {
        let mut res = 0.0;
        for &v in a {
            res += v;
        }
        res
    } else if n <= 128 {
        let mut r = [0.0f64; 8];
        r.copy_from_slice(&a[..8]);
        let mut i = 8;
        while i < n - (n % 8) {
            for j in 0..8 {
                r[j] += a[i + j];
            }
            i += 8;
        }
        let mut res = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]));
        while i < n {
            res += a[i];
            i += 1;
        }
        res
    } else {
        let mut n2 = n / 2;
        n2 -= n2 % 8;
        np_sum(&a[..n2]) + np_sum(&a[n2..])
    }
}

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
pub(crate) fn nearest_outside_window(points: &[f64], dim: usize, min_tsep: usize) -> Vec<usize> {
    dispatch_dim!(dim, nn_kdtree, points, min_tsep)
        .unwrap_or_else(|| nn_brute(points, dim, min_tsep))
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

/// Search through a [`WindowTree`]: rows in chunks (in parallel), each chunk in order, every
/// query seeded with the previous row's neighbour shifted by one.
fn nn_kdtree<const K: usize>(points: &[f64], min_tsep: usize) -> Vec<usize> {
    let pts = to_arrays::<K>(points);
    let n = pts.len();
    if n > u32::MAX as usize {
        // the tree indexes rows with u32: stay exact, no panic
        return nn_brute(points, K, min_tsep);
    }
    let tree = WindowTree::new(&pts);
    let mut out = vec![usize::MAX; n];
    out.par_chunks_mut(512).enumerate().for_each(|(c, chunk)| {
        let mut stack = Vec::with_capacity(64);
        let mut seed = None;
        for (o, slot) in chunk.iter_mut().enumerate() {
            let i = c * 512 + o;
            *slot = match tree.nearest_outside(i, min_tsep, seed, &mut stack) {
                Some(j) => j,
                // unreachable under the caller's precondition: exact scan, no panic
                None => nn_brute_one(points, K, i, min_tsep),
            };
            seed = Some(*slot + 1);
        }
    });
    out
}

fn nn_brute_one(points: &[f64], dim: usize, i: usize, min_tsep: usize) -> usize {
    let n = points.len() / dim;
    let p = &points[i * dim..(i + 1) * dim];
    let mut best = (f64::INFINITY, usize::MAX);
    for j in 0..n {
        if outside_window(i, j, min_tsep) {
            let d = np_euclidean(p, &points[j * dim..(j + 1) * dim]);
            if d < best.0 || best.1 == usize::MAX {
                best = (d, j);
            }
        }
    }
    best.1
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
