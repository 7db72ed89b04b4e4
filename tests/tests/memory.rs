//! Issue 19: a 10-million-row recording (~430 MB, made here in a temporary folder, never
//! committed) is refused or read in bounded memory, never OOM-killed. Each run's peak memory is
//! the child's maximum resident set size from `wait4` (Linux `ru_maxrss`, KiB).
//!
//! What a user gets (docs/robustness.md, "Size limits"):
//! - with the defaults: refused by size (`max_file_size_mb`, 256 MB) before any byte is read;
//! - with `--max-file-size-mb 2000`: refused by `max_samples` (2 500 000) while streaming, the
//!   rows past the limit counted but not stored — `ldh inspect` and `ldh analyze` alike;
//! - with `--max-samples` raised too, `ldh inspect` reads all 10 M rows in under 1 GB: the file
//!   is streamed and only the seven columns are kept.
//!
//! Wall time on the 2-core CI machine: about 10–20 s (writing the file ~2 s, three full reads).

mod common;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

const ROWS: usize = 10_000_000;
/// The bound on any run's peak memory.
const ONE_GB_KIB: i64 = 1_000_000_000 / 1024;

/// Write `ROWS` rows at 100 Hz: `baseline_ok`'s left leg (a simulated walk with standing at
/// both ends) tiled with continuous time, formatted from integers (a few seconds).
fn write_big(path: &Path) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../data-fixtures/bad/baseline_ok/left.csv")
        .canonicalize()
        .unwrap();
    let text = std::fs::read_to_string(src).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    let rests: Vec<&str> = lines.map(|l| l.split_once(',').unwrap().1).collect();
    let mut w = std::io::BufWriter::with_capacity(1 << 20, std::fs::File::create(path).unwrap());
    writeln!(w, "{header}").unwrap();
    let mut line = Vec::with_capacity(128);
    for i in 0..ROWS {
        line.clear();
        write!(line, "{}.{:02},", i / 100, i % 100).unwrap();
        line.extend_from_slice(rests[i % rests.len()].as_bytes());
        line.push(b'\n');
        w.write_all(&line).unwrap();
    }
    w.flush().unwrap();
}

/// Run `ldh args` to the end: exit code, stdout + stderr, and the child's peak resident set
/// size in KiB (from `wait4`, so the child alone, not this test process).
#[allow(clippy::zombie_processes)] // reaped by wait4, which also gives its rusage
fn run_measured(args: &[&str], dir: &Path) -> (i32, String, i64) {
    let out = std::fs::File::create(dir.join("stdout.txt")).unwrap();
    let err = std::fs::File::create(dir.join("stderr.txt")).unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_ldh-under-test"))
        .args(args)
        .stdout(Stdio::from(out))
        .stderr(Stdio::from(err))
        .spawn()
        .unwrap();
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: `rusage` is plain data that wait4 fills; `pid` is our own unwaited child.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let r = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    assert_eq!(r, pid, "wait4: {}", std::io::Error::last_os_error());
    assert!(
        libc::WIFEXITED(status),
        "ldh {args:?} did not exit normally (signal {}): killed or crashed",
        libc::WTERMSIG(status)
    );
    let text = std::fs::read_to_string(dir.join("stdout.txt")).unwrap()
        + &std::fs::read_to_string(dir.join("stderr.txt")).unwrap();
    (libc::WEXITSTATUS(status), text, usage.ru_maxrss)
}

#[test]
fn a_ten_million_row_file_is_refused_or_read_in_under_one_gigabyte() {
    let d = tempfile::tempdir().unwrap();
    let subject = d.path().join("S1");
    std::fs::create_dir(&subject).unwrap();
    let big = subject.join("left.csv");
    let t = std::time::Instant::now();
    write_big(&big);
    // The right leg: the same file (the left leg is refused first; no 2nd copy on disk).
    std::os::unix::fs::symlink(&big, subject.join("right.csv")).unwrap();
    let size_mb = std::fs::metadata(&big).unwrap().len() as f64 / 1e6;
    println!(
        "wrote {ROWS} rows, {size_mb:.0} MB in {:.1} s",
        t.elapsed().as_secs_f64()
    );
    let b = big.to_str().unwrap();
    let out = d.path().join("out");
    let cases: [(&str, Vec<&str>, i32, Vec<String>); 4] = [
        (
            "inspect, defaults: refused by size before reading",
            vec!["inspect", b],
            1,
            vec![
                format!("{b}: the file has {size_mb:.0} MB, above the limit of 256 MB"),
                "--max-file-size-mb".into(),
            ],
        ),
        (
            "inspect, size limit raised: refused by max_samples while streaming",
            vec!["inspect", b, "--max-file-size-mb", "2000"],
            1,
            vec![format!(
                "{b}: {ROWS} data rows, above the limit of 2500000 samples per recording"
            )],
        ),
        (
            "analyze, size limit raised: the leg refused by max_samples, a row with its reason",
            vec![
                "analyze",
                subject.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
                "--max-file-size-mb",
                "2000",
                "--jobs",
                "1",
            ],
            1,
            vec![format!(
                "{ROWS} data rows, above the limit of 2500000 samples per recording"
            )],
        ),
        (
            "inspect, both limits raised: all 10 M rows streamed",
            vec![
                "inspect",
                b,
                "--max-file-size-mb",
                "2000",
                "--max-samples",
                "20000000",
            ],
            0,
            vec![format!(
                "100.00 Hz, {:.1} s, {ROWS} samples",
                (ROWS - 1) as f64 / 100.0
            )],
        ),
    ];
    for (what, args, code, expect) in cases {
        let t = std::time::Instant::now();
        let (got, text, rss_kib) = run_measured(&args, d.path());
        println!(
            "{what}: exit {got}, peak RSS {:.0} MB, {:.1} s",
            rss_kib as f64 * 1024.0 / 1e6,
            t.elapsed().as_secs_f64()
        );
        assert_eq!(got, code, "{what}: {text}");
        assert!(!text.contains("panicked"), "{what}: {text}");
        for e in &expect {
            assert!(text.contains(e.as_str()), "{what}: no {e:?} in {text}");
        }
        assert!(
            rss_kib <= ONE_GB_KIB,
            "{what}: peak RSS {rss_kib} KiB > 1 GB"
        );
    }
    if out.exists() {
        let rows = std::fs::read_to_string(out.join("recordings.csv")).unwrap();
        assert!(rows.lines().count() == 3, "one row per leg: {rows}");
    }
}
