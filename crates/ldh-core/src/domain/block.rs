//! The parameter block of a leg's parameters and of a per-recording row (issue 48): every
//! [`Parameter`]'s value, written by one loop over [`Parameter::TABLE_ORDER`], so a new
//! parameter becomes a column (or a key) with no edit here.
//!
//! Why hand-written serde and not a field per parameter: the values live in a
//! [`PerParameter`] (one slot per parameter), while the tables must keep their columns in the
//! order they always had, between the row's other columns. A derived `#[serde(flatten)]` would
//! write a map, which the CSV writer does not support, so the rows call
//! [`serialize_parameters`] between their other fields, and read the block back from the map
//! of what is left after their own fields ([`ParameterBlock`]).
//!
//! The block: for each parameter of [`Parameter::TABLE_ORDER`] its value under its column (or
//! the key a caller gives), STA's followed by `sta_per_stride` (the same exponent per stride)
//! and `sta_status` (why STA is missing).

use serde::ser::SerializeStruct;
use serde::{Deserialize, Serialize};

use super::{Parameter, PerParameter};

/// How many fields [`serialize_parameters`] writes.
pub const BLOCK_FIELDS: usize = Parameter::ALL.len() + 2;

/// The column after STA's: its value per stride (λ · mean stride time).
pub const STA_PER_STRIDE: &str = "sta_per_stride";

/// The column after [`STA_PER_STRIDE`]: why STA is missing.
pub const STA_STATUS: &str = "sta_status";

/// Write `values` as fields of `s`, in the order of [`Parameter::TABLE_ORDER`], each under
/// `key(p)`; STA's value is followed by `sta_per_stride` and `sta_status`.
pub fn serialize_parameters<S: SerializeStruct, T: Serialize>(
    s: &mut S,
    values: &PerParameter<T>,
    key: fn(Parameter) -> &'static str,
    sta_per_stride: &T,
    sta_status: &str,
) -> Result<(), S::Error> {
    for p in Parameter::TABLE_ORDER {
        s.serialize_field(key(p), &values[p])?;
        if p == Parameter::Sta {
            s.serialize_field(STA_PER_STRIDE, sta_per_stride)?;
            s.serialize_field(STA_STATUS, sta_status)?;
        }
    }
    Ok(())
}

/// The parameter block as read back (JSON: `recordings.json`, a leg's parameters): a value
/// that is absent or `null` is `None`; `sta_status` absent is "".
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ParameterBlock {
    /// Every parameter's value.
    pub values: PerParameter<Option<f64>>,
    /// STA per stride.
    pub sta_per_stride: Option<f64>,
    /// Why STA is missing.
    pub sta_status: String,
}

impl ParameterBlock {
    /// The block from the fields of a map, each parameter's under `key(p)` (the other fields
    /// are left).
    pub fn from_map<E: serde::de::Error>(
        m: &serde_json::Map<String, serde_json::Value>,
        key: fn(Parameter) -> &'static str,
    ) -> Result<ParameterBlock, E> {
        let number = |k: &str| -> Result<Option<f64>, E> {
            match m.get(k) {
                None | Some(serde_json::Value::Null) => Ok(None),
                Some(v) => v
                    .as_f64()
                    .map(Some)
                    .ok_or_else(|| E::custom(format!("{k}: expected a number or null, found {v}"))),
            }
        };
        let mut values = PerParameter::default();
        for p in Parameter::ALL {
            values[p] = number(key(p))?;
        }
        let sta_status = match m.get(STA_STATUS) {
            None | Some(serde_json::Value::Null) => String::new(),
            Some(serde_json::Value::String(s)) => s.clone(),
            Some(v) => return Err(E::custom(format!("{STA_STATUS}: expected text, found {v}"))),
        };
        Ok(ParameterBlock {
            values,
            sta_per_stride: number(STA_PER_STRIDE)?,
            sta_status,
        })
    }
}

impl std::ops::Index<Parameter> for ParameterBlock {
    type Output = Option<f64>;
    fn index(&self, p: Parameter) -> &Option<f64> {
        &self.values[p]
    }
}

impl std::ops::IndexMut<Parameter> for ParameterBlock {
    fn index_mut(&mut self, p: Parameter) -> &mut Option<f64> {
        &mut self.values[p]
    }
}

/// Read as the rest of a row's map (`#[serde(flatten)]`), parameters under their columns.
impl<'de> Deserialize<'de> for ParameterBlock {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let m = serde_json::Map::<String, serde_json::Value>::deserialize(d)?;
        ParameterBlock::from_map(&m, Parameter::column)
    }
}
