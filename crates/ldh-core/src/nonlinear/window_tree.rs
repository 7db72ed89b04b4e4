//! Exact nearest neighbour outside a Theiler window, with a k-d tree whose search skips the
//! excluded index range (issue 17).
//!
//! kiddo's queries cannot exclude items, so a neighbour search with a Theiler window `w` had to
//! ask for the k nearest with a growing k (up to `2w + 2`) and discard the rows inside the
//! window; on gait signals, whose trajectory stays close to itself for many samples, that meant
//! sorting hundreds of results per query. This tree (Bentley 1975; Friedman, Bentley & Finkel
//! 1977: median split on the widest coordinate, leaves of [`LEAF`] rows, bounding boxes) keeps
//! the lowest and highest row index of every node, so a node lying wholly inside the window is
//! skipped, and rows inside it are never measured. The search starts from the neighbour of the
//! previous row shifted by one (trajectories are continuous, so it is usually close to the
//! answer), which bounds the search from the first leaf on.
//!
//! Exactness: every candidate is measured with [`np_euclidean`] (numpy's order), the best is the
//! smallest such distance with the lowest index among ties, and a node is pruned only when the
//! squared distance to its box exceeds the best squared distance by a relative 1e-9 — far more
//! than the rounding of either sum — so no row that could win or tie is ever left out. The
//! result equals the brute-force scan bit for bit whatever the seed or the visiting order.

use super::neighbours::np_euclidean;

/// Rows per leaf.
const LEAF: usize = 12;

struct Node {
    /// Range of `order` this node covers.
    start: u32,
    end: u32,
    /// Children (0 for a leaf: the root is never a child).
    left: u32,
    right: u32,
    /// Lowest and highest row index in the node.
    min_i: u32,
    max_i: u32,
}

/// A k-d tree over the `n` rows of a row-major `n × K` slice (`K` = dimension).
pub(crate) struct WindowTree<'a, const K: usize> {
    pts: &'a [[f64; K]],
    order: Vec<u32>,
    nodes: Vec<Node>,
    /// Bounding boxes: node `k`'s lower corner is `lo[k]`, upper `hi[k]`.
    lo: Vec<[f64; K]>,
    hi: Vec<[f64; K]>,
}

impl<'a, const K: usize> WindowTree<'a, K> {
    /// Build the tree (`O(n log n)`). `pts.len()` must fit in `u32` (callers check).
    pub(crate) fn new(pts: &'a [[f64; K]]) -> Self {
        let n = pts.len();
        let mut t = WindowTree {
            pts,
            order: (0..n as u32).collect(),
            nodes: Vec::with_capacity(2 * n / LEAF + 2),
            lo: Vec::with_capacity(2 * n / LEAF + 2),
            hi: Vec::with_capacity(2 * n / LEAF + 2),
        };
        if n > 0 {
            t.build(0, n);
        }
        t
    }

    fn build(&mut self, start: usize, end: usize) -> u32 {
        let id = self.nodes.len();
        let (mut lo, mut hi) = ([f64::INFINITY; K], [f64::NEG_INFINITY; K]);
        let (mut min_i, mut max_i) = (u32::MAX, 0u32);
        for &r in &self.order[start..end] {
            let p = &self.pts[r as usize];
            for k in 0..K {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
            min_i = min_i.min(r);
            max_i = max_i.max(r);
        }
        self.nodes.push(Node {
            start: start as u32,
            end: end as u32,
            left: 0,
            right: 0,
            min_i,
            max_i,
        });
        self.lo.push(lo);
        self.hi.push(hi);
        if end - start > LEAF {
            let axis = (0..K)
                .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
                .unwrap_or(0);
            let mid = start + (end - start) / 2;
            let pts = self.pts;
            self.order[start..end].select_nth_unstable_by(mid - start, |&a, &b| {
                pts[a as usize][axis].total_cmp(&pts[b as usize][axis])
            });
            let left = self.build(start, mid);
            let right = self.build(mid, end);
            self.nodes[id].left = left;
            self.nodes[id].right = right;
        }
        id as u32
    }

    /// Squared distance from `q` to node `k`'s box (0 inside).
    #[inline]
    fn box_dist_sq(&self, k: usize, q: &[f64; K]) -> f64 {
        let (lo, hi) = (&self.lo[k], &self.hi[k]);
        let mut s = 0.0;
        for d in 0..K {
            let e = (lo[d] - q[d]).max(q[d] - hi[d]).max(0.0);
            s += e * e;
        }
        s
    }

    /// The row `j` with `|i − j| > w` nearest to row `i` (numpy-order Euclidean distance,
    /// lowest `j` among ties), or `None` when every row is inside the window. `seed`, when it
    /// is a row outside the window, starts the search (it never changes the answer).
    /// `stack` is scratch space reused between queries.
    pub(crate) fn nearest_outside(
        &self,
        i: usize,
        w: usize,
        seed: Option<usize>,
        stack: &mut Vec<(u32, f64)>,
    ) -> Option<usize> {
        let q = &self.pts[i];
        let (wlo, whi) = (i.saturating_sub(w), i.saturating_add(w));
        let outside = |j: usize| j < wlo || j > whi;
        let mut best = (f64::INFINITY, usize::MAX);
        if let Some(j) = seed.filter(|&j| j < self.pts.len() && outside(j)) {
            best = (np_euclidean(q, &self.pts[j]), j);
        }
        // prune only boxes clearly farther than the best (see the module docs)
        let bound = |d: f64| d * d * (1.0 + 1e-9);
        stack.clear();
        if !self.nodes.is_empty() {
            stack.push((0, 0.0));
        }
        while let Some((k, lb)) = stack.pop() {
            if lb > bound(best.0) {
                continue;
            }
            let node = &self.nodes[k as usize];
            if node.min_i as usize >= wlo && node.max_i as usize <= whi {
                continue;
            }
            if node.left == 0 {
                for &r in &self.order[node.start as usize..node.end as usize] {
                    let j = r as usize;
                    if outside(j) {
                        let d = np_euclidean(q, &self.pts[j]);
                        if d < best.0 || (d == best.0 && j < best.1) {
                            best = (d, j);
                        }
                    }
                }
                continue;
            }
            let (l, r) = (node.left as usize, node.right as usize);
            let (dl, dr) = (self.box_dist_sq(l, q), self.box_dist_sq(r, q));
            // nearer child last: popped first
            if dl <= dr {
                stack.push((r as u32, dr));
                stack.push((l as u32, dl));
            } else {
                stack.push((l as u32, dl));
                stack.push((r as u32, dr));
            }
        }
        (best.1 != usize::MAX).then_some(best.1)
    }
}

#[cfg(test)]
mod tests {
    use super::super::neighbours::nn_brute;
    use super::*;

    /// A gait-like trajectory (two harmonics, repeated values for exact ties) in 3 dimensions:
    /// every query, whatever the seed, gives the brute-force answer.
    #[test]
    fn nearest_outside_equals_brute_force_whatever_the_seed() {
        let x: Vec<f64> = (0..700)
            .map(|i| {
                let t = i as f64 / 50.0;
                let v = (6.2 * t).sin() + 0.3 * (12.4 * t).cos();
                (v * 64.0).round() / 64.0 // quantised: exact ties
            })
            .collect();
        let flat: Vec<f64> = (0..x.len() - 20)
            .flat_map(|i| [x[i], x[i + 10], x[i + 20]])
            .collect();
        let pts: Vec<[f64; 3]> = flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        let tree = WindowTree::new(&pts);
        let mut stack = Vec::new();
        for w in [0, 1, 7, 50, 300] {
            let want = nn_brute(&flat, 3, w);
            for (i, &j) in want.iter().enumerate() {
                for seed in [
                    None,
                    Some(0),
                    Some(i + w + 1),
                    Some(pts.len() - 1),
                    Some(10_000),
                ] {
                    assert_eq!(
                        tree.nearest_outside(i, w, seed, &mut stack),
                        Some(j),
                        "row {i}, window {w}, seed {seed:?}"
                    );
                }
            }
        }
        // every row inside the window: no neighbour
        assert_eq!(tree.nearest_outside(5, pts.len(), None, &mut stack), None);
    }
}
