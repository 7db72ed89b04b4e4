//! How the rows with a parameter block are written: the per-recording row ([`RecordingRow`],
//! recordings.csv and recordings.json) and the per-stride row ([`StrideRow`], strides.csv and
//! strides.json): their own columns by name and, between them, every parameter's by one loop
//! ([`crate::domain::block::serialize_parameters`]; [`Parameter::PER_STRIDE`]).
//! Hand-written because the parameters are one block ([`crate::domain::ParameterBlock`],
//! [`crate::domain::PerParameter`]) and the CSV writer refuses the map a derived
//! `#[serde(flatten)]` would write; the column order is the one the tables always had
//! (docs/columns.md), checked by the column dictionary's tests and the pinned outputs. A
//! stride row is also read back from strides.csv (`ldh agree`, `ldh report`), so it has a
//! hand-written `Deserialize` too, by column name (CSV or JSON; unknown columns ignored, a
//! missing parameter column empty).

use serde::de::{self, Deserialize, Deserializer, MapAccess, Visitor};
use serde::ser::{Serialize, SerializeStruct, Serializer};

use super::labels::{empty_is_none, Cell};
use super::{RecordingRow, StrideRow, STRIDE_COLUMNS};
use crate::domain::{block, Parameter, PerParameter};

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

impl Serialize for StrideRow {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        // Every field, no `..`: a field added to the row does not compile until it is written.
        let StrideRow {
            subject_id,
            side,
            model,
            stride_index,
            bout,
            hs_time_s,
            to_time_s,
            next_hs_time_s,
            values,
            heading_change_deg,
            valid,
            reason,
            reason_codes,
            trial_id,
        } = self;
        let mut st = s.serialize_struct("StrideRow", STRIDE_COLUMNS.len())?;
        st.serialize_field("subject_id", subject_id)?;
        st.serialize_field("side", side)?;
        st.serialize_field("model", model)?;
        st.serialize_field("stride_index", stride_index)?;
        st.serialize_field("bout", bout)?;
        st.serialize_field("hs_time_s", hs_time_s)?;
        st.serialize_field("to_time_s", to_time_s)?;
        st.serialize_field("next_hs_time_s", next_hs_time_s)?;
        for p in Parameter::PER_STRIDE {
            st.serialize_field(p.column(), &values[p])?;
        }
        st.serialize_field("heading_change_deg", heading_change_deg)?;
        st.serialize_field("valid", valid)?;
        st.serialize_field("reason", reason)?;
        st.serialize_field("reason_codes", reason_codes)?;
        st.serialize_field("trial_id", trial_id)?;
        st.end()
    }
}

impl<'de> Deserialize<'de> for StrideRow {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_struct("StrideRow", &STRIDE_COLUMNS, StrideRowVisitor)
    }
}

/// Reads a stride row's fields by name, as a derived `Deserialize` would (`reason_codes` and
/// `trial_id` default to empty, an absent optional value is `None`, other columns ignored).
struct StrideRowVisitor;

/// A required field's value, or the error that it is missing.
fn required<T, E: de::Error>(v: Option<T>, name: &'static str) -> Result<T, E> {
    v.ok_or_else(|| E::missing_field(name))
}

impl<'de> Visitor<'de> for StrideRowVisitor {
    type Value = StrideRow;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a row of the per-stride table")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<StrideRow, A::Error> {
        let (mut subject_id, mut side, mut model) = (None, None, None);
        let (mut stride_index, mut bout, mut valid, mut reason) = (None, None, None, None);
        let (mut hs_time_s, mut to_time_s, mut next_hs_time_s) = (None, None, None);
        let mut heading_change_deg = None;
        let (mut reason_codes, mut trial_id) = (Default::default(), String::new());
        let mut values = PerParameter::default();
        while let Some(key) = m.next_key::<std::borrow::Cow<'de, str>>()? {
            match key.as_ref() {
                "subject_id" => subject_id = Some(m.next_value()?),
                "side" => side = Some(m.next_value()?),
                "model" => model = Some(m.next_value()?),
                "stride_index" => stride_index = Some(m.next_value()?),
                "bout" => bout = Some(m.next_value()?),
                "hs_time_s" => hs_time_s = m.next_value()?,
                "to_time_s" => to_time_s = m.next_value()?,
                "next_hs_time_s" => next_hs_time_s = m.next_value()?,
                "heading_change_deg" => heading_change_deg = m.next_value()?,
                "valid" => valid = Some(m.next_value()?),
                "reason" => reason = Some(m.next_value()?),
                "reason_codes" => reason_codes = m.next_value()?,
                "trial_id" => trial_id = m.next_value()?,
                other => match Parameter::PER_STRIDE
                    .into_iter()
                    .find(|p| p.column() == other)
                {
                    Some(p) => values[p] = m.next_value()?,
                    None => {
                        m.next_value::<de::IgnoredAny>()?;
                    }
                },
            }
        }
        Ok(StrideRow {
            subject_id: required(subject_id, "subject_id")?,
            side: required(side, "side")?,
            model: required(model, "model")?,
            stride_index: required(stride_index, "stride_index")?,
            bout: required(bout, "bout")?,
            hs_time_s,
            to_time_s,
            next_hs_time_s,
            values,
            heading_change_deg,
            valid: required(valid, "valid")?,
            reason: required(reason, "reason")?,
            reason_codes,
            trial_id,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::attitude::AttitudeModel;
    use crate::Side;

    #[test]
    fn a_stride_row_reads_back_from_csv_and_json_by_column() {
        let mut values = PerParameter::default();
        for (i, p) in Parameter::PER_STRIDE.into_iter().enumerate() {
            values[p] = Some(i as f64 + 0.5);
        }
        values[Parameter::Speed] = None;
        let row = StrideRow {
            subject_id: "S1".into(),
            side: Side::Left.into(),
            model: AttitudeModel::Fusion.into(),
            stride_index: 3,
            bout: 1,
            hs_time_s: Some(1.25),
            to_time_s: None,
            next_hs_time_s: Some(2.5),
            values,
            heading_change_deg: Some(-3.5),
            valid: false,
            reason: "a; b".into(),
            reason_codes: "turn; bout_edge".parse().unwrap(),
            trial_id: "001".into(),
        };
        let text = crate::output::to_csv(std::slice::from_ref(&row), &[]).unwrap();
        assert_eq!(text.lines().next(), Some(STRIDE_COLUMNS.join(",").as_str()));
        let read = |t: &str| -> Result<StrideRow, csv::Error> {
            csv::Reader::from_reader(t.as_bytes())
                .deserialize()
                .next()
                .unwrap()
        };
        assert_eq!(read(&text).unwrap(), row);
        let json = serde_json::to_string(&row).unwrap();
        assert_eq!(serde_json::from_str::<StrideRow>(&json).unwrap(), row);
        // An older table: no trial_id nor reason_codes, a parameter column missing (empty),
        // a column it does not know (ignored).
        let old = read("subject_id,side,model,stride_index,bout,stride_time_s,valid,reason,x\nS1,left,fusion,0,0,1.1,true,,y\n").unwrap();
        assert_eq!(old.value(Parameter::StrideTime), Some(1.1));
        assert_eq!(
            (old.value(Parameter::Wqk), old.trial_id.as_str()),
            (None, "")
        );
        let e = read("subject_id,side\nS1,left\n").unwrap_err();
        assert!(e.to_string().contains("missing field `model`"), "{e}");
    }
}
