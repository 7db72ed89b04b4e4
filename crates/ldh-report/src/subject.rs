//! The per-subject page: one function per section, in page order.

// The section helpers pass plot errors on; `LdhError` is over clippy's 128-byte limit everywhere
// (issue 14 item 7 shrinks it), so the lint is silenced here rather than reported once per helper.
#![allow(clippy::result_large_err)]

use maud::{html, Markup};

use super::cycle::cycle_section;
use super::headline::{headline, make as make_headline};
use super::html::{count, counted, fmt, page, red_box, side_label, VERSION};
use super::reference::Citations;
use super::summary::{clinical_summary, WhyNotes};
use super::trials::person_trials;
use super::verdict::verdicts;
use super::visits::{visit_changes, visits_section};
use super::{LegTrace, ValidReportParams};
use super::{Reference, SubjectReport};
use ldh_core::error::Result;
use ldh_core::gait::StrideCode;
use ldh_core::output::{RecordingRow, StrideRow};
use ldh_core::Side;

mod ident;
mod parameters;
mod signals;

#[cfg(test)]
pub(crate) use parameters::radar_series;
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
    // The figures show one trial (the first of several: its traces and strides); the tables
    // count every trial's strides, as the recordings table sums them.
    let plotted = plotted_trial(s);
    let body = html! {
        (header(s, &sides))
        h2 #summary { "Clinical summary" } "\n"
        (headline(&make_headline(&v, &sides, &s.recordings, reference, &s.context)))
        (warning_box(&sides, &s.recordings))
        (red_box("Missing from this report.", &missing(s)))
        (clinical_summary(&v, reference, &citations, p, &notes))
        @if let Some(c) = visit_changes(&s.recordings, &s.context) {
            (visits_section(&c, html! { h2 #visits { "Change between visits" } "\n" }))
        } @else {
            (person_trials(&s.recordings, &s.context, || html! { h2 #trials { "Trials side by side" } "\n" }))
        }
        (recordings_table(&sides))
        (excluded_strides(&s.strides))
        (parameter_table(&v, &sides, reference, &citations, p, &notes, subject_radar(s, &v, &sides, reference)?))
        (cycle_section(&plotted, &sides, reference, p)?)
        p.print-only.meta { "Printed report: the signal figures (section 3), the stride-by-stride plots (section 4), the methods and the technical appendix (sampling, outliers, mounting, what reading noticed, every quality finding with its code) are in the on-screen report." } "\n"
        div.screen-only { (signals(&plotted)?) (stride_by_stride(&plotted.strides)?) } "\n"

        (classifier(s))
        (methods(&citations))
        div.screen-only { (appendix(s, &sides)) } "\n"
    };
    Ok(page(&format!("Gait report — {}", s.subject_id), body))
}

/// `s` as its figures show it: with several trials, only the first trial's strides (the trial
/// whose traces were kept).
fn plotted_trial(s: &SubjectReport) -> std::borrow::Cow<'_, SubjectReport> {
    match crate::results::first_trial(&s.recordings).1 {
        Some(t) if s.strides.iter().any(|r| r.trial_id != t) => {
            let mut one = s.clone();
            one.strides.retain(|r| r.trial_id == t);
            std::borrow::Cow::Owned(one)
        }
        _ => std::borrow::Cow::Borrowed(s),
    }
}

/// One row per side; a person's several trials averaged (docs/input.md "Trials").
pub(crate) fn person_sides(recordings: &[RecordingRow]) -> Vec<RecordingRow> {
    let all: Vec<&RecordingRow> = recordings.iter().collect();
    [ldh_core::Side::Left, ldh_core::Side::Right]
        .into_iter()
        .filter_map(|side| ldh_core::cohort::person_row(&all, side))
        .collect()
}

fn header(s: &SubjectReport, sides: &[&RecordingRow]) -> Markup {
    let group = sides
        .iter()
        .map(|r| ldh_core::output::labels::text(&r.group))
        .find(|g| !g.is_empty())
        .unwrap_or("");
    let model = sides.first().map(|r| r.model.as_str()).unwrap_or("");
    let affected = sides
        .iter()
        .filter_map(|r| r.affected_side.as_ref())
        .find(|a| **a != ldh_core::output::AffectedSide::Neither)
        .map(|a| a.as_str());
    html! {
        h1 { "Gait report: subject " (s.subject_id) } "\n"
        p.meta {
            "Two shank-worn IMUs; attitude model " b { (model) }
            @if !group.is_empty() {
                "; group in the manifest: " b { (group) }
                @if let Some(a) = affected { ", affected side " b { (a) } }
            }
            @if let Some(t) = sides.iter().find_map(|r| r.trial_mean.as_ref()) {
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
/// measured") or that change no number: they stay out of "Check before reading". No quiet
/// standing withholds the two shank angles and changes nothing else; its message, on the
/// clinical page, read as the tool's own reasoning (issue 50's reading of a HuGaDB page). The
/// two clock findings withhold only the timings between the legs, which the headline's "could
/// not be measured" names and its to-do (synchronise the sensors) answers; their measurement
/// (milliseconds of double support and swing) is for the technical appendix. A walk that never
/// became steady is said first in the headline, before the means it qualifies; the rule's
/// numbers (the longest stretch at one pace) are the appendix's.
const NOT_FOR_THE_BOX: [ldh_core::pipeline::WarningCode; 8] = [
    ldh_core::pipeline::codes::CLOCK_OFFSET,
    ldh_core::pipeline::codes::TWO_CLOCKS,
    ldh_core::pipeline::codes::NO_QUIET_STANDING,
    ldh_core::pipeline::codes::SENSOR_HEIGHT_UNKNOWN,
    ldh_core::pipeline::codes::SV_NOISE,
    ldh_core::pipeline::codes::SV_UNCHECKED,
    ldh_core::pipeline::codes::TOO_LITTLE_STEADY,
    ldh_core::pipeline::codes::NEVER_STEADY,
];

/// The findings of both legs, each once: (severity, code, text, the legs that have it).
fn findings<'a>(
    sides: &[&'a RecordingRow],
) -> Vec<(ldh_core::pipeline::Severity, &'a str, String, Vec<&'a str>)> {
    let mut items: Vec<(ldh_core::pipeline::Severity, &str, String, Vec<&str>)> = Vec::new();
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
/// findings that only withhold a value are in the technical appendix. A mean of trials says
/// each trial's findings (`t2: …`): one message every trial gives is one line naming the
/// trials, and one kind of finding given several times in other words on the same legs (a
/// channel spiking at other times) is one line in plain words saying how often and where
/// (each is in the technical appendix).
fn warning_box(sides: &[&RecordingRow], recordings: &[RecordingRow]) -> Markup {
    use ldh_core::pipeline::{Severity, WarningCode};
    let mut trials: Vec<&str> = Vec::new();
    for r in recordings.iter().filter(|r| !r.trial_id.is_empty()) {
        if !trials.contains(&r.trial_id.as_str()) {
            trials.push(&r.trial_id);
        }
    }
    // (code, message without its trial, the trials that give it, the legs that have it, its
    // severity)
    type Found<'a> = (WarningCode, &'a str, Vec<&'a str>, Vec<String>, Severity);
    let mut found: Vec<Found> = Vec::new();
    for r in sides {
        for w in r
            .warnings
            .at_least(ldh_core::pipeline::Severity::Warning)
            .filter(|w| !NOT_FOR_THE_BOX.contains(&w.code))
        {
            let (trial, message) = trials
                .iter()
                .find_map(|t| Some((Some(*t), w.message.strip_prefix(&format!("{t}: "))?)))
                .unwrap_or((None, w.message.as_str()));
            let side = r.side.to_string();
            match found.iter_mut().find(|x| x.1 == message) {
                Some(x) => {
                    if let Some(t) = trial.filter(|t| !x.2.contains(t)) {
                        x.2.push(t);
                    }
                    if !x.3.contains(&side) {
                        x.3.push(side);
                    }
                }
                None => found.push((
                    w.code,
                    message,
                    trial.into_iter().collect(),
                    vec![side],
                    w.severity,
                )),
            }
        }
    }
    let in_trials = |t: &[&str]| match t {
        [] => String::new(),
        [one] => format!("trial {one}"),
        many => format!("trials {}", many.join(", ")),
    };
    let mut items: Vec<String> = Vec::new();
    let mut said = vec![false; found.len()];
    for i in 0..found.len() {
        if said[i] {
            continue;
        }
        let (code, message, t, legs, severity) = &found[i];
        let same: Vec<usize> = (i..found.len())
            .filter(|&j| !said[j] && found[j].0 == *code && found[j].3 == *legs)
            .collect();
        for &j in &same {
            said[j] = true;
        }
        let who = if legs.len() > 1 {
            "both legs".to_string()
        } else {
            legs.join("")
        };
        if same.len() == 1 {
            // A sensor fault's message is the tool's measurement of the fault (how many
            // samples beyond which limit): in plain words here, the numbers in the appendix.
            let said = if *severity == Severity::Fault {
                format!(
                    "{} (what the sensor recorded is in the technical appendix)",
                    code.plain()
                )
            } else {
                message.to_string()
            };
            items.push(match t.as_slice() {
                [] => format!("{who}: {said}"),
                t => format!("{who} ({}): {said}", in_trials(t)),
            });
            continue;
        }
        let mut where_: Vec<&str> = Vec::new();
        for &j in &same {
            for t in &found[j].2 {
                if !where_.contains(t) {
                    where_.push(t);
                }
            }
        }
        let where_ = match where_.as_slice() {
            [] => String::new(),
            w => format!(", in {}", in_trials(w)),
        };
        items.push(format!(
            "{who}: {} ({} times{where_}; each in the technical appendix)",
            code.plain(),
            same.len()
        ));
    }
    red_box("Check before reading the numbers.", &items)
}

/// The technical appendix (on screen only): the recordings' technical facts (warning codes,
/// sampling rate, samples replaced as outliers, clipping, mounting, STA), what reading and
/// alignment noticed, and every quality finding with its code and severity, each said once with
/// the legs that have it — the tool's words, kept off the clinical pages (issue 50).
fn appendix(s: &SubjectReport, sides: &[&RecordingRow]) -> Markup {
    let items = findings(sides);
    html! {
        h2 #appendix { "Technical appendix" } "\n"
        h3 { "Recording details" } "\n"
        (facts_table(sides, &TECHNICAL_FACTS))
        (reading_notes(s))
        h3 { "Quality findings" } "\n"
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
    for side in [Side::Left, Side::Right] {
        match s.recordings.iter().find(|r| r.side == side) {
            None => missing.push(format!("No {side} recording was given.")),
            Some(r) if !r.is_ok() => missing.push(format!(
                "The {side} recording could not be analysed: {}",
                r.error
            )),
            _ => {}
        }
    }
    if s.traces.is_none() {
        missing.push("Signal plots are not available: this report was built from result tables without signal traces.".into());
    }
    missing
}

/// The recordings-table row of the steady window (shown when strides were excluded).
const STEADY_FACT: &str = "steady walking used";

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

/// The values of [`FACTS`] for one side (a mean of trials: the duration and strides of all
/// trials together, said so).
fn facts(r: &RecordingRow) -> [String; 11] {
    let all = if r.trial_mean.is_some() {
        " (all trials)"
    } else {
        ""
    };
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
        format!("{}{all}", fmt(r.duration_s, 1)),
        fmt(r.fs_hz, 2),
        count(r.outliers_replaced),
        count(r.clipped_samples),
        mounting,
        match (r.strides_total, r.strides_valid) {
            (Some(t), Some(v)) => format!("{t} / {v}{all}"),
            _ => "–".into(),
        },
        steady_fact(r),
        sta_fact(&r.parameters.sta_status),
    ]
}

/// STA's line of the facts: "computed", else the core's status, which says "not computed" or
/// "not measured" itself when it starts so (said once), else is the reason it was not computed.
fn sta_fact(status: &str) -> String {
    if status.is_empty() {
        "computed".into()
    } else if status.starts_with("not ") {
        status.into()
    } else {
        format!("not computed: {status}")
    }
}

/// The steady window of a side in words: "12.0–80.0 s (4 strides at the start excluded)".
fn steady_fact(r: &RecordingRow) -> String {
    let excluded = (
        r.steady_excluded_start.unwrap_or(0),
        r.steady_excluded_end.unwrap_or(0),
    );
    let strides = |n: usize| counted(n, "stride", "strides");
    let ends = match excluded {
        // The window is the walk's (both legs'): a leg none of whose strides could be used
        // (a faulty sensor) has none excluded as unsteady, yet its window is not the whole
        // walk (HuGaDB 07_03's right leg read "4.7–95.0 s (the whole walk)" of 96.6 s).
        (0, 0) if r.strides_valid == Some(0) => "no stride of this leg could be used".to_string(),
        (0, 0) => "the whole walk".to_string(),
        (x, 0) => format!("{} at the start excluded", strides(x)),
        (0, y) => format!("{} at the end excluded", strides(y)),
        (x, y) => format!("{} at the start and {y} at the end excluded", strides(x)),
    };
    match (r.steady_start_s, r.steady_end_s) {
        (Some(a), Some(b)) => format!("{a:.1}–{b:.1} s ({ends})"),
        // A mean of trials: each trial has its own window.
        _ if excluded != (0, 0) => format!("each trial's own ({ends})"),
        _ => "–".into(),
    }
}

/// The rows of [`FACTS`] a clinician reads (section 1): the file, whether it was analysed, how
/// long, the strides and the steady walking used.
const CLINICAL_FACTS: [usize; 5] = [0, 1, 3, 8, 9];
/// The rows of [`FACTS`] that are the tool's own (warning codes, rate, outliers, clipping,
/// mounting, STA): in the technical appendix, on screen only (issue 50).
const TECHNICAL_FACTS: [usize; 6] = [2, 4, 5, 6, 7, 10];

/// The table of `rows` of [`FACTS`], one column per side.
fn facts_table(sides: &[&RecordingRow], rows: &[usize]) -> Markup {
    let values: Vec<[String; 11]> = sides.iter().map(|r| facts(r)).collect();
    html! {
        table {
            "\n"
            tr { th { "fact" } @for r in sides { th { (side_label(r)) } } } "\n"
            @for &i in rows {
                tr { td { (FACTS[i]) } @for v in &values { td { (v[i]) } } } "\n"
            }
        }
        "\n"
    }
}

fn recordings_table(sides: &[&RecordingRow]) -> Markup {
    html! {
        h2 { "1. Recordings" } "\n"
        (facts_table(sides, &CLINICAL_FACTS))
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

/// Strides excluded from the parameters, counted by reason code (one row per code, in its
/// plain wording [`StrideCode::plain`], never the stride's own text) and side (a column each,
/// in the order the sides first appear). A stride excluded for several reasons counts under
/// each, so a last row gives the strides excluded for any reason; a stride of a table written
/// without `reason_codes` counts under "reason not recorded".
fn excluded_strides(strides: &[StrideRow]) -> Markup {
    let mut sides: Vec<String> = Vec::new();
    let mut excl: Vec<(Option<StrideCode>, Vec<usize>)> = Vec::new();
    let mut any: Vec<usize> = Vec::new();
    let count = |counts: &mut Vec<usize>, col: usize| {
        counts.resize(counts.len().max(col + 1), 0);
        counts[col] += 1;
    };
    for st in strides.iter().filter(|st| !st.valid) {
        let side = st.side.to_string();
        let col = match sides.iter().position(|s| *s == side) {
            Some(c) => c,
            None => {
                sides.push(side);
                sides.len() - 1
            }
        };
        count(&mut any, col);
        let mut codes: Vec<Option<StrideCode>> = Vec::new();
        for c in st.reason_codes.excluding() {
            if !codes.contains(&Some(*c)) {
                codes.push(Some(*c));
            }
        }
        if codes.is_empty() {
            codes.push(None);
        }
        for code in codes {
            let row = match excl.iter().position(|e| e.0 == code) {
                Some(r) => r,
                None => {
                    excl.push((code, Vec::new()));
                    excl.len() - 1
                }
            };
            count(&mut excl[row].1, col);
        }
    }
    let total = |counts: &[usize]| counts.iter().sum::<usize>();
    let several = excl.iter().map(|e| total(&e.1)).sum::<usize>() > total(&any);
    let cells = |counts: &[usize]| -> Vec<usize> {
        (0..sides.len())
            .map(|c| counts.get(c).copied().unwrap_or(0))
            .collect()
    };
    html! {
        @if excl.is_empty() {
            p { "No stride was excluded." } "\n"
        } @else {
            h3 { "Strides excluded from the parameters" } "\n"
            table {
                tr { th { "reason" } @for side in &sides { th { (side) " (strides)" } } } "\n"
                @for (code, counts) in &excl {
                    tr {
                        td { (code.map_or("reason not recorded".into(), |c| c.plain())) }
                        @for n in cells(counts) { td.num { (n) } }
                    } "\n"
                }
                tr {
                    td { b { "excluded for any reason" } }
                    @for n in cells(&any) { td.num { b { (n) } } }
                } "\n"
            }
            "\n"
            @if several {
                p.note { "A stride excluded for several reasons is counted under each." } "\n"
            }
        }
    }
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

/// The methods (on screen only: the tool's technical detail) and the references of the
/// published ranges the tables cite (printed).
fn methods(citations: &Citations) -> Markup {
    html! {
        div.screen-only { h2 { "Methods" } "\n"
        p.meta { "Accelerometer and gyroscope are low-pass filtered (4th-order Butterworth, zero phase) after 3-SD outliers of |a| are replaced; the attitude is estimated with an adaptive Kalman filter bank with smoothing (Wang et al.); heel strikes and toe offs come from the sagittal angular velocity; stride length from the integrated shank motion with an ankle lever-arm correction; STA is the largest Lyapunov exponent of the sagittal angular velocity (Rosenstein). Parameters are means over the valid strides." } "\n" }
        @if !citations.0.is_empty() {
            h3 { "References for the published ranges" } "\n"
            ol.refs { @for r in &citations.0 { li { (r) } } } "\n"
        }
    }
}
