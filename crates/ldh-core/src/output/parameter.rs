//! The gait parameters of the per-recording table as a typed [`Parameter`] (paper Table 2 and
//! Table 3, plus PBI): its code, column, name and unit, and [`RecordingRow::value`] in place of
//! a lookup by column name. A column name given from outside (`ldh train --features`, a model
//! file's feature list) becomes a `Parameter` once, by [`Parameter::from_column`], with a typed
//! [`UnknownParameter`] error.

use super::RecordingRow;
use crate::error::LdhError;

/// A gait parameter of the cohort tables, the classifiers and the reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Parameter {
    /// SF, steps/s.
    StepFrequency,
    /// SL, m.
    StrideLength,
    /// SS, m/s.
    Speed,
    /// STT, s.
    StepTime,
    /// ST, s.
    StrideTime,
    /// STP, ratio.
    StanceRatio,
    /// SWP, ratio.
    SwingRatio,
    /// SV, ratio.
    StrideLengthCv,
    /// STV, ratio.
    StrideTimeCv,
    /// STA, 1/s (largest Lyapunov exponent).
    Sta,
    /// WQK, deg.
    Wqk,
    /// PBI, deg (ldh's addition).
    Pbi,
    /// BDK, deg.
    Bdk,
}

/// A column name that is not a parameter of [`Parameter::ALL`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown feature '{0}'; known: {known}", known = Parameter::columns().join(", "))]
pub struct UnknownParameter(pub String);

impl From<UnknownParameter> for LdhError {
    fn from(e: UnknownParameter) -> Self {
        LdhError::param(
            "features",
            &e.0,
            format!(
                "unknown feature; known: {}",
                Parameter::columns().join(", ")
            ),
        )
    }
}

impl Parameter {
    /// Every parameter, in the order of the paper's Table 3 (plus PBI).
    pub const ALL: [Parameter; 13] = [
        Parameter::StepFrequency,
        Parameter::StrideLength,
        Parameter::Speed,
        Parameter::StepTime,
        Parameter::StrideTime,
        Parameter::StanceRatio,
        Parameter::SwingRatio,
        Parameter::StrideLengthCv,
        Parameter::StrideTimeCv,
        Parameter::Sta,
        Parameter::Wqk,
        Parameter::Pbi,
        Parameter::Bdk,
    ];

    /// `(code, column, name, unit)`.
    const fn info(self) -> (&'static str, &'static str, &'static str, &'static str) {
        use Parameter::*;
        match self {
            StepFrequency => (
                "SF",
                "step_frequency_steps_per_s",
                "step frequency",
                "steps/s",
            ),
            StrideLength => ("SL", "stride_length_m", "stride length", "m"),
            Speed => ("SS", "speed_mps", "stride speed", "m/s"),
            StepTime => ("STT", "step_time_s", "step time", "s"),
            StrideTime => ("ST", "stride_time_s", "stride time", "s"),
            StanceRatio => ("STP", "stance_ratio", "stance phase", "ratio"),
            SwingRatio => ("SWP", "swing_ratio", "swing phase", "ratio"),
            StrideLengthCv => (
                "SV",
                "stride_length_cv",
                "stride length variability",
                "ratio",
            ),
            StrideTimeCv => ("STV", "stride_time_cv", "stride time variability", "ratio"),
            Sta => ("STA", "sta_per_s", "gait stability (Lyapunov)", "1/s"),
            Wqk => ("WQK", "wqk_deg", "max shank flexion", "deg"),
            Pbi => ("PBI", "pbi_deg", "peak backward inclination", "deg"),
            Bdk => ("BDK", "bdk_deg", "swing roll excursion", "deg"),
        }
    }

    /// Code in the paper's Table 2 (`SF`, `SL` …; PBI is ldh's addition).
    pub const fn code(self) -> &'static str {
        self.info().0
    }

    /// Column of the per-recording table (units in the name).
    pub const fn column(self) -> &'static str {
        self.info().1
    }

    /// Name for reports.
    pub const fn name(self) -> &'static str {
        self.info().2
    }

    /// Unit.
    pub const fn unit(self) -> &'static str {
        self.info().3
    }

    /// The columns of [`Parameter::ALL`].
    pub fn columns() -> Vec<&'static str> {
        Parameter::ALL.iter().map(|p| p.column()).collect()
    }

    /// The parameter whose column is `column`.
    pub fn from_column(column: &str) -> Result<Parameter, UnknownParameter> {
        Parameter::ALL
            .into_iter()
            .find(|p| p.column() == column)
            .ok_or_else(|| UnknownParameter(column.to_string()))
    }
}

impl std::str::FromStr for Parameter {
    type Err = UnknownParameter;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Parameter::from_column(s)
    }
}

impl RecordingRow {
    fn slot(&mut self, p: Parameter) -> &mut Option<f64> {
        use Parameter::*;
        match p {
            StepFrequency => &mut self.step_frequency_steps_per_s,
            StrideLength => &mut self.stride_length_m,
            Speed => &mut self.speed_mps,
            StepTime => &mut self.step_time_s,
            StrideTime => &mut self.stride_time_s,
            StanceRatio => &mut self.stance_ratio,
            SwingRatio => &mut self.swing_ratio,
            StrideLengthCv => &mut self.stride_length_cv,
            StrideTimeCv => &mut self.stride_time_cv,
            Sta => &mut self.sta_per_s,
            Wqk => &mut self.wqk_deg,
            Pbi => &mut self.pbi_deg,
            Bdk => &mut self.bdk_deg,
        }
    }

    /// The value of `p`, when it is there and finite.
    pub fn value(&self, p: Parameter) -> Option<f64> {
        use Parameter::*;
        match p {
            StepFrequency => self.step_frequency_steps_per_s,
            StrideLength => self.stride_length_m,
            Speed => self.speed_mps,
            StepTime => self.step_time_s,
            StrideTime => self.stride_time_s,
            StanceRatio => self.stance_ratio,
            SwingRatio => self.swing_ratio,
            StrideLengthCv => self.stride_length_cv,
            StrideTimeCv => self.stride_time_cv,
            Sta => self.sta_per_s,
            Wqk => self.wqk_deg,
            Pbi => self.pbi_deg,
            Bdk => self.bdk_deg,
        }
        .filter(|v| v.is_finite())
    }

    /// Set the value of `p` (`None`: empty).
    pub fn set_value(&mut self, p: Parameter, v: Option<f64>) {
        *self.slot(p) = v;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_are_fields_of_the_row_and_read_back() {
        let mut row: RecordingRow = serde_json::from_str(
            r#"{"subject_id":"S1","side":"left","model":"fusion","group":"","affected_side":"",
            "side_role":"","source":"","status":"ok","error":"","fs_hz":null,"duration_s":null,
            "strides_total":null,"strides_valid":null,"stride_time_s":null,"step_time_s":null,
            "step_frequency_steps_per_s":null,"stance_ratio":null,"swing_ratio":null,
            "stride_length_m":null,"speed_mps":null,"stride_length_cv":null,"stride_time_cv":null,
            "sta_per_s":null,"sta_per_stride":null,"sta_status":"","wqk_deg":null,"pbi_deg":null,
            "bdk_deg":null,"mirrored":null,"axial_rotation_deg":null,"outliers_replaced":null,
            "clipped_samples":null}"#,
        )
        .unwrap();
        for (k, p) in Parameter::ALL.into_iter().enumerate() {
            assert_eq!(Parameter::from_column(p.column()), Ok(p));
            assert_eq!(row.value(p), None);
            row.set_value(p, Some(k as f64 + 0.5));
            let json = serde_json::to_value(&row).unwrap();
            assert_eq!(json[p.column()], serde_json::json!(k as f64 + 0.5), "{p:?}");
            assert_eq!(row.value(p), Some(k as f64 + 0.5));
        }
        row.set_value(Parameter::Sta, Some(f64::NAN));
        assert_eq!(row.value(Parameter::Sta), None, "not finite: no value");
        let codes: std::collections::BTreeSet<&str> =
            Parameter::ALL.iter().map(|p| p.code()).collect();
        assert_eq!(codes.len(), Parameter::ALL.len());
    }

    #[test]
    fn an_unknown_column_is_a_typed_error_with_the_known_ones() {
        let e = Parameter::from_column("height_cm").unwrap_err();
        assert_eq!(e, UnknownParameter("height_cm".into()));
        let msg = LdhError::from(e).to_string();
        assert!(
            msg.contains("height_cm") && msg.contains("unknown feature"),
            "{msg}"
        );
        assert!(msg.contains("stride_length_m, speed_mps"), "{msg}");
    }
}
