//! Event times sorted for interval look-ups (issue 19): the strides ask, for every stride, for
//! the toe offs inside it, the toe off that ends its mid-stance search and the other leg's last
//! heel strike before it. A scan of the whole list for each stride made the strides stage
//! quadratic in the recording's length; here a binary search and a walk over the few times near
//! the answer give the scan's answer (the same element, in the list's own order).

/// Times sorted (by `f64::total_cmp`) with their position in the original list; NaN left out
/// (no comparison selects one).
pub(super) struct SortedTimes(Vec<(f64, usize)>);

impl SortedTimes {
    pub(super) fn new(times: &[f64]) -> Self {
        let mut v: Vec<(f64, usize)> = times
            .iter()
            .copied()
            .enumerate()
            .filter(|(_, t)| !t.is_nan())
            .map(|(k, t)| (t, k))
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        SortedTimes(v)
    }

    /// The times `t > lo` for which `inside(t)` holds, where `inside` holds on a prefix of the
    /// times after `lo` in increasing order: (the first of them in list order, how many) — what
    /// `find` and `filter` on the list give.
    pub(super) fn after(&self, lo: f64, inside: impl Fn(f64) -> bool) -> (Option<f64>, usize) {
        if lo.is_nan() {
            return (None, 0);
        }
        let a = self.0.partition_point(|&(t, _)| t <= lo);
        let n = self.0[a..].iter().take_while(|&&(t, _)| inside(t)).count();
        let first = self.0[a..a + n].iter().min_by_key(|&&(_, k)| k);
        (first.map(|&(t, _)| t), n)
    }

    /// The last, in list order, of the times `t < hi` for which `inside(t)` holds, where
    /// `inside` holds on a prefix of the times before `hi` in decreasing order — what `rfind` on
    /// the list gives.
    pub(super) fn last_before(&self, hi: f64, inside: impl Fn(f64) -> bool) -> Option<f64> {
        if hi.is_nan() {
            return None;
        }
        let b = self.0.partition_point(|&(t, _)| t < hi);
        self.0[..b]
            .iter()
            .rev()
            .take_while(|&&(t, _)| inside(t))
            .max_by_key(|&&(_, k)| k)
            .map(|&(t, _)| t)
    }
}

#[cfg(test)]
mod tests {
    use super::SortedTimes;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The look-ups give what the scans they replace give, on unsorted lists with repeats, NaN
    /// and signed zeros.
    #[test]
    fn answers_are_those_of_the_scans() {
        let mut rng = ChaCha8Rng::seed_from_u64(19);
        for _ in 0..2000 {
            let n = rng.gen_range(0..40);
            let v: Vec<f64> = (0..n)
                .map(|_| match rng.gen_range(0..30) {
                    0 => f64::NAN,
                    1 => -0.0,
                    _ => rng.gen_range(0..20) as f64 * 0.25,
                })
                .collect();
            let idx = SortedTimes::new(&v);
            let lo = rng.gen_range(-2..22) as f64 * 0.25;
            let hi = lo + rng.gen_range(-2..12) as f64 * 0.25;
            let w = rng.gen_range(0..8) as f64 * 0.3;
            let within: Vec<f64> = v.iter().copied().filter(|&t| t > lo && t < hi).collect();
            assert_eq!(
                idx.after(lo, |t| t < hi),
                (within.first().copied(), within.len()),
                "{v:?} ({lo}, {hi})"
            );
            let first = v.iter().copied().find(|&t| t > lo && t - lo < w);
            assert_eq!(idx.after(lo, |t| t - lo < w).0, first, "{v:?} {lo} {w}");
            let last = v.iter().copied().rfind(|&c| c < hi && hi - c < w);
            assert_eq!(idx.last_before(hi, |c| hi - c < w), last, "{v:?} {hi} {w}");
        }
    }
}
