//! Byte-for-byte pins of what the commands write, so restructuring commits can prove they
//! changed nothing: `analyze --report` on the demo and on a 10 + 10 simulated cohort, `stats`
//! (with and without `--compare acc`), `train`, `predict`, `report`, `inspect`, `evaluate` and
//! `formats`. Every output file and each command's stdout is hashed (FNV-1a 64, enough to detect
//! a change; this is not a security use) and compared with `tests/pins/outputs.txt`.
//!
//! A commit that changes an output on purpose regenerates the pins and says so:
//! `LDH_PIN_WRITE=1 cargo test --profile ci -p ldh-e2e --test cli_pinned_outputs`, then review
//! `git diff tests/pins/outputs.txt` (one line per file: which outputs changed).
//!
//! Commands run inside a temporary folder with relative paths, so no absolute path reaches an
//! output.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// FNV-1a, 64 bit.
fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// Run `ldh ARGS` in `dir`; stdout goes to `dir/<stdout>`. The exit code must be `code`.
fn run(dir: &Path, args: &[&str], stdout: &str, code: i32) {
    let o = Command::new(env!("CARGO_BIN_EXE_ldh-under-test"))
        .args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .output()
        .expect("runs");
    assert_eq!(
        o.status.code(),
        Some(code),
        "ldh {args:?}: {}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    std::fs::write(dir.join(stdout), &o.stdout).unwrap();
}

fn files(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            files(root, &p, out);
        } else {
            out.push(p.strip_prefix(root).unwrap().to_path_buf());
        }
    }
}

fn pins_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("pins/outputs.txt")
}

#[test]
fn outputs_of_every_command_are_pinned_byte_for_byte() {
    let t = tempfile::tempdir().unwrap();
    let d = t.path();
    analyze_demo_and_cohort(d);
    run_cohort_commands(d);
    let got = output_hashes(d);
    let text: String = got.iter().map(|(k, h)| format!("{h:016x} {k}\n")).collect();
    if std::env::var_os("LDH_PIN_WRITE").is_some() {
        std::fs::create_dir_all(pins_file().parent().unwrap()).unwrap();
        std::fs::write(pins_file(), &text).unwrap();
        eprintln!("wrote {} pins to {}", got.len(), pins_file().display());
        return;
    }
    let diffs = differences_from_pins(&got);
    assert!(
        diffs.is_empty(),
        "outputs differ from tests/pins/outputs.txt (regenerate with LDH_PIN_WRITE=1 only if the \
         change is intended):\n{}",
        diffs.join("\n")
    );
}

/// In `d`: the demo and its analysis with reports, a 10 + 10 simulated cohort and its analysis.
fn analyze_demo_and_cohort(d: &Path) {
    run(d, &["demo", "--out", "demo"], "demo.stdout", 0);
    run(
        d,
        &["analyze", "demo", "--out", "a_demo", "--report"],
        "a_demo.stdout",
        0,
    );
    run(
        d,
        &[
            "simulate",
            "--out",
            "sim",
            "--healthy",
            "10",
            "--ldh",
            "10",
            "--seconds",
            "30",
            "--seed",
            "7",
        ],
        "sim.stdout",
        0,
    );
    run(
        d,
        &["analyze", "sim", "--out", "a_sim", "--report"],
        "a_sim.stdout",
        0,
    );
}

/// In `d`, on the simulated cohort and its analysis: stats, train, predict, report, inspect,
/// evaluate and formats.
fn run_cohort_commands(d: &Path) {
    run(
        d,
        &["stats", "sim", "--out", "s_sim", "--compare", "acc"],
        "s_sim.stdout",
        0,
    );
    run(
        d,
        &["stats", "--results", "a_sim", "--out", "s_sim2"],
        "s_sim2.stdout",
        0,
    );
    run(
        d,
        &[
            "train",
            "--results",
            "a_sim",
            "--out",
            "t_sim",
            "--k",
            "4",
            "--repeats",
            "2",
            "--top-k",
            "6",
        ],
        "t_sim.stdout",
        0,
    );
    run(
        d,
        &[
            "predict",
            "--model",
            "t_sim/model_rf.json",
            "--results",
            "a_sim",
            "--out",
            "p_sim",
        ],
        "p_sim.stdout",
        0,
    );
    run(
        d,
        &[
            "report",
            "a_sim",
            "--out",
            "r_sim",
            "--model",
            "t_sim/model_svm.json",
            "--stats",
            "s_sim",
            "--train",
            "t_sim",
        ],
        "r_sim.stdout",
        0,
    );
    let two = ["sim/H01/left.csv", "sim/L01/right.csv"];
    run(
        d,
        &["inspect", two[0], two[1], "--json"],
        "i_json.stdout",
        0,
    );
    run(d, &["inspect", two[0], two[1]], "i_text.stdout", 0);
    run(
        d,
        &["evaluate", "--truth", "sim", "--json", "ev.json"],
        "ev.stdout",
        0,
    );
    run(d, &["formats"], "formats.stdout", 0);
    run(d, &["formats", "ldh"], "formats_ldh.stdout", 0);
}

/// The hash of every output file under `d` (path relative to `d` → FNV-1a), without the inputs.
fn output_hashes(d: &Path) -> BTreeMap<String, u64> {
    let mut all = Vec::new();
    files(d, d, &mut all);
    let mut got = BTreeMap::new();
    for f in all {
        let key = f.to_string_lossy().replace('\\', "/");
        // The inputs (demo, simulated cohort) are pinned by their own tests.
        if key.starts_with("demo/") || key.starts_with("sim/") {
            continue;
        }
        got.insert(key, fnv1a(&std::fs::read(d.join(&f)).unwrap()));
    }
    got
}

/// What differs between `got` and the pinned hashes: new, changed and missing files.
fn differences_from_pins(got: &BTreeMap<String, u64>) -> Vec<String> {
    let want = std::fs::read_to_string(pins_file()).expect("tests/pins/outputs.txt");
    let want: BTreeMap<String, String> = want
        .lines()
        .filter_map(|l| l.split_once(' '))
        .map(|(h, k)| (k.to_string(), h.to_string()))
        .collect();
    let mut diffs = Vec::new();
    for (k, h) in got {
        match want.get(k) {
            None => diffs.push(format!("new file {k}")),
            Some(w) if *w != format!("{h:016x}") => diffs.push(format!("changed {k}")),
            _ => {}
        }
    }
    for k in want.keys().filter(|k| !got.contains_key(*k)) {
        diffs.push(format!("missing {k}"));
    }
    diffs
}
