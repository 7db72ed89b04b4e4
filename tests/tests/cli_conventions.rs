//! Command-line conventions (issue 18): `-o/-j/-q/-v`, `--input-format` (with `--format` as a
//! hidden alias), a summary on stdout (or `--json`), usage and path problems found before any
//! work with exit code 2, completions and a man page generated from the clap definition.

mod common;
use common::*;

#[test]
fn path_problems_exit_2_before_any_work() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("out");
    let o = ldh(&["analyze", "no/such/folder", "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("no/such/folder: cannot read: no such file or folder"));
    assert!(!out.exists(), "the output folder must not be created");

    let file = d.path().join("a-file");
    std::fs::write(&file, "x").unwrap();
    for cmd in [
        &["analyze", "-o"][..],
        &["simulate", "-o"],
        &["demo", "-o"],
        &["stats", "-o"],
    ] {
        let mut args = cmd.to_vec();
        args.push(file.to_str().unwrap());
        let o = ldh(&args);
        assert_eq!(o.status.code(), Some(2), "{cmd:?}: {}", text(&o));
        assert!(
            text(&o).contains("exists and is not a folder"),
            "{}",
            text(&o)
        );
    }
    // A typo in a choice is a usage error, listing the values.
    let o = ldh(&["analyze", "--model", "fusoin"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("fusion"), "{}", text(&o));
}

#[test]
fn summary_on_stdout_json_for_scripts_and_quiet() {
    let d = tempfile::tempdir().unwrap();
    let out = d.path().join("o");
    let o = ldh_ok(&["analyze", "-o", out.to_str().unwrap(), "-j", "2"]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.starts_with("26 recordings (13 people, model fusion): 26 ok, 0 failed;"),
        "{stdout}"
    );

    let o = ldh_ok(&["analyze", "-o", out.to_str().unwrap(), "--json"]);
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["recordings"], 26);
    assert_eq!(j["ok"], 26);
    assert_eq!(j["failed"], 0);
    assert!(j["valid_strides"].as_u64().unwrap() > 0);
    assert!(j["failures"].as_array().unwrap().is_empty());

    // -q before or after the command: nothing on stdout or stderr when all is well.
    for args in [
        &["-q", "analyze", "-o", out.to_str().unwrap()][..],
        &["analyze", "-q", "-o", out.to_str().unwrap()],
    ] {
        let o = ldh_ok(args);
        assert!(o.stdout.is_empty() && o.stderr.is_empty(), "{}", text(&o));
    }
    let o = ldh(&["-q", "-v", "analyze"]);
    assert_eq!(o.status.code(), Some(2), "-q and -v conflict");
}

#[test]
fn input_format_and_its_old_spelling_read_the_same() {
    let d = tempfile::tempdir().unwrap();
    ldh_core::demo::write_to(d.path()).unwrap();
    let f = d.path().join("H01/left.csv");
    let a = ldh_ok(&["inspect", "--input-format", "ldh", f.to_str().unwrap()]);
    let b = ldh_ok(&["inspect", "--format", "ldh", f.to_str().unwrap()]);
    assert_eq!(a.stdout, b.stdout);
    assert!(!a.stdout.is_empty());
    // The alias stays out of --help.
    let h = ldh_ok(&["analyze", "--help"]);
    let help = String::from_utf8_lossy(&h.stdout);
    assert!(
        help.contains("--input-format") && !help.contains("--format "),
        "{help}"
    );
}

#[test]
fn completions_and_man_page_come_from_the_clap_definition() {
    for shell in ["bash", "zsh", "fish", "powershell", "elvish"] {
        let o = ldh_ok(&["completions", shell]);
        let s = String::from_utf8_lossy(&o.stdout);
        assert!(s.contains("input-format"), "{shell}: {s}");
    }
    let o = ldh_ok(&["man"]);
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(s.contains(".TH ldh 1") && s.contains("analyze"), "{s}");
    // A page per command: `ldh man analyze` is ldh-analyze(1), with its options.
    let o = ldh_ok(&["man", "analyze"]);
    let s = String::from_utf8_lossy(&o.stdout);
    assert!(
        s.contains(".TH ldh-analyze 1") && s.contains("input\\-format"),
        "{s}"
    );
    let o = ldh(&["man", "nosuch"]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        e.contains("no command 'nosuch'") && e.contains("analyze, "),
        "{e}"
    );
    let t = tempfile::tempdir().unwrap();
    let dir = t.path().join("man1");
    ldh_ok(&["man", "--out", dir.to_str().unwrap()]);
    for page in [
        "ldh.1",
        "ldh-analyze.1",
        "ldh-inspect.1",
        "ldh-agree.1",
        "ldh-man.1",
    ] {
        let text =
            std::fs::read_to_string(dir.join(page)).unwrap_or_else(|e| panic!("{page}: {e}"));
        assert!(text.starts_with(".ie") || text.contains(".TH"), "{page}");
    }
}
