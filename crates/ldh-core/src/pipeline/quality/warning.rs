//! Structured warnings: what a quality check found, how serious it is, and which parameters it
//! withholds (docs/quality.md lists every code, its threshold, its source and its consequence).

use serde::{Deserialize, Serialize};
use std::fmt;

pub use crate::domain::codes;
use crate::domain::{Parameter, Reason, ReasonCode, WarningCode, Withheld};

/// `Warning::affects` as the column names of recordings.csv.
mod affects_columns {
    use super::Parameter;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub fn serialize<S: Serializer>(v: &[Parameter], s: S) -> Result<S::Ok, S::Error> {
        let cols: Vec<&str> = v.iter().flat_map(|p| p.withheld_columns()).collect();
        cols.serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Parameter>, D::Error> {
        let mut out: Vec<Parameter> = Vec::new();
        for c in Vec::<String>::deserialize(d)? {
            if let Some(p) = Parameter::from_withheld_column(&c) {
                if !out.contains(&p) {
                    out.push(p);
                }
            }
        }
        Ok(out)
    }
}

/// How serious a finding is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Severity {
    /// Worth knowing; every parameter is still vouched for (e.g. a documented device
    /// convention, accelerometer clipping outside the integration windows).
    Note,
    /// Some parameters, or the interpretation, may be affected; `affects` names what is withheld.
    Warning,
    /// The sensor or the recording is faulty: the affected parameters are withheld.
    Fault,
}

impl Severity {
    /// `note`, `warning` or `fault`.
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Note => "note",
            Severity::Warning => "warning",
            Severity::Fault => "fault",
        }
    }
}

/// One finding of a quality check (or of the reader), with a stable `code`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Warning {
    /// Stable machine-readable code, written as its text, e.g. `gyro_scale_fault`
    /// (docs/quality.md lists them).
    pub code: WarningCode,
    /// How serious it is.
    pub severity: Severity,
    /// What was found, with the numbers, in one readable sentence or two. Never contains " | "
    /// (the separator of the CSV column).
    pub message: String,
    /// The parameters it withholds; empty when none. Written as their column names of
    /// recordings.csv (STA as `sta_per_s` and `sta_per_stride`).
    #[serde(default, with = "affects_columns")]
    pub affects: Vec<Parameter>,
    /// The time span the finding covers, s from the recording's first sample (first and last
    /// sample), for a finding about part of the walk (`channel_fault`): the strides overlapping
    /// it are withheld ([`crate::pipeline::quality::apply_to_strides`]). Absent for findings
    /// about the whole leg.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub span_s: Option<[f64; 2]>,
}

impl Warning {
    /// A finding that withholds nothing (see [`Warning::withholding`]).
    pub fn new(code: WarningCode, severity: Severity, message: impl Into<String>) -> Warning {
        Warning {
            code,
            severity,
            message: message.into().replace(" | ", " / "),
            affects: Vec::new(),
            span_s: None,
        }
    }
    /// The same finding about the span `[start_s, end_s]` only.
    pub fn over_span(mut self, start_s: f64, end_s: f64) -> Warning {
        self.span_s = Some([start_s, end_s]);
        self
    }
    /// The same finding withholding `params`.
    pub fn withholding(mut self, params: &[Parameter]) -> Warning {
        for p in params {
            if !self.affects.contains(p) {
                self.affects.push(*p);
            }
        }
        self
    }
    /// Whether it withholds `p`.
    pub fn withholds(&self, p: Parameter) -> bool {
        self.affects.contains(&p)
    }
    /// The reason it gives a parameter it withholds: its code, with [`Warning::reason`] as the
    /// message.
    pub fn withheld_reason(&self) -> Reason {
        Reason::new(ReasonCode::Finding(self.code), self.reason())
    }
    /// A reader warning (free text from the file checks) as a structured warning.
    pub fn from_reader(text: &str) -> Warning {
        Warning::new(codes::INPUT, Severity::Warning, text)
    }
    /// The short reason for withholding a parameter: the message's first clause, in its own
    /// words ("gyroscope sensor fault"), without the code — the reason reaches the clinical
    /// pages, the code stays in `warnings` (issue 50: no codes on the clinical pages).
    pub fn reason(&self) -> String {
        self.message
            .split([':', ';'])
            .next()
            .unwrap_or(&self.message)
            .trim()
            .to_string()
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} [{}]: {}",
            self.code,
            self.severity.as_str(),
            self.message
        )
    }
}

/// The parameters of recordings.csv, by what they are computed from.
pub mod params {
    use crate::domain::Parameter::{self, *};
    /// Every per-side parameter (in the table's column order).
    pub const ALL: [Parameter; Parameter::COUNT] = Parameter::TABLE_ORDER;
    /// The shank angles (from the attitude).
    pub const ANGLES: [Parameter; 3] = [Wqk, Pbi, Bdk];
    /// The shank angles measured from the vertical (an error of the shank axis moves them).
    pub const INCLINATIONS: [Parameter; 2] = [Wqk, Pbi];
    /// Stride length and what is derived from it (double integration of the acceleration).
    pub const LENGTH: [Parameter; 3] = [StrideLength, Speed, StrideLengthCv];
    /// The parameters that pair the legs.
    pub const PAIRED: [Parameter; 2] = [StepTime, StepFrequency];
    /// Stride-to-stride variability.
    pub const VARIABILITY: [Parameter; 2] = [StrideTimeCv, StrideLengthCv];
}

/// A list of warnings: a JSON array of objects, and one readable CSV cell (the warnings'
/// [`Display`](fmt::Display) forms joined by " | "; a warning never contains " | ").
#[derive(Debug, Clone, Default, PartialEq)]
pub struct WarningList(pub Vec<Warning>);

impl WarningList {
    /// No warnings.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
    /// The warnings.
    pub fn iter(&self) -> std::slice::Iter<'_, Warning> {
        self.0.iter()
    }
    /// The warnings of at least `s`.
    pub fn at_least(&self, s: Severity) -> impl Iterator<Item = &Warning> {
        self.0.iter().filter(move |w| w.severity >= s)
    }
}

impl fmt::Display for WarningList {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, w) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(" | ")?;
            }
            write!(f, "{w}")?;
        }
        Ok(())
    }
}

thread_local! {
    static FLAT: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Run `f` with lists serialised flat (one text cell), as CSV needs.
pub fn flat<R>(f: impl FnOnce() -> R) -> R {
    struct Reset(bool);
    impl Drop for Reset {
        fn drop(&mut self) {
            FLAT.with(|c| c.set(self.0));
        }
    }
    let _reset = Reset(FLAT.with(|c| c.replace(true)));
    f()
}

fn is_flat() -> bool {
    FLAT.with(|c| c.get())
}

impl Serialize for WarningList {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if is_flat() {
            s.serialize_str(&self.to_string())
        } else {
            self.0.serialize(s)
        }
    }
}

impl<'de> Deserialize<'de> for WarningList {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Either {
            List(Vec<Warning>),
            Text(String),
        }
        Ok(match Either::deserialize(d)? {
            Either::List(v) => WarningList(v),
            Either::Text(t) if t.is_empty() => WarningList::default(),
            Either::Text(t) => WarningList(t.split(" | ").map(parse_flat).collect()),
        })
    }
}

/// A warning back from its CSV form `code [severity]: message` (the `affects` are in the
/// `withheld` column).
fn parse_flat(s: &str) -> Warning {
    let parsed = s.split_once(": ").and_then(|(head, message)| {
        let (code, sev) = head.split_once(" [")?;
        let severity = match sev.trim_end_matches(']') {
            "note" => Severity::Note,
            "warning" => Severity::Warning,
            "fault" => Severity::Fault,
            _ => return None,
        };
        Some(Warning::new(code.parse().ok()?, severity, message))
    });
    parsed.unwrap_or_else(|| Warning::from_reader(s))
}

/// Parameters withheld ([`Withheld`], keyed by [`Parameter`]): a JSON object column → reason,
/// and one readable CSV cell (`column: reason` joined by " | ").
#[derive(Debug, Clone, Default, PartialEq)]
pub struct WithheldList(pub Withheld);

impl WithheldList {
    /// Nothing withheld.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
    /// Why `param` is withheld, if it is.
    pub fn reason(&self, param: Parameter) -> Option<&str> {
        self.0.reason(param)
    }
    /// Nothing withheld any more.
    pub fn clear(&mut self) {
        self.0.clear();
    }
}

impl fmt::Display for WithheldList {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, (k, v)) in self.0.columns().into_iter().enumerate() {
            if i > 0 {
                f.write_str(" | ")?;
            }
            write!(f, "{k}: {v}")?;
        }
        Ok(())
    }
}

impl Serialize for WithheldList {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if is_flat() {
            s.serialize_str(&self.to_string())
        } else {
            self.0.serialize(s)
        }
    }
}

impl<'de> Deserialize<'de> for WithheldList {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Either {
            Map(Withheld),
            Text(String),
        }
        Ok(match Either::deserialize(d)? {
            Either::Map(m) => WithheldList(m),
            Either::Text(t) => WithheldList(Withheld::from_columns(
                t.split(" | ").filter_map(|kv| kv.split_once(": ")),
            )),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_are_arrays_in_json_and_one_cell_in_csv() {
        #[derive(Serialize, Deserialize)]
        struct Row {
            id: u32,
            warnings: WarningList,
            withheld: WithheldList,
        }
        let w = WarningList(vec![
            Warning::new(
                codes::GYRO_SCALE_FAULT,
                Severity::Fault,
                "rates of 2400 deg/s; a | b",
            )
            .withholding(&params::ANGLES),
            Warning::new(codes::ACC_CLIPPING, Severity::Note, "clipped at 2 g"),
        ]);
        let wh = WithheldList(Withheld::from_columns([("wqk_deg", "gyro scale fault")]));
        let row = Row {
            id: 1,
            warnings: w.clone(),
            withheld: wh.clone(),
        };
        let j = serde_json::to_value(&row).unwrap();
        assert_eq!(j["warnings"][0]["code"], "gyro_scale_fault");
        assert_eq!(j["warnings"][0]["affects"][2], "bdk_deg");
        assert_eq!(j["withheld"]["wqk_deg"], "gyro scale fault");
        let back: Row = serde_json::from_value(j).unwrap();
        assert_eq!(back.warnings, w);
        let mut c = csv::Writer::from_writer(Vec::new());
        flat(|| c.serialize(&row)).unwrap();
        let text = String::from_utf8(c.into_inner().unwrap()).unwrap();
        assert!(text.contains("gyro_scale_fault [fault]: rates of 2400 deg/s; a / b | acc_clipping [note]: clipped at 2 g"), "{text}");
        assert!(text.contains("wqk_deg: gyro scale fault"), "{text}");
        // Serialised as JSON again outside `flat`.
        assert!(serde_json::to_string(&row)
            .unwrap()
            .starts_with("{\"id\":1,\"warnings\":[{"));
        let mut r = csv::Reader::from_reader(text.as_bytes());
        let back: Row = r.deserialize().next().unwrap().unwrap();
        assert_eq!(back.warnings.0[1].code, "acc_clipping");
        assert_eq!(back.warnings.0.len(), 2);
        assert_eq!(back.withheld, wh);
    }
}
