//! Cohort statistics (paper §3.4 and §4.1, Tables 3–4; SPEC §5): the gait parameters of the
//! LDH subjects' unaffected (LDHH) and affected (LDHE) sides against healthy subjects (H, the
//! mean of both legs), and healthy left vs right (LR).
//!
//! For each parameter: mean ± SD per group; Shapiro–Wilk per group; then
//! * **HE** (LDHH vs LDHE): the two sides of one subject are paired data, so the primary test
//!   is paired — paired t when the differences pass Shapiro–Wilk (p > 0.05), else Wilcoxon
//!   signed-rank — with the paper's independent test beside it;
//! * **H-H** (LDHH vs H) and **E-H** (LDHE vs H): independent — Student's t when both groups
//!   pass Shapiro–Wilk, else Mann–Whitney U (the paper's rule);
//! * **LR** (healthy left vs right): paired, as HE;
//! * one-way ANOVA and Kruskal–Wallis across LDHH, LDHE and H;
//! * Holm-adjusted p-values across the parameters, per comparison, beside the raw ones.
//!
//! A test that is undefined for the data (e.g. constant values) gives no p-value and a note.
//!
//! **Model comparison** (Table 4): every parameter is z-normalised with the healthy group's mean
//! and SD (eq. 18, healthy subjects as the baseline); OFF0 = mean over parameters of the
//! |mean z| of LDHH, OFF1 the same for LDHE (eq. 19). A larger offset separates LDH from
//! healthy gait better.

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};
use crate::output::RecordingRow;
use crate::stats;

mod outcome;
pub use outcome::{stats, StatsOutcome};

/// A gait parameter of the cohort tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Parameter {
    /// Code in the paper's Table 2 (PBI is ldh's addition).
    pub code: &'static str,
    /// Column of the per-recording table.
    pub column: &'static str,
    /// Name.
    pub name: &'static str,
    /// Unit.
    pub unit: &'static str,
}

/// The parameters, in the order of the paper's Table 3 (plus PBI).
pub const PARAMETERS: [Parameter; 13] = [
    Parameter {
        code: "SF",
        column: "step_frequency_steps_per_s",
        name: "step frequency",
        unit: "steps/s",
    },
    Parameter {
        code: "SL",
        column: "stride_length_m",
        name: "stride length",
        unit: "m",
    },
    Parameter {
        code: "SS",
        column: "speed_mps",
        name: "stride speed",
        unit: "m/s",
    },
    Parameter {
        code: "STT",
        column: "step_time_s",
        name: "step time",
        unit: "s",
    },
    Parameter {
        code: "ST",
        column: "stride_time_s",
        name: "stride time",
        unit: "s",
    },
    Parameter {
        code: "STP",
        column: "stance_ratio",
        name: "stance phase",
        unit: "ratio",
    },
    Parameter {
        code: "SWP",
        column: "swing_ratio",
        name: "swing phase",
        unit: "ratio",
    },
    Parameter {
        code: "SV",
        column: "stride_length_cv",
        name: "stride length variability",
        unit: "ratio",
    },
    Parameter {
        code: "STV",
        column: "stride_time_cv",
        name: "stride time variability",
        unit: "ratio",
    },
    Parameter {
        code: "STA",
        column: "sta_per_s",
        name: "gait stability (Lyapunov)",
        unit: "1/s",
    },
    Parameter {
        code: "WQK",
        column: "wqk_deg",
        name: "max shank flexion",
        unit: "deg",
    },
    Parameter {
        code: "PBI",
        column: "pbi_deg",
        name: "peak backward inclination",
        unit: "deg",
    },
    Parameter {
        code: "BDK",
        column: "bdk_deg",
        name: "swing roll excursion",
        unit: "deg",
    },
];

/// The value of a parameter in a per-recording row.
pub fn value(row: &RecordingRow, column: &str) -> Option<f64> {
    match column {
        "step_frequency_steps_per_s" => row.step_frequency_steps_per_s,
        "stride_length_m" => row.stride_length_m,
        "speed_mps" => row.speed_mps,
        "step_time_s" => row.step_time_s,
        "stride_time_s" => row.stride_time_s,
        "stance_ratio" => row.stance_ratio,
        "swing_ratio" => row.swing_ratio,
        "stride_length_cv" => row.stride_length_cv,
        "stride_time_cv" => row.stride_time_cv,
        "sta_per_s" => row.sta_per_s,
        "wqk_deg" => row.wqk_deg,
        "pbi_deg" => row.pbi_deg,
        "bdk_deg" => row.bdk_deg,
        _ => None,
    }
    .filter(|v| v.is_finite())
}

/// One person's row for one side: the row itself when the person has one trial; with several
/// trials (rows sharing `subject_id`), the mean over the trials analysed (`status` ok) of each
/// parameter of [`PARAMETERS`] (and STA per stride) that has a value, so a person counts once in
/// every statistic, classifier and report whatever the number of trials. The aggregate's
/// duration and stride counts are the trials' sums, its `source` and `warnings` each trial's
/// (`t2: ...`), its `trial_id` says `mean of 2 trials (t1, t2)`. When no trial of that side was
/// analysed, the first failed row (its error says why).
pub fn person_row(rows: &[&RecordingRow], side: &str) -> Option<RecordingRow> {
    let all: Vec<&RecordingRow> = rows.iter().copied().filter(|r| r.side == side).collect();
    let ok: Vec<&RecordingRow> = all.iter().copied().filter(|r| r.status == "ok").collect();
    if all.len() <= 1 || ok.is_empty() {
        return all.first().map(|r| (*r).clone());
    }
    if ok.len() == 1 {
        return Some(ok[0].clone());
    }
    let mut out = ok[0].clone();
    let mean = |v: Vec<f64>| (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64);
    for p in PARAMETERS {
        set_value(
            &mut out,
            p.column,
            mean(ok.iter().filter_map(|r| value(r, p.column)).collect()),
        );
    }
    out.sta_per_stride = mean(ok.iter().filter_map(|r| r.sta_per_stride).collect());
    let sum = |f: fn(&RecordingRow) -> Option<usize>| ok.iter().map(|r| f(r)).sum();
    out.strides_total = sum(|r| r.strides_total);
    out.strides_valid = sum(|r| r.strides_valid);
    out.duration_s = ok.iter().map(|r| r.duration_s).sum();
    // Each trial's file, prefixed by its trial.
    out.source = ok
        .iter()
        .map(|r| format!("{}: {}", r.trial_id, r.source))
        .collect::<Vec<_>>()
        .join("; ");
    out.warnings = crate::pipeline::WarningList(
        ok.iter()
            .flat_map(|r| {
                r.warnings.iter().map(|w| {
                    let mut w = w.clone();
                    w.message = format!("{}: {}", r.trial_id, w.message);
                    w
                })
            })
            .collect(),
    );
    out.trial_id = format!(
        "mean of {} trials ({})",
        ok.len(),
        ok.iter()
            .map(|r| r.trial_id.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    );
    Some(out)
}

/// Set a parameter of [`PARAMETERS`] in a per-recording row.
fn set_value(row: &mut RecordingRow, column: &str, v: Option<f64>) {
    let slot = match column {
        "step_frequency_steps_per_s" => &mut row.step_frequency_steps_per_s,
        "stride_length_m" => &mut row.stride_length_m,
        "speed_mps" => &mut row.speed_mps,
        "step_time_s" => &mut row.step_time_s,
        "stride_time_s" => &mut row.stride_time_s,
        "stance_ratio" => &mut row.stance_ratio,
        "swing_ratio" => &mut row.swing_ratio,
        "stride_length_cv" => &mut row.stride_length_cv,
        "stride_time_cv" => &mut row.stride_time_cv,
        "sta_per_s" => &mut row.sta_per_s,
        "wqk_deg" => &mut row.wqk_deg,
        "pbi_deg" => &mut row.pbi_deg,
        "bdk_deg" => &mut row.bdk_deg,
        _ => return,
    };
    *slot = v;
}

/// One subject's values for the cohort analysis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubjectValues {
    /// Subject.
    pub subject_id: String,
    /// LDH: unaffected side; healthy: left leg.
    pub a: RecordingRow,
    /// LDH: affected side; healthy: right leg.
    pub b: RecordingRow,
}

/// The cohort split into groups; subjects that cannot be used are listed in `excluded`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Cohort {
    /// Attitude model of the rows.
    pub model: String,
    /// LDH subjects with both sides analysed (a = unaffected, b = affected).
    pub ldh: Vec<SubjectValues>,
    /// Healthy subjects with both legs analysed (a = left, b = right).
    pub healthy: Vec<SubjectValues>,
    /// Subjects left out, with the reason.
    pub excluded: Vec<String>,
}

/// Minimum subjects per group for the tests.
pub const MIN_GROUP_SIZE: usize = 3;

impl Cohort {
    /// Split per-recording rows (one model) into groups. Errors when a group has fewer than
    /// [`MIN_GROUP_SIZE`] usable subjects, naming what is missing.
    pub fn from_rows(rows: &[RecordingRow]) -> Result<Cohort> {
        let model = rows.first().map(|r| r.model.clone()).unwrap_or_default();
        let mut subjects = crate::output::rows_by_subject(rows);
        subjects.sort_unstable_by(|a, b| a.0.cmp(b.0));
        let mut c = Cohort {
            model,
            ldh: vec![],
            healthy: vec![],
            excluded: vec![],
        };
        for (id, rows) in subjects {
            let (l_own, r_own) = (person_row(&rows, "left"), person_row(&rows, "right"));
            let (l, r) = (l_own.as_ref(), r_own.as_ref());
            let group = l.or(r).map(|x| x.group.clone()).unwrap_or_default();
            let problem = |x: Option<&RecordingRow>, side: &str| -> Option<String> {
                match x {
                    None => Some(format!("{id}: no {side} recording")),
                    Some(x) if x.status != "ok" => {
                        Some(format!("{id}: {side} failed ({})", x.error))
                    }
                    _ => None,
                }
            };
            if let Some(p) = problem(l, "left").or_else(|| problem(r, "right")) {
                c.excluded.push(p);
                continue;
            }
            let (l, r) = (l.expect("checked").clone(), r.expect("checked").clone());
            match group.as_str() {
                "healthy" => c.healthy.push(SubjectValues {
                    subject_id: id.into(),
                    a: l,
                    b: r,
                }),
                "ldh" => match l.affected_side.as_str() {
                    "left" => c.ldh.push(SubjectValues {
                        subject_id: id.into(),
                        a: r,
                        b: l,
                    }),
                    "right" => c.ldh.push(SubjectValues {
                        subject_id: id.into(),
                        a: l,
                        b: r,
                    }),
                    other => c.excluded.push(format!(
                        "{id}: LDH subject without an affected side ('{other}')"
                    )),
                },
                "" => c.excluded.push(format!(
                    "{id}: no group (give a manifest with group and affected_side)"
                )),
                other => c.excluded.push(format!(
                    "{id}: group '{other}' is not compared (the statistics compare ldh with healthy)"
                )),
            }
        }
        for (name, n) in [("LDH", c.ldh.len()), ("healthy", c.healthy.len())] {
            if n < MIN_GROUP_SIZE {
                let why = if c.excluded.is_empty() {
                    String::new()
                } else {
                    format!("; left out: {}", c.excluded.join("; "))
                };
                return Err(LdhError::signal(
                    "cohort statistics",
                    format!("the {name} group has {n} subject(s) with both legs analysed; at least {MIN_GROUP_SIZE} are needed{why}"),
                ));
            }
        }
        Ok(c)
    }

    /// Values of one parameter: (LDHH, LDHE, H = mean of both legs, healthy left, healthy right),
    /// subjects with a missing value dropped pairwise.
    pub fn groups(&self, column: &str) -> Groups {
        let pair = |s: &SubjectValues| Some((value(&s.a, column)?, value(&s.b, column)?));
        let ldh: Vec<(f64, f64)> = self.ldh.iter().filter_map(pair).collect();
        let h: Vec<(f64, f64)> = self.healthy.iter().filter_map(pair).collect();
        Groups {
            ldhh: ldh.iter().map(|p| p.0).collect(),
            ldhe: ldh.iter().map(|p| p.1).collect(),
            h: h.iter().map(|p| (p.0 + p.1) / 2.0).collect(),
            h_left: h.iter().map(|p| p.0).collect(),
            h_right: h.iter().map(|p| p.1).collect(),
        }
    }
}

/// The groups' values of one parameter.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Groups {
    /// LDH unaffected sides.
    pub ldhh: Vec<f64>,
    /// LDH affected sides (paired with `ldhh`).
    pub ldhe: Vec<f64>,
    /// Healthy subjects, mean of both legs.
    pub h: Vec<f64>,
    /// Healthy left legs.
    pub h_left: Vec<f64>,
    /// Healthy right legs (paired with `h_left`).
    pub h_right: Vec<f64>,
}

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
            let g = c.groups(p.column);
            let three: [&[f64]; 3] = [&g.ldhh, &g.ldhe, &g.h];
            ParameterStats {
                code: p.code.into(),
                column: p.column.into(),
                unit: p.unit.into(),
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

pub(crate) fn fmt_p(p: Option<f64>) -> String {
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
    for r in rows {
        let t = |x: &TestResult| format!("{} ({})", fmt_p(x.p), fmt_p(x.p_holm));
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            r.code,
            r.unit,
            fmt_ms(&r.ldhh),
            fmt_ms(&r.ldhe),
            fmt_ms(&r.h),
            t(&r.he_paired),
            t(&r.he_independent),
            t(&r.hh),
            t(&r.eh),
            t(&r.lr),
            t(&r.anova),
            t(&r.kruskal)
        ));
    }
    if !c.excluded.is_empty() {
        s.push_str(&format!("\nLeft out: {}.\n", c.excluded.join("; ")));
    }
    s
}

/// Table 4 for one model: z-normalised group means and the offsets OFF0 / OFF1.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelOffsets {
    /// Model.
    pub model: String,
    /// Parameters used (those with a healthy SD > 0).
    pub codes: Vec<String>,
    /// Mean z of LDHH per parameter.
    pub z_ldhh: Vec<f64>,
    /// Mean z of LDHE per parameter.
    pub z_ldhe: Vec<f64>,
    /// Mean z of H per parameter (0 by construction).
    pub z_h: Vec<f64>,
    /// OFF0: mean |z| of LDHH.
    pub off0: f64,
    /// OFF1: mean |z| of LDHE.
    pub off1: f64,
}

/// z-normalisation against the healthy baseline (eq. 18) and the offsets (eq. 19).
pub fn offsets(c: &Cohort) -> ModelOffsets {
    let mut out = ModelOffsets {
        model: c.model.clone(),
        codes: vec![],
        z_ldhh: vec![],
        z_ldhe: vec![],
        z_h: vec![],
        off0: f64::NAN,
        off1: f64::NAN,
    };
    for p in PARAMETERS {
        let g = c.groups(p.column);
        let (Ok(mu), Ok(sd)) = (stats::mean(&g.h), stats::std_dev(&g.h)) else {
            continue;
        };
        if !(sd > 0.0) || g.ldhh.is_empty() {
            continue;
        }
        let z = |v: &[f64]| v.iter().map(|x| (x - mu) / sd).sum::<f64>() / v.len() as f64;
        out.codes.push(p.code.into());
        out.z_ldhh.push(z(&g.ldhh));
        out.z_ldhe.push(z(&g.ldhe));
        out.z_h.push(z(&g.h));
    }
    // No usable parameter (e.g. every healthy SD is 0): no offset, not 0.
    let m = |v: &[f64]| {
        if v.is_empty() {
            f64::NAN
        } else {
            v.iter().map(|x| x.abs()).sum::<f64>() / v.len() as f64
        }
    };
    out.off0 = m(&out.z_ldhh);
    out.off1 = m(&out.z_ldhe);
    out
}

/// Table 4 as Markdown.
pub fn table4_markdown(models: &[ModelOffsets]) -> String {
    let mut s = String::from("| Model | OFF0 (LDHH) | OFF1 (LDHE) |\n|---|---:|---:|\n");
    for m in models {
        s.push_str(&format!(
            "| {} | {:.2} | {:.2} |\n",
            m.model, m.off0, m.off1
        ));
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
