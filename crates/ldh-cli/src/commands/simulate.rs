//! `ldh simulate`: a cohort with exact ground truth ([`ldh_core::simulate::write_cohort`]).

use std::process::ExitCode;

use anyhow::Result;
use ldh_core::simulate::{write_cohort, CohortParams, SensorModel};

use super::{progress, resolve_format, thread_pool};
use crate::args::SimulateArgs;

/// Run `ldh simulate`.
pub fn run(a: SimulateArgs) -> Result<ExitCode> {
    super::check_out_dir(&a.out)?;
    let format = resolve_format(&a.format)?;
    let params = CohortParams {
        healthy: a.healthy,
        ldh: a.ldh,
        duration_s: a.seconds,
        fs_hz: a.rate_hz,
        seed: a.seed,
        turn: !a.no_turn,
        ldh_severity_min: a.ldh_severity_min,
        sensor: if a.ideal {
            SensorModel::ideal()
        } else {
            SensorModel::default()
        },
    };
    params.validate()?;
    let pool = thread_pool(a.jobs)?;
    let pb = progress(params.len() as u64, "simulate");
    let rows = pool.install(|| write_cohort(&params, &a.out, &format, &|| pb.inc(1)))?;
    pb.finish_and_clear();
    super::note!(
        "wrote {} subjects ({} healthy, {} LDH) to {}",
        rows.len(),
        a.healthy,
        a.ldh,
        a.out.display()
    );
    Ok(ExitCode::SUCCESS)
}
