//! Stairs: a walking bout whose strides climb or descend (issue 52: "label stairs if you detect
//! them").
//!
//! **Per stride.** The lab pipeline integrates every stride between its two foot-flat
//! (zero-velocity) instants for its length (`gait::length`); the same integration gives the
//! ankle's vertical displacement, [`crate::gait::Stride::vertical_m`], ≈ 0 on level ground
//! (it is the integration's own error there) and two risers a stride on stairs: step over
//! step each foot lands two stairs up or down, 2 × 0.15–0.18 m ≈ 0.3–0.36 m (risers of
//! building codes; Riener, Rabuffetti & Frigo, Gait & Posture 15:32–44, 2002, 0.17 m in their
//! standard staircase). A stride is a **stair stride** when its ankle rises or falls by at
//! least `min_rise_m` = **0.15 m**, half the two risers, the bound the pipeline already uses
//! for "the ankle does not come back to the floor level" (`gait::length::MAX_VERTICAL_M`): a
//! stride that ends that far off its floor is not a level stride. Foot-mounted inertial
//! navigation tells floors apart the same way, by the height a ZUPT-integrated stride gains
//! (Foxlin 2005, IEEE CG&A 25(6):38).
//!
//! **Per bout.** A bout is **stairs** when at least `min_share` = **50 %** of the strides whose
//! rise was measured are stair strides going the same way (all up or all down: noise on level
//! ground scatters both ways) and at least `min_strides` = **2** strides are: a flight of
//! stairs is 8–25 s of gait, a whole bout in daily life; a bout mixing a long level walk with
//! a short flight stays walking. Its `stride_rise_m` is the median rise of its measured
//! strides (+ up, − down).
//!
//! **What it does** (docs/free-living.md "Stairs"): a stair bout counts in walking time, steps
//! and the bout counts, and is kept out of the gait-quality aggregates of daily life (the
//! median and P90 of cadence, speed, stride time, stride length, variability and asymmetry of
//! bouts over 30 s), which describe level walking.

use serde::{Deserialize, Serialize};

use crate::error::{LdhError, Result};
use crate::gait::Stride;

/// What kind of gait a bout is (bouts.csv's `kind`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum BoutKind {
    /// Level walking (default).
    #[default]
    Walking,
    /// Stairs, up or down (the sign of `stride_rise_m` says which).
    Stairs,
}

impl BoutKind {
    /// The name in bouts.csv: `walking` or `stairs`.
    pub fn as_str(self) -> &'static str {
        match self {
            BoutKind::Walking => "walking",
            BoutKind::Stairs => "stairs",
        }
    }
}

impl std::fmt::Display for BoutKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The stair rule's parameters (defaults in brackets; module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StairParams {
    /// A stride whose ankle rises or falls at least this much is a stair stride, m [0.15].
    pub min_rise_m: f64,
    /// A bout is stairs when this share of its measured strides are stair strides going the
    /// same way [0.5].
    pub min_share: f64,
    /// … and at least this many are [2].
    pub min_strides: usize,
}

impl Default for StairParams {
    fn default() -> Self {
        StairParams {
            min_rise_m: 0.15,
            min_share: 0.5,
            min_strides: 2,
        }
    }
}

impl StairParams {
    /// Check the parameters (called by `MonitorParams::check`).
    pub fn check(&self) -> Result<()> {
        if !(self.min_rise_m.is_finite() && self.min_rise_m > 0.0) {
            return Err(LdhError::param(
                "stairs.min_rise_m",
                self.min_rise_m,
                "must be finite and > 0",
            ));
        }
        if !(self.min_share > 0.0 && self.min_share <= 1.0) {
            return Err(LdhError::param(
                "stairs.min_share",
                self.min_share,
                "must lie in (0, 1]",
            ));
        }
        Ok(())
    }

    /// The stride rises (+1) or falls (−1) by at least `min_rise_m`; 0 otherwise or unmeasured.
    pub fn stair_direction(&self, s: &Stride) -> i8 {
        if !s.vertical_m.is_finite() {
            0
        } else if s.vertical_m >= self.min_rise_m {
            1
        } else if s.vertical_m <= -self.min_rise_m {
            -1
        } else {
            0
        }
    }

    /// The verdict on a bout from its strides (both legs').
    pub fn classify<'a>(&self, strides: impl IntoIterator<Item = &'a Stride>) -> StairVerdict {
        let (mut up, mut down) = (0usize, 0usize);
        let mut rises: Vec<f64> = Vec::new();
        for s in strides {
            if !s.vertical_m.is_finite() {
                continue;
            }
            rises.push(s.vertical_m);
            match self.stair_direction(s) {
                1 => up += 1,
                -1 => down += 1,
                _ => {}
            }
        }
        let same_way = up.max(down);
        let stairs = same_way >= self.min_strides.max(1)
            && same_way as f64 >= self.min_share * rises.len() as f64;
        StairVerdict {
            kind: if stairs {
                BoutKind::Stairs
            } else {
                BoutKind::Walking
            },
            stair_strides: up + down,
            measured: rises.len(),
            stride_rise_m: crate::stats::median(&mut rises, crate::stats::EvenMedian::Mean)
                .unwrap_or(f64::NAN),
        }
    }
}

/// The stair rule's verdict on one bout.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StairVerdict {
    /// Walking or stairs.
    pub kind: BoutKind,
    /// Strides rising or falling by at least `min_rise_m` (either way).
    pub stair_strides: usize,
    /// Strides whose rise was measured.
    pub measured: usize,
    /// Median rise of the measured strides, m (+ up); NaN when none was.
    pub stride_rise_m: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stride(v: f64) -> Stride {
        Stride {
            stride_index: 0,
            hs_time_s: 0.0,
            to_time_s: 0.6,
            next_hs_time_s: 1.0,
            stride_time_s: 1.0,
            stance_ratio: 0.6,
            double_support_ratio: f64::NAN,
            stride_length_m: 1.2,
            speed_mps: 1.2,
            wqk_deg: 30.0,
            pbi_deg: 20.0,
            bdk_deg: 5.0,
            heading_change_deg: 0.0,
            bout: 0,
            valid: true,
            reason: String::new(),
            findings: Vec::new(),
            vertical_m: v,
        }
    }

    #[test]
    fn a_climbing_bout_is_stairs_and_level_noise_is_not() {
        let p = StairParams::default();
        let up: Vec<Stride> = [0.31, 0.33, 0.02, 0.34, 0.30].map(stride).to_vec();
        let v = p.classify(&up);
        assert_eq!(v.kind, BoutKind::Stairs);
        assert_eq!((v.stair_strides, v.measured), (4, 5));
        assert!((v.stride_rise_m - 0.31).abs() < 1e-12);
        let down: Vec<Stride> = [-0.3, -0.32, f64::NAN, -0.29].map(stride).to_vec();
        let v = p.classify(&down);
        assert_eq!((v.kind, v.measured), (BoutKind::Stairs, 3));
        assert!(v.stride_rise_m < 0.0);
        // Level noise scattering both ways, even when large, is not a flight.
        let level: Vec<Stride> = [0.16, -0.17, 0.02, 0.16, -0.2, 0.01].map(stride).to_vec();
        assert_eq!(p.classify(&level).kind, BoutKind::Walking);
        // One stair stride is not a bout of stairs; no measured stride neither.
        assert_eq!(p.classify(&[stride(0.3)]).kind, BoutKind::Walking);
        assert_eq!(p.classify(&[stride(f64::NAN)]).kind, BoutKind::Walking);
        assert!(p.classify(&[stride(f64::NAN)]).stride_rise_m.is_nan());
    }

    #[test]
    fn parameters_are_checked() {
        assert!(StairParams::default().check().is_ok());
        let bad = StairParams {
            min_share: 0.0,
            ..StairParams::default()
        };
        assert!(bad.check().is_err());
        let bad = StairParams {
            min_rise_m: f64::NAN,
            ..StairParams::default()
        };
        assert!(bad.check().is_err());
    }
}
