//! The bad-input corpus (`data-fixtures/bad/`, documented in its README.md): every case through
//! the command line, with the outcome its `expected.toml` documents and never a panic.
//!
//! `inspect` cases run `ldh inspect --json FILE`; `analyze` cases run `ldh analyze FILES --out
//! TMP` and read `recordings.json`. Cases with `generated = true` are made here at run time (a
//! 0-byte file, a directory, an unreadable file, a symlink loop, a missing file, a 2-hour
//! recording), because git cannot hold them portably or they would be too large.
//! `cli` cases are sequences of runs (`bad_inputs/steps.rs`); `python` cases run in the Python
//! twin only. Every run has a time limit and its peak memory is measured (≤ 1 GB, issue 37).

use std::path::{Path, PathBuf};
use std::time::Instant;
mod common;
use common::*;
#[path = "bad_inputs/steps.rs"]
mod steps;

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../data-fixtures/bad")
}

fn strs(v: &toml::Value, key: &str) -> Vec<String> {
    v.get(key)
        .and_then(|x| x.as_array())
        .map(|a| a.iter().map(|s| s.as_str().unwrap().to_string()).collect())
        .unwrap_or_default()
}

fn s<'a>(v: &'a toml::Value, key: &str) -> &'a str {
    v.get(key).and_then(|x| x.as_str()).unwrap_or("")
}

/// A 2-hour pair: `baseline_ok` (standing at both ends) repeated back to back with continuous
/// time until 7200 s are covered.
pub fn write_two_hour(src: &Path, out: &Path) {
    for side in ["left.csv", "right.csv"] {
        let text = std::fs::read_to_string(src.join(side)).unwrap();
        let mut lines = text.lines();
        let header = lines.next().unwrap();
        let rows: Vec<(f64, &str)> = lines
            .map(|l| {
                let (t, rest) = l.split_once(',').unwrap();
                (t.parse::<f64>().unwrap(), rest)
            })
            .collect();
        let period = rows[1].0 - rows[0].0;
        let span = rows.last().unwrap().0 - rows[0].0 + period;
        let tiles = (7200.0 / span).ceil() as usize;
        let mut out_text = String::with_capacity(text.len() * tiles + 64);
        out_text.push_str(header);
        out_text.push('\n');
        for k in 0..tiles {
            for (t, rest) in &rows {
                out_text.push_str(&format!("{:.2},{rest}\n", t + k as f64 * span));
            }
        }
        std::fs::write(out.join(side), out_text).unwrap();
    }
}

/// 2500 rows (~90 kB) with a NUL byte in acc_y on line 2001, past the first 64 KiB.
fn nul_late() -> String {
    let mut t = String::from("time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n");
    for i in 0..2500 {
        let acc_y = if i == 1999 { "0.0\u{0}10" } else { "0.010" };
        t.push_str(&format!(
            "{}.{:02},1.000,{acc_y},0.020,0.5,0.6,0.7\n",
            i / 100,
            i % 100
        ));
    }
    t
}

/// Make a generated case's input in `dir`; `None` when it cannot be checked here (with the
/// reason printed).
fn generate(kind: &str, dir: &Path) -> Option<()> {
    match kind {
        "missing" => {}
        "zero_byte" => std::fs::write(dir.join("data.csv"), b"").unwrap(),
        "directory" => std::fs::create_dir(dir.join("data.csv")).unwrap(),
        "unreadable" => {
            use std::os::unix::fs::PermissionsExt;
            let f = dir.join("data.csv");
            std::fs::copy(corpus().join("single_spike/data.csv"), &f).unwrap();
            std::fs::set_permissions(&f, std::fs::Permissions::from_mode(0o000)).unwrap();
            if std::fs::read(&f).is_ok() {
                println!("unreadable_file: skipped — running as root (or on a file system without permissions), so chmod 000 does not stop reading");
                return None;
            }
        }
        "symlink_loop" => {
            std::os::unix::fs::symlink(dir.join("loop.csv"), dir.join("data.csv")).unwrap();
            std::os::unix::fs::symlink(dir.join("data.csv"), dir.join("loop.csv")).unwrap();
        }
        "two_hour" => write_two_hour(&corpus().join("baseline_ok"), dir),
        "nul_late" => std::fs::write(dir.join("data.csv"), nul_late()).unwrap(),
        "legs_of_two_people" => {
            // The demo is stored compressed: its two legs written out, with the manifest.
            for (rel, name) in [
                ("H01/left.csv", "h01_left.csv"),
                ("L01/right.csv", "l01_right.csv"),
            ] {
                std::fs::write(dir.join(name), ldh_core::demo::file(rel).unwrap()).unwrap();
            }
            std::fs::write(
                dir.join("manifest.csv"),
                "subject_id,group,affected_side,left,right\nS1,healthy,none,h01_left.csv,l01_right.csv\n",
            )
            .unwrap();
        }
        other => panic!("unknown generator {other}"),
    }
    Some(())
}

fn check_case(name: &str, exp: &toml::Value) -> Result<(), String> {
    match s(exp, "command") {
        "cli" => return steps::check_cli_case(name, exp),
        "python" => {
            println!("{name}: a Python case (crates/ldh-py/tests/test_bad_inputs.py runs it)");
            return Ok(());
        }
        _ => {}
    }
    let tmp = tempfile::tempdir().unwrap();
    let Some(dir) = case_dir(name, exp, tmp.path()) else {
        return Ok(());
    };
    let out_dir = tmp.path().join("out");
    let mut args = command_args(exp, &out_dir)?;
    args.extend(strs(exp, "args"));
    args.extend(
        strs(exp, "files")
            .iter()
            .map(|f| dir.join(f).display().to_string()),
    );
    let scratch = tempfile::tempdir().unwrap();
    let run = steps::run_measured(&args, tmp.path(), scratch.path(), 300.0);
    steps::check_run(&run, "ldh")?;
    let all = &run.text;
    let code = run.code;
    let want = exp
        .get("exit_code")
        .and_then(|x| x.as_integer())
        .unwrap_or(0) as i32;
    if code != Some(want) {
        return Err(format!("exit code {code:?}, expected {want}: {all}"));
    }
    if want == 2 && s(exp, "outcome") == "error" {
        // Refused before any work (a misspelt path): the message is the command's own.
        has(all, &strs(exp, "message_contains"), "error")
    } else if s(exp, "command") == "inspect" {
        check_inspect(exp, &run.stdout, all)
    } else {
        check_analyze(exp, &out_dir)
    }
}

/// The case's folder: the corpus's, or one generated into `tmp` (`None` when the generator is
/// not available here).
fn case_dir(name: &str, exp: &toml::Value, tmp: &Path) -> Option<PathBuf> {
    let generated = exp
        .get("generated")
        .and_then(|x| x.as_bool())
        .unwrap_or(false);
    if !generated {
        return Some(corpus().join(name));
    }
    let d = tmp.join(name);
    std::fs::create_dir(&d).unwrap();
    generate(s(exp, "generate"), &d)?;
    Some(d)
}

/// The command and its fixed options (`inspect --json`, or `analyze` into `out_dir`).
fn command_args(exp: &toml::Value, out_dir: &Path) -> Result<Vec<String>, String> {
    match s(exp, "command") {
        "inspect" => Ok(vec!["inspect".into(), "--json".into()]),
        "analyze" => Ok(vec![
            "analyze".into(),
            "--out".into(),
            out_dir.display().to_string(),
            "--jobs".into(),
            "1".into(),
        ]),
        c => Err(format!("unknown command {c}")),
    }
}

/// Every needle is in `hay` (`what` names the haystack in the failure).
fn has(hay: &str, needles: &[String], what: &str) -> Result<(), String> {
    for n in needles {
        if !hay.contains(n.as_str()) {
            return Err(format!("{what} lacks {n:?}: {hay}"));
        }
    }
    Ok(())
}

/// `inspect --json`'s output against the case (`all`: the whole output, for messages).
fn check_inspect(exp: &toml::Value, stdout: &[u8], all: &str) -> Result<(), String> {
    let outcome = s(exp, "outcome");
    let v: serde_json::Value = serde_json::from_slice(stdout)
        .map_err(|e| format!("inspect --json output is not JSON ({e}): {all}"))?;
    let r = &v[0];
    if outcome == "error" {
        let e = r["error"]
            .as_str()
            .ok_or_else(|| format!("expected an error: {r}"))?;
        return has(e, &strs(exp, "message_contains"), "error");
    }
    if r.get("error").is_some() {
        return Err(format!("unexpected error: {r}"));
    }
    let w: Vec<String> = r["read"]["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap().to_string())
        .collect();
    if outcome == "ok" && !w.is_empty() {
        return Err(format!("unexpected warnings: {w:?}"));
    }
    if outcome == "warning" && w.is_empty() {
        return Err("expected warnings, got none".into());
    }
    has(&w.join(" | "), &strs(exp, "warnings_contain"), "warnings")?;
    has(
        &r["read"]["notes"].to_string(),
        &strs(exp, "notes_contain"),
        "notes",
    )?;
    if let Some(n) = exp.get("outliers_min").and_then(|x| x.as_integer()) {
        let got = r["preprocess"]["outliers_replaced"].as_i64().unwrap();
        if got < n {
            return Err(format!("{got} outliers replaced, expected ≥ {n}"));
        }
    }
    Ok(())
}

/// `analyze`'s recordings.json in `out_dir` against the case (the case's side, if it names one).
fn check_analyze(exp: &toml::Value, out_dir: &Path) -> Result<(), String> {
    let rows = json(&out_dir.join("recordings.json"));
    let rows: Vec<&serde_json::Value> = rows
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| s(exp, "side").is_empty() || r["side"] == s(exp, "side"))
        .collect();
    if rows.is_empty() {
        return Err("no recording rows".into());
    }
    if s(exp, "outcome") == "error" {
        let errs: Vec<&str> = rows
            .iter()
            .filter(|r| r["status"] == "error")
            .map(|r| r["error"].as_str().unwrap())
            .collect();
        if errs.is_empty() {
            return Err(format!("expected a failed recording: {rows:?}"));
        }
        return has(&errs.join(" | "), &strs(exp, "message_contains"), "error");
    }
    rows.iter().try_for_each(|r| check_row(exp, r))
}

/// One analysed recording of a case expected to succeed: its warnings, withheld and measured
/// parameters, valid strides and rate.
fn check_row(exp: &toml::Value, r: &serde_json::Value) -> Result<(), String> {
    let outcome = s(exp, "outcome");
    // analysed: `ok`, or `no_valid_strides` exactly when no stride passed the checks
    let none_valid = r["strides_valid"] == 0;
    let want = if none_valid { "no_valid_strides" } else { "ok" };
    if r["status"] != want {
        return Err(format!("recording failed or its status is not {want}: {r}"));
    }
    // Structured warnings (docs/quality.md): notes are worth knowing but never make a case
    // "not ok".
    let list = r["warnings"].as_array().cloned().unwrap_or_default();
    let line = |x: &serde_json::Value| {
        let f = |k: &str| x[k].as_str().unwrap_or("").to_string();
        format!("{} [{}]: {}", f("code"), f("severity"), f("message"))
    };
    let serious: Vec<String> = list
        .iter()
        .filter(|x| x["severity"] != "note")
        .map(line)
        .collect();
    let all: Vec<String> = list.iter().map(line).collect();
    let flat = all.join(" | ");
    if outcome == "ok" && !serious.is_empty() {
        return Err(format!("unexpected warnings: {serious:?}"));
    }
    if outcome == "warning" && serious.is_empty() {
        return Err(format!("expected a warning, got {all:?}"));
    }
    has(&flat, &strs(exp, "warnings_contain"), "warnings")?;
    has(&flat, &strs(exp, "codes"), "warning codes")?;
    for c in strs(exp, "codes_absent") {
        if list.iter().any(|x| x["code"] == c.as_str()) {
            return Err(format!("unexpected {c}: {all:?}"));
        }
    }
    // Withheld parameters: an empty value (JSON null) and a reason.
    for c in strs(exp, "withheld") {
        if !r[c.as_str()].is_null() || r["withheld"][c.as_str()].as_str().is_none() {
            return Err(format!("{c} not withheld: {r}"));
        }
    }
    for c in strs(exp, "measured") {
        if !r[c.as_str()].is_number() {
            return Err(format!("{c} not measured: {r}"));
        }
    }
    if let Some(n) = exp.get("min_valid_strides").and_then(|x| x.as_integer()) {
        if r["strides_valid"].as_i64().unwrap() < n {
            return Err(format!("fewer than {n} valid strides: {r}"));
        }
    }
    if let Some(f) = exp.get("fs_hz").and_then(|x| x.as_float()) {
        if (r["fs_hz"].as_f64().unwrap() - f).abs() > 1e-6 {
            return Err(format!("fs_hz {} instead of {f}", r["fs_hz"]));
        }
    }
    Ok(())
}

#[test]
fn every_bad_input_gives_its_documented_outcome_and_never_panics() {
    let mut names: Vec<String> = std::fs::read_dir(corpus())
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.path().join("expected.toml").is_file())
        .map(|e| e.file_name().to_string_lossy().to_string())
        .collect();
    names.sort();
    assert!(names.len() >= 60, "only {} cases", names.len());
    let readme = std::fs::read_to_string(corpus().join("README.md")).unwrap();
    let mut failures = Vec::new();
    for name in &names {
        let exp: toml::Value = toml::from_str(
            &std::fs::read_to_string(corpus().join(name).join("expected.toml")).unwrap(),
        )
        .unwrap_or_else(|e| panic!("{name}/expected.toml: {e}"));
        assert!(
            readme.contains(&format!("`{name}`")),
            "{name} is not listed in data-fixtures/bad/README.md"
        );
        let t = Instant::now();
        let r = check_case(name, &exp);
        println!(
            "{name}: {:?} in {:.1} s",
            r.as_ref().map(|_| "ok"),
            t.elapsed().as_secs_f64()
        );
        if let Err(e) = r {
            failures.push(format!("{name}: {e}"));
        }
    }
    assert!(
        failures.is_empty(),
        "{} case(s) failed:\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}
