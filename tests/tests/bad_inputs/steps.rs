//! Cases of the bad-input corpus that are a sequence of `ldh` runs (`command = "cli"`), and the
//! measured run every case goes through: a time limit (a hang fails the case instead of the
//! test run) and the child's peak resident set size from `wait4` (issue 37: ≤ 1 GB on every
//! case). The format is documented in data-fixtures/bad/README.md ("Sequences of runs").

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The bound on any run's peak memory, KiB (`ru_maxrss`).
pub const ONE_GB_KIB: i64 = 1_000_000_000 / 1024;

/// Time a step may take unless its case says otherwise.
const DEFAULT_TIMEOUT_S: f64 = 120.0;

/// One finished (or killed) run of `ldh`.
pub struct Run {
    /// The exit code; `None` when the process was killed by a signal (a crash, or the time limit).
    pub code: Option<i32>,
    /// stdout followed by stderr, lossily decoded.
    pub text: String,
    /// Bytes written to stdout and stderr together.
    pub output_bytes: u64,
    /// Peak resident set size of the child, KiB.
    pub rss_kib: i64,
    /// Whether the time limit killed it.
    pub timed_out: bool,
    /// stdout alone (for `inspect --json`).
    pub stdout: Vec<u8>,
}

/// Text kept of a run's output for messages and checks: enough for every expected fragment,
/// bounded so that a run that floods its output cannot flood the test's memory.
const TEXT_KEEP_BYTES: u64 = 1 << 20;

/// Run `ldh args` in `cwd` with a time limit; stdout and stderr go to files in `scratch`.
pub fn run_measured(args: &[String], cwd: &Path, scratch: &Path, timeout_s: f64) -> Run {
    let out_path = scratch.join(".stdout");
    let err_path = scratch.join(".stderr");
    let child = Command::new(env!("CARGO_BIN_EXE_ldh-under-test"))
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .stdout(Stdio::from(std::fs::File::create(&out_path).unwrap()))
        .stderr(Stdio::from(std::fs::File::create(&err_path).unwrap()))
        .spawn()
        .expect("runs");
    let pid = child.id() as libc::pid_t;
    let (status, usage, timed_out) = wait_with_limit(pid, Duration::from_secs_f64(timeout_s));
    std::mem::forget(child); // reaped by wait4 above
    let read = |p: &Path| -> (Vec<u8>, u64) {
        use std::io::Read;
        let len = std::fs::metadata(p).map(|m| m.len()).unwrap_or(0);
        let mut v = Vec::new();
        if let Ok(f) = std::fs::File::open(p) {
            f.take(TEXT_KEEP_BYTES).read_to_end(&mut v).unwrap();
        }
        (v, len)
    };
    let (stdout, n_out) = read(&out_path);
    let (stderr, n_err) = read(&err_path);
    let _ = std::fs::remove_file(&out_path);
    let _ = std::fs::remove_file(&err_path);
    Run {
        code: libc::WIFEXITED(status).then(|| libc::WEXITSTATUS(status)),
        text: format!(
            "{}{}",
            String::from_utf8_lossy(&stdout),
            String::from_utf8_lossy(&stderr)
        ),
        output_bytes: n_out + n_err,
        rss_kib: usage.ru_maxrss,
        timed_out,
        stdout,
    }
}

/// Wait for child `pid`, killing it after `limit`: its wait status, its resource usage and
/// whether it was killed for time.
fn wait_with_limit(pid: libc::pid_t, limit: Duration) -> (i32, libc::rusage, bool) {
    let start = Instant::now();
    let mut status = 0;
    // SAFETY: `rusage` is plain data that wait4 fills; `pid` is our own unwaited child.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let mut timed_out = false;
    loop {
        let flags = if timed_out { 0 } else { libc::WNOHANG };
        let r = unsafe { libc::wait4(pid, &mut status, flags, &mut usage) };
        if r == pid {
            return (status, usage, timed_out);
        }
        assert!(r == 0, "wait4: {}", std::io::Error::last_os_error());
        if start.elapsed() > limit {
            // SAFETY: signalling our own child, which has not been reaped.
            unsafe { libc::kill(pid, libc::SIGKILL) };
            timed_out = true;
        } else {
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

/// `{case}` and `{tmp}` replaced by the case's folder and the temporary folder.
pub fn expand(s: &str, case: &Path, tmp: &Path) -> String {
    s.replace("{case}", &case.display().to_string())
        .replace("{tmp}", &tmp.display().to_string())
}

/// Run each bash line of `key` in `tmp` (placeholders expanded); the first that fails is the
/// case's failure.
pub fn shell_lines(v: &toml::Value, key: &str, case: &Path, tmp: &Path) -> Result<(), String> {
    for line in super::strs(v, key) {
        let line = expand(&line, case, tmp);
        let o = Command::new("bash")
            .args(["-euo", "pipefail", "-c", &line])
            .current_dir(tmp)
            .output()
            .map_err(|e| format!("{key} `{line}`: {e}"))?;
        if !o.status.success() {
            return Err(format!(
                "{key} `{line}` failed: {}{}",
                String::from_utf8_lossy(&o.stdout),
                String::from_utf8_lossy(&o.stderr)
            ));
        }
    }
    Ok(())
}

/// The checks every measured run passes: no panic, no hang, no crash, memory bounded.
pub fn check_run(run: &Run, what: &str) -> Result<(), String> {
    if run.timed_out {
        return Err(format!("{what}: still running at its time limit (a hang)"));
    }
    if run.text.contains("panicked") {
        return Err(format!("{what}: panicked: {}", run.text));
    }
    if run.code.is_none() {
        return Err(format!(
            "{what}: killed by a signal (a crash): {}",
            run.text
        ));
    }
    if run.rss_kib > ONE_GB_KIB {
        return Err(format!(
            "{what}: peak RSS {:.0} MB > 1 GB",
            run.rss_kib as f64 * 1024.0 / 1e6
        ));
    }
    Ok(())
}

/// A `command = "cli"` case: its setup lines, then each `[[step]]` with its checks, in a fresh
/// temporary folder.
pub fn check_cli_case(name: &str, exp: &toml::Value) -> Result<(), String> {
    let case = super::corpus().join(name).canonicalize().unwrap();
    let tmp_dir = tempfile::tempdir().unwrap();
    let tmp = tmp_dir.path().canonicalize().unwrap();
    let scratch = tempfile::tempdir().unwrap();
    shell_lines(exp, "setup", &case, &tmp)?;
    let steps = exp
        .get("step")
        .and_then(|s| s.as_array())
        .ok_or("a cli case needs at least one [[step]]")?;
    for (i, step) in steps.iter().enumerate() {
        let args: Vec<String> = super::strs(step, "args")
            .iter()
            .map(|a| expand(a, &case, &tmp))
            .collect();
        let what = format!("step {} (ldh {})", i + 1, args.join(" "));
        let timeout = step
            .get("timeout_s")
            .and_then(|x| x.as_float().or(x.as_integer().map(|i| i as f64)))
            .unwrap_or(DEFAULT_TIMEOUT_S);
        let t = Instant::now();
        let run = run_measured(&args, &tmp, scratch.path(), timeout);
        println!(
            "  {what}: exit {:?}, {:.0} MB, {:.1} s",
            run.code,
            run.rss_kib as f64 * 1024.0 / 1e6,
            t.elapsed().as_secs_f64()
        );
        check_run(&run, &what)?;
        check_step(step, &run, &tmp).map_err(|e| format!("{what}: {e}"))?;
        shell_lines(step, "after", &case, &tmp)?;
    }
    Ok(())
}

/// One step's expectations: exit code, text, output size, files present and absent.
fn check_step(step: &toml::Value, run: &Run, tmp: &Path) -> Result<(), String> {
    let want = step
        .get("exit_code")
        .and_then(|x| x.as_integer())
        .unwrap_or(0) as i32;
    if run.code != Some(want) {
        return Err(format!(
            "exit code {:?}, expected {want}: {}",
            run.code, run.text
        ));
    }
    super::has(&run.text, &super::strs(step, "contains"), "output")?;
    for n in super::strs(step, "absent_text") {
        if run.text.contains(n.as_str()) {
            return Err(format!("output contains {n:?}: {}", run.text));
        }
    }
    if let Some(max) = step.get("max_output_bytes").and_then(|x| x.as_integer()) {
        if run.output_bytes > max as u64 {
            return Err(format!(
                "{} bytes of output, at most {max} expected",
                run.output_bytes
            ));
        }
    }
    for p in super::strs(step, "exists") {
        if std::fs::symlink_metadata(tmp.join(&p)).is_err() {
            return Err(format!("{p} does not exist"));
        }
    }
    for p in super::strs(step, "missing") {
        if std::fs::symlink_metadata(tmp.join(&p)).is_ok() {
            return Err(format!("{p} exists"));
        }
    }
    Ok(())
}
