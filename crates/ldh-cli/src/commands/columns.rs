//! `ldh columns [NAME]`: the output column dictionary (`ldh_core::output::columns`).

use std::process::ExitCode;

use ldh_core::output::columns;

/// Run `ldh columns [NAME]`.
pub fn run(name: Option<String>) -> anyhow::Result<ExitCode> {
    let Some(n) = name else {
        print!("{}", columns::markdown());
        return Ok(ExitCode::SUCCESS);
    };
    let found = columns::lookup(&n);
    if found.is_empty() {
        let near = columns::similar(&n);
        anyhow::bail!(
            "no output column is called '{n}'{}; `ldh columns` lists them all",
            if near.is_empty() {
                String::new()
            } else {
                format!(" (did you mean {}?)", near.join(", "))
            }
        );
    }
    for c in found {
        print!("{}", columns::describe(c));
    }
    Ok(ExitCode::SUCCESS)
}
