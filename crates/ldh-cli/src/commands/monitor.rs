//! `ldh monitor`: inputs → `ldh_core::monitor::monitor_many` → the four tables.

use std::process::ExitCode;

use anyhow::Result;

use ldh_core::monitor::write::{write_changes, write_tables};
use ldh_core::monitor::{monitor_many, visit_changes, MonitorParams};
use ldh_core::pipeline::{discover_with, InputOptions};

use crate::args::MonitorArgs;

pub fn run(a: MonitorArgs) -> Result<ExitCode> {
    super::check_out_dir(&a.out)?;
    let params: MonitorParams = match &a.params {
        Some(f) => super::read_toml(f, "monitoring parameters")?,
        None => MonitorParams::default(),
    };
    let params = params.check()?;
    let inputs = discover_with(
        &a.inputs,
        &InputOptions {
            subject_id: a.subject.clone(),
            ..InputOptions::default()
        },
    )?;
    anyhow::ensure!(!inputs.is_empty(), "no subjects found in the inputs");
    let jobs = a.jobs.unwrap_or(0);
    let results = monitor_many(&inputs, &params, jobs)?;
    write_tables(&a.out, &results)?;
    let changes = visit_changes(&results);
    if !changes.is_empty() {
        write_changes(&a.out, &changes)?;
    }
    let pages = ldh_report::write_week_pages(&a.out, &results, &changes)?;
    let mut failed = 0;
    for r in &results {
        let who = match &r.visit {
            Some(v) => format!("{} ({v})", r.subject_id),
            None => r.subject_id.clone(),
        };
        for n in &r.notes {
            super::note!("{who}: {n}");
        }
        for e in &r.errors {
            eprintln!("error: {who}: {e}");
        }
        if !r.errors.is_empty() {
            failed += 1;
        }
        super::note!(
            "{who}: {} day(s), {} valid, {} walking bout(s); clock drift {}",
            r.days.len(),
            r.summary.valid_days,
            r.bouts.len(),
            if r.summary.drift_ppm.is_finite() {
                format!(
                    "{:.1} ppm ({:.2} s a day)",
                    r.summary.drift_ppm, r.summary.drift_s_per_day
                )
            } else {
                "not estimated".into()
            }
        );
    }
    super::note!(
        "wrote bouts.csv, days.csv, summary.csv, periods.csv{}, and {} week page(s) to {}",
        if changes.is_empty() {
            ""
        } else {
            ", changes.csv"
        },
        pages,
        a.out.display()
    );
    Ok(if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
