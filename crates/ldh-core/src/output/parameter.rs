//! The per-recording row as a view of the [`Parameter`]s ([`crate::domain::parameter`]):
//! [`RecordingRow::value`] and [`RecordingRow::set_value`] in place of a lookup by column name.

use super::RecordingRow;
pub use crate::domain::{Parameter, UnknownParameter};
#[cfg(test)]
use crate::error::LdhError;

impl RecordingRow {
    /// The value of `p`, when it is there and finite.
    pub fn value(&self, p: Parameter) -> Option<f64> {
        self.parameters[p].filter(|v| v.is_finite())
    }

    /// Set the value of `p` (`None`: empty).
    pub fn set_value(&mut self, p: Parameter, v: Option<f64>) {
        self.parameters[p] = v;
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
