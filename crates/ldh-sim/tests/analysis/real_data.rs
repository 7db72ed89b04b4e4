//! The real walks of `../shared/realdata` that several analysis tests run (`clocks`,
//! `stairs`, `real_walks`): HuGaDB's overground walking files and TRIPOD's three treadmill
//! runs, each as the subject input ldh is given and its two shanks read on demand.

use super::events_accuracy::tripod::{
    read_physilog, to_ldh_frame, tripod_dir, TRIPOD_RUNS, TRIPOD_UNTIL_S,
};
use super::events_to_hugadb::hugadb_dir;
use ldh_core::io::{read_recording, FormatSpec, ReadParams};
use ldh_core::pipeline::{memory_report, Analysis, LoadedLeg, Source, SubjectInput, SubjectResult};
use ldh_core::recording::{Recording, Side};
use std::path::{Path, PathBuf};

/// The HuGaDB file `file` (`01_00`).
fn hugadb_path(dir: &Path, file: &str) -> PathBuf {
    dir.join(format!("HuGaDB_v1_walking_{file}.txt"))
}

/// TRIPOD's IMU folder of `run`.
fn tripod_imu(dir: &Path, run: &str) -> PathBuf {
    dir.join("Sub_FZ").join(run).join("IMU")
}

/// One HuGaDB file's shank on `side` through the built-in format map.
fn hugadb_leg(dir: &Path, file: &str, side: &str) -> LoadedLeg {
    let path = hugadb_path(dir, file);
    let spec = FormatSpec::builtin(&format!("hugadb-{side}-shank")).unwrap();
    let rp = ReadParams::default().check().unwrap();
    let rec = read_recording(&path, Some(&spec), &rp).unwrap().0;
    let rep = memory_report(&rec);
    Ok((rec, rep, format!("{file}/{side}")))
}

/// The HuGaDB files present (every `HuGaDB_v1_walking_*.txt`), by name.
fn hugadb_files(dir: &Path) -> Vec<String> {
    let mut f: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| {
            let n = e.ok()?.file_name().into_string().ok()?;
            Some(
                n.strip_prefix("HuGaDB_v1_walking_")?
                    .strip_suffix(".txt")?
                    .to_string(),
            )
        })
        .collect();
    f.sort();
    f
}

/// One TRIPOD shank (`LS.csv` / `RS.csv`) of `run`, rows up to `until_s`.
fn tripod_leg(dir: &Path, run: &str, file: &str, side: Side, until_s: f64) -> LoadedLeg {
    let imu = tripod_imu(dir, run);
    let (_, acc, gyro) = read_physilog(&imu.join(file), until_s);
    let rec = Recording::new(128.0, to_ldh_frame(acc), to_ldh_frame(gyro), vec![])
        .unwrap()
        .with_side(side);
    let rep = memory_report(&rec);
    Ok((rec, rep, format!("{run}/{file}")))
}

/// The data set of a [`RealWalk`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum RealSet {
    /// HuGaDB: overground, both shanks on one clock.
    HuGaDb,
    /// TRIPOD: treadmill, one Physilog unit per shank.
    Tripod,
}

/// One real walk: its data set, its id (HuGaDB's file, `01_00`; TRIPOD's run, `PWS`) and the
/// subject input ldh is given (TRIPOD's: a treadmill at the run's belt speed).
pub(crate) struct RealWalk {
    pub set: RealSet,
    pub id: String,
    pub input: SubjectInput,
    dir: PathBuf,
}

impl RealWalk {
    /// TRIPOD's run `run` (`PWS`, …) of `Sub_FZ` under `dir`: a treadmill at `belt_mps`, no
    /// sensor height given (set `input`'s heights to give one).
    pub fn tripod(dir: &Path, run: &str, belt_mps: f64) -> RealWalk {
        RealWalk {
            set: RealSet::Tripod,
            id: run.to_string(),
            // One Physilog file per shank: two clocks (`SubjectInput::clocks`).
            input: SubjectInput {
                subject_id: format!("Sub_FZ {run}"),
                left: Some(Source::Path(tripod_imu(dir, run).join("LS.csv"))),
                right: Some(Source::Path(tripod_imu(dir, run).join("RS.csv"))),
                setting: Some(ldh_core::Setting::Treadmill),
                belt_speed_mps: Some(belt_mps),
                ..SubjectInput::default()
            },
            dir: dir.to_path_buf(),
        }
    }

    /// `HuGaDB 01_00`, `TRIPOD PWS`.
    pub fn name(&self) -> String {
        match self.set {
            RealSet::HuGaDb => format!("HuGaDB {}", self.id),
            RealSet::Tripod => format!("TRIPOD {}", self.id),
        }
    }

    /// The shank on `side`: HuGaDB's whole file, TRIPOD's rows up to `until_s`.
    pub fn leg(&self, side: Side, until_s: f64) -> LoadedLeg {
        match self.set {
            RealSet::HuGaDb => hugadb_leg(&self.dir, &self.id, side.as_str()),
            RealSet::Tripod => {
                let file = if side == Side::Left {
                    "LS.csv"
                } else {
                    "RS.csv"
                };
                tripod_leg(&self.dir, &self.id, file, side, until_s)
            }
        }
    }

    /// Both shanks analysed by `analysis` (TRIPOD's first [`TRIPOD_UNTIL_S`], while the belt
    /// runs steadily).
    pub fn analyse(&self, analysis: &Analysis) -> SubjectResult {
        let leg = |side| self.leg(side, TRIPOD_UNTIL_S);
        analysis.pair(&self.input, leg(Side::Left), leg(Side::Right))
    }
}

/// HuGaDB's walking files, then TRIPOD's three runs; `None`, with the one line that says the
/// test is skipped, when either data set is not found.
pub(crate) fn real_walks() -> Option<Vec<RealWalk>> {
    let (Some(hu), Some(tr)) = (hugadb_dir(), tripod_dir()) else {
        println!("skipped: ../shared/realdata (hugadb, tripod) not found (set LDH_REALDATA)");
        return None;
    };
    let mut walks: Vec<RealWalk> = hugadb_files(&hu)
        .into_iter()
        .map(|file| RealWalk {
            set: RealSet::HuGaDb,
            // One file holds both shanks: one clock (`SubjectInput::clocks`).
            input: SubjectInput {
                subject_id: file.clone(),
                left: Some(Source::Path(hugadb_path(&hu, &file))),
                right: Some(Source::Path(hugadb_path(&hu, &file))),
                ..SubjectInput::default()
            },
            id: file,
            dir: hu.clone(),
        })
        .collect();
    walks.extend(TRIPOD_RUNS.map(|(run, belt)| RealWalk::tripod(&tr, run, belt)));
    Some(walks)
}
