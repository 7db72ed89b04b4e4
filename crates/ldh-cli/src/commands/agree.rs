//! `ldh agree`: an `ldh analyze` run against a laboratory's reference files
//! ([`ldh_core::agreement::run`]).

use std::process::ExitCode;

use anyhow::Result;
use ldh_core::agreement::{self, AgreementParams, LdhResults};

use super::{check_out_dir, read_toml};
use crate::args::AgreeArgs;

/// Run `ldh agree`.
pub fn run(a: AgreeArgs) -> Result<ExitCode> {
    check_out_dir(&a.out)?;
    let mut p = match &a.params {
        Some(f) => read_toml::<AgreementParams>(f, "agreement parameters")?,
        None => AgreementParams::default(),
    };
    if let Some(t) = a.tolerance_s {
        p.tolerance_s = t;
    }
    let params = p.check()?;
    let results = LdhResults::read(&a.results)?;
    let reference = agreement::read_reference(&a.reference, &results, &params)?;
    let report = agreement::run(
        &results,
        &reference,
        &params,
        a.offset_s.unwrap_or_default(),
    )?;
    let files = agreement::write_report(&a.out, &report)?;
    println!("{}", agreement::write::markdown(&report));
    for f in files {
        note!("wrote {}", f.display());
    }
    Ok(ExitCode::SUCCESS)
}
