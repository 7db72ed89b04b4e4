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
//! heap order (node `k` has children `2k`, `2k + 1`; all leaves at one depth), the rows are
//! stored leaf by leaf (axis by axis, so a leaf is measured in a few vector operations), and
//! each node knows its *cell* (the half-spaces of its ancestors' splits). A query first measures
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
//! sum of `np.sum((x - y)**2)`), the distance is its square root, the best is the smallest such distance with the lowest index among ties (`np.argmin`). A row,
//! box or cell is set aside only when a lower bound of its squared distance exceeds the best
//! distance squared by a relative 1e-9 — far more than the rounding of either sum (the bounds
//! are monotone in the rounded coordinate differences, and a sum of non-negative terms is never
//! below one of its terms), so nothing that could win or tie is ever left out. The result
//! equals the brute-force scan bit for bit whatever the seeds or the visiting order (unit test
//! below; property tests in `tests/neighbours.rs`).

/// Most rows per leaf (leaves hold between `LEAF / 2` and `LEAF` rows).
const LEAF: usize = 12;

/// Relative margin of every pruning test (see the module docs).
const MARGIN: f64 = 1.0 + 1e-9;

/// The best candidate so far: distance, row, and the pruning threshold `d² · MARGIN`.
#[derive(Clone, Copy)]
struct Best {
    d: f64,
    j: usize,
    thr: f64,
}

impl Best {
    const NONE: Best = Best {
        d: f64::INFINITY,
        j: usize::MAX,
        thr: f64::INFINITY,
    };

    /// Keep row `j` at squared distance `s` if it is nearer, or as near with a lower index.
    #[inline(always)]
    fn take(&mut self, s: f64, j: usize) {
        let d = s.sqrt();
        if d < self.d || (d == self.d && j < self.j) {
            *self = Best {
                d,
                j,
                thr: d * d * MARGIN,
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
        super::neighbours::np_sum(&sq[..dims])
    }
}

/// An integer whose order is [`f64::total_cmp`]'s (the same transformation): the median
/// selection of the build compares integers instead of transforming both floats at every
/// comparison.
#[inline(always)]
fn total_order_key(v: f64) -> i64 {
    let b = v.to_bits() as i64;
    b ^ ((((b >> 63) as u64) >> 1) as i64)
}

/// Widen the box `lo..hi` to hold `p` (NaN coordinates are left out).
#[inline(always)]
fn grow<const K: usize>(lo: &mut [f64; K], hi: &mut [f64; K], p: &[f64; K]) {
    for a in 0..K {
        if p[a] < lo[a] {
            lo[a] = p[a];
        }
        if p[a] > hi[a] {
            hi[a] = p[a];
        }
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
    /// Build the tree (`O(n log n)`). `rows.len()` must fit in `u32` (callers check).
    pub(crate) fn new(rows: Vec<[f64; K]>) -> Self {
        let n = rows.len();
        let mut depth = 0;
        while n.div_ceil(1 << depth) > LEAF {
            depth += 1;
        }
        let first_leaf = 1usize << depth;
        let nodes = 2 * first_leaf;
        let (mut lo, mut hi) = ([f64::INFINITY; K], [f64::NEG_INFINITY; K]);
        for p in &rows {
            grow(&mut lo, &mut hi, p);
        }
        let mut t = WindowTree {
            rows,
            block: Vec::new(),
            slot_row: Vec::new(),
            idx: (0..n as u32).collect(),
            leaf_of: vec![0; n],
            first_leaf,
            range: vec![(0, 0); nodes],
            boxes: vec![
                NodeBox {
                    lo: [f64::INFINITY; K],
                    hi: [f64::NEG_INFINITY; K],
                    span: (u32::MAX, 0),
                };
                nodes
            ],
            cells: vec![([f64::NEG_INFINITY; K], [f64::INFINITY; K]); nodes],
        };
        let mut keys = vec![(0i64, 0u32); n];
        t.split(1, 0, n, (lo, hi), &mut keys);
        t.fill_blocks();
        t.boxes();
        t
    }

    /// Number of rows.
    pub(crate) fn len(&self) -> usize {
        self.rows.len()
    }

    /// Partition node `k` (rows `idx[start..end]`) and its descendants: median split on the
    /// widest side of `ext` (the node's cell clipped to the bounding box of all rows; choosing
    /// the axis from it needs no pass over the rows), the leaf of every row.
    fn split(
        &mut self,
        k: usize,
        start: usize,
        end: usize,
        ext: ([f64; K], [f64; K]),
        keys: &mut [(i64, u32)],
    ) {
        self.range[k] = (start as u32, end as u32);
        if k >= self.first_leaf {
            for &r in &self.idx[start..end] {
                self.leaf_of[r as usize] = k as u32;
            }
            return;
        }
        let (lo, hi) = ext;
        let axis = (0..K)
            .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
            .unwrap_or(0);
        let mid = start + (end - start) / 2;
        let (left, right) = (2 * k, 2 * k + 1);
        (self.cells[left], self.cells[right]) = (self.cells[k], self.cells[k]);
        let (mut ext_l, mut ext_r) = (ext, ext);
        if end > start {
            let keys = &mut keys[start..end];
            for (key, &r) in keys.iter_mut().zip(&self.idx[start..end]) {
                *key = (total_order_key(self.rows[r as usize][axis]), r);
            }
            keys.select_nth_unstable_by_key(mid - start, |key| key.0);
            for (r, key) in self.idx[start..end].iter_mut().zip(keys.iter()) {
                *r = key.1;
            }
            // left rows ≤ v ≤ right rows on the axis (total order ⊂ numeric order; NaN, which
            // sorts last, leaves the cells as they are)
            let v = self.rows[keys[mid - start].1 as usize][axis];
            if !v.is_nan() {
                self.cells[left].1[axis] = v;
                self.cells[right].0[axis] = v;
                ext_l.1[axis] = v;
                ext_r.0[axis] = v;
            }
        }
        self.split(left, start, mid, ext_l, keys);
        self.split(right, mid, end, ext_r, keys);
    }

    /// The padded leaf blocks, from the rows in leaf order.
    fn fill_blocks(&mut self) {
        let leaves = self.first_leaf;
        self.block = vec![f64::NAN; leaves * K * LEAF];
        self.slot_row = vec![u32::MAX; leaves * LEAF];
        for l in 0..leaves {
            let (a, b) = self.range[leaves + l];
            for (slot, &r) in self.idx[a as usize..b as usize].iter().enumerate() {
                self.slot_row[l * LEAF + slot] = r;
                for ax in 0..K {
                    self.block[(l * K + ax) * LEAF + slot] = self.rows[r as usize][ax];
                }
            }
        }
    }

    /// Bounding boxes and row spans, from the leaves up.
    fn boxes(&mut self) {
        for k in self.first_leaf..2 * self.first_leaf {
            let (a, b) = self.range[k];
            let (mut lo, mut hi) = ([f64::INFINITY; K], [f64::NEG_INFINITY; K]);
            let (mut min_i, mut max_i) = (u32::MAX, 0u32);
            for &r in &self.idx[a as usize..b as usize] {
                grow(&mut lo, &mut hi, &self.rows[r as usize]);
                min_i = min_i.min(r);
                max_i = max_i.max(r);
            }
            self.boxes[k] = NodeBox {
                lo,
                hi,
                span: (min_i, max_i),
            };
        }
        for k in (1..self.first_leaf).rev() {
            let (l, r) = (2 * k, 2 * k + 1);
            let (a, b) = (self.boxes[l], self.boxes[r]);
            let (mut lo, mut hi) = (a.lo, a.hi);
            grow(&mut lo, &mut hi, &b.lo);
            grow(&mut lo, &mut hi, &b.hi);
            self.boxes[k] = NodeBox {
                lo,
                hi,
                span: (a.span.0.min(b.span.0), a.span.1.max(b.span.1)),
            };
        }
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

    /// Measure the admitted rows of leaf `k`.
    #[inline(always)]
    fn scan_leaf<const FULL: bool>(&self, k: usize, qy: &Query<K, FULL>, best: &mut Best) {
        let l = k - self.first_leaf;
        let mut s = [0.0f64; LEAF];
        if qy.dims() < 8 {
            // numpy's plain loop, axis by axis, for all slots at once (vectorised)
            for (ax, &qa) in qy.q[..qy.dims()].iter().enumerate() {
                let col = &self.block[(l * K + ax) * LEAF..][..LEAF];
                for (sp, &x) in s.iter_mut().zip(col) {
                    let d = qa - x;
                    *sp += d * d;
                }
            }
        } else {
            for (slot, sp) in s.iter_mut().enumerate() {
                let p: [f64; K] = std::array::from_fn(|ax| self.block[(l * K + ax) * LEAF + slot]);
                *sp = sq_dist(qy.q, &p, qy.dims());
            }
        }
        // most leaves hold no row that can win or tie: one test for the leaf, on the least
        // squared distance (two lanes of selects; NaN padding is never selected)
        let mut m = [f64::INFINITY; 2];
        for pair in s.chunks_exact(2) {
            for (m, &v) in m.iter_mut().zip(pair) {
                *m = if v < *m { v } else { *m };
            }
        }
        if !(m[0] <= best.thr || m[1] <= best.thr) {
            return;
        }
        let (min_i, max_i) = self.boxes[k].span;
        // every row of the leaf admitted: no test per row
        let clear = (max_i as usize) < qy.limit
            && ((max_i as usize) < qy.win.0 || (min_i as usize) > qy.win.1);
        for (&v, &j) in s.iter().zip(&self.slot_row[l * LEAF..][..LEAF]) {
            // v > thr ⇒ √v > d: cannot win or tie
            if v <= best.thr && (clear || qy.admits(j as usize)) {
                best.take(v, j as usize);
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
                    // selects, no branch
                    let left_first = dl <= dr;
                    let near = if left_first { (l, dl) } else { (r, dr) };
                    let far = if left_first { (r, dr) } else { (l, dl) };
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
