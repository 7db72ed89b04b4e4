//! Helpers shared by the end-to-end tests.
#![allow(dead_code)]

pub mod html;
pub mod print;

use std::process::{Command, Output};

/// Run the `ldh` command (the `ldh-under-test` binary, i.e. `ldh_cli::run`).
pub fn ldh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ldh-under-test"))
        .args(args)
        .output()
        .expect("runs")
}

/// stdout and stderr of a run, for messages.
pub fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// Parse a JSON file.
pub fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A CSV file's rows as cells by column name.
pub fn read_csv(p: &std::path::Path) -> Vec<std::collections::HashMap<String, String>> {
    let mut r = csv::Reader::from_path(p).unwrap();
    let h = r.headers().unwrap().clone();
    r.records()
        .map(|x| {
            let x = x.unwrap();
            h.iter()
                .zip(x.iter())
                .map(|(a, b)| (a.to_string(), b.to_string()))
                .collect()
        })
        .collect()
}

/// Run `ldh` and require success (the output is shown when it fails).
pub fn ldh_ok(args: &[&str]) -> Output {
    let o = ldh(args);
    assert!(o.status.success(), "ldh {args:?}: {}", text(&o));
    o
}

/// `ldh simulate` a cohort of `healthy` + `ldh_n` subjects of `seconds` s into `dir`.
pub fn simulate_cohort(dir: &std::path::Path, healthy: u32, ldh_n: u32, seconds: u32, seed: u64) {
    ldh_ok(&[
        "simulate",
        "--out",
        dir.to_str().unwrap(),
        "--healthy",
        &healthy.to_string(),
        "--ldh",
        &ldh_n.to_string(),
        "--seconds",
        &seconds.to_string(),
        "--seed",
        &seed.to_string(),
    ]);
}
