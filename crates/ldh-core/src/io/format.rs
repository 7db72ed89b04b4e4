//! Vendor formats: a small TOML column map that says which columns hold time, acceleration and
//! angular velocity, in which units, and how the sensor's axes map onto ldh's axes
//! (x along the shank, y anterior-posterior, z medio-lateral; paper §2.2, SPEC §2).
//!
//! The maps shipped with ldh live in `data-fixtures/formats/*.toml` and are compiled in
//! ([`FormatSpec::builtin`]); a user may pass their own file ([`FormatSpec::from_toml_file`]).
//!
//! ```toml
//! name = "xsens-mtmanager"
//! delimiter = "\t"            # "auto" (default), ",", ";" or "\t"
//! decimal = "."               # "." (default) or "," (European exports with ";" or tab)
//! comment_prefixes = ["//"]   # lines starting with these are skipped
//! skip_rows_after_header = 0  # e.g. 1 for a units row under the column names
//! [time]
//! column = "PacketCounter"    # omit for files without time
//! unit = "counter"            # "s" | "ms" | "us" | "counter" | "iso8601" | "none"
//! rate_hz = 100.0             # required for "counter" and "none"
//! counter_wrap = 65536        # counters that wrap around
//! [acc]
//! columns = ["Acc_X", "Acc_Y", "Acc_Z"]
//! unit = "m/s2"               # "g" | "m/s2"
//! scale = 1.0                 # raw value × scale = value in `unit` (for integer counts)
//! range = 156.9               # full scale in `unit`, for saturation detection (optional)
//! [gyro]
//! columns = ["Gyr_X", "Gyr_Y", "Gyr_Z"]
//! unit = "rad/s"              # "deg/s" | "rad/s"
//! [axes]
//! map = ["+x", "+y", "+z"]    # ldh x, y, z = these signed input axes (a rotation, det = +1)
//! ```

use serde::{Deserialize, Serialize};
use std::path::Path;

use crate::error::{LdhError, Result};

mod axes;
mod fields;

pub use axes::AxisMap;
pub use fields::{
    AccUnit, AxesSpec, ChannelSpec, ColumnRef, Decimal, Delimiter, GyroUnit, SensorSelect,
    TimeSpec, TimeUnit,
};

/// A vendor format: the column map of one kind of CSV export.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FormatSpec {
    /// Short name (e.g. `ldh`, `xsens-mtmanager`).
    pub name: String,
    /// One line on where the format comes from.
    #[serde(default)]
    pub description: String,
    /// Field delimiter; default auto-detected.
    #[serde(default)]
    pub delimiter: Delimiter,
    /// Decimal separator; default `.`.
    #[serde(default)]
    pub decimal: Decimal,
    /// Lines starting with any of these (after leading white space) are skipped.
    #[serde(default)]
    pub comment_prefixes: Vec<String>,
    /// Rows under the header row to skip (e.g. a row of units).
    #[serde(default)]
    pub skip_rows_after_header: usize,
    /// Which sensor to read in a file holding several (a column prefix or a block); default:
    /// the file holds one sensor.
    #[serde(default, skip_serializing_if = "SensorSelect::is_default")]
    pub sensor: SensorSelect,
    /// Time column.
    #[serde(default)]
    pub time: TimeSpec,
    /// Accelerometer columns.
    pub acc: ChannelSpec<AccUnit>,
    /// Gyroscope columns.
    pub gyro: ChannelSpec<GyroUnit>,
    /// Axis map (default identity).
    #[serde(default)]
    pub axes: AxesSpec,
}

/// Names of the formats compiled into ldh.
pub const BUILTIN_FORMATS: [&str; 6] = [
    "ldh",
    "xsens-mtmanager",
    "shimmer-consensys",
    "raw-counts",
    "hugadb-right-shank",
    "hugadb-left-shank",
];

/// The built-in formats tried, in this order, when no format is given. The HuGaDB maps are
/// not among them: both read the same files (one per leg), so the leg must be chosen.
pub const DETECTED_FORMATS: [&str; 4] =
    ["ldh", "xsens-mtmanager", "shimmer-consensys", "raw-counts"];

const BUILTIN_TOML: [(&str, &str); 6] = [
    (
        "ldh",
        include_str!("../../../../data-fixtures/formats/ldh.toml"),
    ),
    (
        "xsens-mtmanager",
        include_str!("../../../../data-fixtures/formats/xsens-mtmanager.toml"),
    ),
    (
        "shimmer-consensys",
        include_str!("../../../../data-fixtures/formats/shimmer-consensys.toml"),
    ),
    (
        "raw-counts",
        include_str!("../../../../data-fixtures/formats/raw-counts.toml"),
    ),
    (
        "hugadb-right-shank",
        include_str!("../../../../data-fixtures/formats/hugadb-right-shank.toml"),
    ),
    (
        "hugadb-left-shank",
        include_str!("../../../../data-fixtures/formats/hugadb-left-shank.toml"),
    ),
];

impl Default for FormatSpec {
    /// The ldh default format: `time_s, acc_x, acc_y, acc_z, gyro_x, gyro_y, gyro_z` in s, g and
    /// deg/s, delimiter auto-detected.
    fn default() -> Self {
        FormatSpec::builtin("ldh").expect("the built-in ldh format parses")
    }
}

impl FormatSpec {
    /// Parse a format from TOML text; `origin` names it in error messages.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Self> {
        let spec: FormatSpec = toml::from_str(text).map_err(|e| LdhError::Format {
            name: origin.to_string(),
            reason: e.to_string(),
        })?;
        spec.validate()?;
        Ok(spec)
    }

    /// Read a format from a TOML file (a regular file of at most
    /// [`super::MAX_FORMAT_MB`] MB: [`super::read_text_limited`]).
    pub fn from_toml_file(path: impl AsRef<Path>) -> Result<Self> {
        let path = path.as_ref();
        let text =
            super::read_text_limited(path, super::MAX_FORMAT_MB, "a column map (format TOML)")?;
        FormatSpec::from_toml_str(&text, &path.display().to_string())
    }

    /// A format named on a command line or in an API call: a path to a TOML column map (a name
    /// ending in `.toml`, or an existing file), else a built-in format's name.
    pub fn resolve(name: &str) -> Result<Self> {
        let p = Path::new(name);
        if p.extension().is_some_and(|e| e == "toml") || p.is_file() {
            FormatSpec::from_toml_file(p)
        } else {
            FormatSpec::builtin(name)
        }
    }

    /// The shipped TOML text of a built-in format, comments included (what `ldh formats NAME`
    /// prints), or `None` for an unknown name.
    pub fn builtin_text(name: &str) -> Option<&'static str> {
        BUILTIN_TOML
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, t)| *t)
    }

    /// One of the formats shipped with ldh ([`BUILTIN_FORMATS`]).
    pub fn builtin(name: &str) -> Result<Self> {
        let (_, text) = BUILTIN_TOML
            .iter()
            .find(|(n, _)| *n == name)
            .ok_or_else(|| LdhError::Format {
                name: name.to_string(),
                reason: format!(
                    "no such built-in format; known: {}",
                    BUILTIN_FORMATS.join(", ")
                ),
            })?;
        FormatSpec::from_toml_str(text, name)
    }

    /// All built-in formats.
    pub fn builtins() -> Vec<FormatSpec> {
        BUILTIN_FORMATS
            .iter()
            .map(|n| FormatSpec::builtin(n).expect("built-in formats parse"))
            .collect()
    }

    /// The built-in formats tried when none is given ([`DETECTED_FORMATS`]), parsed once per
    /// process (parsing their TOML was ≈ 6 % of reading a 30 s leg, issue 17).
    pub fn detected() -> &'static [FormatSpec] {
        static DETECTED: std::sync::OnceLock<Vec<FormatSpec>> = std::sync::OnceLock::new();
        DETECTED.get_or_init(|| {
            DETECTED_FORMATS
                .iter()
                .map(|n| FormatSpec::builtin(n).expect("built-in formats parse"))
                .collect()
        })
    }

    /// Serialize to TOML.
    pub fn to_toml(&self) -> String {
        toml::to_string_pretty(self).unwrap_or_default()
    }

    /// This format with the stated sampling rate replaced.
    pub fn with_rate_hz(mut self, rate_hz: f64) -> Self {
        self.time.rate_hz = Some(rate_hz);
        self
    }

    /// This format with another axis map.
    pub fn with_axes(mut self, map: [&str; 3]) -> Self {
        self.axes.map = map.map(|s| s.to_string());
        self
    }

    fn err(&self, reason: impl Into<String>) -> LdhError {
        LdhError::Format {
            name: self.name.clone(),
            reason: reason.into(),
        }
    }

    /// Check the description is complete and consistent.
    pub fn validate(&self) -> Result<()> {
        if self.decimal == Decimal::Comma && self.delimiter == Delimiter::Comma {
            return Err(self.err("decimal = \",\" cannot be used with delimiter = \",\""));
        }
        match self.time.unit {
            TimeUnit::Counter | TimeUnit::None => {
                match self.time.rate_hz {
                    Some(r) if r.is_finite() && r > 0.0 => {}
                    _ => return Err(self.err(
                        "time.rate_hz (> 0) is required when time.unit is \"counter\" or \"none\"",
                    )),
                }
            }
            _ => {
                if self.time.column.is_none() {
                    return Err(self.err(
                        "time.column is missing; set time.unit = \"none\" and time.rate_hz for files without time",
                    ));
                }
            }
        }
        if self.time.unit == TimeUnit::None && self.time.column.is_some() {
            return Err(self.err("time.unit = \"none\" but time.column is set"));
        }
        if let Some(r) = self.time.rate_hz {
            if !(r.is_finite() && r > 0.0) {
                return Err(self.err(format!("time.rate_hz = {r} must be > 0")));
            }
        }
        for (what, scale, range) in [
            ("acc", self.acc.scale, self.acc.range),
            ("gyro", self.gyro.scale, self.gyro.range),
        ] {
            if !(scale.is_finite() && scale != 0.0) {
                return Err(self.err(format!(
                    "{what}.scale = {scale} must be finite and non-zero"
                )));
            }
            if let Some(r) = range {
                if !(r.is_finite() && r > 0.0) {
                    return Err(self.err(format!("{what}.range = {r} must be > 0")));
                }
            }
        }
        self.axis_map()?;
        self.check_columns()?;
        Ok(())
    }

    fn check_columns(&self) -> Result<()> {
        if self.sensor.block == Some(0) {
            return Err(self.err("sensor.block counts from 1"));
        }
        let refs = self
            .time
            .column
            .iter()
            .map(|c| ("time.column", c))
            .chain(self.acc.columns.iter().map(|c| ("acc.columns", c)))
            .chain(self.gyro.columns.iter().map(|c| ("gyro.columns", c)));
        for (what, c) in refs {
            match c {
                ColumnRef::Index(0) => {
                    return Err(self.err(format!("{what}: column numbers count from 1, not 0")))
                }
                ColumnRef::AnyOf(v) if v.is_empty() || v.iter().any(|n| n.trim().is_empty()) => {
                    return Err(self.err(format!(
                        "{what}: a list of alternative names must hold non-empty names"
                    )))
                }
                ColumnRef::Name(n) if n.trim().is_empty() => {
                    return Err(self.err(format!("{what}: empty column name")))
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// The columns the format reads, as written in messages, in the order time (if any), acc
    /// x y z, gyro x y z (`acc_x`, `RS_acc_x|acc_rs_x`, `#7`).
    pub fn required_columns(&self) -> Vec<String> {
        let p = self.sensor.prefix.as_str();
        self.time
            .column
            .iter()
            .chain(self.acc.columns.iter())
            .chain(self.gyro.columns.iter())
            .map(|c| c.describe(p))
            .collect()
    }

    /// The header a writer gives a file in this format: the prefix and the first name of each
    /// column (time first, if any). Errors for a map that selects columns by number.
    pub fn column_names_for_writing(&self) -> Result<Vec<String>> {
        let p = self.sensor.prefix.as_str();
        self.time
            .column
            .iter()
            .chain(self.acc.columns.iter())
            .chain(self.gyro.columns.iter())
            .map(|c| match c.names().first() {
                Some(n) => Ok(format!("{p}{n}")),
                None => Err(self.err(format!(
                    "column {} is given by number: a file cannot be written in this format",
                    c.describe(p)
                ))),
            })
            .collect()
    }
}
