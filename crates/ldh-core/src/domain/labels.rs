//! The labels every stage shares (issue 48): which leg ([`Side`]) or legs ([`Legs`]), where the walk happened
//! ([`Setting`]), a subject's group ([`Group`]) and affected side ([`AffectedSide`]), and the
//! kind of a gait event ([`EventKind`]). Each is defined once, here; the modules that used to
//! hold them (`recording`, `pipeline`, `output`) re-export them.

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};

/// Which leg a sensor is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// Left shank.
    Left,
    /// Right shank.
    Right,
}

impl Side {
    /// `"left"` or `"right"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Side::Left => "left",
            Side::Right => "right",
        }
    }
    /// The other leg.
    pub fn other(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }
}

impl std::fmt::Display for Side {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for Side {
    type Err = LdhError;
    fn from_str(s: &str) -> Result<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "left" | "l" => Ok(Side::Left),
            "right" | "r" => Ok(Side::Right),
            other => Err(LdhError::param("side", other, "expected 'left' or 'right'")),
        }
    }
}

/// Which legs a value is of: one leg, or both pooled (a bout both sensors saw, the pooled row
/// of an event agreement). Written `left`, `right` or `both`.
#[derive(
    Debug, Clone, Copy, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize,
)]
#[serde(rename_all = "lowercase")]
pub enum Legs {
    /// The left leg alone.
    Left,
    /// The right leg alone.
    Right,
    /// Both legs (the default).
    #[default]
    Both,
}

impl Legs {
    /// `"left"`, `"right"` or `"both"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Legs::Left => "left",
            Legs::Right => "right",
            Legs::Both => "both",
        }
    }
}

impl From<Side> for Legs {
    fn from(s: Side) -> Self {
        match s {
            Side::Left => Legs::Left,
            Side::Right => Legs::Right,
        }
    }
}

impl std::fmt::Display for Legs {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Where the walk happened. It decides whether a stride can be a turn: on a treadmill no stride
/// is (yaw drift is not a turn). Default overground.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Setting {
    /// Walking over the ground: turns happen and are detected.
    #[default]
    Overground,
    /// Walking on a treadmill: no turns.
    Treadmill,
}

impl Setting {
    /// `"overground"` or `"treadmill"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Setting::Overground => "overground",
            Setting::Treadmill => "treadmill",
        }
    }
}

impl std::fmt::Display for Setting {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for Setting {
    type Err = LdhError;
    fn from_str(s: &str) -> Result<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "overground" => Ok(Setting::Overground),
            "treadmill" => Ok(Setting::Treadmill),
            other => Err(LdhError::param(
                "setting",
                other,
                "expected 'overground' or 'treadmill'",
            )),
        }
    }
}

/// A subject's group (one type for the manifest, the tables, the cohort statistics and the
/// simulator): the reference group, the LDH group (whose
/// affected side is compared with the unaffected one), or any other label (carried into the
/// tables, not compared). As a manifest names it: the reference group, the LDH group (whose
/// affected side is compared with the unaffected one), or any other label (carried into the
/// tables, not compared).
#[derive(Debug, Clone, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(from = "String", into = "String")]
pub enum Group {
    /// `healthy` (also written `h` or `control`): the reference group.
    Healthy,
    /// `ldh`: lumbar disc herniation, one affected side.
    Ldh,
    /// Any other label, as written (e.g. `stroke`).
    Other(String),
}

impl Group {
    /// `healthy`, `ldh` or the label.
    pub fn as_str(&self) -> &str {
        match self {
            Group::Healthy => "healthy",
            Group::Ldh => "ldh",
            Group::Other(s) => s,
        }
    }
}

impl From<String> for Group {
    fn from(s: String) -> Self {
        match s.trim().to_ascii_lowercase().as_str() {
            "healthy" | "h" | "control" => Group::Healthy,
            "ldh" => Group::Ldh,
            _ => Group::Other(s.trim().to_string()),
        }
    }
}

impl From<Group> for String {
    fn from(g: Group) -> String {
        g.as_str().to_string()
    }
}

impl std::fmt::Display for Group {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The affected side a subject's manifest gives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AffectedSide {
    /// `left`.
    Left,
    /// `right`.
    Right,
    /// `none`: the manifest gives a group and no affected side (a healthy subject).
    Neither,
}

impl AffectedSide {
    /// The side, when one is affected.
    pub fn side(self) -> Option<Side> {
        match self {
            AffectedSide::Left => Some(Side::Left),
            AffectedSide::Right => Some(Side::Right),
            AffectedSide::Neither => None,
        }
    }
}

impl From<Side> for AffectedSide {
    fn from(s: Side) -> Self {
        match s {
            Side::Left => AffectedSide::Left,
            Side::Right => AffectedSide::Right,
        }
    }
}

/// Kind of a gait event.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum EventKind {
    /// Heel strike.
    #[serde(rename = "HS")]
    HeelStrike,
    /// Toe off.
    #[serde(rename = "TO")]
    ToeOff,
}

impl EventKind {
    /// `"HS"` or `"TO"`, as `events.csv` and reference files write it.
    pub fn as_str(self) -> &'static str {
        match self {
            EventKind::HeelStrike => "HS",
            EventKind::ToeOff => "TO",
        }
    }
}

impl std::fmt::Display for EventKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for EventKind {
    type Err = LdhError;
    /// `HS` or `TO` (any case, surrounding spaces ignored).
    fn from_str(s: &str) -> Result<Self> {
        match s.trim().to_ascii_uppercase().as_str() {
            "HS" => Ok(EventKind::HeelStrike),
            "TO" => Ok(EventKind::ToeOff),
            other => Err(LdhError::param(
                "event",
                other,
                "expected 'HS' (heel strike) or 'TO' (toe off)",
            )),
        }
    }
}
