//! Issue 19 (hostile inputs): output names, model files, odd inputs, concurrent runs.

mod common;
use common::{ldh, ldh_ok, simulate_cohort, text};

/// Subjects `P 1`, `P_1` and `P/1` (one manifest, three different recordings) get three report
/// and trace files, each showing its own subject's recordings and numbers, and the cohort index
/// links each id to its own file.
#[test]
fn similar_subject_ids_get_distinct_reports_with_their_own_data() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("c");
    simulate_cohort(&c, 3, 0, 20, 5);
    let ids = ["P 1", "P_1", "P/1"];
    let mut m = String::from("subject_id,group,affected_side,left,right\n");
    for (id, h) in ids.iter().zip(["H01", "H02", "H03"]) {
        m += &format!("{id},healthy,none,{h}/left.csv,{h}/right.csv\n");
    }
    std::fs::write(c.join("names.csv"), m).unwrap();
    let out = d.path().join("out");
    ldh_ok(&[
        "analyze",
        c.join("names.csv").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--report",
    ]);
    let rows = common::json(&out.join("recordings.json"));
    let subjects = out.join("reports").join("subjects");
    let mut files: Vec<String> = std::fs::read_dir(&subjects)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    files.sort();
    assert_eq!(files.len(), 3, "{files:?}");
    assert_eq!(std::fs::read_dir(out.join("traces")).unwrap().count(), 3);
    let index = std::fs::read_to_string(out.join("reports").join("index.html")).unwrap();
    for id in ids.iter() {
        let stem = ldh_core::output::names::file_stem(id);
        let html = std::fs::read_to_string(subjects.join(format!("{stem}.html"))).unwrap();
        assert!(html.contains(&format!("Gait report — {id}")), "{stem}");
        // The files by name only, no folders (issue 36 item 5): that the page shows this
        // subject's data, not another's, is checked by its stride time below.
        assert!(html.contains("left.csv (left leg)"), "{stem}");
        for any in ["H01", "H02", "H03"] {
            assert!(
                !html.contains(&format!("{any}/left.csv")),
                "{stem} shows a folder"
            );
        }
        // Its stride time (one value per walk since issue 36: the mean of both legs, shown to
        // 0.01 s) is the one in recordings.json for this id.
        let legs: Vec<f64> = rows
            .as_array()
            .unwrap()
            .iter()
            .filter(|r| r["subject_id"] == *id)
            .map(|r| r["stride_time_s"].as_f64().unwrap())
            .collect();
        assert_eq!(legs.len(), 2, "{stem}");
        let st = format!("{:.2}", (legs[0] + legs[1]) / 2.0);
        assert!(html.contains(&st), "{stem}: stride time {st} not shown");
        assert!(
            index.contains(&format!("subjects/{stem}.html\">{}</a>", id)),
            "index link of {id}"
        );
    }
}

/// Ids that would share a file on a case-insensitive file system are refused before any work.
#[test]
fn ids_equal_ignoring_case_are_refused_before_any_work() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("c");
    simulate_cohort(&c, 2, 0, 20, 5);
    std::fs::write(
        c.join("case.csv"),
        "subject_id,group,affected_side,left,right\n\
         p1,healthy,none,H01/left.csv,H01/right.csv\n\
         P1,healthy,none,H02/left.csv,H02/right.csv\n",
    )
    .unwrap();
    let out = d.path().join("out");
    let o = ldh(&[
        "analyze",
        c.join("case.csv").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(text(&o).contains("\"p1\" and \"P1\""), "{}", text(&o));
    assert!(!out.join("recordings.csv").exists());
}

#[test]
fn fifos_devices_and_huge_files_are_refused_before_reading() {
    let d = tempfile::tempdir().unwrap();
    // /dev/zero never ends; a FIFO without a writer blocks forever: both refused at once.
    let fifo = d.path().join("pipe.csv");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .map(|s| s.success())
        .unwrap_or(false);
    let mut files = vec!["/dev/zero".to_string()];
    if made {
        files.push(fifo.to_str().unwrap().to_string());
    } else {
        println!("skipped the FIFO case: mkfifo is not available");
    }
    for f in &files {
        let o = ldh(&["inspect", f]);
        assert_eq!(o.status.code(), Some(1), "{f}: {}", text(&o));
        assert!(
            text(&o).contains(&format!("{f}: cannot read: not a regular file")),
            "{}",
            text(&o)
        );
    }
    // A file above the declared limit is refused with its size and the way to raise the limit.
    ldh_core::demo::write_to(d.path()).unwrap();
    let f = d.path().join("H01/left.csv");
    let o = ldh(&["inspect", "--max-file-size-mb", "0.1", f.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("above the limit of 0.1 MB (raise it with --max-file-size-mb"),
        "{}",
        text(&o)
    );
    ldh_ok(&["inspect", f.to_str().unwrap()]);
}

#[test]
fn a_second_run_into_the_same_folder_is_refused_and_a_stale_lock_taken_over() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let lock = out.join(".ldh.lock");
    // A running process (this test) holds the lock: refused, nothing written.
    std::fs::write(&lock, std::process::id().to_string()).unwrap();
    let o = ldh(&["analyze", "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("another ldh run"), "{}", text(&o));
    assert!(!out.join("recordings.csv").exists());
    // A killed run's lock (no such process): taken over; the lock is gone after the run.
    std::fs::write(&lock, "4194305").unwrap();
    ldh_ok(&["analyze", "-o", out.to_str().unwrap()]);
    assert!(out.join("recordings.csv").exists());
    assert!(!lock.exists(), "the lock is removed at the end of the run");
}

#[test]
fn absurd_thread_counts_are_bounded_by_the_cores() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("out");
    let o = ldh_ok(&["analyze", "-j", "1000000", "-o", out.to_str().unwrap()]);
    assert!(
        text(&o).contains("1000000 worker threads requested"),
        "{}",
        text(&o)
    );
}

/// Simulations too large to hold (a day at 2000 Hz: 172.8 M samples per leg) or counts that
/// overflow are refused before any work with the declared limit (exit 2), never an abort, and
/// no output folder is made. The largest allowed simulation still runs.
#[test]
fn impossible_simulation_sizes_are_refused_with_the_declared_limit() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("sim");
    let o = out.to_str().unwrap();
    let cases: [(&[&str], &str); 6] = [
        (
            &["--seconds", "86400", "--rate-hz", "2000"],
            "duration_s × fs_hz = 86400.0 s × 2000.0 Hz: a simulated leg holds at most 1000000 samples (500 s at 2000.0 Hz)",
        ),
        (
            &["--seconds", "1e308"],
            "duration_s × fs_hz = 1e308 s × 100.0 Hz: a simulated leg holds at most 1000000 samples (2.8 h at 100.0 Hz)",
        ),
        (
            &["--family", "b", "--seconds", "3600", "--rate-hz", "2000"],
            "a simulated leg holds at most 1000000 samples",
        ),
        (
            &["--healthy", "18446744073709551615", "--ldh", "1"],
            "healthy + ldh = 18446744073709551615 + 1: a simulated cohort holds at most 100000 subjects",
        ),
        (
            &["--healthy", "1000000", "--ldh", "0"],
            "healthy + ldh = 1000000 + 0: a simulated cohort holds at most 100000 subjects",
        ),
        (
            &["--family", "b", "--healthy", "9223372036854775807", "--ldh", "9223372036854775807"],
            "a simulated cohort holds at most 100000 subjects",
        ),
    ];
    for (args, msg) in cases {
        let mut argv = vec!["simulate", "--out", o];
        argv.extend_from_slice(args);
        let r = ldh(&argv);
        assert_eq!(r.status.code(), Some(2), "{args:?}: {}", text(&r));
        assert!(text(&r).contains(msg), "{args:?}: {}", text(&r));
        assert!(!text(&r).contains("panicked"), "{}", text(&r));
        assert!(!out.exists(), "{args:?}: an output folder was made");
    }
}

/// One leg too large for the memory (here: a 100 MB, 2.4 M-row file, within the file-size
/// limit, under a 500 MB address-space limit) fails alone with its reason; the other leg and
/// the other subject are analysed and written, exit 1 (it used to abort the batch, exit 134).
/// `--max-samples` is raised so that the leg is never refused by its row count instead
/// (`max_samples`, `tests/tests/memory.rs`), whatever the default.
#[test]
fn a_leg_too_large_for_the_memory_fails_alone() {
    use std::io::Write;
    let d = tempfile::tempdir().unwrap();
    let (a, b) = (d.path().join("A"), d.path().join("B"));
    let base =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data-fixtures/bad/baseline_ok");
    std::fs::create_dir(&a).unwrap();
    std::fs::create_dir(&b).unwrap();
    for side in ["left.csv", "right.csv"] {
        std::fs::copy(base.join(side), b.join(side)).unwrap();
    }
    std::fs::copy(base.join("right.csv"), a.join("right.csv")).unwrap();
    let csv = std::fs::read_to_string(base.join("left.csv")).unwrap();
    let mut lines = csv.lines();
    let header = lines.next().unwrap();
    let rows: Vec<&str> = lines.map(|l| l.split_once(',').unwrap().1).collect();
    let mut f = std::io::BufWriter::new(std::fs::File::create(a.join("left.csv")).unwrap());
    writeln!(f, "{header}").unwrap();
    for k in 0..3000 * rows.len() {
        writeln!(f, "{:.2},{}", k as f64 / 100.0, rows[k % rows.len()]).unwrap();
    }
    f.flush().unwrap();
    drop(f);
    let out = d.path().join("out");
    let cmd = format!(
        "ulimit -v 500000 && exec '{}' analyze '{}' '{}' -o '{}' -j 1 --max-samples 100000000",
        env!("CARGO_BIN_EXE_ldh-under-test"),
        a.display(),
        b.display(),
        out.display()
    );
    let o = std::process::Command::new("sh")
        .args(["-c", &cmd])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let rows = common::json(&out.join("recordings.json"));
    let rows = rows.as_array().unwrap();
    assert_eq!(rows.len(), 4, "{rows:?}");
    for r in rows {
        if r["subject_id"] == "A" && r["side"] == "left" {
            assert_eq!(r["status"], "error");
            let e = r["error"].as_str().unwrap();
            assert!(
                e.contains("A/left.csv: not enough memory to read it"),
                "{e}"
            );
        } else {
            assert_eq!(r["status"], "ok", "{r}");
        }
    }
}
