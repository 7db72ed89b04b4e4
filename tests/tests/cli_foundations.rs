//! The command line's foundations: simulate, inspect, formats, demo.

use std::path::Path;
mod common;
use common::*;
use std::process::Command;

fn files_of(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v = Vec::new();
    for sub in std::fs::read_dir(dir).unwrap() {
        let p = sub.unwrap().path();
        if p.is_dir() {
            for f in std::fs::read_dir(&p).unwrap() {
                let f = f.unwrap().path();
                v.push((
                    f.strip_prefix(dir).unwrap().display().to_string(),
                    std::fs::read(&f).unwrap(),
                ));
            }
        } else {
            v.push((
                p.strip_prefix(dir).unwrap().display().to_string(),
                std::fs::read(&p).unwrap(),
            ));
        }
    }
    v.sort();
    v
}

#[test]
fn simulate_writes_a_cohort_and_is_byte_identical_for_a_seed_whatever_the_jobs() {
    let d = tempfile::tempdir().unwrap();
    let a = d.path().join("a");
    let b = d.path().join("b");
    let args = |out: &Path, jobs: &str| {
        vec![
            "simulate".to_string(),
            "--out".into(),
            out.display().to_string(),
            "--healthy".into(),
            "2".into(),
            "--ldh".into(),
            "3".into(),
            "--seconds".into(),
            "15".into(),
            "--seed".into(),
            "9".into(),
            "--jobs".into(),
            jobs.into(),
        ]
    };
    let o = Command::new(env!("CARGO_BIN_EXE_ldh-under-test"))
        .args(args(&a, "1"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let o = Command::new(env!("CARGO_BIN_EXE_ldh-under-test"))
        .args(args(&b, "2"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let (fa, fb) = (files_of(&a), files_of(&b));
    assert_eq!(
        fa.len(),
        2 + 5 * 3,
        "{:?}",
        fa.iter().map(|f| &f.0).collect::<Vec<_>>()
    );
    assert!(fa == fb, "same seed, different bytes with --jobs 1 and 2");
    let manifest = std::fs::read_to_string(a.join("manifest.csv")).unwrap();
    assert!(
        manifest.starts_with("subject_id,group,affected_side,left,right,sensor_height_m,clocks\n")
    );
    assert_eq!(manifest.lines().filter(|l| l.contains(",ldh,")).count(), 3);
    // Every written recording is read back by `inspect` without error.
    let left = a.join("L01/left.csv");
    let o = ldh(&["inspect", left.to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("ldh format, 100.00 Hz"), "{}", text(&o));
}

#[test]
fn simulate_in_a_vendor_format_and_at_other_rates() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("x");
    let o = ldh(&[
        "simulate",
        "--out",
        out.to_str().unwrap(),
        "--healthy",
        "1",
        "--ldh",
        "0",
        "--seconds",
        "14",
        "--rate-hz",
        "200",
        "--format",
        "xsens-mtmanager",
    ]);
    assert!(o.status.success(), "{}", text(&o));
    // The Xsens map states 100 Hz (its PacketCounter has no time): a 200 Hz export needs a copy
    // of the map with its own rate, made from `ldh formats`.
    let o = ldh(&["formats", "xsens-mtmanager"]);
    let toml = String::from_utf8(o.stdout)
        .unwrap()
        .replace("rate_hz = 100.0", "rate_hz = 200.0");
    let map = d.path().join("xsens200.toml");
    std::fs::write(&map, toml).unwrap();
    let o = ldh(&[
        "inspect",
        "--json",
        "--input-format",
        map.to_str().unwrap(),
        out.join("H01/left.csv").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v[0]["read"]["format"], "xsens-mtmanager", "{v}");
    assert!((v[0]["read"]["fs_hz"].as_f64().unwrap() - 200.0).abs() < 1e-6);
    let o = ldh(&[
        "simulate",
        "--out",
        out.to_str().unwrap(),
        "--healthy",
        "1",
        "--ldh",
        "0",
        "--seconds",
        "14",
        "--rate-hz",
        "50",
    ]);
    assert!(o.status.success());
    let o = ldh(&[
        "inspect",
        "--json",
        out.join("H01/right.csv").to_str().unwrap(),
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert!((v[0]["read"]["fs_hz"].as_f64().unwrap() - 50.0).abs() < 1e-6);
}

#[test]
fn inspect_reports_each_bad_file_and_keeps_going() {
    let d = tempfile::tempdir().unwrap();
    ldh_core::demo::write_to(d.path()).unwrap();
    let bad = d.path().join("bad.csv");
    std::fs::write(
        &bad,
        "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z\n0.0,1,0,0,0,0,zero\n",
    )
    .unwrap();
    let empty = d.path().join("empty.csv");
    std::fs::write(&empty, "").unwrap();
    let good = d.path().join("H01/left.csv");
    let o = ldh(&[
        "inspect",
        bad.to_str().unwrap(),
        good.to_str().unwrap(),
        empty.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let t = text(&o);
    assert!(
        t.contains("bad.csv:2:7") && t.contains("'zero' is not a number"),
        "{t}"
    );
    assert!(t.contains("empty.csv: the file is empty"), "{t}");
    assert!(t.contains("H01/left.csv: ldh format"), "{t}");
    assert!(t.contains("2 of 3 file(s) failed"), "{t}");
    assert!(!t.contains("panicked"));
}

/// A misspelt path is refused before any work, in the words and with the exit code (2) of
/// `ldh analyze` (issue 51: one wording and exit code for a missing file in every command).
#[test]
fn inspect_refuses_a_missing_file_as_analyze_does() {
    let d = tempfile::tempdir().unwrap();
    ldh_core::demo::write_to(d.path()).unwrap();
    let good = d.path().join("H01/left.csv");
    let o = ldh(&["inspect", good.to_str().unwrap(), "/nonexistent/x.csv"]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("/nonexistent/x.csv: cannot read: no such file or folder"),
        "{}",
        text(&o)
    );
    let a = ldh(&[
        "analyze",
        "/nonexistent/x.csv",
        "/nonexistent/y.csv",
        "-o",
        d.path().join("out").to_str().unwrap(),
    ]);
    assert_eq!(a.status.code(), Some(2), "{}", text(&a));
    assert!(
        text(&a).contains("/nonexistent/x.csv: cannot read: no such file or folder"),
        "{}",
        text(&a)
    );
}

#[test]
fn formats_lists_and_prints_and_usage_errors_exit_2() {
    let o = ldh(&["formats"]);
    assert!(o.status.success());
    for n in ["ldh", "xsens-mtmanager", "shimmer-consensys", "raw-counts"] {
        assert!(text(&o).contains(n));
    }
    let o = ldh(&["formats", "xsens-mtmanager"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("PacketCounter"));
    let o = ldh(&["formats", "nope"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("no such built-in format"));
    let o = ldh(&["simulate"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("--out"));
    let o = ldh(&[
        "simulate",
        "--out",
        "/tmp/x",
        "--healthy",
        "0",
        "--ldh",
        "0",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("at least one subject"), "{}", text(&o));
    let o = ldh(&["--help"]);
    assert!(o.status.success() && text(&o).contains("simulate"));
}

#[test]
fn demo_writes_the_embedded_cohort() {
    let d = tempfile::tempdir().unwrap();
    let o = ldh(&["demo", "--out", d.path().to_str().unwrap()]);
    assert!(o.status.success(), "{}", text(&o));
    for s in ldh_core::demo::SUBJECTS {
        for side in ["left", "right"] {
            let f = d.path().join(s).join(format!("{side}.csv"));
            let written = std::fs::read_to_string(&f).unwrap();
            assert_eq!(
                written,
                ldh_core::demo::file(&format!("{s}/{side}.csv")).unwrap()
            );
        }
    }
    assert_eq!(
        std::fs::read_to_string(d.path().join("manifest.csv")).unwrap(),
        ldh_core::demo::file("manifest.csv").unwrap()
    );
}

/// `--acc-range-g 2` gives family a the ±2 g accelerometer of HuGaDB: the same walk (every
/// draw unchanged), clipped in swing; the stride length reconstructs the clipped samples and is
/// reported (issue 20). Family b draws its ranges itself and refuses the flag.
#[test]
fn simulate_with_a_two_g_accelerometer() {
    let d = tempfile::tempdir().unwrap();
    let sim = |name: &str, extra: &[&str]| {
        let out = d.path().join(name);
        let mut args = vec![
            "simulate",
            "--out",
            out.to_str().unwrap(),
            "--healthy",
            "1",
            "--ldh",
            "0",
            "--seconds",
            "20",
        ];
        args.extend_from_slice(extra);
        ldh_ok(&args);
        out
    };
    let (g2, g8) = (sim("g2", &["--acc-range-g", "2"]), sim("g8", &[]));
    let clipped = |dir: &std::path::Path| {
        let o = ldh_ok(&[
            "inspect",
            "--json",
            dir.join("H01/left.csv").to_str().unwrap(),
        ]);
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        v[0]["read"]["saturated_samples"].as_u64().unwrap()
    };
    assert!(clipped(&g2) > 50, "{}", clipped(&g2));
    assert_eq!(clipped(&g8), 0);
    let out = d.path().join("a2");
    ldh_ok(&[
        "analyze",
        g2.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--no-sta",
    ]);
    let rows = json(&out.join("recordings.json"));
    for r in rows.as_array().unwrap() {
        let sl = r["stride_length_m"].as_f64().unwrap_or(f64::NAN);
        assert!((1.0..1.8).contains(&sl), "{r}");
    }
    let o = ldh(&[
        "simulate",
        "--family",
        "b",
        "--out",
        d.path().join("b").to_str().unwrap(),
        "--acc-range-g",
        "2",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("--acc-range-g"), "{}", text(&o));
}
