//! How a per-recording row is written ([`RecordingRow`], recordings.csv and recordings.json):
//! its own columns by name and, between them, every parameter's by one loop
//! ([`crate::domain::block::serialize_parameters`]). Hand-written because the parameters are
//! one [`crate::domain::ParameterBlock`] and the CSV writer refuses the map a derived
//! `#[serde(flatten)]` would write; the column order is the one the tables always had
//! (docs/columns.md), checked by the column dictionary's tests and the pinned outputs.

use serde::ser::{Serialize, SerializeStruct, Serializer};

use super::labels::{empty_is_none, Cell};
use super::RecordingRow;
use crate::domain::{block, Parameter};

/// An optional label written as its cell text ("" for `None`), as [`empty_is_none`] writes it.
struct Text<'a, T>(&'a Option<T>);

impl<T: Cell> Serialize for Text<'_, T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        empty_is_none::serialize(self.0, s)
    }
}

/// The row's own columns before the parameters.
const HEAD: usize = 15;
/// The row's own columns after the parameters.
const TAIL: usize = 14;

impl Serialize for RecordingRow {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        // Every field, no `..`: a field added to the row does not compile until it is written.
        let RecordingRow {
            subject_id,
            side,
            model,
            group,
            affected_side,
            side_role,
            source,
            status,
            error,
            warnings,
            withheld,
            fs_hz,
            duration_s,
            strides_total,
            strides_valid,
            parameters,
            mirrored,
            axial_rotation_deg,
            outliers_replaced,
            clipped_samples,
            trial_id,
            setting,
            walk_cadence_steps_per_min,
            steady_start_s,
            steady_end_s,
            steady_excluded_start,
            steady_excluded_end,
            belt_speed_mps,
            visit,
            recorded_at,
            trial_mean: _, // not a column: the mean's text is `trial_id`
        } = self;
        let mut st = s.serialize_struct("RecordingRow", HEAD + block::BLOCK_FIELDS + TAIL)?;
        st.serialize_field("subject_id", subject_id)?;
        st.serialize_field("side", side)?;
        st.serialize_field("model", model)?;
        st.serialize_field("group", &Text(group))?;
        st.serialize_field("affected_side", &Text(affected_side))?;
        st.serialize_field("side_role", &Text(side_role))?;
        st.serialize_field("source", source)?;
        st.serialize_field("status", status)?;
        st.serialize_field("error", error)?;
        st.serialize_field("warnings", warnings)?;
        st.serialize_field("withheld", withheld)?;
        st.serialize_field("fs_hz", fs_hz)?;
        st.serialize_field("duration_s", duration_s)?;
        st.serialize_field("strides_total", strides_total)?;
        st.serialize_field("strides_valid", strides_valid)?;
        block::serialize_parameters(
            &mut st,
            &parameters.values,
            Parameter::column,
            &parameters.sta_per_stride,
            &parameters.sta_status,
        )?;
        st.serialize_field("mirrored", mirrored)?;
        st.serialize_field("axial_rotation_deg", axial_rotation_deg)?;
        st.serialize_field("outliers_replaced", outliers_replaced)?;
        st.serialize_field("clipped_samples", clipped_samples)?;
        st.serialize_field("trial_id", trial_id)?;
        st.serialize_field("setting", &Text(setting))?;
        st.serialize_field("walk_cadence_steps_per_min", walk_cadence_steps_per_min)?;
        st.serialize_field("steady_start_s", steady_start_s)?;
        st.serialize_field("steady_end_s", steady_end_s)?;
        st.serialize_field("steady_excluded_start", steady_excluded_start)?;
        st.serialize_field("steady_excluded_end", steady_excluded_end)?;
        st.serialize_field("belt_speed_mps", belt_speed_mps)?;
        st.serialize_field("visit", visit)?;
        st.serialize_field("recorded_at", recorded_at)?;
        st.end()
    }
}
