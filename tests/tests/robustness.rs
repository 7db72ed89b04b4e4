//! Issue 9: determinism whatever `--jobs` is, and no half-written output when a run is killed.

mod common;
use common::{ldh_ok, simulate_cohort};
use std::collections::BTreeMap;
use std::path::Path;

/// Every file under `dir` (relative path → bytes).
fn tree(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p.strip_prefix(dir).unwrap().display().to_string();
                out.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    out
}

/// analyze (with reports and traces), stats and train write the same bytes with 1, 2 and 3
/// worker threads and batches of 1, 7 and 64 subjects (20 subjects: batches end at different
/// subjects; 30 s walks, long enough for SV to be checked and trained on).
#[test]
fn every_output_is_byte_identical_whatever_the_jobs() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("cohort");
    simulate_cohort(&c, 10, 10, 30, 21);
    let mut trees = Vec::new();
    for (jobs, batch) in [("1", "1"), ("2", "7"), ("3", "64")] {
        let out = d.path().join(format!("out{jobs}"));
        let res = out.join("res");
        ldh_ok(&[
            "analyze",
            c.to_str().unwrap(),
            "--out",
            res.to_str().unwrap(),
            "--report",
            "--jobs",
            jobs,
            "--batch",
            batch,
        ]);
        ldh_ok(&[
            "stats",
            "--results",
            res.to_str().unwrap(),
            "--out",
            out.join("stats").to_str().unwrap(),
            "--jobs",
            jobs,
        ]);
        ldh_ok(&[
            "train",
            "--results",
            res.to_str().unwrap(),
            "--out",
            out.join("train").to_str().unwrap(),
            "--k",
            "3",
            "--repeats",
            "2",
            "--jobs",
            jobs,
        ]);
        trees.push(tree(&out));
    }
    assert!(trees[0].len() > 40, "{:?}", trees[0].keys());
    for t in &trees[1..] {
        assert_eq!(
            t.keys().collect::<Vec<_>>(),
            trees[0].keys().collect::<Vec<_>>()
        );
        for (k, v) in t {
            assert!(v == &trees[0][k], "{k} differs between --jobs values");
        }
    }
}

/// A run killed with SIGKILL at any moment leaves every output file either as it was before or
/// as the complete new version, never half-written, and never old files beside new ones (the
/// run clears the earlier run's files before it writes; issue 37); the next run removes the
/// killed run's temporary files and writes exactly what an uninterrupted run writes (nothing
/// skipped, nothing duplicated).
#[test]
fn a_killed_run_leaves_old_or_new_files_and_a_rerun_completes() {
    let d = tempfile::tempdir().unwrap();
    let c = d.path().join("cohort");
    simulate_cohort(&c, 12, 12, 30, 21);
    let run = |out: &Path, extra: &[&str]| {
        let mut args = vec![
            "analyze",
            c.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        ldh_ok(&args);
        tree(out)
    };
    // "Old": the ACC-only model without STA; "new": the default analysis with reports.
    let old = run(&d.path().join("old"), &["--model", "acc", "--no-sta"]);
    let new = run(&d.path().join("new"), &["--report", "--jobs", "2"]);
    let mut outcomes = (0, 0, 0); // (all old, mixed, all new)
    for (i, delay_ms) in [5u64, 30, 80, 150, 250, 400, 600, 900].iter().enumerate() {
        let out = d.path().join(format!("k{i}"));
        std::fs::create_dir_all(&out).unwrap();
        for (k, v) in &old {
            std::fs::write(out.join(k), v).unwrap();
        }
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_ldh-under-test"))
            .args([
                "analyze",
                c.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ])
            .args(["--report", "--jobs", "2"])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(*delay_ms));
        child.kill().unwrap(); // SIGKILL
        child.wait().unwrap();
        let got = tree(&out);
        let (mut n_old, mut n_new) = (0, 0);
        for (k, v) in &got {
            let name = Path::new(k)
                .file_name()
                .unwrap()
                .to_string_lossy()
                .to_string();
            if name.starts_with('.') && name.contains(".tmp-") || name == ".ldh.lock" {
                continue; // the killed run's temporary file or lock: never an output
            }
            if name == "ldh-run.json" && v.windows(17).any(|w| w == b"\"complete\": false") {
                continue; // the killed run's in-progress marker: says no run is complete
            }
            let is_old = old.get(k) == Some(v);
            let is_new = new.get(k) == Some(v);
            assert!(
                is_old || is_new,
                "{k} is neither the old nor the new version after a kill at {delay_ms} ms"
            );
            n_old += (is_old && !is_new) as usize;
            n_new += (is_new && !is_old) as usize; // a file both versions share is neither
        }
        match (n_old > 0, n_new > 0) {
            (true, false) => outcomes.0 += 1,
            (true, true) => outcomes.1 += 1,
            _ => outcomes.2 += 1,
        }
        // Re-run: exactly the uninterrupted result, and no temporary file left.
        ldh_ok(&[
            "analyze",
            c.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--report",
            "--jobs",
            "2",
        ]);
        let again = tree(&out);
        for (k, v) in &new {
            assert!(again.get(k) == Some(v), "{k} differs after the re-run");
        }
        for k in again.keys() {
            assert!(
                new.contains_key(k) || old.contains_key(k),
                "{k} left behind after the re-run"
            );
        }
    }
    eprintln!("kill outcomes (all old, mixed, all new): {outcomes:?}");
    assert_eq!(outcomes.1, 0, "old and new files side by side");
}
