//! The label columns of the per-recording table (`side`, `model`, `group`, `affected_side`,
//! `side_role`, `status`, `setting`) as enums, so that cohort, ml and report match on values
//! instead of comparing strings.
//!
//! The table is also *read back* — `recordings.json` of an earlier run, or one a user wrote —
//! and reading has always accepted any text in these columns (a group `stroke` is carried and
//! left out of the statistics with its name; a side `LEFT` is simply not a left leg). So every
//! label is total: [`Label`] holds one of the values ldh writes ([`Known`]) or, verbatim, any
//! other text; the group is [`Group`], which has its own `Other`. A column that may be
//! empty ("not said") is an `Option`, written as an empty cell / empty JSON string (never
//! `null`) through [`empty_is_none`]. Reading goes through `String`, so a wrong JSON type gives
//! the same error as before, and writing gives the same bytes as the string columns did.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::attitude::AttitudeModel;
pub use crate::domain::AffectedSide;
use crate::domain::{Group, Setting, Side};

/// A value ldh writes in a label column, with its cell text.
pub trait Known: Sized + Copy + PartialEq + 'static {
    /// Every value.
    const ALL: &'static [Self];
    /// The cell text (`left`, `fusion`, `ok` …).
    fn cell(self) -> &'static str;
}

/// A label column's value: one ldh writes, or any other text read from a table (kept as
/// written; ldh never writes one).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Label<T> {
    /// A value ldh knows.
    Known(T),
    /// Any other text, as read.
    Other(String),
}

impl<T: Known> Label<T> {
    /// The value whose cell text is exactly `s`, else `Other(s)`.
    pub fn parse(s: &str) -> Label<T> {
        match T::ALL.iter().find(|v| v.cell() == s) {
            Some(v) => Label::Known(*v),
            None => Label::Other(s.to_string()),
        }
    }

    /// The cell text.
    pub fn as_str(&self) -> &str {
        match self {
            Label::Known(v) => v.cell(),
            Label::Other(s) => s,
        }
    }

    /// The known value, if it is one.
    pub fn known(&self) -> Option<T> {
        match self {
            Label::Known(v) => Some(*v),
            Label::Other(_) => None,
        }
    }
}

impl<T: Known> PartialEq<T> for Label<T> {
    fn eq(&self, other: &T) -> bool {
        self.known() == Some(*other)
    }
}

impl<T: Known> From<T> for Label<T> {
    fn from(v: T) -> Self {
        Label::Known(v)
    }
}

impl<T: Known> std::fmt::Display for Label<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl<T: Known> Serialize for Label<T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

impl<'de, T: Known> Deserialize<'de> for Label<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        String::deserialize(d).map(|s| Label::parse(&s))
    }
}

impl Known for Side {
    const ALL: &'static [Side] = &[Side::Left, Side::Right];
    fn cell(self) -> &'static str {
        self.as_str()
    }
}

impl Known for AttitudeModel {
    const ALL: &'static [AttitudeModel] = &[AttitudeModel::Fusion, AttitudeModel::Acc];
    fn cell(self) -> &'static str {
        self.as_str()
    }
}

impl Known for Setting {
    const ALL: &'static [Setting] = &[Setting::Overground, Setting::Treadmill];
    fn cell(self) -> &'static str {
        self.as_str()
    }
}

/// Whether a recording was analysed (`ok`), analysed without a single valid stride
/// (`no_valid_strides`: every parameter is withheld, `withheld` says why), or failed (`error`,
/// the row's `error` says why).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// `ok`: analysed, at least one valid stride.
    Ok,
    /// `no_valid_strides`: analysed, but no stride passed the checks, so no parameter was
    /// measured (a walk too short, or every stride left out).
    NoValidStrides,
    /// `error`: failed.
    Error,
}

impl Known for Status {
    const ALL: &'static [Status] = &[Status::Ok, Status::NoValidStrides, Status::Error];
    fn cell(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::NoValidStrides => "no_valid_strides",
            Status::Error => "error",
        }
    }
}

impl Known for AffectedSide {
    const ALL: &'static [AffectedSide] = &[
        AffectedSide::Left,
        AffectedSide::Right,
        AffectedSide::Neither,
    ];
    fn cell(self) -> &'static str {
        match self {
            AffectedSide::Left => "left",
            AffectedSide::Right => "right",
            AffectedSide::Neither => "none",
        }
    }
}

/// A side's role in the cohort analysis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SideRole {
    /// `affected`: the affected side of an LDH subject (LDHE).
    Affected,
    /// `unaffected`: the other side of an LDH subject (LDHH).
    Unaffected,
    /// `healthy`: a leg of a healthy subject (H).
    Healthy,
}

impl Known for SideRole {
    const ALL: &'static [SideRole] = &[SideRole::Affected, SideRole::Unaffected, SideRole::Healthy];
    fn cell(self) -> &'static str {
        match self {
            SideRole::Affected => "affected",
            SideRole::Unaffected => "unaffected",
            SideRole::Healthy => "healthy",
        }
    }
}

/// A label that may be missing: its cell text, and the value a non-empty cell holds.
pub trait Cell: Sized {
    /// The cell text.
    fn text(&self) -> &str;
    /// The value of a non-empty cell (total: any text is a value).
    fn from_text(s: &str) -> Self;
}

impl<T: Known> Cell for Label<T> {
    fn text(&self) -> &str {
        self.as_str()
    }
    fn from_text(s: &str) -> Self {
        Label::parse(s)
    }
}

/// In a table the group is exactly `healthy` or `ldh`, anything else kept as written (the
/// manifest's spellings `h`, `control` were mapped when the table was written).
impl Cell for Group {
    fn text(&self) -> &str {
        self.as_str()
    }
    fn from_text(s: &str) -> Self {
        match s {
            "healthy" => Group::Healthy,
            "ldh" => Group::Ldh,
            o => Group::Other(o.to_string()),
        }
    }
}

/// `#[serde(with = "empty_is_none")]` for an `Option` label: `None` is an empty cell (an empty
/// JSON string, not `null`), and an empty cell reads as `None`.
pub mod empty_is_none {
    use super::Cell;
    use serde::{Deserialize, Deserializer, Serializer};

    /// The cell text, empty for `None`.
    pub fn serialize<S: Serializer, T: Cell>(v: &Option<T>, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(v.as_ref().map_or("", |x| x.text()))
    }

    /// `None` for an empty cell.
    pub fn deserialize<'de, D: Deserializer<'de>, T: Cell>(d: D) -> Result<Option<T>, D::Error> {
        let s = String::deserialize(d)?;
        Ok((!s.is_empty()).then(|| T::from_text(&s)))
    }
}

/// The cell text of an optional label (empty for `None`), for reports that print it.
pub fn text<T: Cell>(v: &Option<T>) -> &str {
    v.as_ref().map_or("", |x| x.text())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, PartialEq, Serialize, Deserialize)]
    struct Typed {
        side: Label<Side>,
        #[serde(with = "empty_is_none")]
        group: Option<Group>,
        #[serde(default, with = "empty_is_none")]
        setting: Option<Label<Setting>>,
    }

    /// The string columns the labels replaced.
    #[derive(Debug, Serialize, Deserialize)]
    struct Strings {
        side: String,
        group: String,
        #[serde(default)]
        setting: String,
    }

    #[test]
    fn json_reads_and_writes_what_the_string_columns_did() {
        for text in [
            r#"{"side":"left","group":"","setting":"treadmill"}"#,
            r#"{"side":"LEFT","group":"stroke","setting":"Treadmill"}"#,
            r#"{"side":"","group":"ldh","setting":""}"#,
        ] {
            let t: Typed = serde_json::from_str(text).unwrap();
            let s: Strings = serde_json::from_str(text).unwrap();
            assert_eq!(serde_json::to_string(&t).unwrap(), text);
            assert_eq!(serde_json::to_string(&s).unwrap(), text);
        }
        let t: Typed = serde_json::from_str(r#"{"side":"right","group":"healthy"}"#).unwrap();
        assert_eq!(t.side, Side::Right);
        assert_eq!(t.group, Some(Group::Healthy));
        assert_eq!(t.setting, None, "a missing setting is not said");
        let t: Typed = serde_json::from_str(r#"{"side":"LEFT","group":"H"}"#).unwrap();
        assert_eq!(t.side, Label::Other("LEFT".into()), "kept as written");
        assert_eq!(
            t.group,
            Some(Group::Other("H".into())),
            "no manifest spellings"
        );
    }

    #[test]
    fn json_errors_are_the_string_columns_errors() {
        for text in [
            r#"{"side":null,"group":""}"#,
            r#"{"side":"left","group":3}"#,
            r#"{"side":"left"}"#,
            r#"{"side":"left","group":"","setting":[1]}"#,
        ] {
            let t = serde_json::from_str::<Typed>(text).unwrap_err().to_string();
            let s = serde_json::from_str::<Strings>(text)
                .unwrap_err()
                .to_string();
            assert_eq!(t, s, "{text}");
        }
    }

    #[test]
    fn csv_empty_cells_are_none_and_written_back_empty() {
        let text = "side,group,setting\nright,,\nleft,ldh,overground\nx,y,z\n";
        let rows: Vec<Typed> = csv::Reader::from_reader(text.as_bytes())
            .deserialize()
            .collect::<std::result::Result<_, _>>()
            .unwrap();
        assert_eq!(rows[0].group, None);
        assert_eq!(rows[0].setting, None);
        assert_eq!(rows[1].setting, Some(Setting::Overground.into()));
        assert_eq!(rows[2].setting, Some(Label::Other("z".into())));
        let mut w = csv::Writer::from_writer(Vec::new());
        for r in &rows {
            w.serialize(r).unwrap();
        }
        assert_eq!(String::from_utf8(w.into_inner().unwrap()).unwrap(), text);
    }

    #[test]
    fn every_known_value_reads_back_as_itself() {
        fn check<T: Known + std::fmt::Debug>() {
            for v in T::ALL {
                assert_eq!(Label::<T>::parse(v.cell()), Label::Known(*v));
            }
        }
        check::<Side>();
        check::<AttitudeModel>();
        check::<Setting>();
        check::<Status>();
        check::<AffectedSide>();
        check::<SideRole>();
        assert_eq!(AffectedSide::Neither.side(), None);
        assert_eq!(AffectedSide::from(Side::Left).side(), Some(Side::Left));
    }
}
