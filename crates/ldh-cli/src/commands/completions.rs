//! `ldh completions SHELL` and `ldh man`: generated from the clap definition
//! ([`clap_complete`], [`clap_mangen`]), so they never disagree with `--help`.

use std::process::ExitCode;

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::CommandFactory;

use crate::args::{Cli, Shell};

/// Print the completion script for `shell` on stdout.
pub fn run(shell: Shell) -> Result<ExitCode> {
    let mut cmd = Cli::command();
    clap_complete::generate(shell, &mut cmd, "ldh", &mut std::io::stdout());
    Ok(ExitCode::SUCCESS)
}

/// Print the manual page (roff) of `ldh`, or of one of its commands (`ldh-analyze(1)`), on
/// stdout; with `out`, write every page (`ldh.1`, `ldh-analyze.1`, …) into that folder.
pub fn man(command: Option<&str>, out: Option<PathBuf>) -> Result<ExitCode> {
    let mut cmd = Cli::command().disable_help_subcommand(true);
    cmd.build();
    if let Some(dir) = out {
        std::fs::create_dir_all(&dir)
            .with_context(|| format!("{}: cannot make the folder", dir.display()))?;
        clap_mangen::generate_to(cmd, &dir)
            .with_context(|| format!("{}: cannot write the manual pages", dir.display()))?;
        return Ok(ExitCode::SUCCESS);
    }
    let page = match command {
        None => cmd,
        Some(name) => match cmd.find_subcommand(name) {
            Some(sub) => sub.clone(),
            None => {
                let known: Vec<&str> = cmd.get_subcommands().map(|s| s.get_name()).collect();
                anyhow::bail!(
                    "ldh man: no command '{name}'; the commands are {}",
                    known.join(", ")
                );
            }
        },
    };
    clap_mangen::Man::new(page).render(&mut std::io::stdout())?;
    Ok(ExitCode::SUCCESS)
}
