//! All the end-to-end tests in one test binary (issue 51: the 17 files built as 17 binaries took
//! 45 s of CPU to compile and link in the `ci` profile, as one binary 20 s; and the tests of all
//! the files share the two cores instead of running one binary after another). Each file stays a
//! module named as the file, so a test's name says where it is: `cli_pipeline::analyze_…`.
//!
//! ```sh
//! cargo test --profile ci -p ldh-e2e --test e2e                          # every end-to-end test
//! cargo test --profile ci -p ldh-e2e --test e2e cli_pinned_outputs::     # the tests of one file
//! cargo test --profile ci -p ldh-e2e --test cli_pinned_outputs           # one file built alone
//! ```
//!
//! Each file is loaded with `#[path]`, so its own `mod common;` finds `common/` as when it is
//! built alone (`tests/Cargo.toml` keeps each file a target of its own with `test = false`: not
//! built by `cargo test`, but `--test <file>` still works). A new file must be added here and
//! there; `every_test_file_is_in_this_binary` fails until it is.

// Each file's own `mod common;` (it must still build alone) loads `common/` once per file here.
#![allow(clippy::duplicate_mod)]

#[path = "bad_inputs.rs"]
mod bad_inputs;
#[path = "cli_agree.rs"]
mod cli_agree;
#[path = "cli_conventions.rs"]
mod cli_conventions;
#[path = "cli_foundations.rs"]
mod cli_foundations;
#[path = "cli_inputs.rs"]
mod cli_inputs;
#[path = "cli_monitor.rs"]
mod cli_monitor;
#[path = "cli_pinned_outputs.rs"]
mod cli_pinned_outputs;
#[path = "cli_pipeline.rs"]
mod cli_pipeline;
#[path = "cli_report.rs"]
mod cli_report;
#[path = "cli_report_real.rs"]
mod cli_report_real;
#[path = "cli_stats.rs"]
mod cli_stats;
#[path = "cli_train.rs"]
mod cli_train;
#[path = "cli_visits.rs"]
mod cli_visits;
#[path = "fuzz_replay.rs"]
mod fuzz_replay;
#[path = "hostile.rs"]
mod hostile;
#[path = "memory.rs"]
mod memory;
#[path = "output_folder.rs"]
mod output_folder;
#[path = "robustness.rs"]
mod robustness;

/// Every `tests/tests/*.rs` file is a module of this binary and a `test = false` target in
/// `tests/Cargo.toml` (else `cargo test` would build it a second time as its own binary).
#[test]
fn every_test_file_is_in_this_binary() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let this = include_str!("e2e.rs");
    let manifest = include_str!("../Cargo.toml");
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(&dir).unwrap() {
        let name = entry.unwrap().file_name().into_string().unwrap();
        let Some(stem) = name.strip_suffix(".rs") else {
            continue;
        };
        if stem == "e2e" {
            continue;
        }
        if !this.contains(&format!("#[path = \"{name}\"]\nmod {stem};")) {
            missing.push(format!("{name}: no `mod {stem};` in tests/tests/e2e.rs"));
        }
        if !manifest.contains(&format!(
            "[[test]]\nname = \"{stem}\"\npath = \"tests/{name}\"\ntest = false\n"
        )) {
            missing.push(format!(
                "{name}: no `[[test]]` with `test = false` in tests/Cargo.toml"
            ));
        }
    }
    assert!(missing.is_empty(), "{}", missing.join("\n"));
}
