//! The first screen of a subject's page: a clinical summary in a clinician's words and units
//! (cadence in steps/min, speed m/s, stride length m, stance % of the gait cycle, variability as
//! CV %, left-right asymmetry %), each value beside the normal range it was judged against and
//! that range's source, a plain-language flag ("below normal", "within normal", …) and ▲/▼ for
//! values outside it, and "not measured: <reason>" — never a number, never a mark — for what a
//! quality check withheld or could not be computed.
//!
//! The asymmetry is the symmetry index of Robinson et al. (J Manipulative Physiol Ther
//! 1987;10(4):172–176), flagged above [`super::ReportParams::asymmetry_flag_pct`].

use maud::{html, Markup};

use super::html::fmt;
use super::reference::no_published_reason;
use super::subject::Citations;
use super::{symmetry_index_pct, Reference, ReferenceRange, ReferenceSource, ValidReportParams};
use crate::output::{Parameter, RecordingRow};

/// One line of the summary: a parameter column shown in clinical units.
pub(crate) struct Measure {
    /// What a clinician calls it.
    pub label: &'static str,
    /// The clinical unit.
    pub unit: &'static str,
    /// The parameter.
    pub parameter: Parameter,
    /// Factor from the table's unit to the clinical unit.
    pub scale: f64,
    /// Decimals shown.
    pub decimals: usize,
}

const fn m(
    label: &'static str,
    unit: &'static str,
    parameter: Parameter,
    scale: f64,
    decimals: usize,
) -> Measure {
    Measure {
        label,
        unit,
        parameter,
        scale,
        decimals,
    }
}

/// The summary's measures, in clinical units.
pub(crate) const MEASURES: [Measure; 7] = [
    m("Cadence", "steps/min", Parameter::StepFrequency, 60.0, 0),
    m("Walking speed", "m/s", Parameter::Speed, 1.0, 2),
    m("Stride length", "m", Parameter::StrideLength, 1.0, 2),
    m("Stride time", "s", Parameter::StrideTime, 1.0, 2),
    m(
        "Stance",
        "% of gait cycle",
        Parameter::StanceRatio,
        100.0,
        1,
    ),
    m(
        "Stride time variability",
        "CV %",
        Parameter::StrideTimeCv,
        100.0,
        1,
    ),
    m(
        "Stride length variability",
        "CV %",
        Parameter::StrideLengthCv,
        100.0,
        1,
    ),
];

/// Left-right asymmetry lines: (label, parameter).
const ASYMMETRY: [(&str, Parameter); 4] = [
    ("Step time asymmetry", Parameter::StepTime),
    ("Stance asymmetry", Parameter::StanceRatio),
    ("Stride length asymmetry", Parameter::StrideLength),
    ("Shank swing asymmetry (WQK)", Parameter::Wqk),
];

/// Why a side has no value of `p` (the quality check's reason first), or `None` when it has
/// one.
pub(crate) fn not_measured(r: &RecordingRow, p: Parameter) -> Option<String> {
    if !r.is_ok() {
        return Some("not analysed (see above)".into());
    }
    if let Some(why) = r.withheld.reason(p.column()) {
        return Some(why.to_string());
    }
    if r.value(p).is_some() {
        return None;
    }
    if p == Parameter::Sta && !r.sta_status.is_empty() {
        return Some(r.sta_status.clone());
    }
    Some(match r.strides_valid {
        Some(0) => "no valid stride".into(),
        _ => "not computable from these strides".into(),
    })
}

/// The mark and plain words of a value judged against a range: `(▲, "above normal")`,
/// `(▼, "below normal")`, no mark "within normal", or "no reference".
pub(crate) fn judged(v: f64, rr: Option<&ReferenceRange>) -> (Option<&'static str>, &'static str) {
    match rr.map(|r| (r.low, r.high)) {
        Some((Some(l), _)) if v < l => (Some("▼"), "below normal"),
        Some((_, Some(h))) if v > h => (Some("▲"), "above normal"),
        Some((Some(_), Some(_))) => (None, "within normal"),
        _ => (None, "no reference"),
    }
}

/// The range in clinical units and where it comes from.
fn range_cells(
    rr: Option<&ReferenceRange>,
    m: &Measure,
    citations: &Citations,
) -> (String, String) {
    match rr {
        Some(ReferenceRange {
            low: Some(l),
            high: Some(h),
            source,
            ..
        }) => {
            let d = m.decimals;
            let src = match source {
                ReferenceSource::Cohort { n_subjects } => {
                    format!("healthy subjects of this cohort (n = {n_subjects})")
                }
                ReferenceSource::Published(c) => {
                    format!("published normal values [{}]", citations.number(c))
                }
                ReferenceSource::None => String::new(),
            };
            (
                format!(
                    "{}–{}",
                    fmt(Some(l * m.scale), d),
                    fmt(Some(h * m.scale), d)
                ),
                src,
            )
        }
        Some(r) => (
            format!("no reference (n = {})", r.n_reference),
            // the reason is in section 2's note (one line here keeps the page count)
            if no_published_reason(&r.column).is_some() {
                "too few healthy subjects; no published range (section 2)".into()
            } else {
                "too few healthy subjects".into()
            },
        ),
        None => ("no reference".into(), "none available".into()),
    }
}

/// One side's cell: the value with its mark and flag, or "not measured: reason".
fn side_cell(r: Option<&&RecordingRow>, m: &Measure, rr: Option<&ReferenceRange>) -> Markup {
    let Some(r) = r else {
        return html! { td.nm { "not measured: no recording" } };
    };
    if let Some(why) = not_measured(r, m.parameter) {
        return html! { td.nm { "not measured: " (why) } };
    }
    let v = r.value(m.parameter).unwrap_or(f64::NAN);
    let (mark, words) = judged(v, rr);
    html! {
        td.num.out[mark.is_some()] {
            (fmt(Some(v * m.scale), m.decimals)) @if let Some(k) = mark { " " (k) }
            " " span.flagword { (words) }
        }
    }
}

/// One plain sentence: what lies outside its range and what was not measured.
fn headline(sides: &[&RecordingRow], reference: &Reference) -> Markup {
    let mut outside: Vec<String> = Vec::new();
    // a leg not analysed is one entry, not one per measure
    let mut missing: Vec<String> = sides
        .iter()
        .filter(|r| !r.is_ok())
        .map(|r| format!("every measure of the {} leg (not analysed)", r.side))
        .collect();
    for m in &MEASURES {
        let rr = reference.range(m.parameter);
        for r in sides.iter().filter(|r| r.is_ok()) {
            match not_measured(r, m.parameter) {
                Some(_) => missing.push(format!("{} ({})", m.label.to_lowercase(), r.side)),
                None => {
                    let v = r.value(m.parameter).unwrap_or(f64::NAN);
                    if let (Some(_), words) = judged(v, rr) {
                        outside.push(format!("{} {words} ({})", m.label.to_lowercase(), r.side));
                    }
                }
            }
        }
    }
    html! {
        p.headline {
            @if outside.is_empty() {
                "No measured value lies outside its normal range."
            } @else {
                b { "Outside the normal range: " } (outside.join("; ")) "."
            }
            @if !missing.is_empty() {
                " " b { "Not measured: " } (missing.join(", ")) " (reasons in the table)."
            }
        }
        "\n"
    }
}

/// The clinical summary (first screen of the subject page).
pub(crate) fn clinical_summary(
    sides: &[&RecordingRow],
    reference: &Reference,
    citations: &Citations,
    p: &ValidReportParams,
) -> Markup {
    let left = sides.iter().find(|r| r.side == crate::Side::Left);
    let right = sides.iter().find(|r| r.side == crate::Side::Right);
    let limit = p.0.asymmetry_flag_pct;
    let si = |p: Parameter| -> Result<f64, String> {
        let (l, r) = (
            left.ok_or("no left recording")?,
            right.ok_or("no right recording")?,
        );
        if let Some(w) = not_measured(l, p) {
            return Err(format!("left {w}"));
        }
        if let Some(w) = not_measured(r, p) {
            return Err(format!("right {w}"));
        }
        let (a, b) = (
            l.value(p).unwrap_or(f64::NAN),
            r.value(p).unwrap_or(f64::NAN),
        );
        symmetry_index_pct(a, b).ok_or_else(|| "not defined for these values".into())
    };
    let no_pair = match (left, right) {
        (None, None) => Some("no recording".to_string()),
        (Some(l), Some(r)) if !l.is_ok() && !r.is_ok() => {
            Some("neither leg was analysed (see above)".into())
        }
        (None, _) => Some("no left recording".to_string()),
        (_, None) => Some("no right recording".to_string()),
        (Some(l), _) if !l.is_ok() => Some("the left leg was not analysed (see above)".into()),
        (_, Some(r)) if !r.is_ok() => Some("the right leg was not analysed (see above)".into()),
        _ => None,
    };
    html! {
        h2 #summary { "Clinical summary" } "\n"
        (headline(sides, reference))
        table.summary {
            "\n"
            tr { th { "measure (unit)" } th { "left" } th { "right" } th { "normal range" } th { "judged against" } } "\n"
            @for m in &MEASURES {
                @let rr = reference.range(m.parameter);
                @let (range, src) = range_cells(rr, m, citations);
                tr {
                    td { b { (m.label) } " (" (m.unit) ")" }
                    (side_cell(left, m, rr)) (side_cell(right, m, rr))
                    td.num { (range) } td { (src) }
                }
                "\n"
            }
            @if let Some(why) = &no_pair {
                // no asymmetry can be computed: one row says why, not one per measure
                tr {
                    td { b { "Left–right asymmetry" } " (SI %)" }
                    td.nm colspan="2" { "not measured: " (why) }
                    td.num { "|SI| ≤ " (format!("{limit:.0}")) }
                    td { "asymmetry threshold (Robinson et al. 1987)" }
                }
                "\n"
            }
            @for (label, parameter) in ASYMMETRY.iter().filter(|_| no_pair.is_none()) {
                tr {
                    td { b { (label) } " (SI %, left vs right)" }
                    @match si(*parameter) {
                        Ok(v) => {
                            @let flag = v.abs() > limit;
                            td.num.out[flag] colspan="2" {
                                (format!("{v:+.1}")) @if flag { " ◆" } " "
                                span.flagword { (if flag { "asymmetric" } else { "symmetric" }) }
                            }
                        }
                        Err(why) => { td.nm colspan="2" { "not measured: " (why) } }
                    }
                    td.num { "|SI| ≤ " (format!("{limit:.0}")) }
                    td { "asymmetry threshold (Robinson et al. 1987)" }
                }
                "\n"
            }
        }
        "\n"
        p.meta {
            "▲ above, ▼ below the normal range; ◆ asymmetry beyond the threshold (also shaded). "
            "SI = 100·(L − R)/((L + R)/2) %: positive when the left value is larger. "
            "The shank angles (WQK, PBI, BDK) and gait stability (STA) are in section 2 with their own reference."
        }
        "\n"
    }
}
