//! Table 3 (paper §3.4, SPEC §5): per parameter the groups' mean ± SD and Shapiro–Wilk, the
//! paired and independent tests chosen by normality, ANOVA and Kruskal–Wallis, Holm-adjusted per
//! comparison; as Markdown and as flat CSV rows.

use serde::{Deserialize, Serialize};

use super::{Cohort, PARAMETERS};
use crate::stats;

/// A test outcome: which test, its p-value and the Holm-adjusted one, or why there is none.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct TestResult {
    /// Test used (`paired t`, `wilcoxon`, `student t`, `mann-whitney u`, `anova`, `kruskal`).
    pub test: String,
    /// Statistic.
    pub statistic: Option<f64>,
    /// p-value.
    pub p: Option<f64>,
    /// Holm-adjusted p across the parameters of the same comparison.
    pub p_holm: Option<f64>,
    /// Why there is no p-value.
    pub note: String,
}

/// Mean and SD (ddof = 1) of a group.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Subjects.
    pub n: usize,
    /// Mean.
    pub mean: Option<f64>,
    /// SD.
    pub sd: Option<f64>,
    /// Shapiro–Wilk p.
    pub shapiro_p: Option<f64>,
}

/// One row of Table 3.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParameterStats {
    /// The parameter.
    pub code: String,
    /// Column name.
    pub column: String,
    /// Unit.
    pub unit: String,
    /// LDH unaffected side.
    pub ldhh: Summary,
    /// LDH affected side.
    pub ldhe: Summary,
    /// Healthy (mean of both legs).
    pub h: Summary,
    /// LDHH vs LDHE, paired (primary).
    pub he_paired: TestResult,
    /// LDHH vs LDHE, independent (the paper's test).
    pub he_independent: TestResult,
    /// LDHH vs H.
    pub hh: TestResult,
    /// LDHE vs H.
    pub eh: TestResult,
    /// Healthy left vs right, paired.
    pub lr: TestResult,
    /// One-way ANOVA over LDHH, LDHE, H.
    pub anova: TestResult,
    /// Kruskal–Wallis over LDHH, LDHE, H.
    pub kruskal: TestResult,
}

fn summary(x: &[f64]) -> Summary {
    Summary {
        n: x.len(),
        mean: stats::mean(x).ok(),
        sd: stats::std_dev(x).ok(),
        shapiro_p: stats::shapiro(x).ok().map(|r| r.pvalue),
    }
}

fn normal(x: &[f64]) -> bool {
    stats::shapiro(x).map(|r| r.pvalue > 0.05).unwrap_or(false)
}

fn outcome(test: &str, r: std::result::Result<(f64, f64), stats::StatsError>) -> TestResult {
    match r {
        Ok((s, p)) => TestResult {
            test: test.into(),
            statistic: Some(s),
            p: Some(p),
            p_holm: None,
            note: String::new(),
        },
        Err(e) => TestResult {
            test: test.into(),
            note: e.to_string(),
            ..TestResult::default()
        },
    }
}

fn paired(a: &[f64], b: &[f64]) -> TestResult {
    use stats::Alternative::TwoSided;
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| y - x).collect();
    if normal(&d) {
        outcome(
            "paired t",
            stats::ttest_rel(a, b, TwoSided).map(|r| (r.statistic, r.pvalue)),
        )
    } else {
        outcome(
            "wilcoxon",
            stats::wilcoxon_paired(a, b, TwoSided).map(|r| (r.statistic, r.pvalue)),
        )
    }
}

fn independent(a: &[f64], b: &[f64]) -> TestResult {
    use stats::Alternative::TwoSided;
    if normal(a) && normal(b) {
        outcome(
            "student t",
            stats::ttest_ind(a, b, true, TwoSided).map(|r| (r.statistic, r.pvalue)),
        )
    } else {
        outcome(
            "mann-whitney u",
            stats::mannwhitneyu(a, b, TwoSided).map(|r| (r.statistic, r.pvalue)),
        )
    }
}

/// Table 3: statistics for every parameter, Holm-adjusted per comparison.
pub fn table3(c: &Cohort) -> Vec<ParameterStats> {
    let mut rows: Vec<ParameterStats> = PARAMETERS
        .iter()
        .map(|p| {
            let g = c.groups(*p);
            let three: [&[f64]; 3] = [&g.ldhh, &g.ldhe, &g.h];
            ParameterStats {
                code: p.code().into(),
                column: p.column().into(),
                unit: p.unit().into(),
                ldhh: summary(&g.ldhh),
                ldhe: summary(&g.ldhe),
                h: summary(&g.h),
                he_paired: paired(&g.ldhh, &g.ldhe),
                he_independent: independent(&g.ldhh, &g.ldhe),
                hh: independent(&g.ldhh, &g.h),
                eh: independent(&g.ldhe, &g.h),
                lr: paired(&g.h_left, &g.h_right),
                anova: outcome(
                    "anova",
                    stats::f_oneway(&three).map(|r| (r.statistic, r.pvalue)),
                ),
                kruskal: outcome(
                    "kruskal",
                    stats::kruskal(&three).map(|r| (r.statistic, r.pvalue)),
                ),
            }
        })
        .collect();
    type Field = fn(&mut ParameterStats) -> &mut TestResult;
    let fields: [Field; 7] = [
        |r| &mut r.he_paired,
        |r| &mut r.he_independent,
        |r| &mut r.hh,
        |r| &mut r.eh,
        |r| &mut r.lr,
        |r| &mut r.anova,
        |r| &mut r.kruskal,
    ];
    for f in fields {
        let idx: Vec<usize> = (0..rows.len())
            .filter(|&i| f(&mut rows[i]).p.is_some())
            .collect();
        let ps: Vec<f64> = idx
            .iter()
            .map(|&i| f(&mut rows[i]).p.expect("filtered"))
            .collect();
        if let Ok(adj) = stats::holm(&ps) {
            for (k, &i) in idx.iter().enumerate() {
                f(&mut rows[i]).p_holm = Some(adj[k]);
            }
        }
    }
    rows
}

/// A p-value as the tables print it.
pub fn fmt_p(p: Option<f64>) -> String {
    match p {
        Some(p) if p < 0.001 => "<0.001".into(),
        Some(p) => format!("{p:.3}"),
        None => "–".into(),
    }
}

pub(crate) fn fmt_ms(s: &Summary) -> String {
    match (s.mean, s.sd) {
        (Some(m), Some(sd)) => format!("{m:.3} (±{sd:.3})"),
        (Some(m), None) => format!("{m:.3}"),
        _ => "–".into(),
    }
}

/// [`fmt_ms`] with the number of subjects when fewer than the group's `group_n` have the value
/// (the others' withheld: recordings.csv `withheld` says why).
pub fn fmt_ms_n(s: &Summary, group_n: usize) -> String {
    if s.n < group_n {
        format!("{} (n = {})", fmt_ms(s), s.n)
    } else {
        fmt_ms(s)
    }
}

/// Whether some cell of `rows` has fewer subjects than its group ([`fmt_ms_n`]).
pub fn any_partial(rows: &[ParameterStats], c: &Cohort) -> bool {
    let (l, h) = (c.ldh.len(), c.healthy.len());
    rows.iter()
        .any(|r| r.ldhh.n < l || r.ldhe.n < l || r.h.n < h)
}

/// The sentence under a table with partial cells.
pub const PARTIAL_NOTE: &str = "A cell with its own n has fewer subjects than its group: the others' values were not measured (recordings.csv `withheld` says why; e.g. the ACC-only model reports no stride length, and stride length variability is withheld on walks under ≈ 25 s).";

/// Table 3 as Markdown, laid out like the paper's (HE is the paired test; Holm in brackets).
pub fn table3_markdown(rows: &[ParameterStats], c: &Cohort) -> String {
    let mut s = format!(
        "Model `{}`: LDH n = {}, healthy n = {}. Mean (± SD); p-values, Holm-adjusted across parameters in brackets. HE is paired ({}), the paper's independent test in the next column.\n\n",
        c.model,
        c.ldh.len(),
        c.healthy.len(),
        "paired t or Wilcoxon by Shapiro–Wilk of the differences"
    );
    s.push_str("| Feature | unit | LDHH | LDHE | H | HE (paired) | HE (indep.) | H-H | E-H | LR | ANOVA | Kruskal |\n");
    s.push_str("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    let (nl, nh) = (c.ldh.len(), c.healthy.len());
    for r in rows {
        let t = |x: &TestResult| format!("{} ({})", fmt_p(x.p), fmt_p(x.p_holm));
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            r.code,
            r.unit,
            fmt_ms_n(&r.ldhh, nl),
            fmt_ms_n(&r.ldhe, nl),
            fmt_ms_n(&r.h, nh),
            t(&r.he_paired),
            t(&r.he_independent),
            t(&r.hh),
            t(&r.eh),
            t(&r.lr),
            t(&r.anova),
            t(&r.kruskal)
        ));
    }
    if any_partial(rows, c) {
        s.push_str(&format!("\n{PARTIAL_NOTE}\n"));
    }
    if !c.excluded.is_empty() {
        s.push_str(&format!("\nLeft out: {}.\n", c.excluded.join("; ")));
    }
    s
}

/// A flat row of Table 3 for CSV (one per parameter).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Table3Row {
    /// Model.
    pub model: String,
    /// Parameter code.
    pub code: String,
    /// Unit.
    pub unit: String,
    /// LDHH n, mean, SD, Shapiro p.
    pub ldhh_n: usize,
    /// .
    pub ldhh_mean: Option<f64>,
    /// .
    pub ldhh_sd: Option<f64>,
    /// .
    pub ldhh_shapiro_p: Option<f64>,
    /// LDHE n, mean, SD, Shapiro p.
    pub ldhe_n: usize,
    /// .
    pub ldhe_mean: Option<f64>,
    /// .
    pub ldhe_sd: Option<f64>,
    /// .
    pub ldhe_shapiro_p: Option<f64>,
    /// H n, mean, SD, Shapiro p.
    pub h_n: usize,
    /// .
    pub h_mean: Option<f64>,
    /// .
    pub h_sd: Option<f64>,
    /// .
    pub h_shapiro_p: Option<f64>,
    /// HE paired: test, p, Holm p.
    pub he_paired_test: String,
    /// .
    pub he_paired_p: Option<f64>,
    /// .
    pub he_paired_p_holm: Option<f64>,
    /// HE independent.
    pub he_independent_test: String,
    /// .
    pub he_independent_p: Option<f64>,
    /// .
    pub he_independent_p_holm: Option<f64>,
    /// H-H.
    pub hh_test: String,
    /// .
    pub hh_p: Option<f64>,
    /// .
    pub hh_p_holm: Option<f64>,
    /// E-H.
    pub eh_test: String,
    /// .
    pub eh_p: Option<f64>,
    /// .
    pub eh_p_holm: Option<f64>,
    /// LR.
    pub lr_test: String,
    /// .
    pub lr_p: Option<f64>,
    /// .
    pub lr_p_holm: Option<f64>,
    /// ANOVA.
    pub anova_p: Option<f64>,
    /// .
    pub anova_p_holm: Option<f64>,
    /// Kruskal–Wallis.
    pub kruskal_p: Option<f64>,
    /// .
    pub kruskal_p_holm: Option<f64>,
    /// Notes of undefined tests.
    pub notes: String,
}

/// Flatten Table 3 for CSV.
pub fn table3_rows(model: &str, rows: &[ParameterStats]) -> Vec<Table3Row> {
    rows.iter()
        .map(|r| {
            let notes: Vec<String> = [
                ("HE paired", &r.he_paired),
                ("HE independent", &r.he_independent),
                ("H-H", &r.hh),
                ("E-H", &r.eh),
                ("LR", &r.lr),
                ("ANOVA", &r.anova),
                ("Kruskal", &r.kruskal),
            ]
            .iter()
            .filter(|(_, t)| !t.note.is_empty())
            .map(|(n, t)| format!("{n}: {}", t.note))
            .collect();
            Table3Row {
                model: model.into(),
                code: r.code.clone(),
                unit: r.unit.clone(),
                ldhh_n: r.ldhh.n,
                ldhh_mean: r.ldhh.mean,
                ldhh_sd: r.ldhh.sd,
                ldhh_shapiro_p: r.ldhh.shapiro_p,
                ldhe_n: r.ldhe.n,
                ldhe_mean: r.ldhe.mean,
                ldhe_sd: r.ldhe.sd,
                ldhe_shapiro_p: r.ldhe.shapiro_p,
                h_n: r.h.n,
                h_mean: r.h.mean,
                h_sd: r.h.sd,
                h_shapiro_p: r.h.shapiro_p,
                he_paired_test: r.he_paired.test.clone(),
                he_paired_p: r.he_paired.p,
                he_paired_p_holm: r.he_paired.p_holm,
                he_independent_test: r.he_independent.test.clone(),
                he_independent_p: r.he_independent.p,
                he_independent_p_holm: r.he_independent.p_holm,
                hh_test: r.hh.test.clone(),
                hh_p: r.hh.p,
                hh_p_holm: r.hh.p_holm,
                eh_test: r.eh.test.clone(),
                eh_p: r.eh.p,
                eh_p_holm: r.eh.p_holm,
                lr_test: r.lr.test.clone(),
                lr_p: r.lr.p,
                lr_p_holm: r.lr.p_holm,
                anova_p: r.anova.p,
                anova_p_holm: r.anova.p_holm,
                kruskal_p: r.kruskal.p,
                kruskal_p_holm: r.kruskal.p_holm,
                notes: notes.join("; "),
            }
        })
        .collect()
}
