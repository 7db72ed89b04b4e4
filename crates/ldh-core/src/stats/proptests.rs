//! Property tests: p-values in [0, 1]; Holm-adjusted ≥ raw, capped at 1 and
//! monotone in the raw order; two-sided tests invariant to swapping samples.

use proptest::prelude::*;

use super::*;

fn sample(min: usize, max: usize) -> impl Strategy<Value = Vec<f64>> {
    // values on a 1/8 grid, so that ties occur often
    prop::collection::vec((-80i32..80).prop_map(|v| f64::from(v) / 8.0), min..max)
}

fn alternative() -> impl Strategy<Value = Alternative> {
    prop_oneof![
        Just(Alternative::TwoSided),
        Just(Alternative::Less),
        Just(Alternative::Greater)
    ]
}

fn in_unit(p: f64) -> bool {
    (0.0..=1.0).contains(&p)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn pvalues_are_probabilities(x in sample(3, 40), y in sample(3, 40), alt in alternative()) {
        if let Ok(r) = shapiro(&x) { prop_assert!(in_unit(r.pvalue) && r.statistic > 0.0 && r.statistic <= 1.0 + 1e-12); }
        if let Ok(r) = mannwhitneyu(&x, &y, alt) { prop_assert!(in_unit(r.pvalue)); }
        for eq in [true, false] {
            if let Ok(r) = ttest_ind(&x, &y, eq, alt) { prop_assert!(in_unit(r.pvalue)); }
        }
        if let Ok(r) = ttest_1samp(&x, 0.5, alt) { prop_assert!(in_unit(r.pvalue)); }
        let n = x.len().min(y.len());
        if let Ok(r) = ttest_rel(&x[..n], &y[..n], alt) { prop_assert!(in_unit(r.pvalue)); }
        if let Ok(r) = wilcoxon_paired(&x[..n], &y[..n], alt) { prop_assert!(in_unit(r.pvalue)); }
        if let Ok(r) = pearsonr(&x[..n], &y[..n], alt) {
            prop_assert!(in_unit(r.pvalue) && (-1.0..=1.0).contains(&r.statistic));
        }
        if let Ok(r) = f_oneway(&[&x, &y]) { prop_assert!(in_unit(r.pvalue)); }
        if let Ok(r) = kruskal(&[&x, &y]) { prop_assert!(in_unit(r.pvalue) && r.statistic >= -1e-9); }
    }

    #[test]
    fn never_nan(x in sample(0, 12), y in sample(0, 12), alt in alternative()) {
        // whatever the input (tiny, constant, empty), the result is an error or finite
        let mut ps = Vec::new();
        if let Ok(r) = shapiro(&x) { ps.push((r.statistic, r.pvalue)); }
        if let Ok(r) = mannwhitneyu(&x, &y, alt) { ps.push((r.statistic, r.pvalue)); }
        if let Ok(r) = ttest_ind(&x, &y, true, alt) { ps.push((r.statistic, r.pvalue)); }
        if let Ok(r) = ttest_ind(&x, &y, false, alt) { ps.push((r.statistic, r.pvalue)); }
        if let Ok(r) = ttest_1samp(&x, 0.0, alt) { ps.push((r.statistic, r.pvalue)); }
        if let Ok(r) = wilcoxon(&x, alt) { ps.push((r.statistic, r.pvalue)); }
        if let Ok(r) = f_oneway(&[&x, &y]) { ps.push((r.statistic, r.pvalue)); }
        if let Ok(r) = kruskal(&[&x, &y]) { ps.push((r.statistic, r.pvalue)); }
        let n = x.len().min(y.len());
        if let Ok(r) = pearsonr(&x[..n], &y[..n], alt) { ps.push((r.statistic, r.pvalue)); }
        for (s, p) in ps {
            prop_assert!(s.is_finite() && p.is_finite() && in_unit(p), "s={s} p={p}");
        }
    }

    #[test]
    fn holm_adjusted_dominates_and_is_monotone(p in prop::collection::vec(0.0f64..=1.0, 0..30)) {
        let adj = holm(&p).unwrap();
        prop_assert_eq!(adj.len(), p.len());
        for i in 0..p.len() {
            prop_assert!(adj[i] >= p[i] && adj[i] <= 1.0);
            for j in 0..p.len() {
                if p[i] <= p[j] {
                    prop_assert!(adj[i] <= adj[j], "raw {} <= {} but adjusted {} > {}", p[i], p[j], adj[i], adj[j]);
                }
            }
        }
    }

    #[test]
    fn two_sided_tests_are_symmetric_in_the_samples(x in sample(2, 30), y in sample(2, 30)) {
        let ts = Alternative::TwoSided;
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(1e-300) + 1e-15;
        match (mannwhitneyu(&x, &y, ts), mannwhitneyu(&y, &x, ts)) {
            (Ok(a), Ok(b)) => {
                prop_assert!(close(a.pvalue, b.pvalue), "{} vs {}", a.pvalue, b.pvalue);
                prop_assert!(close(a.statistic + b.statistic, (x.len() * y.len()) as f64));
            }
            (a, b) => prop_assert_eq!(a.is_err(), b.is_err()),
        }
        for eq in [true, false] {
            match (ttest_ind(&x, &y, eq, ts), ttest_ind(&y, &x, eq, ts)) {
                (Ok(a), Ok(b)) => {
                    prop_assert!(close(a.pvalue, b.pvalue));
                    prop_assert!(close(a.statistic, -b.statistic));
                }
                (a, b) => prop_assert_eq!(a.is_err(), b.is_err()),
            }
        }
        let n = x.len().min(y.len());
        match (ttest_rel(&x[..n], &y[..n], ts), ttest_rel(&y[..n], &x[..n], ts)) {
            (Ok(a), Ok(b)) => prop_assert!(close(a.pvalue, b.pvalue)),
            (a, b) => prop_assert_eq!(a.is_err(), b.is_err()),
        }
        match (wilcoxon_paired(&x[..n], &y[..n], ts), wilcoxon_paired(&y[..n], &x[..n], ts)) {
            (Ok(a), Ok(b)) => {
                prop_assert!(close(a.pvalue, b.pvalue));
                prop_assert_eq!(a.statistic, b.statistic);
            }
            (a, b) => prop_assert_eq!(a.is_err(), b.is_err()),
        }
        match (pearsonr(&x[..n], &y[..n], ts), pearsonr(&y[..n], &x[..n], ts)) {
            (Ok(a), Ok(b)) => prop_assert!(close(a.pvalue, b.pvalue)),
            (a, b) => prop_assert_eq!(a.is_err(), b.is_err()),
        }
        match (f_oneway(&[&x, &y]), f_oneway(&[&y, &x])) {
            (Ok(a), Ok(b)) => prop_assert!((a.pvalue - b.pvalue).abs() <= 1e-9),
            (a, b) => prop_assert_eq!(a.is_err(), b.is_err()),
        }
        match (kruskal(&[&x, &y]), kruskal(&[&y, &x])) {
            (Ok(a), Ok(b)) => prop_assert!((a.pvalue - b.pvalue).abs() <= 1e-9),
            (a, b) => prop_assert_eq!(a.is_err(), b.is_err()),
        }
    }

    #[test]
    fn one_sided_pvalues_complement(x in sample(3, 25), y in sample(3, 25)) {
        // for continuous-distribution tests, P(less) + P(greater) = 1
        if let (Ok(l), Ok(g)) = (ttest_ind(&x, &y, false, Alternative::Less), ttest_ind(&x, &y, false, Alternative::Greater)) {
            prop_assert!((l.pvalue + g.pvalue - 1.0).abs() < 1e-9);
        }
        let n = x.len().min(y.len());
        if let (Ok(l), Ok(g)) = (pearsonr(&x[..n], &y[..n], Alternative::Less), pearsonr(&x[..n], &y[..n], Alternative::Greater)) {
            prop_assert!((l.pvalue + g.pvalue - 1.0).abs() < 1e-9);
        }
    }
}
