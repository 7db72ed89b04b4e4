//! The parameters of the agreement statistics and of the event matching, and their check.

use serde::{Deserialize, Serialize};

use super::AgreementError;

/// Parameters of [`super::agreement`], [`super::test_retest`], [`crate::events::match_events`] and
/// [`crate::events::estimate_clock_offset`] (unchecked; [`AgreementParams::check`] validates them once).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AgreementParams {
    /// Multiple of the SD of the differences that gives the limits of agreement (pingouin's
    /// `agreement=`). Default 1.96.
    pub loa_sd_multiplier: f64,
    /// Confidence level of the intervals of the bias, the limits of agreement and the ICCs.
    /// Default 0.95.
    pub confidence_level: f64,
    /// Largest |ldh − reference| time of two events that may be matched, s. Default 0.2.
    pub tolerance_s: f64,
    /// The clock-offset search looks at offsets in [−max, +max], s. Default 5.0.
    pub max_clock_offset_s: f64,
    /// Grid step of the clock-offset search, s (the estimate itself is refined to the median
    /// error, off the grid). Default 0.01 (one sample at 100 Hz).
    pub clock_offset_step_s: f64,
}

impl Default for AgreementParams {
    fn default() -> Self {
        AgreementParams {
            loa_sd_multiplier: 1.96,
            confidence_level: 0.95,
            tolerance_s: 0.2,
            max_clock_offset_s: 5.0,
            clock_offset_step_s: 0.01,
        }
    }
}

/// Most grid points the clock-offset search may evaluate (2·max/step + 1).
pub const MAX_OFFSET_GRID_POINTS: f64 = 200_001.0;

impl AgreementParams {
    /// Validate: multiplier > 0 and finite; confidence level in (0, 1); tolerance > 0 and
    /// finite; max clock offset ≥ 0 and finite; 0 < step ≤ tolerance, and at most
    /// [`MAX_OFFSET_GRID_POINTS`] grid points.
    pub fn check(&self) -> Result<ValidAgreementParams, AgreementError> {
        let bad = |name: &'static str, value: f64, reason: &'static str| {
            Err(AgreementError::InvalidParam {
                name,
                value: value.to_string(),
                reason,
            })
        };
        if !(self.loa_sd_multiplier > 0.0 && self.loa_sd_multiplier.is_finite()) {
            return bad(
                "loa_sd_multiplier",
                self.loa_sd_multiplier,
                "must be a finite number > 0",
            );
        }
        if !(self.confidence_level > 0.0 && self.confidence_level < 1.0) {
            return bad(
                "confidence_level",
                self.confidence_level,
                "must lie in (0, 1)",
            );
        }
        if !(self.tolerance_s > 0.0 && self.tolerance_s.is_finite()) {
            return bad(
                "tolerance_s",
                self.tolerance_s,
                "must be a finite number > 0",
            );
        }
        if !(self.max_clock_offset_s >= 0.0 && self.max_clock_offset_s.is_finite()) {
            return bad(
                "max_clock_offset_s",
                self.max_clock_offset_s,
                "must be a finite number ≥ 0",
            );
        }
        let step = self.clock_offset_step_s;
        if !(step > 0.0 && step <= self.tolerance_s) {
            return bad(
                "clock_offset_step_s",
                step,
                "must lie in (0, tolerance_s]: a coarser grid can step over every match",
            );
        }
        if 2.0 * self.max_clock_offset_s / step + 1.0 > MAX_OFFSET_GRID_POINTS {
            return bad(
                "clock_offset_step_s",
                step,
                "too fine for max_clock_offset_s: more than 200 001 grid points",
            );
        }
        Ok(ValidAgreementParams(self.clone()))
    }
}

/// Checked [`AgreementParams`].
#[derive(Debug, Clone, PartialEq)]
pub struct ValidAgreementParams(AgreementParams);

impl ValidAgreementParams {
    /// The parameters.
    pub fn params(&self) -> &AgreementParams {
        &self.0
    }
}

impl Default for ValidAgreementParams {
    fn default() -> Self {
        AgreementParams::default()
            .check()
            .expect("the defaults are valid")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_are_valid_and_round_trip_through_toml() {
        let p = AgreementParams::default();
        p.check().unwrap();
        let s = toml::to_string(&p).unwrap();
        assert!(s.contains("tolerance_s = 0.2"), "{s}");
        let back: AgreementParams = toml::from_str(&s).unwrap();
        assert_eq!(back, p);
        let partial: AgreementParams = toml::from_str("tolerance_s = 0.05").unwrap();
        assert_eq!(partial.tolerance_s, 0.05);
        assert_eq!(partial.loa_sd_multiplier, 1.96);
        assert!(toml::from_str::<AgreementParams>("tolerance = 0.05").is_err());
    }

    #[test]
    fn each_bad_value_is_named() {
        let cases: Vec<(AgreementParams, &str)> = vec![
            (
                AgreementParams {
                    loa_sd_multiplier: 0.0,
                    ..Default::default()
                },
                "loa_sd_multiplier",
            ),
            (
                AgreementParams {
                    confidence_level: 1.0,
                    ..Default::default()
                },
                "confidence_level",
            ),
            (
                AgreementParams {
                    confidence_level: f64::NAN,
                    ..Default::default()
                },
                "confidence_level",
            ),
            (
                AgreementParams {
                    tolerance_s: -0.1,
                    ..Default::default()
                },
                "tolerance_s",
            ),
            (
                AgreementParams {
                    tolerance_s: f64::INFINITY,
                    ..Default::default()
                },
                "tolerance_s",
            ),
            (
                AgreementParams {
                    max_clock_offset_s: -1.0,
                    ..Default::default()
                },
                "max_clock_offset_s",
            ),
            (
                AgreementParams {
                    clock_offset_step_s: 0.5,
                    ..Default::default()
                },
                "clock_offset_step_s",
            ),
            (
                AgreementParams {
                    clock_offset_step_s: 1e-6,
                    ..Default::default()
                },
                "clock_offset_step_s",
            ),
        ];
        for (p, name) in cases {
            match p.check() {
                Err(AgreementError::InvalidParam { name: n, .. }) => assert_eq!(n, name),
                other => panic!("{name}: {other:?}"),
            }
        }
    }
}
