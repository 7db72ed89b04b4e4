//! The embedded demo cohort (SPEC §8): the default data of `ldh analyze`.
//!
//! Thirteen simulated people — ten healthy and three with LDH (affected sides right, left,
//! left) — 35 s each at 100 Hz: 3 s standing, a straight walk, a 180° turn, the walk back and
//! 3 s standing, as written by
//! `ldh simulate --out DIR --healthy 10 --ldh 3 --seconds 35 --seed 1`
//! (`ldh_sim::demo::demo_cohort_params`; `data-fixtures/scripts/make_demo.sh` regenerates the
//! stored copy). Ten healthy people is what the reports need for the cohort's own healthy
//! reference range of every parameter (`ldh_report::ReportParams::min_healthy_subjects`), three
//! a group for the cohort statistics ([`crate::cohort::MIN_GROUP_SIZE`]); each leg has 15 or
//! more steady strides (at least 10 are needed for the variability). The recordings are stored
//! gzip-compressed in `data-fixtures/cohort/<subject>/<side>.csv.gz` (1.8 MB for 5.9 MB of
//! CSV) and compiled into the library, so the binary and the wheel analyse them anywhere; each
//! is decompressed the first time it is asked for. The simulator's `truth.json` files are not
//! shipped (`ldh simulate` with the settings above writes them). A test in `ldh-sim` checks
//! the files are byte-identical to a fresh simulation.

use std::io::Read;
use std::path::Path;
use std::sync::OnceLock;

use crate::error::Result;
use crate::io::write_atomic;

/// How a demo file is stored in the library.
enum Stored {
    /// As text.
    Text(&'static str),
    /// gzip-compressed text.
    Gz(&'static [u8]),
}

/// The stored files: the manifest, the settings, then the left and right leg of each subject
/// (compressed), in that order.
macro_rules! stored {
    ($($id:literal),*) => {
        [
            (
                "manifest.csv",
                Stored::Text(include_str!("../../../data-fixtures/cohort/manifest.csv")),
            ),
            (
                "cohort.json",
                Stored::Text(include_str!("../../../data-fixtures/cohort/cohort.json")),
            ),
            $(
                (
                    concat!($id, "/left.csv"),
                    Stored::Gz(include_bytes!(concat!(
                        "../../../data-fixtures/cohort/", $id, "/left.csv.gz"
                    ))),
                ),
                (
                    concat!($id, "/right.csv"),
                    Stored::Gz(include_bytes!(concat!(
                        "../../../data-fixtures/cohort/", $id, "/right.csv.gz"
                    ))),
                ),
            )*
        ]
    };
}

/// Number of files of the demo cohort (manifest, settings, two legs per subject).
const N_FILES: usize = 2 + 2 * SUBJECTS.len();

/// The files as stored, in [`paths`] order.
static STORED: [(&str, Stored); N_FILES] = stored!(
    "H01", "H02", "H03", "H04", "H05", "H06", "H07", "H08", "H09", "H10", "L01", "L02", "L03"
);

/// The decompressed text of each stored file, filled on first use.
static TEXT: [OnceLock<String>; N_FILES] = [const { OnceLock::new() }; N_FILES];

/// The subject identifiers of the demo cohort.
pub const SUBJECTS: [&str; 13] = [
    "H01", "H02", "H03", "H04", "H05", "H06", "H07", "H08", "H09", "H10", "L01", "L02", "L03",
];

/// The paths of the demo cohort's files, relative to the cohort folder: `manifest.csv`,
/// `cohort.json` (the simulator's settings), then `<subject>/left.csv` and `<subject>/right.csv`.
pub fn paths() -> impl Iterator<Item = &'static str> {
    STORED.iter().map(|(rel, _)| *rel)
}

/// The content of one demo file, by relative path (e.g. `"H01/left.csv"`).
pub fn file(rel: &str) -> Option<&'static str> {
    let i = STORED.iter().position(|(p, _)| *p == rel)?;
    Some(match &STORED[i].1 {
        Stored::Text(t) => *t,
        Stored::Gz(bytes) => TEXT[i]
            .get_or_init(|| {
                let mut text = String::new();
                flate2::read::GzDecoder::new(*bytes)
                    .read_to_string(&mut text)
                    .expect("the embedded demo files are valid gzip'd UTF-8 (tested)");
                text
            })
            .as_str(),
    })
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

/// Write the demo cohort into `dir` (created if missing), as plain CSV; returns the number of
/// files.
pub fn write_to(dir: &Path) -> Result<usize> {
    for rel in paths() {
        let content = file(rel).expect("a path of the demo cohort");
        write_atomic(dir.join(rel), content.as_bytes())?;
    }
    Ok(N_FILES)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_leg_reads_and_an_unknown_one_is_named() {
        for id in SUBJECTS {
            for side in ["left", "right"] {
                let r = recording(&format!("{id}/{side}.csv")).unwrap();
                assert_eq!((r.fs_hz, r.len()), (100.0, 3501));
            }
        }
        let e = recording("H99/left.csv").unwrap_err().to_string();
        assert!(e.contains("H99/left.csv"), "{e}");
    }

    #[test]
    fn the_manifest_names_every_stored_leg() {
        let manifest = file("manifest.csv").unwrap();
        let listed: Vec<&str> = manifest
            .lines()
            .skip(1)
            .flat_map(|l| l.split(',').skip(3).take(2))
            .collect();
        let stored: Vec<&str> = paths().skip(2).collect();
        assert_eq!(listed, stored);
        assert_eq!(paths().count(), N_FILES);
    }

    #[test]
    fn write_to_writes_every_file() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(write_to(dir.path()).unwrap(), N_FILES);
        let left = std::fs::read_to_string(dir.path().join("L03/left.csv")).unwrap();
        assert!(left.starts_with("time_s,acc_x,"), "{}", &left[..40]);
        assert_eq!(left, file("L03/left.csv").unwrap());
    }
}
