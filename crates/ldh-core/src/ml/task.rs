//! The classification task (three classes or binary) and its class names: what both the
//! dataset builder and the per-recording candidates read, below both.

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};

/// Classification task.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Task {
    /// LDHH (0) / LDHE (1) / H (2).
    #[cfg_attr(feature = "clap", value(alias = "3"))]
    ThreeClass,
    /// H (0) / LDHE (1).
    #[cfg_attr(feature = "clap", value(alias = "2"))]
    Binary,
}

impl std::str::FromStr for Task {
    type Err = LdhError;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "three-class" | "3" => Ok(Task::ThreeClass),
            "binary" | "2" => Ok(Task::Binary),
            o => Err(LdhError::param(
                "task",
                o,
                "expected 'three-class' or 'binary'",
            )),
        }
    }
}

impl Task {
    /// Class names in label order.
    pub fn class_names(self) -> Vec<String> {
        match self {
            Task::ThreeClass => vec!["LDHH".into(), "LDHE".into(), "H".into()],
            Task::Binary => vec!["H".into(), "LDHE".into()],
        }
    }
    /// `three-class` or `binary`.
    pub fn as_str(self) -> &'static str {
        match self {
            Task::ThreeClass => "three-class",
            Task::Binary => "binary",
        }
    }
}
