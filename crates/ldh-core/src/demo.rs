//! The embedded demo cohort (SPEC §8): the default data of `ldh analyze`.
//!
//! Four simulated subjects (two healthy, two LDH, affected sides left and right), 25 s each at
//! 100 Hz with a 180° turn, as written by
//! `ldh simulate --out data-fixtures/cohort --healthy 2 --ldh 2 --seconds 25 --seed 2`
//! (`ldh_sim::demo::demo_cohort_params`). The files are compiled into the library so the binary
//! and the wheel can analyse them anywhere; a test in `ldh-sim` checks they are byte-identical to
//! a fresh simulation.

use std::path::Path;

use crate::error::Result;
use crate::io::write_atomic;

/// The files of the demo cohort: (path relative to the cohort folder, content).
pub const FILES: [(&str, &str); 14] = [
    (
        "manifest.csv",
        include_str!("../../../data-fixtures/cohort/manifest.csv"),
    ),
    (
        "cohort.json",
        include_str!("../../../data-fixtures/cohort/cohort.json"),
    ),
    (
        "H01/left.csv",
        include_str!("../../../data-fixtures/cohort/H01/left.csv"),
    ),
    (
        "H01/right.csv",
        include_str!("../../../data-fixtures/cohort/H01/right.csv"),
    ),
    (
        "H01/truth.json",
        include_str!("../../../data-fixtures/cohort/H01/truth.json"),
    ),
    (
        "H02/left.csv",
        include_str!("../../../data-fixtures/cohort/H02/left.csv"),
    ),
    (
        "H02/right.csv",
        include_str!("../../../data-fixtures/cohort/H02/right.csv"),
    ),
    (
        "H02/truth.json",
        include_str!("../../../data-fixtures/cohort/H02/truth.json"),
    ),
    (
        "L01/left.csv",
        include_str!("../../../data-fixtures/cohort/L01/left.csv"),
    ),
    (
        "L01/right.csv",
        include_str!("../../../data-fixtures/cohort/L01/right.csv"),
    ),
    (
        "L01/truth.json",
        include_str!("../../../data-fixtures/cohort/L01/truth.json"),
    ),
    (
        "L02/left.csv",
        include_str!("../../../data-fixtures/cohort/L02/left.csv"),
    ),
    (
        "L02/right.csv",
        include_str!("../../../data-fixtures/cohort/L02/right.csv"),
    ),
    (
        "L02/truth.json",
        include_str!("../../../data-fixtures/cohort/L02/truth.json"),
    ),
];

/// The subject identifiers of the demo cohort.
pub const SUBJECTS: [&str; 4] = ["H01", "H02", "L01", "L02"];

/// The content of one demo file, by relative path (e.g. `"H01/left.csv"`).
pub fn file(rel: &str) -> Option<&'static str> {
    FILES.iter().find(|(p, _)| *p == rel).map(|(_, c)| *c)
}

/// One leg of the demo cohort read as `ldh analyze` reads a file (default format and reading),
/// by relative path (e.g. `"H01/left.csv"`); an unknown path is a "not found" read error.
pub fn recording(rel: &str) -> Result<crate::Recording> {
    let path = Path::new(rel);
    let text = file(rel).ok_or_else(|| crate::LdhError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(
            std::io::ErrorKind::NotFound,
            "not a file of the embedded demo cohort",
        ),
    })?;
    let read = crate::io::ReadParams::default().check()?;
    Ok(crate::io::read_recording_bytes(text.as_bytes(), path, None, &read)?.0)
}

/// Write the demo cohort into `dir` (created if missing); returns the number of files.
pub fn write_to(dir: &Path) -> Result<usize> {
    for (rel, content) in FILES {
        write_atomic(dir.join(rel), content.as_bytes())?;
    }
    Ok(FILES.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_leg_reads_and_an_unknown_one_is_named() {
        for id in SUBJECTS {
            for side in ["left", "right"] {
                let r = recording(&format!("{id}/{side}.csv")).unwrap();
                assert_eq!((r.fs_hz, r.len()), (100.0, 2501));
            }
        }
        let e = recording("H09/left.csv").unwrap_err().to_string();
        assert!(e.contains("H09/left.csv"), "{e}");
    }

    #[test]
    fn write_to_writes_every_file() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(write_to(dir.path()).unwrap(), FILES.len());
        assert!(dir.path().join("L02/truth.json").exists());
    }
}
