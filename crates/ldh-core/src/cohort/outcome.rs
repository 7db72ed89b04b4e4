//! `ldh stats` as one call: Table 3 per attitude model and Table 4 comparing the models. The
//! radar charts and box plots are drawn from [`StatsOutcome::cohorts`] and
//! [`StatsOutcome::offsets`] by `ldh_report::figures::stats_figures`.

use super::{offsets, table3, table3_markdown, table3_rows, table4_markdown, Cohort};
use crate::error::Result;
use crate::output::{self, RecordingRow};

/// What [`stats`] produced: the Markdown tables and every file of `ldh stats`' output folder.
#[derive(Debug, Clone)]
pub struct StatsOutcome {
    /// `stats.md`: Table 3 per model, then Table 4.
    pub markdown: String,
    /// Table 4 offsets, one per model.
    pub offsets: Vec<super::ModelOffsets>,
    /// The cohort of every model, in the order of the tables.
    pub cohorts: Vec<Cohort>,
    /// `(file name, content)` of every table file, in writing order (the figures are
    /// `ldh_report::figures::stats_figures`').
    pub files: Vec<(String, String)>,
}

/// Cohort statistics of per-recording tables, one table per attitude model (the first is the
/// primary one).
pub fn stats(models: &[Vec<RecordingRow>]) -> Result<StatsOutcome> {
    let mut files: Vec<(String, String)> = Vec::new();
    let mut md = String::from("# Cohort statistics (ldh stats)\n\n");
    let mut all_rows = Vec::new();
    let mut offs = Vec::new();
    let mut cohorts = Vec::new();
    for rows in models {
        let cohort = Cohort::from_rows(rows)?;
        let t3 = table3(&cohort);
        md.push_str(&format!(
            "## Table 3 — model {}\n\n{}\n",
            cohort.model,
            table3_markdown(&t3, &cohort)
        ));
        all_rows.extend(table3_rows(cohort.model.as_str(), &t3));
        let off = offsets(&cohort);
        offs.push(off);
        cohorts.push(cohort);
    }
    md.push_str(&format!(
        "## Table 4 — model comparison\n\n{}",
        table4_markdown(&offs)
    ));
    files.push(("table3.csv".into(), output::to_csv(&all_rows, &[])?));
    files.push((
        "table3.json".into(),
        serde_json::to_string_pretty(&all_rows)?,
    ));
    files.push(("table4.json".into(), serde_json::to_string_pretty(&offs)?));
    files.push(("stats.md".into(), md.clone()));
    Ok(StatsOutcome {
        markdown: md,
        offsets: offs,
        cohorts,
        files,
    })
}
