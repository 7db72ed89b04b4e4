//! `ldh predict`: classify recordings with a saved model ([`ldh_core::ml::predict`]).

use std::process::ExitCode;

use anyhow::Result;

use super::{rows_for, thread_pool};
use crate::args::PredictArgs;

/// Run `ldh predict`.
pub fn run(a: PredictArgs) -> Result<ExitCode> {
    super::check_out_dir(&a.out)?;
    let model = ldh_core::ml::read_model(&a.model)?;
    let rows = match &a.results {
        Some(d) => ldh_core::output::read_recordings(d)?,
        None => rows_for(
            &a.inputs,
            model.attitude_model.parse()?,
            &thread_pool(None)?,
        )?,
    };
    let outcome = ldh_core::ml::predict(&model, &rows)?;
    let file = a.out.join("predictions.csv");
    ldh_core::io::write_atomic(&file, outcome.csv.as_bytes())?;
    print!("{}", outcome.csv);
    super::note!(
        "decision support, not a diagnosis: predictions in {}",
        file.display()
    );
    Ok(if outcome.failed > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}
