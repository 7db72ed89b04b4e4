//! What one input of a run is — a subject (or one trial of a subject) with its two recordings'
//! sources and the manifest's labels — below both the manifest parser and input discovery,
//! which make them.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

use super::heights::SensorHeights;
pub use crate::domain::Group;
use crate::error::{LdhError, Result};
use crate::io::{read_recording, read_recording_bytes, FormatSpec, ReadReport, ValidReadParams};
use crate::recording::{Recording, Side};

/// Where a recording comes from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Source {
    /// A file.
    Path(PathBuf),
    /// A file of the embedded demo cohort (relative path).
    Embedded(String),
}

impl Source {
    /// A label for messages and tables.
    pub fn label(&self) -> String {
        match self {
            Source::Path(p) => p.display().to_string(),
            Source::Embedded(r) => format!("<demo>/{r}"),
        }
    }
    /// Read the recording.
    pub fn read(
        &self,
        format: Option<&FormatSpec>,
        params: &ValidReadParams,
    ) -> Result<(Recording, ReadReport)> {
        match self {
            Source::Path(p) => read_recording(p, format, params),
            Source::Embedded(rel) => {
                let text = crate::demo::file(rel)
                    .ok_or_else(|| LdhError::signal("demo", format!("no embedded file {rel}")))?;
                read_recording_bytes(text.as_bytes(), Path::new(&self.label()), format, params)
            }
        }
    }
}

/// Whether the two legs' recordings share one clock: every timing between the legs (step time,
/// step frequency, double support) compares one recording's events with the other's, and a
/// clock offset between two recordings moves it (`pipeline::quality::clocks`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Clocks {
    /// One clock: both legs read from one file (HuGaDB), the embedded demo, a simulator, or
    /// stated by the caller.
    One,
    /// Two files from two sensors, nothing said of their synchronisation: their clocks may be
    /// apart by an unknown offset (TRIPOD's Physilog units: 55–184 ms).
    Two,
}

impl Clocks {
    /// The manifest's spelling (`one`, `two`), which [`std::str::FromStr`] reads back.
    pub fn as_str(self) -> &'static str {
        match self {
            Clocks::One => "one",
            Clocks::Two => "two",
        }
    }
}

impl std::str::FromStr for Clocks {
    type Err = LdhError;
    /// `one` (the sensors were synchronised, or one device recorded both legs) or `two`,
    /// case-insensitive; anything else is a parameter error naming the value as given (the
    /// manifest's `clocks` column and Python's `clocks=` read it with this).
    fn from_str(s: &str) -> Result<Self> {
        let key = s.trim().to_ascii_lowercase();
        [Clocks::One, Clocks::Two]
            .into_iter()
            .find(|c| c.as_str() == key)
            .ok_or_else(|| LdhError::param("clocks", s, "expected 'one' or 'two'"))
    }
}

/// One subject (or one trial of a subject) to analyse.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct SubjectInput {
    /// Identifier (the person: a person's trials share it).
    pub subject_id: String,
    /// Group, when a manifest gives it.
    pub group: Option<Group>,
    /// Affected side, when a manifest gives it (`None` for none or unknown).
    pub affected_side: Option<Side>,
    /// The manifest left `affected_side` empty for a subject outside the healthy group: the
    /// side is unknown (said in the results), not "none".
    #[serde(default)]
    pub affected_side_unknown: bool,
    /// Left recording.
    pub left: Option<Source>,
    /// Right recording.
    pub right: Option<Source>,
    /// Sensor height above the ankle for both legs, m (manifest column `sensor_height_m`); a
    /// leg's own height ([`Self::left_sensor_height_m`], [`Self::right_sensor_height_m`]) wins
    /// for that leg ([`Self::sensor_height_m_of`]).
    pub sensor_height_m: Option<f64>,
    /// The left sensor's height above the ankle, m (manifest column `left_sensor_height_m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub left_sensor_height_m: Option<f64>,
    /// The right sensor's height above the ankle, m (manifest column `right_sensor_height_m`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub right_sensor_height_m: Option<f64>,
    /// Where the walk happened (`None`: not said, treated as overground).
    #[serde(default)]
    pub setting: Option<crate::recording::Setting>,
    /// Column map of the left file (manifest `left_format` or `format`); `None`: the one given
    /// to the analysis, else detected.
    #[serde(default)]
    pub left_format: Option<FormatSpec>,
    /// Column map of the right file (manifest `right_format` or `format`).
    #[serde(default)]
    pub right_format: Option<FormatSpec>,
    /// Trial of the person (manifest `trial_id` or `trial`); `None` for a single recording pair.
    #[serde(default)]
    pub trial_id: Option<String>,
    /// Treadmill belt speed, m/s (manifest `belt_speed_mps`; only with a treadmill setting).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub belt_speed_mps: Option<f64>,
    /// The visit (session) of this recording pair, a free label (manifest `visit`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub visit: Option<String>,
    /// Files of a subject folder not taken for a leg, each named with why (ignored, ambiguous,
    /// a dangling symlink; [`super::pairing`]): a missing leg's error names them, and a leg
    /// that was found lists them among its reader's notes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unpaired: Vec<String>,
    /// Whether the legs share one clock, when the caller knows (a simulator: one; two arrays:
    /// as said, else two, [`super::arrays_subject`]); `None`: from the sources
    /// ([`Self::clocks`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clocks: Option<Clocks>,
}

impl SubjectInput {
    /// The heights this input gives: for both legs and per leg.
    pub fn sensor_heights(&self) -> SensorHeights {
        SensorHeights {
            both_m: self.sensor_height_m,
            left_m: self.left_sensor_height_m,
            right_m: self.right_sensor_height_m,
        }
    }

    /// Whether the legs share one clock: as stated ([`Self::clocks`] field), else one when both
    /// legs come from the same file (HuGaDB's files hold both shanks) or from the embedded demo
    /// (simulated on one clock), two when they come from two files; `None` when the legs were
    /// handed over without their sources and nothing was stated (not judged).
    pub fn clocks(&self) -> Option<Clocks> {
        if self.clocks.is_some() {
            return self.clocks;
        }
        match (self.left.as_ref()?, self.right.as_ref()?) {
            (l, r) if l == r => Some(Clocks::One),
            (Source::Embedded(_), Source::Embedded(_)) => Some(Clocks::One),
            _ => Some(Clocks::Two),
        }
    }

    /// The height of `side`'s sensor, m: its own, else the subject's; `None`: the run's
    /// (`--sensor-height-m`, parameters) or the assumed one.
    pub fn sensor_height_m_of(&self, side: Side) -> Option<f64> {
        self.sensor_heights().of(side)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clocks_from_the_sources() {
        let path = |p: &str| Some(Source::Path(PathBuf::from(p)));
        let input = |left, right| SubjectInput {
            left,
            right,
            ..SubjectInput::default()
        };
        // HuGaDB: one file holds both shanks.
        let one_file = input(path("walk.txt"), path("walk.txt"));
        assert_eq!(one_file.clocks(), Some(Clocks::One));
        // TRIPOD: one file per shank.
        let two_files = input(path("LS.csv"), path("RS.csv"));
        assert_eq!(two_files.clocks(), Some(Clocks::Two));
        // The embedded demo, simulated on one clock.
        let demo = |r: &str| Some(Source::Embedded(r.into()));
        let demo_input = input(demo("H01/left.csv"), demo("H01/right.csv"));
        assert_eq!(demo_input.clocks(), Some(Clocks::One));
        // Stated (a simulator), and not known.
        let stated = SubjectInput {
            clocks: Some(Clocks::One),
            ..two_files
        };
        assert_eq!(stated.clocks(), Some(Clocks::One));
        assert_eq!(input(None, None).clocks(), None);
    }

    #[test]
    fn clocks_are_read_by_name_and_a_bad_value_is_named() {
        assert_eq!(" One ".parse::<Clocks>().unwrap(), Clocks::One);
        assert_eq!("TWO".parse::<Clocks>().unwrap(), Clocks::Two);
        let e = "three".parse::<Clocks>().unwrap_err();
        assert_eq!(e.kind(), crate::error::ErrorKind::Param);
        let msg = e.to_string();
        assert!(msg.contains("clocks") && msg.contains("three"), "{msg}");
    }
}
