//! `ldh completions SHELL` and `ldh man`: generated from the clap definition
//! ([`clap_complete`], [`clap_mangen`]), so they never disagree with `--help`.

use std::process::ExitCode;

use anyhow::Result;
use clap::CommandFactory;

use crate::args::{Cli, Shell};

/// Print the completion script for `shell` on stdout.
pub fn run(shell: Shell) -> Result<ExitCode> {
    let mut cmd = Cli::command();
    clap_complete::generate(shell, &mut cmd, "ldh", &mut std::io::stdout());
    Ok(ExitCode::SUCCESS)
}

/// Print the manual page (roff) on stdout.
pub fn man() -> Result<ExitCode> {
    clap_mangen::Man::new(Cli::command()).render(&mut std::io::stdout())?;
    Ok(ExitCode::SUCCESS)
}
