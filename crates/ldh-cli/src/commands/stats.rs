//! `ldh stats`: cohort statistics, Tables 3 and 4 ([`ldh_core::cohort::stats`]).

use std::process::ExitCode;

use anyhow::Result;
use ldh_core::attitude::AttitudeModel;

use super::{rows_for, rows_from, thread_pool, write_files};
use crate::args::StatsArgs;

/// Run `ldh stats`.
pub fn run(a: StatsArgs) -> Result<ExitCode> {
    super::check_out_dir(&a.out)?;
    let pool = thread_pool(a.jobs)?;
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
    write_files(&a.out, &outcome.files)?;
    println!("{}", outcome.markdown);
    super::note!("tables and figures in {}", a.out.display());
    Ok(ExitCode::SUCCESS)
}
