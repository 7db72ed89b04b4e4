//! Values that a check may withhold (issue 48): [`Reason`], a typed code carrying its message;
//! [`Measured`], a value or the reason it is not one; [`PerParameter`], one `T` for every
//! [`Parameter`]; [`Withheld`], the reasons a leg's (or a row's) parameters are withheld,
//! keyed by [`Parameter`] and written as the `withheld` column (column → reason).
//!
//! The reason's code decides; its message is only shown (no code reads a message's text).

use std::collections::BTreeMap;

use super::Parameter;

/// What kind of reason withholds a value.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum ReasonCode {
    /// A quality finding withheld it: its stable warning code (docs/quality.md).
    Finding(super::WarningCode),
    /// Too few of the leg's valid strides have a stride length that passed its checks
    /// ([`crate::gait::MIN_LENGTH_SHARE`], [`crate::gait::MIN_LENGTH_STRIDES`]).
    LengthNotVouched,
    /// Read back from a table, or several trials' reasons merged: only the message is known.
    Read,
}

/// Why a value is withheld: a typed [`ReasonCode`] and the message a person reads.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Reason {
    /// What kind of reason it is.
    pub code: ReasonCode,
    /// The message, as the tables show it.
    pub message: String,
}

impl Reason {
    /// A reason of `code` with `message`.
    pub fn new(code: ReasonCode, message: impl Into<String>) -> Reason {
        Reason {
            code,
            message: message.into(),
        }
    }
    /// A reason read back from a table (its code is not written).
    pub fn read(message: impl Into<String>) -> Reason {
        Reason::new(ReasonCode::Read, message)
    }
}

impl std::fmt::Display for Reason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// A value, or the reason it was not measured.
#[derive(Debug, Clone, PartialEq)]
pub enum Measured {
    /// The value (finite).
    Value(f64),
    /// Withheld, with the reason.
    Withheld(Reason),
}

impl Measured {
    /// The value, if there is one.
    pub fn value(&self) -> Option<f64> {
        match self {
            Measured::Value(v) => Some(*v),
            Measured::Withheld(_) => None,
        }
    }
}

/// One `T` for every [`Parameter`], indexed by the parameter.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct PerParameter<T>([T; Parameter::ALL.len()]);

impl<T> PerParameter<T> {
    /// `f(p)` for every parameter `p`.
    pub fn from_fn(mut f: impl FnMut(Parameter) -> T) -> PerParameter<T> {
        PerParameter(std::array::from_fn(|i| f(Parameter::ALL[i])))
    }
    /// Every parameter with its value, in the order of [`Parameter::ALL`].
    pub fn iter(&self) -> impl Iterator<Item = (Parameter, &T)> {
        Parameter::ALL.into_iter().zip(self.0.iter())
    }
}

impl<T> std::ops::Index<Parameter> for PerParameter<T> {
    type Output = T;
    fn index(&self, p: Parameter) -> &T {
        &self.0[p.index()]
    }
}

impl<T> std::ops::IndexMut<Parameter> for PerParameter<T> {
    fn index_mut(&mut self, p: Parameter) -> &mut T {
        &mut self.0[p.index()]
    }
}

/// The parameters withheld and why, keyed by [`Parameter`]. Written as column → reason (a JSON
/// object; one CSV cell `column: reason` joined by ` | `), the columns in alphabetical order
/// and STA's reason under both its columns (`sta_per_s`, `sta_per_stride`).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Withheld(pub BTreeMap<Parameter, Reason>);

impl Withheld {
    /// Nothing withheld.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
    /// How many parameters are withheld.
    pub fn len(&self) -> usize {
        self.0.len()
    }
    /// Whether `p` is withheld.
    pub fn contains(&self, p: Parameter) -> bool {
        self.0.contains_key(&p)
    }
    /// Why `p` is withheld, if it is.
    pub fn get(&self, p: Parameter) -> Option<&Reason> {
        self.0.get(&p)
    }
    /// Why `p` is withheld, as the message (`None`: it is not).
    pub fn reason(&self, p: Parameter) -> Option<&str> {
        self.0.get(&p).map(|r| r.message.as_str())
    }
    /// Withhold `p` for `reason`, replacing an earlier reason.
    pub fn insert(&mut self, p: Parameter, reason: Reason) {
        self.0.insert(p, reason);
    }
    /// Withhold `p` for `reason` unless it is withheld already.
    pub fn insert_first(&mut self, p: Parameter, reason: impl FnOnce() -> Reason) {
        self.0.entry(p).or_insert_with(reason);
    }
    /// Nothing withheld any more.
    pub fn clear(&mut self) {
        self.0.clear();
    }
    /// The parameters withheld with their reasons.
    pub fn iter(&self) -> impl Iterator<Item = (Parameter, &Reason)> {
        self.0.iter().map(|(p, r)| (*p, r))
    }
    /// `(column, message)` in the order the tables write them (alphabetical by column).
    pub fn columns(&self) -> Vec<(&'static str, &str)> {
        let mut v: Vec<(&'static str, &str)> = self
            .0
            .iter()
            .flat_map(|(p, r)| {
                p.withheld_columns()
                    .into_iter()
                    .map(move |c| (c, r.message.as_str()))
            })
            .collect();
        v.sort_by_key(|(c, _)| *c);
        v
    }
    /// From `(column, message)` pairs as a table holds them (columns that are no parameter's
    /// are dropped; STA's second column adds nothing to its first).
    pub fn from_columns<'a>(pairs: impl IntoIterator<Item = (&'a str, &'a str)>) -> Withheld {
        let mut out = Withheld::default();
        for (c, m) in pairs {
            if let Some(p) = Parameter::from_withheld_column(c) {
                out.insert_first(p, || Reason::read(m));
            }
        }
        out
    }
}

impl serde::Serialize for Withheld {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let cols = self.columns();
        let mut m = s.serialize_map(Some(cols.len()))?;
        for (c, r) in cols {
            m.serialize_entry(c, r)?;
        }
        m.end()
    }
}

impl<'de> serde::Deserialize<'de> for Withheld {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let m = BTreeMap::<String, String>::deserialize(d)?;
        Ok(Withheld::from_columns(
            m.iter().map(|(k, v)| (k.as_str(), v.as_str())),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn withheld_is_written_by_column_with_sta_under_both() {
        let mut w = Withheld::default();
        w.insert(Parameter::Wqk, Reason::read("a"));
        w.insert(Parameter::Sta, Reason::read("b"));
        w.insert(Parameter::Bdk, Reason::read("c"));
        let j = serde_json::to_string(&w).unwrap();
        assert_eq!(
            j,
            r#"{"bdk_deg":"c","sta_per_s":"b","sta_per_stride":"b","wqk_deg":"a"}"#
        );
        let back: Withheld = serde_json::from_str(&j).unwrap();
        assert_eq!(back, w);
        let mut per = PerParameter::from_fn(|p| p.code().len());
        per[Parameter::Sta] = 9;
        assert_eq!(per[Parameter::Sta], 9);
        assert_eq!(per.iter().count(), Parameter::ALL.len());
    }
}
