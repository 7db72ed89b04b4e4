//! The column map of a per-step walkway export ([`WalkwayMap`], TOML): which column is the
//! foot, the heel strike, the toe off and each stride parameter, in which unit
//! (`docs/agreement.md`, "Walkway exports"; read by [`super::walkway`]).

use crate::domain::parameter::GAIT_CYCLE_FRACTION;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{Location, Result};
use crate::output::Parameter;

use super::error::boxed;
use super::ReferenceError;
use crate::output::results::STRIDE_PARAMETERS;

/// A unit of a walkway column, converted to ldh's unit of the key by a factor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum WalkwayUnit {
    /// Seconds.
    #[serde(rename = "s")]
    Seconds,
    /// Milliseconds (÷ 1000).
    #[serde(rename = "ms")]
    Milliseconds,
    /// Metres.
    #[serde(rename = "m")]
    Metres,
    /// Centimetres (÷ 100).
    #[serde(rename = "cm")]
    Centimetres,
    /// Millimetres (÷ 1000).
    #[serde(rename = "mm")]
    Millimetres,
    /// Metres per second.
    #[serde(rename = "m/s")]
    MetresPerSecond,
    /// Centimetres per second (÷ 100).
    #[serde(rename = "cm/s")]
    CentimetresPerSecond,
    /// A fraction, 0–1.
    #[serde(rename = "ratio")]
    Ratio,
    /// Per cent (÷ 100).
    #[serde(rename = "%")]
    Percent,
    /// Degrees.
    #[serde(rename = "deg")]
    Degrees,
}

impl WalkwayUnit {
    /// The unit as the map writes it.
    pub fn name(self) -> &'static str {
        use WalkwayUnit::*;
        match self {
            Seconds => "s",
            Milliseconds => "ms",
            Metres => "m",
            Centimetres => "cm",
            Millimetres => "mm",
            MetresPerSecond => "m/s",
            CentimetresPerSecond => "cm/s",
            Ratio => "ratio",
            Percent => "%",
            Degrees => "deg",
        }
    }

    /// (ldh's unit this converts to, the divisor: value in ldh's unit = value / divisor, a
    /// division so that e.g. 131.2 cm is the double nearest 1.312 m).
    pub(crate) fn to_ldh(self) -> (&'static str, f64) {
        use WalkwayUnit::*;
        match self {
            Seconds => ("s", 1.0),
            Milliseconds => ("s", 1e3),
            Metres => ("m", 1.0),
            Centimetres => ("m", 1e2),
            Millimetres => ("m", 1e3),
            MetresPerSecond => ("m/s", 1.0),
            CentimetresPerSecond => ("m/s", 1e2),
            Ratio => (GAIT_CYCLE_FRACTION, 1.0),
            Percent => (GAIT_CYCLE_FRACTION, 1e2),
            Degrees => ("deg", 1.0),
        }
    }
}

/// One mapped column: its name in the export's header and its unit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MappedColumn {
    /// The export's column (matched trimmed, without regard to case).
    pub column: String,
    /// Its unit.
    pub unit: WalkwayUnit,
}

/// The foot column and its values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SideColumn {
    /// The export's column.
    pub column: String,
    /// Values meaning the left foot (without regard to case), e.g. `["L", "Left"]`.
    pub left: Vec<String>,
    /// Values meaning the right foot.
    pub right: Vec<String>,
}

/// Which heel strike a footfall's stride values belong to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StrideAnchor {
    /// The stride starts at this footfall's heel strike.
    #[default]
    Start,
    /// The stride ends at this footfall's heel strike (GAITRite, Zeno): it starts at the same
    /// foot's previous heel strike.
    End,
}

/// The column map of a per-step walkway export (TOML; `data-fixtures/agreement/` has one for a
/// GAITRite-like export).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WalkwayMap {
    /// Short name.
    pub name: String,
    /// Where the format comes from.
    #[serde(default)]
    pub description: String,
    /// Field delimiter: `,` (default), `;` or a tab.
    #[serde(default = "comma")]
    pub delimiter: String,
    /// Lines above the header row (a title block).
    #[serde(default)]
    pub skip_rows_before_header: usize,
    /// The subject's column (else `--subject-id`).
    #[serde(default)]
    pub subject_column: Option<String>,
    /// The trial's column (else `--trial-id`, or none).
    #[serde(default)]
    pub trial_column: Option<String>,
    /// The foot.
    pub side: SideColumn,
    /// First contact (heel strike), a time.
    #[serde(default)]
    pub heel_strike: Option<MappedColumn>,
    /// Last contact (toe off), a time.
    #[serde(default)]
    pub toe_off: Option<MappedColumn>,
    /// Which heel strike the stride values belong to.
    #[serde(default)]
    pub stride_anchor: StrideAnchor,
    /// Stride parameters: a column of `strides.csv` (`stride_time_s`, `stride_length_m`,
    /// `speed_mps`, `stance_ratio`, …) → its export column.
    #[serde(default)]
    pub strides: std::collections::BTreeMap<String, MappedColumn>,
}

fn comma() -> String {
    ",".into()
}
impl WalkwayMap {
    /// Read and check a map. Errors name the file, and the TOML's line and column.
    pub fn from_toml_str(text: &str, file: &Path) -> Result<WalkwayMap> {
        let bad = |loc: Location, reason: String| boxed(ReferenceError::Map { loc, reason });
        let map: WalkwayMap = toml::from_str(text).map_err(|e| {
            let loc = match e.span() {
                Some(span) => {
                    let before = &text[..span.start.min(text.len())];
                    let line = before.matches('\n').count() as u64 + 1;
                    let col = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
                    Location::cell(file, line, col)
                }
                None => Location::file(file),
            };
            bad(loc, e.message().to_string())
        })?;
        map.check().map_err(|r| bad(Location::file(file), r))?;
        Ok(map)
    }

    /// Read a map file.
    pub fn from_toml_file(path: &Path) -> Result<WalkwayMap> {
        let text = crate::io::read_text_limited(path, crate::io::MAX_FORMAT_MB, "a column map")?;
        WalkwayMap::from_toml_str(&text, path)
    }

    pub(crate) fn delimiter_byte(&self) -> Option<u8> {
        match self.delimiter.as_str() {
            "," => Some(b','),
            ";" => Some(b';'),
            "\t" => Some(b'\t'),
            _ => None,
        }
    }

    /// Every stride key a per-stride parameter, every unit that parameter's (or a time).
    fn check(&self) -> std::result::Result<(), String> {
        if self.delimiter_byte().is_none() {
            return Err(format!(
                "delimiter '{}' is not ',', ';' or a tab",
                self.delimiter
            ));
        }
        for (what, c) in [
            ("heel_strike", &self.heel_strike),
            ("toe_off", &self.toe_off),
        ] {
            if let Some(c) = c {
                if c.unit.to_ldh().0 != "s" {
                    return Err(format!(
                        "{what}: unit '{:?}' is not a time (s or ms)",
                        c.unit
                    ));
                }
            }
        }
        if self.heel_strike.is_none() && self.toe_off.is_none() && self.strides.is_empty() {
            return Err("the map names no heel_strike, toe_off or strides column".into());
        }
        if !self.strides.is_empty() && self.heel_strike.is_none() {
            return Err("strides need the heel_strike column (each stride's time)".into());
        }
        for (key, c) in &self.strides {
            let p = Parameter::from_column(key)
                .ok()
                .filter(|p| STRIDE_PARAMETERS.contains(p))
                .ok_or_else(|| {
                    format!(
                        "strides.{key}: not a per-stride parameter; known: {}",
                        STRIDE_PARAMETERS.map(|p| p.column()).join(", ")
                    )
                })?;
            if c.unit.to_ldh().0 != p.unit() {
                return Err(format!(
                    "strides.{key}: unit '{}' does not convert to {}",
                    c.unit.name(),
                    p.unit()
                ));
            }
        }
        Ok(())
    }
}
