//! The per-subject page: one function per section, in page order.

// The section helpers pass plot errors on; `LdhError` is over clippy's 128-byte limit everywhere
// (issue 14 item 7 shrinks it), so the lint is silenced here rather than reported once per helper.
#![allow(clippy::result_large_err)]

use maud::{html, Markup};

use super::cycle::cycle_section;
use super::headline::{headline, make as make_headline};
use super::html::{count, fmt, page, red_box, side_label, VERSION};
use super::summary::{clinical_summary, WhyNotes};
use super::verdict::verdicts;
use super::visits::{visit_changes, visits_section};
use super::{LegTrace, ValidReportParams};
use super::{Reference, ReferenceRange, ReferenceSource, SubjectReport};
use crate::cohort::PARAMETERS;
use crate::error::Result;
use crate::output::{RecordingRow, StrideRow};

mod ident;
mod parameters;
mod signals;

use parameters::{parameter_table, subject_radar};
use signals::{signals, stride_by_stride};

/// The per-subject report as an HTML page.
pub fn subject_html(
    s: &SubjectReport,
    reference: &Reference,
    p: &ValidReportParams,
) -> Result<String> {
    let own = person_sides(&s.recordings);
    let sides: Vec<&RecordingRow> = own.iter().collect();
    let citations = Citations::of(reference);
    // Every verdict of the page, made once: the headline, the summary and section 2 render it.
    let v = verdicts(&sides, reference, p.0.asymmetry_flag_pct);
    // Why values were not measured: numbered once for the page, listed under the first table.
    let notes = WhyNotes::default();
    let body = html! {
        (header(s, &sides))
        h2 #summary { "Clinical summary" } "\n"
        (headline(&make_headline(&v, &sides, &s.recordings, reference, &s.context)))
        (warning_box(&sides))
        (red_box("Missing from this report.", &missing(s)))
        (clinical_summary(&v, reference, &citations, p, &notes))
        @if let Some(c) = visit_changes(&s.recordings, &s.context) {
            (visits_section(&c, html! { h2 #visits { "Change between visits" } "\n" }))
        }
        (recordings_table(&sides))
        (reading_notes(s))
        (excluded_strides(&s.strides))
        (parameter_table(&v, &sides, reference, &citations, p, &notes))
        (subject_radar(s, &sides, reference)?)
        (cycle_section(s, &sides, reference, p)?)
        p.print-only.meta { "Printed report: the signal figures (section 3), the stride-by-stride plots (section 4) and the technical appendix (every quality finding with its code) are in the on-screen report." } "\n"
        div.screen-only { (signals(s)?) (stride_by_stride(&s.strides)?) } "\n"

        (classifier(s))
        (methods(&citations))
        div.screen-only { (appendix(&sides)) } "\n"
    };
    Ok(page(&format!("Gait report — {}", s.subject_id), body))
}

/// One row per side; a person's several trials averaged (docs/input.md "Trials").
pub(crate) fn person_sides(recordings: &[RecordingRow]) -> Vec<RecordingRow> {
    let all: Vec<&RecordingRow> = recordings.iter().collect();
    [crate::Side::Left, crate::Side::Right]
        .into_iter()
        .filter_map(|side| crate::cohort::person_row(&all, side))
        .collect()
}

/// The published sources cited by the parameter table, numbered in table order.
pub(crate) struct Citations(Vec<String>);

impl Citations {
    pub(crate) fn of(reference: &Reference) -> Citations {
        let mut v: Vec<String> = Vec::new();
        for par in PARAMETERS.iter() {
            if let Some(ReferenceRange {
                low: Some(_),
                high: Some(_),
                source: ReferenceSource::Published(c),
                ..
            }) = reference.range(*par)
            {
                if !v.contains(c) {
                    v.push(c.clone());
                }
            }
        }
        Citations(v)
    }
    /// The number `[k]` of a citation.
    pub(crate) fn number(&self, c: &str) -> usize {
        self.0.iter().position(|x| x == c).unwrap_or(0) + 1
    }
}

fn header(s: &SubjectReport, sides: &[&RecordingRow]) -> Markup {
    let group = sides
        .iter()
        .map(|r| crate::output::labels::text(&r.group))
        .find(|g| !g.is_empty())
        .unwrap_or("");
    let model = sides.first().map(|r| r.model.as_str()).unwrap_or("");
    let affected = sides
        .iter()
        .map(|r| crate::output::labels::text(&r.affected_side))
        .find(|a| !a.is_empty() && *a != "none");
    html! {
        h1 { "Gait report: subject " (s.subject_id) } "\n"
        p.meta {
            "Two shank-worn IMUs; attitude model " b { (model) }
            @if !group.is_empty() {
                "; group in the manifest: " b { (group) }
                @if let Some(a) = affected { ", affected side " b { (a) } }
            }
            @if let Some(t) = sides.iter().map(|r| r.trial_id.as_str()).find(|t| t.starts_with("mean of")) {
                "; values are the " b { (t) } " (plots: trial "
                (s.recordings.first().map_or("", |r| r.trial_id.as_str())) ")"
            }
            ". Generated by ldh " (VERSION) ". Times are seconds from each recording's first sample."
            @if let Some(c) = &s.context.calibration { " " (c.sentence()) }
            (ident::identification_inline(&s.recordings))
        }
        "\n"
        (ident::identification_list(&s.recordings))
    }
}

/// Findings whose only effect is a value withheld (said in the headline's "could not be
/// measured") or that change no number: they stay out of "Check before reading".
const NOT_FOR_THE_BOX: [&str; 4] = [
    crate::pipeline::codes::SENSOR_HEIGHT_UNKNOWN,
    crate::pipeline::codes::SV_NOISE,
    crate::pipeline::codes::SV_UNCHECKED,
    crate::pipeline::codes::TOO_LITTLE_STEADY,
];

/// The findings of both legs, each once: (severity, code, text, the legs that have it).
fn findings<'a>(
    sides: &[&'a RecordingRow],
) -> Vec<(crate::pipeline::Severity, &'a str, String, Vec<&'a str>)> {
    let mut items: Vec<(crate::pipeline::Severity, &str, String, Vec<&str>)> = Vec::new();
    for r in sides {
        for w in r.warnings.iter() {
            let text = w.to_string();
            match items.iter_mut().find(|x| x.2 == text) {
                Some(x) => x.3.push(r.side.as_str()),
                None => items.push((w.severity, w.code.as_str(), text, vec![r.side.as_str()])),
            }
        }
    }
    items.sort_by_key(|x| std::cmp::Reverse(x.0));
    items
}

/// "Check before reading the numbers": the quality problems that change the numbers (sensor
/// faults, drift, gyroscope bias not removed…), in their own words, each once; notes and
/// findings that only withhold a value are in the technical appendix.
fn warning_box(sides: &[&RecordingRow]) -> Markup {
    // Each message once, with the legs that have it ("both legs" when both say the same).
    let mut found: Vec<(String, Vec<String>)> = Vec::new();
    for r in sides {
        for w in r
            .warnings
            .at_least(crate::pipeline::Severity::Warning)
            .filter(|w| !NOT_FOR_THE_BOX.contains(&w.code.as_str()))
        {
            let side = r.side.to_string();
            match found.iter_mut().find(|(m, _)| *m == w.message) {
                Some((_, legs)) if !legs.contains(&side) => legs.push(side),
                Some(_) => {}
                None => found.push((w.message.clone(), vec![side])),
            }
        }
    }
    let items: Vec<String> = found
        .into_iter()
        .map(|(m, legs)| {
            let who = if legs.len() > 1 {
                "both legs".to_string()
            } else {
                legs.join("")
            };
            format!("{who}: {m}")
        })
        .collect();
    red_box("Check before reading the numbers.", &items)
}

/// The technical appendix: every quality finding with its code and severity, each said once
/// with the legs (and how many) that have it.
fn appendix(sides: &[&RecordingRow]) -> Markup {
    let items = findings(sides);
    html! {
        h2 #appendix { "Technical appendix: quality findings" } "\n"
        @if items.is_empty() {
            p { "No quality check found anything." } "\n"
        } @else {
            p.meta { "Codes as in recordings.csv (docs/quality.md); each finding once, with the legs that have it." } "\n"
            ul.meta {
                @for (_, _, text, legs) in &items {
                    @let who = if legs.len() > 1 { "both legs" } else { legs[0] };
                    li { (who) ": " (text) } "\n"
                }
            }
            "\n"
        }
    }
}

/// What the page cannot show, and why.
fn missing(s: &SubjectReport) -> Vec<String> {
    let mut missing: Vec<String> = Vec::new();
    for side in ["left", "right"] {
        match s.recordings.iter().find(|r| r.side.as_str() == side) {
            None => missing.push(format!("No {side} recording was given.")),
            Some(r) if !r.is_ok() => missing.push(format!(
                "The {side} recording could not be analysed: {}",
                r.error
            )),
            _ => {}
        }
    }
    if s.traces.is_none() {
        missing.push("Signal plots are not available: this report was built from result tables without signal traces (run `ldh analyze --report` to include them).".into());
    }
    missing
}

/// The recordings-table row of the steady window (shown when strides were excluded).
const STEADY_FACT: &str = "steady walking used (docs/pipeline.md)";

/// Names of the rows of the recordings table.
const FACTS: [&str; 11] = [
    "file",
    "status",
    "warnings",
    "duration (s)",
    "sampling rate (Hz)",
    "samples replaced as outliers (3 SD of |a|)",
    "clipped samples",
    "mounting",
    "strides detected / used",
    STEADY_FACT,
    "STA",
];

/// The values of [`FACTS`] for one side.
fn facts(r: &RecordingRow) -> [String; 11] {
    let mounting = match (r.mirrored, r.axial_rotation_deg) {
        (Some(m), Some(a)) => format!(
            "{}; rotated {a:.0}° about the shank",
            if m {
                "mirrored (y axis backwards)"
            } else {
                "y axis forwards"
            }
        ),
        _ => "–".into(),
    };
    [
        super::html::base_name(&r.source),
        if r.is_ok() {
            "analysed".into()
        } else {
            format!("failed: {}", r.error)
        },
        if r.warnings.is_empty() {
            "none".into()
        } else {
            let codes: Vec<&str> = r.warnings.iter().map(|w| w.code.as_str()).collect();
            format!("{} (technical appendix)", codes.join(", "))
        },
        fmt(r.duration_s, 1),
        fmt(r.fs_hz, 2),
        count(r.outliers_replaced),
        count(r.clipped_samples),
        mounting,
        match (r.strides_total, r.strides_valid) {
            (Some(t), Some(v)) => format!("{t} / {v}"),
            _ => "–".into(),
        },
        steady_fact(r),
        if r.sta_status.is_empty() {
            "computed".into()
        } else {
            format!("not computed: {}", r.sta_status)
        },
    ]
}

/// The steady window of a side in words: "12.0–80.0 s (4 strides at the start excluded)".
fn steady_fact(r: &RecordingRow) -> String {
    let (Some(a), Some(b)) = (r.steady_start_s, r.steady_end_s) else {
        return "–".into();
    };
    let ends = match (
        r.steady_excluded_start.unwrap_or(0),
        r.steady_excluded_end.unwrap_or(0),
    ) {
        (0, 0) => "the whole walk".to_string(),
        (x, 0) => format!("{x} stride(s) at the start excluded"),
        (0, y) => format!("{y} stride(s) at the end excluded"),
        (x, y) => format!("{x} stride(s) at the start and {y} at the end excluded"),
    };
    format!("{a:.1}–{b:.1} s ({ends})")
}

fn recordings_table(sides: &[&RecordingRow]) -> Markup {
    let values: Vec<[String; 11]> = sides.iter().map(|r| facts(r)).collect();
    html! {
        h2 { "1. Recordings" } "\n"
        table {
            "\n"
            tr { th { "fact" } @for r in sides { th { (side_label(r)) } } } "\n"
            @for (i, name) in FACTS.iter().enumerate() {
                tr { td { (name) } @for v in &values { td { (v[i]) } } } "\n"
            }
        }
        "\n"
    }
}

/// What reading and alignment found, per leg (needs the traces).
fn reading_notes(s: &SubjectReport) -> Markup {
    let legs: &[LegTrace] = s.traces.as_ref().map(|t| &t.legs[..]).unwrap_or(&[]);
    html! {
        @for leg in legs {
            @let notes = leg_notes(leg);
            @if !notes.is_empty() {
                p.note { b { (leg.side) " — what reading and alignment found:" } " " (notes.join(" · ")) } "\n"
            }
        }
    }
}

fn leg_notes(leg: &LegTrace) -> Vec<String> {
    let mut notes: Vec<String> = leg.alignment_notes.clone();
    notes.extend(leg.read_notes.iter().cloned());
    for (from, len) in &leg.gaps_s {
        notes.push(format!(
            "gap of {len:.2} s after t = {from:.2} s (file clock)"
        ));
    }
    notes
}

/// Strides excluded from the parameters, counted by reason (one row each) and side (a column
/// each, in the order the sides first appear).
fn excluded_strides(strides: &[StrideRow]) -> Markup {
    let mut sides: Vec<String> = Vec::new();
    let mut excl: Vec<(String, Vec<usize>)> = Vec::new();
    for st in strides.iter().filter(|st| !st.valid) {
        let side = st.side.to_string();
        let col = match sides.iter().position(|s| *s == side) {
            Some(c) => c,
            None => {
                sides.push(side);
                sides.len() - 1
            }
        };
        let reason = reason_kind(&st.reason);
        let row = match excl.iter().position(|e| e.0 == reason) {
            Some(r) => r,
            None => {
                excl.push((reason, Vec::new()));
                excl.len() - 1
            }
        };
        let counts = &mut excl[row].1;
        counts.resize(counts.len().max(col + 1), 0);
        counts[col] += 1;
    }
    html! {
        @if excl.is_empty() {
            p { "No stride was excluded." } "\n"
        } @else {
            h3 { "Strides excluded from the parameters" } "\n"
            table {
                tr { th { "reason" } @for side in &sides { th { (side) " (strides)" } } } "\n"
                @for (reason, counts) in &excl {
                    tr {
                        td { (reason) }
                        @for c in 0..sides.len() { td.num { (counts.get(c).copied().unwrap_or(0)) } }
                    } "\n"
                }
            }
            "\n"
        }
    }
}

/// The kind of an exclusion reason: each "; "-separated reason without its numbers in
/// parentheses ("turning (124 deg heading change)" → "turning"), so strides group by kind.
fn reason_kind(reason: &str) -> String {
    if reason.trim().is_empty() {
        return "excluded".into();
    }
    let mut kinds: Vec<String> = Vec::new();
    for part in reason.split("; ") {
        let k = part.split(" (").next().unwrap_or(part).trim().to_string();
        if !k.is_empty() && !kinds.contains(&k) {
            kinds.push(k);
        }
    }
    kinds.join("; ")
}

/// Section 5: the classifier's output, worded as decision support.
fn classifier(s: &SubjectReport) -> Markup {
    let Some((preds, classes, desc)) = &s.predictions else {
        return html! {};
    };
    html! {
        h2 { "5. Classifier output (decision support)" } "\n"
        p.support {
            b { "Decision support, not a diagnosis." }
            " A statistical model (" (desc) ") compares this subject's gait parameters with those of the people it was trained on. Its output is one piece of evidence for the clinician, who weighs it with the examination and imaging; it can be wrong, especially for people unlike the training cohort."
        }
        "\n"
        table {
            tr { th { "side" } th { "most similar class" } @for c in classes { th { "p(" (c) ")" } } th { "note" } } "\n"
            @for pr in preds {
                tr {
                    td { (pr.side) }
                    td { (pr.predicted_class.as_deref().unwrap_or("no output")) }
                    @for k in 0..classes.len() {
                        td.num { (pr.probabilities.as_ref().and_then(|v| v.get(k)).map(|x| format!("{x:.2}")).unwrap_or("–".into())) }
                    }
                    td { (pr.note) }
                }
                "\n"
            }
        }
        "\n"
    }
}

fn methods(citations: &Citations) -> Markup {
    html! {
        h2 { "Methods" } "\n"
        p.meta { "Accelerometer and gyroscope are low-pass filtered (4th-order Butterworth, zero phase) after 3-SD outliers of |a| are replaced; the attitude is estimated with an adaptive Kalman filter bank with smoothing (Wang et al.); heel strikes and toe offs come from the sagittal angular velocity; stride length from the integrated shank motion with an ankle lever-arm correction; STA is the largest Lyapunov exponent of the sagittal angular velocity (Rosenstein). Parameters are means over the valid strides." } "\n"
        @if !citations.0.is_empty() {
            h3 { "References for the published ranges" } "\n"
            ol.refs { @for r in &citations.0 { li { (r) } } } "\n"
        }
    }
}
