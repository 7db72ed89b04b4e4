//! The files of `ldh agree`: `agreement.csv` (one row per event kind and side, and per
//! parameter and level), `agreement.json` (the whole [`AgreementReport`], pairs and unmatched
//! events included), `agreement.md` (the same tables for reading) and the pages the caller rendered
//! (`agreement.html`, the page with the figures, is `ldh_report::agreement_page`'s). All are
//! rendered before the first is written, and each is written atomically.

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::error::Result;

use super::run::AgreementReport;

/// One row of `agreement.csv`: an event kind on one side, or a parameter at one level. Empty
/// cells where a value does not apply or could not be computed (`note` says why).
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct AgreementRow {
    /// `events`, `stride` or `recording`.
    pub level: String,
    /// `HS`, `TO` or the parameter's column.
    pub quantity: String,
    /// `left`, `right` or `both`.
    pub side: String,
    /// `all`, or the subjects' group (event rows per group, when there are two or more).
    pub group: String,
    /// ldh events (events).
    pub n_ldh: Option<usize>,
    /// Reference events (events).
    pub n_reference: Option<usize>,
    /// Matched events, or pairs used (parameters).
    pub n_matched: Option<usize>,
    /// Pairs dropped for a missing value (parameters).
    pub n_dropped: Option<usize>,
    /// Matched / reference events.
    pub recall: Option<f64>,
    /// Matched / ldh events.
    pub precision: Option<f64>,
    /// F1.
    pub f1: Option<f64>,
    /// Mean ldh − reference (s for events; the parameter's unit).
    pub bias: Option<f64>,
    /// SD of the differences.
    pub sd: Option<f64>,
    /// Bias confidence interval, low.
    pub bias_ci_low: Option<f64>,
    /// Bias confidence interval, high.
    pub bias_ci_high: Option<f64>,
    /// Lower limit of agreement.
    pub loa_lower: Option<f64>,
    /// Its confidence interval, low.
    pub loa_lower_ci_low: Option<f64>,
    /// Its confidence interval, high.
    pub loa_lower_ci_high: Option<f64>,
    /// Upper limit of agreement.
    pub loa_upper: Option<f64>,
    /// Its confidence interval, low.
    pub loa_upper_ci_low: Option<f64>,
    /// Its confidence interval, high.
    pub loa_upper_ci_high: Option<f64>,
    /// Slope of the difference on the mean (proportional bias).
    pub proportional_bias_slope: Option<f64>,
    /// Its two-sided p-value.
    pub proportional_bias_pvalue: Option<f64>,
    /// Mean |difference|.
    pub mae: Option<f64>,
    /// MAE / mean |reference| (parameters).
    pub relative_mae: Option<f64>,
    /// 95th percentile of |error| (events).
    pub p95_abs: Option<f64>,
    /// ICC(2,1).
    pub icc_2_1: Option<f64>,
    /// Its confidence interval, low.
    pub icc_2_1_ci_low: Option<f64>,
    /// Its confidence interval, high.
    pub icc_2_1_ci_high: Option<f64>,
    /// ICC(3,1).
    pub icc_3_1: Option<f64>,
    /// Its confidence interval, low.
    pub icc_3_1_ci_low: Option<f64>,
    /// Its confidence interval, high.
    pub icc_3_1_ci_high: Option<f64>,
    /// Pearson's r.
    pub pearson_r: Option<f64>,
    /// Why a parameter's statistics are empty.
    pub note: String,
}

/// The rows of `agreement.csv`.
pub fn rows(report: &AgreementReport) -> Vec<AgreementRow> {
    let mut out = Vec::new();
    for e in report.events.iter().chain(&report.events_by_group) {
        let s = &e.summary;
        out.push(AgreementRow {
            level: "events".into(),
            quantity: e.event.to_string(),
            side: e.side.to_string(),
            group: e.group.clone(),
            n_ldh: Some(s.n_ldh),
            n_reference: Some(s.n_reference),
            n_matched: Some(s.n_matched),
            recall: s.recall,
            precision: s.precision,
            f1: s.f1,
            bias: s.bias_s,
            sd: s.sd_s,
            mae: s.mae_s,
            p95_abs: s.p95_abs_s,
            ..Default::default()
        });
    }
    for p in &report.parameters {
        let mut row = AgreementRow {
            level: p.level.to_string(),
            quantity: p.parameter.clone(),
            side: crate::domain::Legs::Both.to_string(),
            group: super::run::ALL_GROUPS.into(),
            note: p.not_computed.clone().unwrap_or_default(),
            ..Default::default()
        };
        if let Some(a) = &p.agreement {
            let l = &a.limits;
            row.n_matched = Some(a.n_pairs);
            row.n_dropped = Some(a.n_dropped);
            row.bias = Some(l.bias);
            row.sd = Some(l.sd_diff);
            (row.bias_ci_low, row.bias_ci_high) = (Some(l.bias_ci.0), Some(l.bias_ci.1));
            row.loa_lower = Some(l.lower);
            (row.loa_lower_ci_low, row.loa_lower_ci_high) =
                (Some(l.lower_ci.0), Some(l.lower_ci.1));
            row.loa_upper = Some(l.upper);
            (row.loa_upper_ci_low, row.loa_upper_ci_high) =
                (Some(l.upper_ci.0), Some(l.upper_ci.1));
            row.proportional_bias_slope = Some(a.proportional_bias.slope);
            row.proportional_bias_pvalue = Some(a.proportional_bias.pvalue);
            row.mae = Some(a.mae);
            row.relative_mae = Some(a.relative_mae);
            let (i2, i3) = (&a.icc.icc_2_1, &a.icc.icc_3_1);
            row.icc_2_1 = Some(i2.value);
            (row.icc_2_1_ci_low, row.icc_2_1_ci_high) = (Some(i2.ci_low), Some(i2.ci_high));
            row.icc_3_1 = Some(i3.value);
            (row.icc_3_1_ci_low, row.icc_3_1_ci_high) = (Some(i3.ci_low), Some(i3.ci_high));
            row.pearson_r = Some(a.pearson_r);
        } else {
            row.n_matched = Some(p.pairs.len());
        }
        out.push(row);
    }
    out
}

fn f(x: Option<f64>, digits: usize) -> String {
    x.map_or_else(|| "—".to_string(), |v| format!("{v:.digits$}"))
}

/// The Markdown tables of a report.
pub fn markdown(report: &AgreementReport) -> String {
    let mut s = String::from("# Agreement with the reference\n\n");
    s.push_str(&format!(
        "Reference: {}. Tolerance {} s.\n\n",
        report.reference_files.join(", "),
        report.params.tolerance_s
    ));
    if report
        .offsets
        .iter()
        .any(|o| o.source != super::run::OffsetSource::None)
    {
        s.push_str("| subject | trial | clock offset (s) | source |\n|---|---|---:|---|\n");
        for o in &report.offsets {
            s.push_str(&format!(
                "| {} | {} | {:+.4} | {} |\n",
                o.subject_id, o.trial_id, o.offset_s, o.source
            ));
        }
        s.push('\n');
    }
    if !report.events.is_empty() {
        s.push_str("## Events (errors ldh − reference, ms)\n\n");
        if let [g] = report.groups.as_slice() {
            s.push_str(&format!(
                "Every subject is in group {} ({} subjects).\n\n",
                g.group, g.subjects
            ));
        }
        event_table(&mut s, &report.events, false);
    }
    if !report.events_by_group.is_empty() {
        s.push_str("## Events per group (errors ldh − reference, ms)\n\n");
        let n: Vec<String> = report
            .groups
            .iter()
            .map(|g| format!("{} {} subjects", g.group, g.subjects))
            .collect();
        s.push_str(&format!("Groups: {}.\n\n", n.join(", ")));
        event_table(&mut s, &report.events_by_group, true);
    }
    if !report.parameters.is_empty() {
        s.push_str(&format!(
            "## Parameters (differences ldh − reference; {} of {} reference strides matched)\n\n",
            report.strides_matched, report.reference_strides
        ));
        s.push_str("| level | parameter | n | bias [95 % CI] | limits of agreement | MAE (relative) | ICC(2,1) [CI] | ICC(3,1) | r |\n");
        s.push_str("|---|---|---:|---|---|---|---|---:|---:|\n");
        for p in &report.parameters {
            match &p.agreement {
                Some(a) => {
                    let l = &a.limits;
                    let i2 = &a.icc.icc_2_1;
                    s.push_str(&format!(
                        "| {} | {} | {} | {:+.4} [{:+.4}, {:+.4}] | {:+.4} to {:+.4} | {:.4} ({:.1} %) | {:.3} [{:.3}, {:.3}] | {:.3} | {:.3} |\n",
                        p.level, p.parameter, a.n_pairs, l.bias, l.bias_ci.0, l.bias_ci.1, l.lower, l.upper,
                        a.mae, a.relative_mae * 100.0, i2.value, i2.ci_low, i2.ci_high, a.icc.icc_3_1.value, a.pearson_r
                    ));
                }
                None => s.push_str(&format!(
                    "| {} | {} | {} | not computed: {} | | | | | |\n",
                    p.level,
                    p.parameter,
                    p.pairs.len(),
                    p.not_computed.as_deref().unwrap_or("").replace('|', "/")
                )),
            }
        }
    }
    s
}

/// One Markdown table of event rows (with a group column when `by_group`).
fn event_table(s: &mut String, rows: &[super::run::EventAgreement], by_group: bool) {
    let (gh, gl) = if by_group {
        ("group | ", "---|")
    } else {
        ("", "")
    };
    s.push_str(&format!(
        "| {gh}event | side | ldh / reference / matched | recall | precision | F1 | bias | SD | MAE | P95 |\n"
    ));
    s.push_str(&format!(
        "|{gl}---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n"
    ));
    for e in rows {
        let m = &e.summary;
        let ms = |x: Option<f64>| f(x.map(|v| v * 1e3), 1);
        let g = if by_group {
            format!("{} | ", e.group.replace('|', "/"))
        } else {
            String::new()
        };
        s.push_str(&format!(
            "| {g}{} | {} | {} / {} / {} | {} | {} | {} | {} | {} | {} | {} |\n",
            e.event,
            e.side,
            m.n_ldh,
            m.n_reference,
            m.n_matched,
            f(m.recall, 3),
            f(m.precision, 3),
            f(m.f1, 3),
            ms(m.bias_s),
            ms(m.sd_s),
            ms(m.mae_s),
            ms(m.p95_abs_s)
        ));
    }
    s.push('\n');
}

/// Write `agreement.csv`, `agreement.json`, `agreement.md` and then `pages` (`(file name,
/// content)`, rendered by the caller: `agreement.html` from `ldh_report::agreement_page`) into
/// `dir` (created when missing). Every file is rendered first; each is then written atomically.
/// Returns the paths.
pub fn write_report(
    dir: &Path,
    report: &AgreementReport,
    pages: &[(&str, &str)],
) -> Result<Vec<PathBuf>> {
    let csv = crate::output::to_csv(&rows(report), &["level"])?;
    let json = serde_json::to_string_pretty(report)?;
    let md = markdown(report);
    std::fs::create_dir_all(dir).map_err(|e| crate::LdhError::Write {
        path: dir.to_path_buf(),
        reason: e.to_string(),
    })?;
    let mut out = Vec::new();
    let tables = [
        ("agreement.csv", csv.as_str()),
        ("agreement.json", json.as_str()),
        ("agreement.md", md.as_str()),
    ];
    for (name, text) in tables.iter().chain(pages) {
        let p = dir.join(name);
        crate::io::write_atomic(&p, text.as_bytes())?;
        out.push(p);
    }
    Ok(out)
}
