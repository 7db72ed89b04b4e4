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

    /// The height of `side`'s sensor, m: its own, else the subject's; `None`: the run's
    /// (`--sensor-height-m`, parameters) or the assumed one.
    pub fn sensor_height_m_of(&self, side: Side) -> Option<f64> {
        self.sensor_heights().of(side)
    }
}
