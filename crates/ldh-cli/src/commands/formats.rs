//! `ldh formats`: list the built-in vendor formats or print one as TOML.

use std::process::ExitCode;

use ldh_core::io::FormatSpec;

/// Run `ldh formats [NAME]`.
pub fn run(name: Option<String>) -> anyhow::Result<ExitCode> {
    match name {
        None => {
            for f in FormatSpec::builtins() {
                println!("{:<20} {}", f.name, f.description);
            }
        }
        Some(n) => print!("{}", super::resolve_format(&n)?.to_toml()),
    }
    Ok(ExitCode::SUCCESS)
}
