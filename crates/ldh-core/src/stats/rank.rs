//! Average ranks with tie counts (scipy `_rankdata(x, 'average', return_ties=True)`).

/// Average ranks (1-based) of finite data, plus the size of every group of
/// tied values (one entry per distinct value, in increasing value order).
pub(crate) fn rank_average(x: &[f64]) -> (Vec<f64>, Vec<usize>) {
    let n = x.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| x[a].total_cmp(&x[b]));
    let mut ranks = vec![0.0; n];
    let mut ties = Vec::new();
    let mut start = 0;
    while start < n {
        let mut end = start + 1;
        while end < n && x[order[end]] == x[order[start]] {
            end += 1;
        }
        // ordinal ranks start+1 ..= end; their average
        let rank = (start + 1 + end) as f64 / 2.0;
        for &i in &order[start..end] {
            ranks[i] = rank;
        }
        ties.push(end - start);
        start = end;
    }
    (ranks, ties)
}

/// Σ (t³ − t) over tie groups, the tie term of the rank tests.
pub(crate) fn tie_term(ties: &[usize]) -> f64 {
    ties.iter()
        .map(|&t| {
            let t = t as f64;
            t * t * t - t
        })
        .sum()
}
