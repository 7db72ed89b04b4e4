//! `ldh train`: cross-validate and save classifiers ([`ldh_core::ml::train`]).

use std::process::ExitCode;

use anyhow::Result;
use ldh_core::attitude::AttitudeModel;
use ldh_core::ml::TrainParams;

use super::{progress, rows_from, thread_pool, write_files};
use crate::args::TrainArgs;

/// Run `ldh train`.
pub fn run(a: TrainArgs) -> Result<ExitCode> {
    super::check_out_dir(&a.out)?;
    let pool = thread_pool(a.jobs)?;
    let rows = rows_from(
        a.results.as_deref(),
        &a.inputs,
        AttitudeModel::Fusion,
        &pool,
    )?;
    let params = TrainParams {
        task: a.task,
        classifiers: a.classifiers,
        k: a.k,
        repeats: a.repeats,
        seed: a.seed,
        top_k: a.top_k,
        features: a
            .features
            .map(|f| f.iter().map(|s| s.trim().to_string()).collect()),
        min_feature_coverage: a.min_feature_coverage,
    };
    let pb = progress(0, "train");
    let outcome = pool.install(|| {
        ldh_core::ml::train_with_progress(&rows, &params, &|n| {
            pb.set_length(n as u64);
            pb.inc(1)
        })
    });
    pb.finish_and_clear();
    let outcome = outcome?;
    for n in &outcome.notes {
        super::note!("note: {n}");
    }
    let figures = ldh_report::figures::train_figures(&outcome)?;
    write_files(&a.out, &outcome.files)?;
    write_files(&a.out, &figures)?;
    println!("{}", outcome.markdown);
    super::note!("report, models and figures in {}", a.out.display());
    Ok(ExitCode::SUCCESS)
}
