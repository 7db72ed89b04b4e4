//! `ldh agree`: an `ldh analyze` run against a laboratory's reference files
//! ([`ldh_core::agreement::run`]).

use std::process::ExitCode;

use anyhow::Result;
use ldh_core::agreement::{self, AgreementParams};
use ldh_core::output::LdhResults;

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
    let mut reference = agreement::read_reference(&a.reference, &results, &params)?;
    if let Some(map) = &a.walkway_map {
        let map = agreement::WalkwayMap::from_toml_file(map)?;
        let ids = agreement::WalkwayIds {
            subject_id: a.subject_id.clone(),
            trial_id: a.trial_id.clone(),
        };
        for w in &a.walkway {
            agreement::read_walkway(w, &map, &ids, &results, &params, &mut reference)?;
        }
    }
    let report = agreement::run(
        &results,
        &reference,
        &params,
        a.offset_s.unwrap_or_default(),
    )?;
    // The calibration is measured before anything is written: a refusal writes nothing.
    let calibration = match &a.write_params {
        Some(f) => {
            let p = agreement::calibrated_params(
                &report,
                results.analysis_params.as_ref(),
                a.reference_system.as_deref(),
            )?;
            Some((f, agreement::params_toml(&p)?))
        }
        None => None,
    };
    let page = ldh_report::agreement_page::agreement_html(&report)?;
    let files = agreement::write_report(&a.out, &report, &[("agreement.html", &page)])?;
    println!("{}", agreement::write::markdown(&report));
    for f in files {
        note!("wrote {}", f.display());
    }
    if let Some((f, text)) = calibration {
        ldh_core::io::write_atomic(f, text.as_bytes())?;
        note!("wrote {} (use it with ldh analyze --params)", f.display());
    }
    Ok(ExitCode::SUCCESS)
}
