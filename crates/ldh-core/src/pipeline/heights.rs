//! Per-side sensor heights (issue 39; docs/input.md "Sensor height"): each leg's stride length
//! uses its own sensor's height above the ankle. A source of heights — a manifest row, or the
//! options of a run (`--sensor-height-m`, `--left-sensor-height-m`, `--right-sensor-height-m`,
//! the same keywords in Python) — may give one height for both legs, one per leg, or both.
//!
//! Within one source the per-side value is used for its leg and the subject's for a leg
//! without one; a per-side value that *differs* from the subject's value of the same source is
//! refused (two different heights for one sensor: a typing mistake, not a choice). Across
//! sources the manifest row wins over the run's options, leg by leg.

use crate::error::{LdhError, Result};
use crate::recording::Side;

/// The highest sensor height accepted, m (as [`crate::gait::StrideParams::check`]): just below
/// the knee is ≈ 0.35 m.
pub const MAX_SENSOR_HEIGHT_M: f64 = 0.5;

/// The sensor heights one source gives, m: for both legs, for the left, for the right.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SensorHeights {
    /// One height for both legs (`sensor_height_m`).
    pub both_m: Option<f64>,
    /// The left sensor's (`left_sensor_height_m`).
    pub left_m: Option<f64>,
    /// The right sensor's (`right_sensor_height_m`).
    pub right_m: Option<f64>,
}

/// A per-side height that contradicts the same source's height for both legs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeightConflict {
    /// The leg.
    pub side: Side,
    /// Its own height, m.
    pub side_m: f64,
    /// The height given for both legs, m.
    pub both_m: f64,
}

impl HeightConflict {
    /// The per-side column or option name (`left_sensor_height_m`).
    pub fn column(&self) -> &'static str {
        match self.side {
            Side::Left => "left_sensor_height_m",
            Side::Right => "right_sensor_height_m",
        }
    }

    /// What to do, for messages.
    pub fn reason(&self) -> String {
        format!(
            "differs from sensor_height_m = {} given for both legs; give one height per leg \
             either way (leave sensor_height_m empty when the legs differ)",
            self.both_m
        )
    }
}

impl SensorHeights {
    /// The height of `side`'s sensor: its own, else the one for both legs.
    pub fn of(&self, side: Side) -> Option<f64> {
        match side {
            Side::Left => self.left_m,
            Side::Right => self.right_m,
        }
        .or(self.both_m)
    }

    /// The first leg whose own height differs from the one for both legs, if any.
    pub fn conflict(&self) -> Option<HeightConflict> {
        let both_m = self.both_m?;
        [(Side::Left, self.left_m), (Side::Right, self.right_m)]
            .into_iter()
            .find_map(|(side, h)| {
                h.filter(|h| *h != both_m).map(|side_m| HeightConflict {
                    side,
                    side_m,
                    both_m,
                })
            })
    }

    /// Check the heights of a run's options: each leg's in (0, [`MAX_SENSOR_HEIGHT_M`]] m, and
    /// no per-side height that contradicts the one for both legs ([`LdhError::Param`]). The
    /// height for both legs is checked with the stride parameters it is part of.
    pub fn check(&self) -> Result<Self> {
        for (name, h) in [
            ("left_sensor_height_m", self.left_m),
            ("right_sensor_height_m", self.right_m),
        ] {
            if let Some(h) = h {
                if !(h.is_finite() && h > 0.0 && h <= MAX_SENSOR_HEIGHT_M) {
                    return Err(LdhError::param(name, h, "must lie in (0, 0.5] m"));
                }
            }
        }
        if let Some(c) = self.conflict() {
            return Err(LdhError::param(c.column(), c.side_m, c.reason()));
        }
        Ok(*self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_leg_takes_its_own_height_else_the_one_for_both() {
        let h = SensorHeights {
            both_m: Some(0.1),
            left_m: None,
            right_m: Some(0.1),
        };
        assert_eq!(
            (h.of(Side::Left), h.of(Side::Right)),
            (Some(0.1), Some(0.1))
        );
        assert!(h.check().is_ok());
        let h = SensorHeights {
            both_m: None,
            left_m: Some(0.08),
            right_m: Some(0.14),
        };
        assert_eq!(
            (h.of(Side::Left), h.of(Side::Right)),
            (Some(0.08), Some(0.14))
        );
        let only_left = SensorHeights {
            left_m: Some(0.08),
            ..SensorHeights::default()
        };
        assert_eq!(only_left.of(Side::Right), None, "not given: assumed later");
    }

    #[test]
    fn a_side_that_contradicts_the_height_for_both_legs_is_refused() {
        let h = SensorHeights {
            both_m: Some(0.1),
            left_m: Some(0.1),
            right_m: Some(0.14),
        };
        let c = h.conflict().unwrap();
        assert_eq!((c.side, c.column()), (Side::Right, "right_sensor_height_m"));
        let e = h.check().unwrap_err().to_string();
        assert!(
            e.contains("right_sensor_height_m") && e.contains("0.14"),
            "{e}"
        );
        assert!(
            e.contains("sensor_height_m = 0.1 given for both legs"),
            "{e}"
        );
        let bad = SensorHeights {
            left_m: Some(0.0),
            ..SensorHeights::default()
        };
        assert!(bad
            .check()
            .unwrap_err()
            .to_string()
            .contains("left_sensor_height_m"));
        let high = SensorHeights {
            right_m: Some(0.6),
            ..SensorHeights::default()
        };
        assert!(high.check().is_err());
    }
}
