//! `ldh inspect`: what the reader detected in sensor files ([`ldh_core::io::inspect`]).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use ldh_core::io::{inspect, GapPolicy, Inspection, ReadParams};
use rayon::prelude::*;

use super::resolve_format;
use crate::args::InspectArgs;

/// Run `ldh inspect`.
pub fn run(a: InspectArgs) -> Result<ExitCode> {
    // A misspelt path stops the command before any work, as in every command (exit 2).
    ldh_core::io::require_existing(&a.files)?;
    let format = a.format.as_deref().map(resolve_format).transpose()?;
    let rp = ReadParams {
        max_gap_s: a.max_gap_s,
        gap_policy: if a.reject_gaps {
            GapPolicy::Reject
        } else {
            GapPolicy::Split
        },
        max_file_size_mb: a
            .max_file_size_mb
            .unwrap_or(ReadParams::default().max_file_size_mb),
        max_samples: a
            .max_samples
            .map_or(ReadParams::default().max_samples, |n| n as usize),
        ..ReadParams::default()
    }
    .check()?;
    let outcomes: Vec<(PathBuf, Result<Inspection, String>)> = a
        .files
        .par_iter()
        .map(|f| {
            let r = inspect(f, format.as_ref(), &rp).map_err(|e| e.to_string());
            (f.clone(), r)
        })
        .collect();
    let failed = outcomes.iter().filter(|o| o.1.is_err()).count();
    if a.json {
        let v: Vec<serde_json::Value> = outcomes
            .iter()
            .map(|(f, r)| match r {
                Ok(i) => i.to_json(),
                Err(e) => Ok(serde_json::json!({"file": f, "error": e})),
            })
            .collect::<ldh_core::Result<_>>()?;
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        for (_, r) in &outcomes {
            match r {
                Ok(i) => {
                    println!("{}", i.line());
                    for c in i.column_lines() {
                        println!("  {c}");
                    }
                }
                Err(e) => eprintln!("error: {e}"),
            }
        }
    }
    for (f, r) in &outcomes {
        if let Ok(i) = r {
            for w in &i.read.warnings {
                eprintln!("warning: {}: {w}", f.display());
            }
        }
    }
    if failed > 0 {
        eprintln!("{failed} of {} file(s) failed", outcomes.len());
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}
