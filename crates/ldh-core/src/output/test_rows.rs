//! A per-recording row for the tests of the tables built from rows (ML, cohort).

use super::RecordingRow;
use crate::domain::Parameter;

/// A recording row of `id` with only its speed (m/s) measured .
pub(crate) fn row(id: &str, group: &str, side: &str, speed: f64) -> RecordingRow {
    let mut r: RecordingRow = serde_json::from_value(serde_json::json!({
        "subject_id": id, "side": side, "model": "fusion", "group": group, "affected_side": "",
        "side_role": "", "source": "", "status": "ok", "error": "", "fs_hz": 100.0,
        "duration_s": 20.0, "strides_total": 10, "strides_valid": 8, "stride_time_s": null,
        "step_time_s": null, "step_frequency_steps_per_s": null, "stance_ratio": null,
        "swing_ratio": null, "stride_length_m": null, "speed_mps": null,
        "stride_length_cv": null, "stride_time_cv": null, "sta_per_s": null,
        "sta_per_stride": null, "sta_status": "", "wqk_deg": null, "pbi_deg": null,
        "bdk_deg": null, "mirrored": false, "axial_rotation_deg": 0.0,
        "outliers_replaced": 0, "clipped_samples": 0
    }))
    .unwrap();
    r.parameters[Parameter::Speed] = Some(speed);
    r
}
