//! Ground truth of a simulated subject: the `truth.json` file ([`SubjectTruth`]) and reading it
//! back ([`read_truth`]).

use serde::{Deserialize, Serialize};
use std::path::Path;

use super::{family_b, Group, LegTruth, SimSubject, SubjectParams};
use crate::error::{LdhError, Result};
use crate::recording::Side;

/// Version tag of the ground-truth JSON.
pub const TRUTH_SCHEMA: &str = "ldh-sim-truth/1";
/// The ground-truth file of one subject (`truth.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubjectTruth {
    /// [`TRUTH_SCHEMA`].
    pub schema: String,
    /// Subject.
    pub subject_id: String,
    /// Group.
    pub group: Group,
    /// Affected side (LDH).
    pub affected_side: Option<Side>,
    /// Sampling rate, Hz.
    pub fs_hz: f64,
    /// The parameters the subject was simulated with.
    pub params: SubjectParams,
    /// Left leg truth.
    pub left: LegTruth,
    /// Right leg truth.
    pub right: LegTruth,
    /// Family B subjects: the full parameters (`params` is then a family A-shaped summary).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub family_b: Option<family_b::SubjectParamsB>,
}

fn round_to(v: &mut [f64], decimals: i32) {
    let k = 10f64.powi(decimals);
    for x in v {
        *x = (*x * k).round() / k;
    }
}

impl SimSubject {
    /// The truth file's content (angles rounded to 0.001°).
    pub fn truth(&self) -> SubjectTruth {
        let mut left = self.left.truth.clone();
        let mut right = self.right.truth.clone();
        for t in [&mut left, &mut right] {
            round_to(&mut t.pitch_deg, 3);
            round_to(&mut t.roll_deg, 3);
            round_to(&mut t.yaw_deg, 3);
        }
        SubjectTruth {
            schema: TRUTH_SCHEMA.to_string(),
            subject_id: self.params.subject_id.clone(),
            group: self.params.group,
            affected_side: self.params.affected_side,
            fs_hz: self.params.fs_hz,
            params: self.params.clone(),
            left,
            right,
            family_b: self.family_b.clone(),
        }
    }
}

/// Read a `truth.json`.
pub fn read_truth(path: impl AsRef<Path>) -> Result<SubjectTruth> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| LdhError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|e| LdhError::Format {
        name: path.display().to_string(),
        reason: format!("not a ground-truth file: {e}"),
    })
}
