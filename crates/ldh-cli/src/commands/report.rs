//! `ldh report`: HTML reports of an `ldh analyze` output folder, read once
//! ([`ldh_report::RunResults::read`], [`ldh_report::build`]).

use std::process::ExitCode;

use anyhow::Result;
use ldh_report::{BuildSources, ReportParams, RunResults};

use super::{read_toml, thread_pool};
use crate::args::ReportArgs;

/// Run `ldh report`.
pub fn run(a: ReportArgs) -> Result<ExitCode> {
    let params = match &a.params {
        Some(f) => read_toml::<ReportParams>(f, "report parameters")?,
        None => ReportParams::default(),
    }
    .check()?;
    let model = a
        .model
        .as_deref()
        .map(ldh_core::ml::read_model)
        .transpose()?;
    let out = a.out.clone().unwrap_or_else(|| a.results.join("reports"));
    super::check_out_dir(&out)?;
    let pool = thread_pool(a.jobs)?;
    ldh_core::io::remove_stale_temp_files(&out)?;
    // The run's tables, traces and calibration, read once.
    let results = RunResults::read(&a.results)?;
    let src = BuildSources {
        model: model.as_ref(),
        stats: a.stats.as_deref(),
        train: a.train.as_deref(),
        reliability: a.reliability.as_deref(),
    };
    let n = super::build_reports(&pool, &results, &out, src, &params)?.subjects;
    super::note!(
        "{n} subject reports in {} and the cohort report {}",
        out.join("subjects").display(),
        out.join("index.html").display()
    );
    Ok(ExitCode::SUCCESS)
}
