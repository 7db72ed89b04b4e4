//! Exact nearest neighbour outside a Theiler window, with a k-d tree whose search skips the
//! excluded index range and starts at the query's own leaf (issue 17).
//!
//! kiddo's queries cannot exclude items, so a neighbour search with a Theiler window `w` had to
//! ask for the k nearest with a growing k (up to `2w + 2`) and discard the rows inside the
//! window; on gait signals, whose trajectory stays close to itself for many samples, that meant
//! sorting hundreds of results per query. This tree (Bentley 1975; Friedman, Bentley & Finkel
//! 1977: median split, bounding boxes) keeps the lowest and highest row index of every node, so
//! a node lying wholly inside the window is skipped, and rows inside it are never measured.
//!
//! The search is Friedman, Bentley & Finkel's bottom-up one: the tree is balanced and stored in
//! heap order (node `k` has children `2k`, `2k + 1`; all leaves at one depth; built from rows
//! kept sorted on every axis, see `build.rs`), the rows are stored leaf by leaf (axis by axis,
//! so a leaf is measured four slots at a time with `wide`'s vectors, and the rows that may win
//! come out as a bit mask), and each node knows its *cell* (the half-spaces of its ancestors'
//! splits). A query first measures
//! a few seed rows given by the caller (e.g. the previous row's neighbour shifted by one:
//! trajectories are continuous, so that is usually the answer), then its own leaf, and walks
//! up: at each level the subtree not yet visited is searched top-down with box pruning, and the
//! walk stops as soon as the ball around the query with the best distance lies inside the
//! current node's cell ("ball within bounds"), since no row outside the cell can then be as
//! near. With a tight seed this ends a few levels above the leaf instead of descending from the
//! root.
//!
//! One tree serves several metrics: a query may measure only the first `dims ≤ K` coordinates
//! and only the rows below a `limit` (Rosenstein's method reuses the tree false nearest
//! neighbours built for its last dimension, over fewer rows). Boxes restricted to the first
//! `dims` axes bound that metric as well; cells do only while no split on a later axis bounds
//! them, so such a query walks further up (a tree per dimension is faster for false nearest
//! neighbours: one over 4 coordinates, asked for 2 and 3, took 1.4× longer in all). Coordinates
//! that do not exist (past the end of the series) are NaN; such rows are beyond the limit of
//! every metric that uses the axis, and NaN fails every comparison.
//!
//! Exactness: every candidate's squared distance is summed in numpy's order (`sq_dist`, the
//! sum of `np.sum((x - y)**2)`; the vector lanes of a leaf scan perform the same IEEE
//! operations in the same order), the distance is its square root, the best is the smallest
//! such distance with the lowest index among ties (`np.argmin`; see `Best::take`, which
//! compares the squares and takes roots only for near ties). A row,
//! box or cell is set aside only when a lower bound of its squared distance exceeds the best
//! squared distance by a relative 1e-9 — far more than the rounding of either sum (the bounds
//! are monotone in the rounded coordinate differences, and a sum of non-negative terms is never
//! below one of its terms), so nothing that could win or tie is ever left out. The result
//! equals the brute-force scan bit for bit whatever the seeds or the visiting order (unit test
//! below; property tests in `tests/neighbours.rs`).

use wide::f64x4;

mod build;
pub(crate) use build::{delay_orders, total_order};

/// Most rows per leaf (leaves hold between `LEAF / 2` and `LEAF` rows). 24 (a 30 s leg's tree
/// is then 7 levels deep, ≈ 23 rows a leaf): with the four-lane scans, fewer and fuller leaves
/// cost less than more node visits (12: 3.5 ms, 24: 3.1–3.2 ms, 48: 3.3 ms per `gait_sta`).
const LEAF: usize = 24;

/// Four-lane vectors per leaf axis.
const LANES: usize = LEAF / 4;

// a leaf is whole four-lane vectors, and its slots fit the bit mask of a scan
const _: () = assert!(LEAF.is_multiple_of(4) && LEAF <= 32);

/// Relative margin of every pruning test (see the module docs).
const MARGIN: f64 = 1.0 + 1e-9;

/// The best candidate so far: squared distance (numpy's sum), row, and the pruning threshold
/// `s · MARGIN`.
#[derive(Clone, Copy)]
struct Best {
    s: f64,
    j: usize,
    thr: f64,
}

impl Best {
    const NONE: Best = Best {
        s: f64::INFINITY,
        j: usize::MAX,
        thr: f64::INFINITY,
    };

    /// Keep row `j` at squared distance `s` if its distance `√s` (rounded, as nolds compares
    /// distances) is smaller, or equal with a lower index. The roots are taken only when the
    /// two squares lie within a relative 4e-15 of each other: beyond that gap the rounded roots
    /// are ordered as the squares are (√ halves the relative gap, ≈ 2e-15 after the rounding of
    /// the product, far more than the two roundings of 2⁻⁵³), so the hot paths need no root.
    #[inline(always)]
    fn take(&mut self, s: f64, j: usize) {
        let better = if s < self.s * (1.0 - 4e-15) {
            true
        } else if s > self.s * (1.0 + 4e-15) {
            false
        } else {
            let (d, d_best) = (s.sqrt(), self.s.sqrt());
            d < d_best || (d == d_best && j < self.j)
        };
        if better {
            *self = Best {
                s,
                j,
                thr: s * MARGIN,
            };
        }
    }
}

/// Squared distance over the first `dims` axes, in numpy's order (the plain loop below eight
/// axes, [`np_sq_sum`]'s blocks from eight on).
#[inline(always)]
fn sq_dist<const K: usize>(a: &[f64; K], b: &[f64; K], dims: usize) -> f64 {
    if dims < 8 {
        let mut s = 0.0;
        for ax in 0..dims {
            let d = a[ax] - b[ax];
            s += d * d;
        }
        s
    } else {
        let mut sq = [0.0; K];
        for ax in 0..dims {
            let d = a[ax] - b[ax];
            sq[ax] = d * d;
        }
        super::npsum::np_sum(&sq[..dims])
    }
}

/// What one query asks: its row, window (inclusive row range excluded), the rows it may take
/// (`< limit`) and the number of axes measured.
/// `FULL`: every axis measured (`dims == K`), known at compile time so that the loops over the
/// axes unroll.
#[derive(Clone, Copy)]
struct Query<'q, const K: usize, const FULL: bool> {
    q: &'q [f64; K],
    win: (usize, usize),
    limit: usize,
    dims: usize,
}

impl<const K: usize, const FULL: bool> Query<'_, K, FULL> {
    /// Number of axes measured.
    #[inline(always)]
    fn dims(&self) -> usize {
        if FULL {
            K
        } else {
            self.dims
        }
    }

    /// Whether every row with an index in `span` is inside the window or beyond the limit.
    #[inline(always)]
    fn excludes(&self, (min_i, max_i): (u32, u32)) -> bool {
        let (min_i, max_i) = (min_i as usize, max_i as usize);
        min_i >= self.limit || (min_i >= self.win.0 && max_i <= self.win.1)
    }

    #[inline(always)]
    fn admits(&self, j: usize) -> bool {
        j < self.limit && (j < self.win.0 || j > self.win.1)
    }
}

/// A balanced k-d tree over rows of `K` coordinates.
pub(crate) struct WindowTree<const K: usize> {
    /// The rows in row order (the queries).
    rows: Vec<[f64; K]>,
    /// Leaf `l` (node `first_leaf + l`) holds the coordinates of its rows axis by axis in
    /// `block[(l·K + a)·LEAF..][..LEAF]`, padded with NaN (a padding slot fails every distance
    /// test), and their row indices in `slot_row[l·LEAF..][..LEAF]` (`u32::MAX` when padding).
    block: Vec<f64>,
    slot_row: Vec<u32>,
    /// The rows in leaf order while the tree is built.
    idx: Vec<u32>,
    /// The leaf (node number) of every row.
    leaf_of: Vec<u32>,
    /// First leaf number (`2^depth`); nodes `first_leaf..2·first_leaf` are the leaves.
    first_leaf: usize,
    /// Per node, in heap order (index 0 unused): range of `idx` while building, bounding box
    /// and row span, cell (lower and upper corner).
    range: Vec<(u32, u32)>,
    boxes: Vec<NodeBox<K>>,
    cells: Vec<([f64; K], [f64; K])>,
}

/// A node's bounding box and the lowest and highest row index in it.
#[derive(Clone, Copy)]
struct NodeBox<const K: usize> {
    lo: [f64; K],
    hi: [f64; K],
    span: (u32, u32),
}

impl<const K: usize> WindowTree<K> {
    /// Number of rows.
    pub(crate) fn len(&self) -> usize {
        self.rows.len()
    }

    /// Squared distance from the query to node `k`'s box (0 inside), summed in axis order.
    #[inline(always)]
    fn box_dist_sq<const FULL: bool>(&self, k: usize, qy: &Query<K, FULL>) -> f64 {
        let (b, q) = (&self.boxes[k], qy.q);
        let mut s = 0.0;
        for a in 0..qy.dims() {
            let (below, above) = (b.lo[a] - q[a], q[a] - b.hi[a]);
            // max(below, above, 0) by selects (maxsd; no NaN here)
            let e = if below > above { below } else { above };
            let e = if e > 0.0 { e } else { 0.0 };
            s += e * e;
        }
        s
    }

    /// Whether every row outside node `k`'s cell is farther from the query than the threshold
    /// allows (the query lies in the cell). Only the measured axes separate: a cell bounded on
    /// an axis the query does not measure (a split there) never encloses the ball, since the
    /// rows beyond that bound may be as near as any in the cell.
    #[inline(always)]
    fn ball_inside_cell<const FULL: bool>(&self, k: usize, qy: &Query<K, FULL>, thr: f64) -> bool {
        let ((lo, hi), q) = (&self.cells[k], qy.q);
        // one branch for the whole test (the conditions are unpredictable)
        let mut inside = true;
        for a in 0..qy.dims() {
            let (dl, dh) = (q[a] - lo[a], hi[a] - q[a]);
            inside &= (dl * dl > thr) & (dh * dh > thr);
        }
        for a in qy.dims()..K {
            inside &= (lo[a] == f64::NEG_INFINITY) & (hi[a] == f64::INFINITY);
        }
        inside
    }

    /// Squared distances from the query to the slots of leaf `l` over the measured axes, below
    /// eight axes: numpy's plain loop (`0.0 + d₀² + d₁² + …`, axis by axis), for four slots at
    /// a time (`wide`'s lanewise subtract, multiply and add are the scalar IEEE operations, so
    /// every lane holds the bits of [`sq_dist`]). NaN padding stays NaN.
    #[inline(always)]
    fn leaf_sq_lanes<const FULL: bool>(&self, l: usize, qy: &Query<K, FULL>) -> [f64x4; LANES] {
        let (cols, _) = self.block[l * K * LEAF..][..K * LEAF].as_chunks::<LEAF>();
        let mut acc = [f64x4::ZERO; LANES];
        for (col, &qa) in cols.iter().zip(&qy.q[..qy.dims()]) {
            let qv = f64x4::splat(qa);
            for (a, c) in acc.iter_mut().zip(col.as_chunks::<4>().0) {
                let d = qv - f64x4::new(*c);
                *a += d * d;
            }
        }
        acc
    }

    /// Measure the admitted rows of leaf `k`.
    #[inline(always)]
    fn scan_leaf<const FULL: bool>(&self, k: usize, qy: &Query<K, FULL>, best: &mut Best) {
        let l = k - self.first_leaf;
        let mut s = [0.0f64; LEAF];
        // the slots that may win or tie (v ≤ thr; NaN padding never is), one bit each
        let mut mask = 0u32;
        if qy.dims() < 8 {
            let thr = f64x4::splat(best.thr);
            for (c, a) in self.leaf_sq_lanes(l, qy).iter().enumerate() {
                mask |= a.simd_le(thr).to_bitmask() << (4 * c);
                s[4 * c..][..4].copy_from_slice(a.as_array());
            }
        } else {
            for (slot, sp) in s.iter_mut().enumerate() {
                let p: [f64; K] = std::array::from_fn(|ax| self.block[(l * K + ax) * LEAF + slot]);
                *sp = sq_dist(qy.q, &p, qy.dims());
                mask |= ((*sp <= best.thr) as u32) << slot;
            }
        }
        // most leaves hold no row that can win or tie: one test for the leaf
        if mask == 0 {
            return;
        }
        let (min_i, max_i) = self.boxes[k].span;
        // every row of the leaf admitted: no test per row
        let clear = (max_i as usize) < qy.limit
            && ((max_i as usize) < qy.win.0 || (min_i as usize) > qy.win.1);
        let rows = &self.slot_row[l * LEAF..][..LEAF];
        if !clear {
            // the admitted slots only
            let mut m = mask;
            while m != 0 {
                let slot = m.trailing_zeros() as usize;
                m &= m - 1;
                mask &= !((!qy.admits(rows[slot] as usize) as u32) << slot);
            }
        }
        // the least squared distance of the leaf first (no square root, no chain of updates
        // of the best through it): a slot with v > v_min·(1 + 4e-15) has √v > √v_min once
        // rounded (√ halves the relative gap, ≈ 2e-15 after the rounding of the product, far
        // more than the two roundings of 2⁻⁵³), so it can neither win nor tie; the rest (nearly
        // always the one slot) go through `take`, which keeps the lowest index among ties
        let mut v_min = f64::INFINITY;
        let mut m = mask;
        while m != 0 {
            let slot = m.trailing_zeros() as usize;
            m &= m - 1;
            v_min = v_min.min(s[slot]);
        }
        let near = v_min * (1.0 + 4e-15);
        while mask != 0 {
            let slot = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let v = s[slot];
            // v > thr ⇒ √v > d: cannot win or tie
            if v <= near && v <= best.thr {
                best.take(v, rows[slot] as usize);
            }
        }
    }

    /// Top-down search of the subtree under `root`, pruned by boxes, the window and the limit:
    /// the nearer child is visited next without going through the stack, the farther one is
    /// pushed only if its box may still hold a winner (the threshold only shrinks, so it is
    /// tested again when popped).
    #[inline(always)]
    fn search_subtree<const FULL: bool>(
        &self,
        root: usize,
        qy: &Query<K, FULL>,
        best: &mut Best,
        stack: &mut Vec<(u32, f64)>,
    ) {
        stack.clear();
        let mut cur = (root as u32, self.box_dist_sq(root, qy));
        loop {
            let (k, lb) = (cur.0 as usize, cur.1);
            if lb <= best.thr && !qy.excludes(self.boxes[k].span) {
                if k >= self.first_leaf {
                    self.scan_leaf(k, qy, best);
                } else {
                    let (l, r) = (2 * k as u32, 2 * k as u32 + 1);
                    let (dl, dr) = (
                        self.box_dist_sq(l as usize, qy),
                        self.box_dist_sq(r as usize, qy),
                    );
                    // the nearer child (the left one on a tie) next: index arithmetic and
                    // min/max, no branch (box distances are never NaN)
                    let right_first = dl > dr;
                    let near = (l | right_first as u32, dl.min(dr));
                    let far = (near.0 ^ 1, dl.max(dr));
                    if far.1 <= best.thr {
                        stack.push(far);
                    }
                    cur = near;
                    continue;
                }
            }
            match stack.pop() {
                Some(next) => cur = next,
                None => return,
            }
        }
    }

    /// The row `j < limit` with `|i − j| > w` nearest to row `i` < `limit` over the first
    /// `dims` coordinates (numpy-order Euclidean distance, lowest `j` among ties), or `None`
    /// when no row is admitted. The admitted `seeds` are measured first (they never change the
    /// answer, only how soon the search ends). `stack` is scratch space reused between queries.
    pub(crate) fn nearest_outside(
        &self,
        i: usize,
        (w, limit, dims): (usize, usize, usize),
        seeds: &[Option<usize>],
        stack: &mut Vec<(u32, f64)>,
    ) -> Option<usize> {
        let (win, limit) = (
            (i.saturating_sub(w), i.saturating_add(w)),
            limit.min(self.rows.len()),
        );
        let q = &self.rows[i];
        let dims = dims.clamp(1, K);
        if dims == K {
            let qy = Query::<K, true> {
                q,
                win,
                limit,
                dims,
            };
            self.search(i, &qy, seeds, stack)
        } else {
            let qy = Query::<K, false> {
                q,
                win,
                limit,
                dims,
            };
            self.search(i, &qy, seeds, stack)
        }
    }

    /// [`Self::nearest_outside`] for one query: the seeds, the query's own leaf, then up.
    #[inline(always)]
    fn search<const FULL: bool>(
        &self,
        i: usize,
        qy: &Query<K, FULL>,
        seeds: &[Option<usize>],
        stack: &mut Vec<(u32, f64)>,
    ) -> Option<usize> {
        let mut best = Best::NONE;
        for &j in seeds.iter().flatten() {
            if qy.admits(j) {
                let s = sq_dist(qy.q, &self.rows[j], qy.dims());
                if s <= best.thr {
                    best.take(s, j);
                }
            }
        }
        let mut k = self.leaf_of[i] as usize;
        if !qy.excludes(self.boxes[k].span) {
            self.scan_leaf(k, qy, &mut best);
        }
        while k > 1 && !self.ball_inside_cell(k, qy, best.thr) {
            self.search_subtree(k ^ 1, qy, &mut best, stack);
            k /= 2;
        }
        (best.j != usize::MAX).then_some(best.j)
    }
}

#[cfg(test)]
mod tests {
    use super::super::neighbours::nn_brute;
    use super::*;

    /// A gait-like trajectory (two harmonics, repeated values for exact ties) in 3 dimensions:
    /// every query, whatever the seeds, gives the brute-force answer, also over the first one
    /// or two coordinates of the same tree and below a row limit.
    #[test]
    fn nearest_outside_equals_brute_force_whatever_the_seed() {
        let x: Vec<f64> = (0..700)
            .map(|i| {
                let t = i as f64 / 50.0;
                let v = (6.2 * t).sin() + 0.3 * (12.4 * t).cos();
                (v * 64.0).round() / 64.0 // quantised: exact ties
            })
            .collect();
        let rows: Vec<[f64; 3]> = (0..x.len() - 20)
            .map(|i| [x[i], x[i + 10], x[i + 20]])
            .collect();
        let n = rows.len();
        let tree = WindowTree::new(rows.clone());
        let mut stack = Vec::new();
        for (dims, limit) in [(3, n), (2, n), (1, n), (3, n - 37), (2, n / 2)] {
            let flat: Vec<f64> = rows[..limit]
                .iter()
                .flat_map(|r| r[..dims].to_vec())
                .collect();
            for w in [0, 1, 7, 50, 300] {
                if limit < 2 * w + 2 {
                    continue;
                }
                let want = nn_brute(&flat, dims, w);
                for (i, &j) in want.iter().enumerate() {
                    for seeds in [
                        vec![],
                        vec![Some(0)],
                        vec![Some(i + w + 1), None],
                        vec![Some(n - 1), Some(j), Some(i)],
                        vec![Some(10_000)],
                    ] {
                        assert_eq!(
                            tree.nearest_outside(i, (w, limit, dims), &seeds, &mut stack),
                            Some(j),
                            "row {i}, window {w}, dims {dims}, limit {limit}, seeds {seeds:?}"
                        );
                    }
                }
            }
        }
        // every row inside the window: no neighbour
        assert_eq!(tree.nearest_outside(5, (n, n, 3), &[], &mut stack), None);
    }
}
