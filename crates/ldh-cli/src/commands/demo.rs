//! `ldh demo`: write the embedded demo cohort to a folder.

use std::path::Path;
use std::process::ExitCode;

/// Run `ldh demo`.
pub fn run(out: &Path) -> anyhow::Result<ExitCode> {
    super::check_out_dir(out)?;
    let n = ldh_core::demo::write_to(out)?;
    super::note!("wrote the demo cohort ({n} files) to {}", out.display());
    Ok(ExitCode::SUCCESS)
}
