//! Building a [`WindowTree`]: median splits from rows kept sorted on every axis.
//!
//! Every axis has a list of the rows sorted on it (node `k`'s rows occupy the same range of
//! every list). A node splits at the median of its widest axis: the first half of that axis's
//! list goes left; the other lists are partitioned stably, so they stay sorted and no selection
//! is needed at any level (`O(K·n)` per level after the sorts). For a delay embedding the axes
//! are shifted copies of one series, so one sort of the series gives every axis's list (and
//! serves every tree built over it, see [`delay_orders`]). The split only shapes the tree:
//! which rows a node holds never changes a query's answer (see the module docs of the parent).

use super::{NodeBox, WindowTree, LEAF};

/// An integer whose order is [`f64::total_cmp`]'s (the same transformation): the sorts compare
/// integers instead of transforming both floats at every comparison.
#[inline(always)]
fn total_order_key(v: f64) -> i64 {
    let b = v.to_bits() as i64;
    b ^ ((((b >> 63) as u64) >> 1) as i64)
}

/// The positions of `x` sorted by [`f64::total_cmp`] (NaN after every number); ties in any
/// order. `x.len()` must fit in `u32` (callers check).
pub(crate) fn total_order(x: &[f64]) -> Vec<u32> {
    let mut keyed: Vec<(i64, u32)> = x
        .iter()
        .zip(0u32..)
        .map(|(&v, t)| (total_order_key(v), t))
        .collect();
    keyed.sort_unstable_by_key(|e| e.0);
    keyed.into_iter().map(|e| e.1).collect()
}

/// Per axis `a < K`, the rows `0..rows` of the delay embedding of `x` (row `i`, axis `a` =
/// `x[i + a·lag]`, NaN past the end of `x`) sorted on that axis, from `x_order` =
/// [`total_order`] of `x`: the positions `t` with `a·lag ≤ t < a·lag + rows` in that order,
/// shifted to rows, then the rows whose coordinate lies past the end (NaN sorts last).
pub(crate) fn delay_orders<const K: usize>(
    x_len: usize,
    x_order: &[u32],
    lag: usize,
    rows: usize,
) -> Vec<Vec<u32>> {
    (0..K)
        .map(|a| {
            let off = a * lag;
            let mut list: Vec<u32> = x_order
                .iter()
                .map(|&t| t as usize)
                .filter(|&t| t >= off && t < off + rows)
                .map(|t| (t - off) as u32)
                .collect();
            list.extend((x_len.saturating_sub(off).min(rows)..rows).map(|i| i as u32));
            list
        })
        .collect()
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

/// Scratch space of the build: each row's side of the current split, and one side's rows.
struct Scratch {
    right: Vec<bool>,
    tmp: Vec<u32>,
}

impl<const K: usize> WindowTree<K> {
    /// Build the tree (`O(n log n)`), sorting every axis. `rows.len()` must fit in `u32`
    /// (callers check).
    pub(crate) fn new(rows: Vec<[f64; K]>) -> Self {
        let orders = (0..K)
            .map(|a| total_order(&rows.iter().map(|r| r[a]).collect::<Vec<f64>>()))
            .collect();
        Self::with_orders(rows, orders)
    }

    /// Build the tree from `orders[a]`, the rows sorted on axis `a` by [`f64::total_cmp`]
    /// (ties in any order), for every `a < K` (e.g. from [`delay_orders`]).
    pub(crate) fn with_orders(rows: Vec<[f64; K]>, mut orders: Vec<Vec<u32>>) -> Self {
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
            idx: Vec::new(),
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
        let mut scratch = Scratch {
            right: vec![false; n],
            tmp: vec![0; n],
        };
        t.split(1, (0, n), (lo, hi), &mut orders, &mut scratch);
        // every list holds each leaf's rows in its range: the first gives the leaf order
        t.idx = orders.swap_remove(0);
        t.fill_blocks();
        t.boxes();
        t
    }

    /// Partition node `k` (rows `orders[a][start..end]`, sorted on each axis `a`) and its
    /// descendants: median split on the widest side of `ext` (the node's cell clipped to the
    /// bounding box of all rows; choosing the axis from it needs no pass over the rows), the
    /// leaf of every row.
    fn split(
        &mut self,
        k: usize,
        (start, end): (usize, usize),
        ext: ([f64; K], [f64; K]),
        orders: &mut [Vec<u32>],
        scratch: &mut Scratch,
    ) {
        self.range[k] = (start as u32, end as u32);
        if k >= self.first_leaf {
            for &r in &orders[0][start..end] {
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
            let sorted = &orders[axis][start..end];
            for (p, &r) in sorted.iter().enumerate() {
                scratch.right[r as usize] = p >= mid - start;
            }
            // left rows ≤ v ≤ right rows on the axis (total order ⊂ numeric order; NaN, which
            // sorts last, leaves the cells as they are)
            let v = self.rows[sorted[mid - start] as usize][axis];
            for (a, list) in orders.iter_mut().enumerate() {
                if a != axis {
                    partition_stable(&mut list[start..end], &scratch.right, &mut scratch.tmp);
                }
            }
            if !v.is_nan() {
                self.cells[left].1[axis] = v;
                self.cells[right].0[axis] = v;
                ext_l.1[axis] = v;
                ext_r.0[axis] = v;
            }
        }
        self.split(left, (start, mid), ext_l, orders, scratch);
        self.split(right, (mid, end), ext_r, orders, scratch);
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
}

/// Reorder `list` so that the rows with `right[r] == false` come first, each side in its
/// previous order. Both destinations are written for every row and only the chosen one's
/// cursor advances (no branch on the side, which is unpredictable).
fn partition_stable(list: &mut [u32], right: &[bool], tmp: &mut [u32]) {
    let tmp = &mut tmp[..list.len()];
    let (mut w, mut t) = (0, 0);
    for p in 0..list.len() {
        let r = list[p];
        let is_right = right[r as usize] as usize;
        // w, t ≤ p (`min` only tells the compiler, which then drops the bounds checks)
        list[w.min(p)] = r;
        tmp[t.min(p)] = r;
        w += 1 - is_right;
        t += is_right;
    }
    list[w..].copy_from_slice(&tmp[..t]);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every axis's list from one sort of the series is a permutation of the rows sorted on
    /// that axis (rows past the end of the series, NaN there, last), ties and all.
    #[test]
    fn delay_orders_sort_every_axis() {
        let x: Vec<f64> = (0..300)
            .map(|i| ((i as f64 * 0.31).sin() * 8.0).round() / 8.0)
            .collect();
        let (lag, rows) = (7, 290);
        let orders = delay_orders::<4>(x.len(), &total_order(&x), lag, rows);
        for (a, list) in orders.iter().enumerate() {
            let at = |i: u32| x.get(i as usize + a * lag).copied().unwrap_or(f64::NAN);
            let mut seen = list.clone();
            seen.sort_unstable();
            assert_eq!(seen, (0..rows as u32).collect::<Vec<_>>(), "axis {a}");
            for w in list.windows(2) {
                assert!(at(w[0]).total_cmp(&at(w[1])).is_le(), "axis {a}: {w:?}");
            }
        }
    }

    /// The stable partition keeps each side's order.
    #[test]
    fn partition_keeps_each_side_in_order() {
        let mut list: Vec<u32> = (0..20).rev().collect();
        let right: Vec<bool> = (0..20).map(|r| r % 3 == 0).collect();
        let mut tmp = vec![0; 20];
        partition_stable(&mut list, &right, &mut tmp);
        let want: Vec<u32> = (0..20)
            .rev()
            .filter(|r| r % 3 != 0)
            .chain((0..20).rev().filter(|r| r % 3 == 0))
            .collect();
        assert_eq!(list, want);
    }
}
