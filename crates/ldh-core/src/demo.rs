//! The embedded demo cohort (SPEC §8): the default data of `ldh analyze`.
//!
//! Four simulated subjects (two healthy, two LDH, affected sides left and right), 25 s each at
//! 100 Hz with a 180° turn, as written by
//! `ldh simulate --out data-fixtures/cohort --healthy 2 --ldh 2 --seconds 25 --seed 2`
//! ([`demo_cohort_params`]). The files are compiled into the library so the binary and the wheel
//! can analyse them anywhere; a test checks they are byte-identical to a fresh simulation.

use std::path::Path;

use crate::error::Result;
use crate::io::write_atomic;
use crate::simulate::CohortParams;

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

/// The parameters that generate the demo cohort.
pub fn demo_cohort_params() -> CohortParams {
    CohortParams {
        healthy: 2,
        ldh: 2,
        duration_s: 25.0,
        fs_hz: 100.0,
        seed: 2,
        ..CohortParams::default()
    }
}

/// The content of one demo file, by relative path (e.g. `"H01/left.csv"`).
pub fn file(rel: &str) -> Option<&'static str> {
    FILES.iter().find(|(p, _)| *p == rel).map(|(_, c)| *c)
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
    use crate::io::FormatSpec;

    #[test]
    fn the_shipped_cohort_is_what_the_simulator_writes() {
        let dir = tempfile::tempdir().unwrap();
        let p = demo_cohort_params();
        crate::simulate::write_cohort(&p, dir.path(), &FormatSpec::default(), &|| {}).unwrap();
        let manifest = std::fs::read_to_string(dir.path().join("manifest.csv")).unwrap();
        assert_eq!(manifest, file("manifest.csv").unwrap());
        for (rel, content) in FILES.iter().filter(|(r, _)| r.contains('/')) {
            let fresh = std::fs::read_to_string(dir.path().join(rel)).unwrap();
            assert!(
                fresh == *content,
                "{rel} differs from a fresh simulation: regenerate data-fixtures/cohort"
            );
        }
        let sides: Vec<&str> = file("manifest.csv")
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split(',').nth(2).unwrap())
            .collect();
        assert_eq!(sides, ["none", "none", "left", "right"]);
    }

    #[test]
    fn write_to_writes_every_file() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(write_to(dir.path()).unwrap(), FILES.len());
        assert!(dir.path().join("L02/truth.json").exists());
    }
}
