//! Real-world inputs through the CLI: HuGaDB's original multi-sensor files read per leg with
//! only a manifest and the shipped column maps; unit-suffixed CSVs without a map; trials,
//! free group labels, settings; `--subject`; `ldh formats` printing the shipped text.

mod common;
use common::*;
use std::path::{Path, PathBuf};

/// `../shared/realdata/hugadb` from the workspace root (or `$LDH_REALDATA/hugadb`; a worktree
/// two levels down also finds `../../shared`).
fn hugadb() -> Option<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut c: Vec<PathBuf> = Vec::new();
    if let Some(d) = std::env::var_os("LDH_REALDATA") {
        c.push(PathBuf::from(d).join("hugadb"));
    }
    c.push(root.join("../shared/realdata/hugadb"));
    c.push(root.join("../../shared/realdata/hugadb"));
    c.into_iter().find(|d| d.join("PROVENANCE.md").is_file())
}

#[test]
fn hugadb_original_files_are_analysed_per_leg_from_a_manifest() {
    let Some(data) = hugadb() else {
        println!("skipped: ../shared/realdata/hugadb not found");
        return;
    };
    // Files with valid shank gyroscopes on both legs (PROVENANCE.md), both column spellings:
    // 01_00 and 10_00-Test are spelled RS_acc_x, 06_00 acc_rs_x.
    let files = [
        "HuGaDB_v1_walking_01_00.txt",
        "HuGaDB_v1_walking_06_00.txt",
        "HuGaDB_v1_walking_10_00-Test.txt",
    ];
    let t = tempfile::tempdir().unwrap();
    let mut m =
        String::from("subject_id,group,affected_side,left,right,left_format,right_format\n");
    for (i, f) in files.iter().enumerate() {
        let p = data.join(f);
        // One absolute path, the others relative to the manifest's folder.
        let cell = if i == 0 {
            p.canonicalize().unwrap().display().to_string()
        } else {
            pathdiff(
                &p.canonicalize().unwrap(),
                &t.path().canonicalize().unwrap(),
            )
        };
        m.push_str(&format!(
            "{},healthy,none,\"{cell}\",\"{cell}\",hugadb-left-shank,hugadb-right-shank\n",
            &f[18..23]
        ));
    }
    let manifest = t.path().join("manifest.csv");
    std::fs::write(&manifest, &m).unwrap();
    let out = t.path().join("out");
    let o = ldh(&[
        "analyze",
        manifest.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--no-sta",
    ]);
    let rows = read_csv(&out.join("recordings.csv"));
    assert_eq!(rows.len(), 2 * files.len(), "{}", text(&o));
    for r in &rows {
        println!(
            "{} {}: {} fs {} Hz, {} s, strides {}/{} {}",
            r["subject_id"],
            r["side"],
            r["status"],
            r["fs_hz"],
            r["duration_s"],
            r["strides_valid"],
            r["strides_total"],
            r["error"]
        );
        assert_eq!(
            r["status"], "ok",
            "{} {}: {}",
            r["subject_id"], r["side"], r["error"]
        );
        assert!((r["fs_hz"].parse::<f64>().unwrap() - 58.8).abs() < 1e-6);
        assert!(r["strides_total"].parse::<usize>().unwrap() > 0);
        // PROVENANCE.md: shank-gyro stride periods of 46-64 samples (0.78-1.09 s at 58.8 Hz).
        let st: f64 = r["stride_time_s"].parse().unwrap();
        assert!(
            (0.75..1.12).contains(&st),
            "{} {}: {st}",
            r["subject_id"],
            r["side"]
        );
    }
    // Both legs walk the same walk: their stride times agree (each leg from its own sensor).
    for pair in rows.chunks(2) {
        let st = |r: &std::collections::HashMap<String, String>| -> f64 {
            r["stride_time_s"].parse().unwrap()
        };
        assert_eq!(pair[0]["subject_id"], pair[1]["subject_id"]);
        let (l, r) = (st(&pair[0]), st(&pair[1]));
        assert!(
            (l - r).abs() / l < 0.02,
            "{}: {l} vs {r}",
            pair[0]["subject_id"]
        );
    }
    hugadb_issue_20_criteria(&out);
}

/// Issue 20 on the clean HuGaDB files: no reported shank angle beyond ±90°, left/right stride
/// length within 10 % wherever both legs report one, and heel strikes alternating
/// between the legs (≥ 99 % of consecutive heel strikes within a walking bout).
fn hugadb_issue_20_criteria(out: &Path) {
    let strides = read_csv(&out.join("strides.csv"));
    let num = |r: &std::collections::HashMap<String, String>, k: &str| -> Option<f64> {
        r[k].parse::<f64>().ok().filter(|x| x.is_finite())
    };
    let mut angles = 0;
    for r in &strides {
        for k in ["wqk_deg", "pbi_deg", "bdk_deg"] {
            if let (Some(v), "true") = (num(r, k), r["valid"].as_str()) {
                angles += 1;
                assert!(
                    v.abs() <= 90.0,
                    "{} {} {k} = {v}",
                    r["subject_id"],
                    r["side"]
                );
            }
        }
    }
    // the legs' stride lengths as reported (recordings.csv; withheld legs are empty)
    let recs = read_csv(&out.join("recordings.csv"));
    let subjects: std::collections::BTreeSet<&str> =
        recs.iter().map(|r| r["subject_id"].as_str()).collect();
    let mut compared = 0;
    for s in &subjects {
        let len = |side: &str| {
            recs.iter()
                .find(|r| r["subject_id"] == *s && r["side"] == side)
                .and_then(|r| num(r, "stride_length_m"))
        };
        println!(
            "{s}: stride length left {:?} m, right {:?} m",
            len("left"),
            len("right")
        );
        for r in recs.iter().filter(|r| r["subject_id"] == *s) {
            // a leg without a stride length says why (withheld, never silently empty)
            assert!(
                num(r, "stride_length_m").is_some() || r["withheld"].contains("stride_length_m"),
                "{s} {}: stride length empty without a reason",
                r["side"]
            );
        }
        if let (Some(l), Some(r)) = (len("left"), len("right")) {
            compared += 1;
            assert!((l - r).abs() / l.max(r) <= 0.10, "{s}: {l} vs {r}");
        }
    }
    let events = read_csv(&out.join("events.csv"));
    let (mut pairs, mut alternating) = (0usize, 0usize);
    for s in &subjects {
        let mut hs: Vec<(f64, &str)> = events
            .iter()
            .filter(|e| e["subject_id"] == *s && e["event"] == "HS")
            .map(|e| (e["time_s"].parse().unwrap(), e["side"].as_str()))
            .collect();
        hs.sort_by(|a, b| a.0.total_cmp(&b.0));
        for w in hs.windows(2) {
            // a pause longer than 2 s (standing, turning back) starts a new bout
            if w[1].0 - w[0].0 < 2.0 {
                pairs += 1;
                alternating += usize::from(w[0].1 != w[1].1);
            }
        }
    }
    let share = alternating as f64 / pairs.max(1) as f64;
    println!(
        "HuGaDB: {angles} reported stride angles, all within ±90°; {compared} subjects with both \
         legs' stride lengths compared; heel strikes alternate in {alternating} of {pairs} ({:.1} %)",
        100.0 * share
    );
    assert!(pairs > 0 && share >= 0.99, "alternation {share}");
}

/// `path` relative to `base` (both absolute, canonical).
fn pathdiff(path: &Path, base: &Path) -> String {
    let (p, b): (Vec<_>, Vec<_>) = (path.components().collect(), base.components().collect());
    let common = p.iter().zip(&b).take_while(|(x, y)| x == y).count();
    let mut out = PathBuf::new();
    for _ in common..b.len() {
        out.push("..");
    }
    for c in &p[common..] {
        out.push(c);
    }
    out.display().to_string()
}

/// A simulated subject's left/right files rewritten with unit-suffixed column names.
fn suffixed_pair(dir: &Path) -> (PathBuf, PathBuf) {
    simulate_cohort(&dir.join("sim"), 1, 0, 30, 3);
    let sub = std::fs::read_dir(dir.join("sim"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.is_dir())
        .unwrap();
    let mut out = Vec::new();
    for side in ["left", "right"] {
        let text = std::fs::read_to_string(sub.join(format!("{side}.csv"))).unwrap();
        let text = text.replacen(
            "time_s,acc_x,acc_y,acc_z,gyro_x,gyro_y,gyro_z",
            "time_s,acc_x_g,acc_y_g,acc_z_g,gyro_x_dps,gyro_y_dps,gyro_z_dps",
            1,
        );
        assert!(text.starts_with("time_s,acc_x_g"), "{}", &text[..80]);
        let p = dir.join(format!("P07_{side}.csv"));
        std::fs::write(&p, text).unwrap();
        out.push(p);
    }
    (out[0].clone(), out[1].clone())
}

#[test]
fn unit_suffixed_files_read_without_a_map_and_take_their_subject_id_from_the_names() {
    let t = tempfile::tempdir().unwrap();
    let (l, r) = suffixed_pair(t.path());
    let out = t.path().join("out");
    ldh_ok(&[
        "analyze",
        l.to_str().unwrap(),
        r.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--no-sta",
        "--setting",
        "treadmill",
    ]);
    let rows = read_csv(&out.join("recordings.csv"));
    assert_eq!(rows.len(), 2);
    for r in &rows {
        assert_eq!(r["subject_id"], "P07");
        assert_eq!(r["status"], "ok", "{}", r["error"]);
        assert_eq!(r["setting"], "treadmill");
    }
    let out2 = t.path().join("out2");
    ldh_ok(&[
        "analyze",
        l.to_str().unwrap(),
        r.to_str().unwrap(),
        "--out",
        out2.to_str().unwrap(),
        "--no-sta",
        "--subject",
        "patient-7",
    ]);
    let rows = read_csv(&out2.join("recordings.csv"));
    assert!(rows
        .iter()
        .all(|r| r["subject_id"] == "patient-7" && r["setting"].is_empty()));
    let o = ldh(&["analyze", "--setting", "stairs", l.to_str().unwrap()]);
    assert!(
        !o.status.success() && text(&o).contains("treadmill"),
        "{}",
        text(&o)
    );
}

#[test]
fn manifest_with_trials_labels_and_unknown_sides() {
    let t = tempfile::tempdir().unwrap();
    let (l, r) = suffixed_pair(t.path());
    let (l, r) = (l.display(), r.display());
    let manifest = t.path().join("trials.csv");
    std::fs::write(
        &manifest,
        format!(
            "subject_id,trial_id,group,affected_side,left,right\n\
             P1,a,stroke,,{l},{r}\nP1,b,stroke,,{l},{r}\nP2,a,healthy,,{l},{r}\n"
        ),
    )
    .unwrap();
    let out = t.path().join("out");
    ldh_ok(&[
        "analyze",
        manifest.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--no-sta",
        "--report",
    ]);
    let rows = read_csv(&out.join("recordings.csv"));
    let got: Vec<(&str, &str, &str, &str)> = rows
        .iter()
        .map(|r| {
            (
                r["subject_id"].as_str(),
                r["trial_id"].as_str(),
                r["group"].as_str(),
                r["affected_side"].as_str(),
            )
        })
        .collect();
    assert_eq!(
        got,
        [
            ("P1", "a", "stroke", ""),
            ("P1", "a", "stroke", ""),
            ("P1", "b", "stroke", ""),
            ("P1", "b", "stroke", ""),
            ("P2", "a", "healthy", "none"),
            ("P2", "a", "healthy", "none"),
        ]
    );
    assert!(rows[0]["warnings"].contains("affected side unknown"));
    // Each trial's traces in its own file.
    assert!(out.join("traces/P1~trial-a.json").is_file());
    assert!(out.join("traces/P1~trial-b.json").is_file());
    let strides = read_csv(&out.join("strides.csv"));
    assert!(strides.iter().any(|s| s["trial_id"] == "b"));
    // One report per person, its values the mean of the trials, its plots from the first.
    let page = std::fs::read_to_string(out.join("reports/subjects/P1.html")).unwrap();
    assert!(
        page.contains("mean of 2 trials (a, b)") && page.contains("plots: trial a"),
        "{}",
        &page[..page.len().min(3000)]
    );
    assert!(!page.contains("Signal plots are not available"));
    assert!(!out.join("reports/subjects/P1~trial-a.html").exists());
    // A typo in the header is refused, naming it.
    std::fs::write(&manifest, "subject_id,left,rigth\nP1,a,b\n").unwrap();
    let o = ldh(&[
        "analyze",
        manifest.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(text(&o).contains("unknown column 'rigth'"), "{}", text(&o));
}

#[test]
fn formats_prints_the_shipped_file_with_its_comments() {
    let o = ldh_ok(&["formats", "xsens-mtmanager"]);
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(
        s.contains("cable pointing down") && s.contains("axis map is the identity"),
        "{s}"
    );
    let o = ldh_ok(&["formats", "hugadb-left-shank"]);
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(
        s.contains("[\"LS_acc_x\", \"acc_ls_x\"]") && s.contains("x axis points DOWN"),
        "{s}"
    );
    let o = ldh_ok(&["formats"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("hugadb-right-shank"));
}
