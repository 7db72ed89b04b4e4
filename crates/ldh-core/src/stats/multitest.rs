//! Holm's step-down multiple-testing correction. statrs has none.

use super::StatsError;

/// Holm-adjusted p-values, equal to
/// `statsmodels.stats.multitest.multipletests(p, method="holm")[1]`:
/// with p sorted ascending, p̃_(i) = max_{j ≤ i} min(1, (m − j + 1)·p_(j)),
/// returned in the input order. Adjusted ≥ raw, monotone in the raw order,
/// capped at 1; reject H_i at level α iff p̃_i ≤ α. Empty input gives an
/// empty vector.
///
/// Errors: a value outside [0, 1] or NaN ([`StatsError::InvalidArgument`]).
pub fn holm(pvalues: &[f64]) -> Result<Vec<f64>, StatsError> {
    if let Some((i, p)) = pvalues
        .iter()
        .enumerate()
        .find(|(_, p)| !(0.0..=1.0).contains(*p))
    {
        return Err(StatsError::InvalidArgument {
            test: "holm",
            detail: format!("p-value {p} at index {i} is not in [0, 1]"),
        });
    }
    let m = pvalues.len();
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&a, &b| pvalues[a].total_cmp(&pvalues[b]));
    let mut out = vec![0.0; m];
    let mut running = 0.0f64;
    for (rank, &i) in order.iter().enumerate() {
        let adj = pvalues[i] * (m - rank) as f64;
        running = running.max(adj);
        out[i] = running.min(1.0);
    }
    Ok(out)
}
