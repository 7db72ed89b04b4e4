//! `ldh stats` as one call: Table 3 per attitude model, the radar charts, the box plots of the
//! primary (fusion) model and Table 4 comparing the models.

use super::{offsets, table3, table3_markdown, table3_rows, table4_markdown, Cohort, PARAMETERS};
use crate::attitude::AttitudeModel;
use crate::error::Result;
use crate::output::{self, RecordingRow};
use crate::plots;

/// What [`stats`] produced: the Markdown tables and every file of `ldh stats`' output folder.
#[derive(Debug, Clone)]
pub struct StatsOutcome {
    /// `stats.md`: Table 3 per model, then Table 4.
    pub markdown: String,
    /// Table 4 offsets, one per model.
    pub offsets: Vec<super::ModelOffsets>,
    /// `(file name, content)` of every output file, in writing order.
    pub files: Vec<(String, String)>,
}

/// Cohort statistics of per-recording tables, one table per attitude model (the first is the
/// primary one; box plots are drawn for the fusion model).
pub fn stats(models: &[Vec<RecordingRow>]) -> Result<StatsOutcome> {
    let mut files: Vec<(String, String)> = Vec::new();
    let mut md = String::from("# Cohort statistics (ldh stats)\n\n");
    let mut all_rows = Vec::new();
    let mut offs = Vec::new();
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
        let series = [
            ("LDHH".to_string(), off.z_ldhh.clone()),
            ("LDHE".to_string(), off.z_ldhe.clone()),
            ("H".to_string(), off.z_h.clone()),
        ];
        let radar = plots::radar_svg(
            &format!("Gait parameters, {} model (z vs healthy)", cohort.model),
            &off.codes,
            &series,
        )?;
        files.push((format!("radar_{}.svg", cohort.model), radar));
        if cohort.model == AttitudeModel::Fusion {
            files.extend(box_plots(&cohort)?);
        }
        offs.push(off);
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
        files,
    })
}

/// One box plot per parameter with healthy values (LDHH, LDHE, H).
fn box_plots(cohort: &Cohort) -> Result<Vec<(String, String)>> {
    let mut files = Vec::new();
    for p in PARAMETERS {
        let g = cohort.groups(p);
        if g.h.is_empty() {
            continue;
        }
        let svg = plots::boxplot_svg(
            &format!("{} ({})", p.code(), p.unit()),
            &[
                ("LDHH".into(), g.ldhh),
                ("LDHE".into(), g.ldhe),
                ("H".into(), g.h),
            ],
            true,
        )?;
        files.push((format!("box_{}.svg", p.code()), svg));
    }
    Ok(files)
}
