//! Issue 37 (nothing mixed, nothing outside `--out`): an output folder holds one run, marked
//! by `ldh-run.json`; re-runs replace the whole set, killed runs leave no complete marker,
//! links inside `--out` are never followed, and no two subjects or trials share a file.

mod common;
use common::{ldh, ldh_ok, simulate_cohort, text};
use std::path::{Path, PathBuf};

/// Every file under `d` (relative paths, sorted), links included as files.
fn files(d: &Path) -> Vec<String> {
    fn walk(root: &Path, d: &Path, out: &mut Vec<String>) {
        for e in std::fs::read_dir(d).unwrap().flatten() {
            let p = e.path();
            if e.file_type().unwrap().is_dir() {
                walk(root, &p, out);
            } else {
                out.push(p.strip_prefix(root).unwrap().to_string_lossy().to_string());
            }
        }
    }
    let mut out = Vec::new();
    if d.exists() {
        walk(d, d, &mut out);
    }
    out.sort();
    out
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A manifest at `path` naming `rows` of (subject, trial, recording folder).
fn manifest(path: &Path, rows: &[(&str, &str, &Path)]) {
    let mut m = String::from("subject_id,trial_id,group,affected_side,left,right\n");
    for (id, trial, dir) in rows {
        m += &format!(
            "{id},{trial},healthy,none,{},{}\n",
            dir.join("left.csv").display(),
            dir.join("right.csv").display()
        );
    }
    std::fs::write(path, m).unwrap();
}

/// What the complete marker of `out` lists, or `None` without a complete marker.
fn listed(out: &Path) -> Option<Vec<String>> {
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("ldh-run.json")).ok()?).unwrap();
    (m["complete"] == true).then(|| {
        m["files"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f["path"].as_str().unwrap().to_string())
            .collect()
    })
}

/// A re-run (with or without `--report`) keeps nothing of the earlier run: its reports and
/// traces go with it, so `ldh report` never draws an earlier recording beside new numbers.
#[test]
fn a_rerun_replaces_the_whole_result_set() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("c");
    simulate_cohort(&c, 3, 0, 20, 5);
    let out = d.path().join("out");
    let (a, b) = (d.path().join("a.csv"), d.path().join("b.csv"));
    manifest(
        &a,
        &[("H01", "", &c.join("H01")), ("H02", "", &c.join("H02"))],
    );
    // H01 is now another recording (H03's), and H02 is gone.
    manifest(&b, &[("H01", "", &c.join("H03"))]);
    ldh_ok(&["analyze", s(&a), "-o", s(&out), "--report"]);
    assert!(out.join("traces/H02.json").is_file());
    let first = listed(&out).expect("complete marker");
    assert!(first.contains(&"traces/H01.json".to_string()), "{first:?}");
    ldh_ok(&["analyze", s(&b), "-o", s(&out)]);
    let got = files(&out);
    let want: Vec<String> = [
        "events.csv",
        "ldh-run.json",
        "params.json",
        "recordings.csv",
        "recordings.json",
        "strides.csv",
        "strides.json",
    ]
    .map(String::from)
    .to_vec();
    assert_eq!(got, want, "nothing of the first run is left");
    // `ldh report` of the new run: no trace, so no signals drawn (never the old H01's).
    let o = ldh_ok(&["report", s(&out)]);
    let page = std::fs::read_to_string(out.join("reports/subjects/H01.html")).unwrap();
    // Pages name files without folders (issue 36 item 5): the new recording is the table's.
    let table = std::fs::read_to_string(out.join("recordings.csv")).unwrap();
    assert!(table.contains("H03/left.csv") && !table.contains("H01/left.csv"));
    assert!(page.contains("left.csv (left leg)"), "the new recording");
    assert!(
        page.contains("Signal plots are not available"),
        "{}",
        text(&o)
    );
    assert!(!out.join("reports/subjects/H02.html").exists());
    // And with --report: the new run's own trace.
    ldh_ok(&["analyze", s(&a), "-o", s(&out), "--report"]);
    ldh_ok(&["analyze", s(&b), "-o", s(&out), "--report"]);
    assert!(!out.join("traces/H02.json").exists());
    assert!(!out.join("reports/subjects/H02.html").exists());
    let trace = std::fs::read_to_string(out.join("traces/H01.json")).unwrap();
    let fresh = tempfile::tempdir().unwrap();
    ldh_ok(&["analyze", s(&b), "-o", s(fresh.path()), "--report"]);
    assert_eq!(
        trace,
        std::fs::read_to_string(fresh.path().join("traces/H01.json")).unwrap(),
        "the trace is the new recording's"
    );
    assert_eq!(files(&out), files(fresh.path()));
}

/// Files ldh did not write make the run refuse, naming them, and stay untouched; nothing is
/// written.
#[test]
fn files_ldh_did_not_write_refuse_the_run() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("out");
    std::fs::create_dir_all(out.join("traces")).unwrap();
    std::fs::write(out.join("thesis.docx"), "mine").unwrap();
    std::fs::write(out.join("traces/notes.txt"), "mine").unwrap();
    let o = ldh(&["analyze", "-o", s(&out)]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("'thesis.docx', 'traces/notes.txt' that no ldh analyze run wrote"),
        "{}",
        text(&o)
    );
    assert_eq!(files(&out), ["thesis.docx", "traces/notes.txt"]);
}

/// A run killed with SIGKILL over an earlier run never leaves a folder that looks complete
/// with files of two runs: either the earlier run whole (its marker complete and every file it
/// lists as it wrote it), or no complete marker — and then `ldh report` refuses the folder.
#[test]
fn a_killed_rerun_never_leaves_a_complete_looking_mix() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("c");
    simulate_cohort(&c, 6, 6, 30, 9);
    let out = d.path().join("out");
    ldh_ok(&[
        "analyze",
        s(&c),
        "-o",
        s(&out),
        "--report",
        "--model",
        "acc",
    ]);
    let before: Vec<(String, Vec<u8>)> = files(&out)
        .into_iter()
        .map(|f| (f.clone(), std::fs::read(out.join(&f)).unwrap()))
        .collect();
    let mut refused = 0;
    for delay_ms in [0u64, 20, 60, 150, 300, 600] {
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_ldh-under-test"))
            .args(["analyze", s(&c), "-o", s(&out), "--report", "-j", "2"])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(delay_ms));
        child.kill().unwrap();
        child.wait().unwrap();
        match listed(&out) {
            Some(_) => {
                // The earlier run whole (killed before it was touched) or the new one whole.
                let m: serde_json::Value = common::json(&out.join("ldh-run.json"));
                for f in m["files"].as_array().unwrap() {
                    let p = out.join(f["path"].as_str().unwrap());
                    let len = std::fs::metadata(&p).map(|m| m.len()).unwrap_or(u64::MAX);
                    assert_eq!(len, f["bytes"].as_u64().unwrap(), "{}", p.display());
                }
                ldh_ok(&["report", s(&out), "-o", s(&d.path().join("r"))]);
            }
            None => {
                let o = ldh(&["report", s(&out), "-o", s(&d.path().join("r"))]);
                assert_eq!(o.status.code(), Some(2), "{}", text(&o));
                assert!(text(&o).contains("did not finish"), "{}", text(&o));
                refused += 1;
            }
        }
        // The re-run over whatever was left completes.
        ldh_ok(&[
            "analyze",
            s(&c),
            "-o",
            s(&out),
            "--report",
            "--model",
            "acc",
        ]);
        let again: Vec<(String, Vec<u8>)> = files(&out)
            .into_iter()
            .map(|f| (f.clone(), std::fs::read(out.join(&f)).unwrap()))
            .collect();
        assert!(
            again == before,
            "the re-run is exactly the uninterrupted run"
        );
    }
    eprintln!("{refused} of 6 kills left an unfinished folder");
}

/// A link inside `--out` (planted after a run) is never followed: the run refuses naming it
/// and nothing is written where it points; `ldh report` into its default folder likewise.
#[cfg(unix)]
#[test]
fn links_inside_the_output_folder_are_refused() {
    let d = tempfile::tempdir().unwrap();
    let (out, elsewhere) = (d.path().join("out"), d.path().join("elsewhere"));
    std::fs::create_dir(&elsewhere).unwrap();
    ldh_ok(&["analyze", "-o", s(&out)]);
    for (link, target) in [
        ("reports", elsewhere.clone()),
        ("traces", elsewhere.clone()),
        ("params.json", elsewhere.join("params.json")),
    ] {
        let _ = std::fs::remove_file(out.join(link)); // params.json: the run's file
        std::os::unix::fs::symlink(&target, out.join(link)).unwrap();
        let o = ldh(&["analyze", "-o", s(&out), "--report"]);
        assert_eq!(o.status.code(), Some(2), "{link}: {}", text(&o));
        assert!(
            text(&o).contains(&format!("'{link}' in the output folder is a symbolic link")),
            "{}",
            text(&o)
        );
        assert!(
            files(&elsewhere).is_empty(),
            "{link}: {:?}",
            files(&elsewhere)
        );
        assert!(out.join(link).symlink_metadata().is_ok(), "the link stays");
        std::fs::remove_file(out.join(link)).unwrap();
    }
    ldh_ok(&["analyze", "-o", s(&out)]);
    std::os::unix::fs::symlink(&elsewhere, out.join("reports")).unwrap();
    let o = ldh(&["report", s(&out)]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("symbolic link"), "{}", text(&o));
    assert!(files(&elsewhere).is_empty(), "{:?}", files(&elsewhere));
}

/// Subject `P1__trial_2` and subject `P1`, trial `2` (two different recordings) get their own
/// trace files, in parallel too, and each report is built from its own recording's signals.
#[test]
fn a_subject_named_like_a_trial_key_keeps_its_own_trace() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("c");
    simulate_cohort(&c, 2, 0, 20, 11);
    let m = d.path().join("m.csv");
    manifest(
        &m,
        &[
            ("P1__trial_2", "", &c.join("H01")),
            ("P1", "2", &c.join("H02")),
        ],
    );
    let traces = |out: &PathBuf, stem: &str| -> serde_json::Value {
        common::json(&out.join("traces").join(format!("{stem}.json")))
    };
    let mut seen = Vec::new();
    for jobs in ["1", "2"] {
        let out = d.path().join(format!("out{jobs}"));
        ldh_ok(&["analyze", s(&m), "-o", s(&out), "--report", "-j", jobs]);
        let (a, b) = (traces(&out, "P1__trial_2"), traces(&out, "P1~trial-2"));
        assert_eq!(a["subject_id"], "P1__trial_2");
        assert!(a.get("trial_id").is_none());
        assert_eq!(
            (b["subject_id"].as_str(), b["trial_id"].as_str()),
            (Some("P1"), Some("2"))
        );
        assert_ne!(a["legs"], b["legs"], "two recordings, two traces");
        // Pages name files without folders (issue 36 item 5): each page by its trial.
        for (stem, ident) in [
            ("P1__trial_2", "Recorded: files "),
            ("P1", "Recorded: trial 2: files "),
        ] {
            let page =
                std::fs::read_to_string(out.join(format!("reports/subjects/{stem}.html"))).unwrap();
            assert!(page.contains(ident), "{stem}");
            assert!(!page.contains("Signal plots are not available"), "{stem}");
        }
        seen.push(files(&out));
    }
    assert_eq!(seen[0], seen[1]);
}

/// A trace put in place of another (here another subject's) is not drawn: `ldh report` takes
/// only files the run's marker lists with their content, and says which it left out.
#[test]
fn a_trace_that_is_not_the_runs_is_not_drawn() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("out");
    ldh_ok(&["analyze", "-o", s(&out), "--report"]);
    std::fs::copy(out.join("traces/H02.json"), out.join("traces/H01.json")).unwrap();
    let o = ldh_ok(&["report", s(&out)]);
    assert!(
        text(&o).contains("H01.json: not the trace the run of these tables wrote"),
        "{}",
        text(&o)
    );
    let page = std::fs::read_to_string(out.join("reports/subjects/H01.html")).unwrap();
    assert!(page.contains("Signal plots are not available"));
    // A folder whose run did not finish is refused.
    let marker = out.join("ldh-run.json");
    let m = std::fs::read_to_string(&marker).unwrap();
    std::fs::write(
        &marker,
        m.replace("\"complete\": true", "\"complete\": false"),
    )
    .unwrap();
    let o = ldh(&["report", s(&out)]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("did not finish"), "{}", text(&o));
}

/// An empty manifest is an error naming it, before an output folder is made.
#[test]
fn an_empty_manifest_is_refused() {
    let d = tempfile::tempdir().unwrap();
    let m = d.path().join("m.csv");
    std::fs::write(&m, "subject_id,left,right\n").unwrap();
    let out = d.path().join("out");
    let o = ldh(&["analyze", s(&m), "-o", s(&out)]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("the manifest has no subjects"),
        "{}",
        text(&o)
    );
    assert!(!out.exists());
}
