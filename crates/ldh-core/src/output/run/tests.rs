use super::*;

fn files_in(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    fn walk(root: &Path, d: &Path, out: &mut Vec<String>) {
        for e in std::fs::read_dir(d).unwrap().flatten() {
            let p = e.path();
            let rel = p.strip_prefix(root).unwrap().to_string_lossy().to_string();
            if e.file_type().unwrap().is_dir() {
                walk(root, &p, out);
            } else {
                out.push(rel);
            }
        }
    }
    walk(dir, dir, &mut out);
    out.sort();
    out
}

#[test]
fn a_finished_run_lists_its_files_and_a_rerun_replaces_them_all() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("out");
    let run = OutputRun::begin(&dir, RunKind::Analyze).unwrap();
    run.write("recordings.json", b"[]").unwrap();
    run.write("traces/H01.json", b"{}").unwrap();
    run.write("traces/P%201.json", b"{1}").unwrap();
    let mut w = run.create("strides.csv").unwrap();
    w.write_all(b"a,b\n1,2\n").unwrap();
    w.finish().unwrap();
    let m = run.finish().unwrap();
    assert!(m.complete);
    assert_eq!(m.files.len(), 4);
    assert!(m.lists("traces/H01.json", b"{}"));
    assert!(!m.lists("traces/H01.json", b"{ }"));
    assert_eq!(m.run_id.len(), 16);
    assert_eq!(read_marker(&dir).unwrap().unwrap(), m);
    // An older run's report folder (no marker of its own) is an ldh name too.
    std::fs::create_dir_all(dir.join("reports/subjects")).unwrap();
    std::fs::write(dir.join("reports/subjects/OLD.html"), "x").unwrap();
    std::fs::write(dir.join(".strides.csv.tmp-4194305-0"), "x").unwrap();
    // The second run keeps none of the first's files.
    let run = OutputRun::begin(&dir, RunKind::Analyze).unwrap();
    let during = read_marker(&dir).unwrap().unwrap();
    assert!(!during.complete && during.files.is_empty());
    assert_eq!(files_in(&dir), [".ldh.lock", MARKER]);
    run.write("recordings.json", b"[1]").unwrap();
    let m2 = run.finish().unwrap();
    assert_ne!(m2.run_id, m.run_id);
    assert_eq!(files_in(&dir), ["ldh-run.json", "recordings.json"]);
}

#[test]
fn a_run_killed_before_its_marker_leaves_no_complete_marker() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("out");
    let run = OutputRun::begin(&dir, RunKind::Analyze).unwrap();
    run.write("recordings.json", b"[]").unwrap();
    run.finish().unwrap();
    let run = OutputRun::begin(&dir, RunKind::Analyze).unwrap();
    run.write("recordings.json", b"[2]").unwrap();
    drop(run); // as a kill: no finish
    assert!(!read_marker(&dir).unwrap().unwrap().complete);
}

#[test]
fn files_no_ldh_run_wrote_refuse_the_run_and_stay() {
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("out");
    std::fs::create_dir_all(dir.join("traces")).unwrap();
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    std::fs::write(dir.join("recordings.csv"), "old").unwrap();
    std::fs::write(dir.join("traces/keep.txt"), "mine").unwrap();
    std::fs::create_dir(dir.join("data")).unwrap();
    let e = OutputRun::begin(&dir, RunKind::Analyze)
        .unwrap_err()
        .to_string();
    assert!(e.contains("'data/', 'notes.txt', 'traces/keep.txt'"), "{e}");
    assert!(e.contains("never removes other files"), "{e}");
    assert!(dir.join("recordings.csv").exists() && dir.join("notes.txt").exists());
    assert!(!dir.join(".ldh.lock").exists());
    // A report folder holds no tables: the analysis' files are not its own.
    let e = OutputRun::begin(&dir.join("traces"), RunKind::Report)
        .unwrap_err()
        .to_string();
    assert!(e.contains("'keep.txt'"), "{e}");
}

#[cfg(unix)]
#[test]
fn links_inside_the_folder_are_never_followed() {
    let t = tempfile::tempdir().unwrap();
    let (dir, elsewhere) = (t.path().join("out"), t.path().join("elsewhere"));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::create_dir_all(&elsewhere).unwrap();
    std::os::unix::fs::symlink(&elsewhere, dir.join("reports")).unwrap();
    let e = OutputRun::begin(&dir, RunKind::Analyze)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("'reports' in the output folder is a symbolic link"),
        "{e}"
    );
    assert!(
        dir.join("reports").symlink_metadata().is_ok(),
        "the link is not removed"
    );
    // A link planted while the run writes is refused at the next write through it.
    std::fs::remove_file(dir.join("reports")).unwrap();
    let run = OutputRun::begin(&dir, RunKind::Analyze).unwrap();
    std::os::unix::fs::symlink(&elsewhere, dir.join("traces")).unwrap();
    let e = run.write("traces/H01.json", b"{}").unwrap_err().to_string();
    assert!(
        e.contains("traces: cannot write: is a symbolic link"),
        "{e}"
    );
    std::os::unix::fs::symlink(elsewhere.join("x.json"), dir.join("params.json")).unwrap();
    assert!(run.write("params.json", b"{}").is_err());
    assert!(run.write("../x.json", b"{}").is_err());
    assert_eq!(std::fs::read_dir(&elsewhere).unwrap().count(), 0);
}

/// A run killed between creating `.ldh.lock` and writing its id leaves an empty lock: the next
/// run takes it over (after a second's wait) instead of refusing the folder for good.
#[test]
fn an_empty_lock_left_by_a_killed_run_is_taken_over() {
    let d = tempfile::tempdir().unwrap();
    let lock = d.path().join(".ldh.lock");
    std::fs::write(&lock, "").unwrap();
    assert_eq!(crate::io::writer::live_holder(&lock), None);
    let held = crate::io::writer::OutputLock::acquire(d.path()).unwrap();
    assert_eq!(
        std::fs::read_to_string(&lock).unwrap(),
        std::process::id().to_string()
    );
    drop(held);
    assert!(!lock.exists());
}
