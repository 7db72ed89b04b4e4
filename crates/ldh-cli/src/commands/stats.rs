//! `ldh stats`: cohort statistics, Tables 3 and 4 ([`ldh_core::cohort::stats`]), or with
//! `--reliability` the test–retest reliability of every parameter
//! ([`ldh_core::agreement::reliability_table`]).

use std::process::ExitCode;

use anyhow::Result;
use ldh_core::attitude::AttitudeModel;

use super::{rows_for, rows_from, thread_pool, write_files};
use crate::args::StatsArgs;

/// Run `ldh stats`.
pub fn run(a: StatsArgs) -> Result<ExitCode> {
    super::check_out_dir(&a.out)?;
    let pool = thread_pool(a.jobs)?;
    if a.reliability {
        return reliability(&a, &pool);
    }
    let mut models = vec![rows_from(
        a.results.as_deref(),
        &a.inputs,
        AttitudeModel::Fusion,
        &pool,
    )?];
    if let Some(m) = a.compare {
        models.push(rows_for(&a.inputs, m.into(), &pool)?);
    }
    let outcome = ldh_core::cohort::stats(&models)?;
    let figures = ldh_report::figures::stats_figures(&outcome)?;
    write_files(&a.out, &outcome.files)?;
    write_files(&a.out, &figures)?;
    println!("{}", outcome.markdown);
    super::note!("tables and figures in {}", a.out.display());
    Ok(ExitCode::SUCCESS)
}

/// `ldh stats --reliability`: the test–retest table of the repeated trials
/// ([`ldh_core::agreement::reliability_table`]), written as reliability.csv, .json and .md.
fn reliability(a: &StatsArgs, pool: &rayon::ThreadPool) -> Result<ExitCode> {
    let rows = rows_from(a.results.as_deref(), &a.inputs, AttitudeModel::Fusion, pool)?;
    ldh_core::cohort::require_repeated_trials(&rows)?;
    let params = ldh_core::agreement::AgreementParams::default().check()?;
    let table = ldh_core::cohort::reliability_table(&rows, &params);
    let level = params.params().confidence_level;
    write_files(&a.out, &table.files(level)?)?;
    println!("{}", table.to_markdown(level));
    super::note!("reliability.csv, .json and .md in {}", a.out.display());
    Ok(ExitCode::SUCCESS)
}
