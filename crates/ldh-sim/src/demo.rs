//! The simulation behind `ldh-core`'s embedded demo cohort ([`ldh_core::demo`]): the files are
//! generated once by `ldh simulate --out data-fixtures/cohort --healthy 2 --ldh 2 --seconds 25
//! --seed 2` and compiled into `ldh-core`; the test below checks they are byte-identical to a
//! fresh simulation with [`demo_cohort_params`].

use crate::CohortParams;

/// The parameters that generate the demo cohort (two healthy, two LDH, 25 s at 100 Hz, seed 2).
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

#[cfg(test)]
mod tests {
    use super::*;
    use ldh_core::demo::{file, FILES};
    use ldh_core::io::FormatSpec;

    #[test]
    fn the_shipped_cohort_is_what_the_simulator_writes() {
        let dir = tempfile::tempdir().unwrap();
        let p = demo_cohort_params();
        crate::write_cohort(&p, dir.path(), &FormatSpec::default(), &|| {}).unwrap();
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
}
