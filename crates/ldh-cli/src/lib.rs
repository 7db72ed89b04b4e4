#![doc = include_str!("../README.md")]
//!
//! ## Layout
//!
//! The `ldh` command line: argument parsing ([`args`]), one adapter per command
//! ([`commands`]), files, parallelism, progress, output and exit codes. No signal processing
//! happens here; every computation is a call into `ldh_core`.
//!
//! Exit codes: 0 all good; 1 some inputs failed (the others' results are written); 2 usage or
//! a failure that stopped the whole command.

use std::process::ExitCode;

use clap::Parser;

pub mod args;
pub mod commands;

pub use args::Cli;
use args::Command;
pub use commands::resolve_format;

/// Run the command line with these arguments (the first is the program name).
pub fn run<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            };
        }
    };
    commands::set_verbosity(cli.verbosity);
    let r = match cli.command {
        Command::Analyze(a) => commands::analyze::run(a),
        Command::Monitor(a) => commands::monitor::run(a),
        Command::Report(a) => commands::report::run(a),
        Command::Evaluate(a) => commands::evaluate::run(a),
        Command::Agree(a) => commands::agree::run(a),
        Command::Stats(a) => commands::stats::run(a),
        Command::Train(a) => commands::train::run(a),
        Command::Predict(a) => commands::predict::run(a),
        Command::Simulate(a) => commands::simulate::run(a),
        Command::Inspect(a) => commands::inspect::run(a),
        Command::Formats { name } => commands::formats::run(name),
        Command::Columns { name } => commands::columns::run(name),
        Command::Demo { out } => commands::demo::run(&out),
        Command::Completions { shell } => commands::completions::run(shell),
        Command::Man { command, out } => commands::completions::man(command.as_deref(), out),
    };
    match r {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {}", message(&e));
            ExitCode::from(2)
        }
    }
}

/// The error and its causes, each cause once (core errors already print their source).
fn message(e: &anyhow::Error) -> String {
    let mut msg = e.to_string();
    for cause in e.chain().skip(1) {
        let text = cause.to_string();
        if !msg.contains(&text) {
            msg.push_str(": ");
            msg.push_str(&text);
        }
    }
    msg
}
