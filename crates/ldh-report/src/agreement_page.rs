//! `agreement.html`, the page `ldh agree` writes beside its tables (`docs/agreement.md`,
//! "The page"): a summary in plain words, the event table per side and group with the
//! unmatched events, the event-timing error histograms, and per parameter and level the
//! parameter table and a Bland–Altman plot (Bland & Altman 1986, 1999; the bias and limits of
//! agreement with their confidence intervals as `pingouin.plot_blandaltman` draws them).
//!
//! The page frame, CSS, figure numbering and print widths are the reports' (`html.rs`,
//! [`crate::plots::PrintWidth`]); every spliced value is escaped by maud.
//!
//! Which parameters "agree" is said once, in the summary, by one rule: ICC(2,1) ≥
//! [`GOOD_ICC`] (Koo & Li 2016: 0.75 is where "good" agreement begins); a bias whose
//! confidence interval excludes 0 is named as systematic.

use maud::{html, Markup};

use crate::html::{figure, fmt, page};
use crate::plots;
use ldh_core::error::Result;
use ldh_core::output::Parameter;

use ldh_core::agreement::run::{
    AgreementReport, EventAgreement, Level, OffsetSource, ParameterResult, System,
};
use ldh_core::domain::{EventKind, Legs};
use ldh_core::Side;

/// The ICC(2,1) from which a parameter is said to agree with the reference (Koo & Li 2016,
/// "good": 0.75–0.9, "excellent" above).
pub const GOOD_ICC: f64 = 0.75;

/// The event kinds, in the order of the page's tables and figures.
const EVENT_KINDS: [EventKind; 2] = [EventKind::HeelStrike, EventKind::ToeOff];

/// The parameter's name and unit for a column (the column itself when it is no parameter).
fn name_unit(column: &str) -> (String, String) {
    match Parameter::from_column(column) {
        Ok(p) => (p.name().to_string(), p.unit().to_string()),
        Err(_) => (column.to_string(), "value".to_string()),
    }
}

fn ms(x: Option<f64>) -> String {
    fmt(x.map(|v| v * 1e3), 1)
}

fn pct(x: Option<f64>) -> String {
    fmt(x.map(|v| v * 1e2), 1)
}

fn event_name(kind: EventKind) -> &'static str {
    match kind {
        EventKind::HeelStrike => "heel strikes",
        EventKind::ToeOff => "toe offs",
    }
}

/// The summary in plain words: events matched, timing bias and limits, which parameters agree.
fn summary(r: &AgreementReport) -> Markup {
    let k = r.params.loa_sd_multiplier;
    let both: Vec<&EventAgreement> = r.events.iter().filter(|e| e.side == Legs::Both).collect();
    let events: Vec<String> = both
        .iter()
        .map(|e| {
            let s = &e.summary;
            let limits = match (s.bias_s, s.sd_s) {
                (Some(b), Some(sd)) => format!(
                    ", timing bias {} ms (limits of agreement {} to {} ms)",
                    ms(Some(b)),
                    ms(Some(b - k * sd)),
                    ms(Some(b + k * sd))
                ),
                _ => String::new(),
            };
            format!(
                "{} of {} reference {} were matched ({} %){}",
                s.n_matched,
                s.n_reference,
                event_name(e.event),
                pct(s.recall),
                limits
            )
        })
        .collect();
    let false_pos = r
        .unmatched_events
        .iter()
        .filter(|u| u.system == System::Ldh)
        .count();
    let label = |p: &ParameterResult| {
        let (n, _) = name_unit(&p.parameter);
        format!("{n} (per {})", p.level)
    };
    let mut good = Vec::new();
    let mut poor = Vec::new();
    let mut none = Vec::new();
    let mut biased = Vec::new();
    for p in &r.parameters {
        match &p.agreement {
            Some(a) if a.icc.icc_2_1.value >= GOOD_ICC => good.push(label(p)),
            Some(_) => poor.push(label(p)),
            None => none.push(label(p)),
        }
        if let Some(a) = &p.agreement {
            if a.limits.bias_ci.0 > 0.0 || a.limits.bias_ci.1 < 0.0 {
                biased.push(label(p));
            }
        }
    }
    let list = |v: &[String]| v.join(", ");
    html! {
        div.headline {
            @if !events.is_empty() {
                p { (events.join("; ")) ". " (false_pos) " ldh events inside the span the reference covers had no reference partner (tolerance " (r.params.tolerance_s * 1e3) " ms)." }
            }
            @if !r.parameters.is_empty() {
                p {
                    @if !good.is_empty() { "Agree with the reference (ICC(2,1) ≥ " (GOOD_ICC) "): " (list(&good)) ". " }
                    @if !poor.is_empty() { "Do not agree (ICC(2,1) < " (GOOD_ICC) "): " (list(&poor)) ". " }
                    @if !none.is_empty() { "Not computed (too few pairs or constant values): " (list(&none)) ". " }
                    @if !biased.is_empty() { "A systematic bias (its 95 % interval excludes 0): " (list(&biased)) "." }
                }
            }
        }
    }
}

/// The event table: pooled rows, then per group.
fn event_table(r: &AgreementReport) -> Markup {
    html! {
        table {
            tr { th { "group" } th { "event" } th { "side" } th { "ldh" } th { "reference" } th { "matched" }
                 th { "recall" } th { "precision" } th { "F1" } th { "bias (ms)" } th { "SD (ms)" } th { "MAE (ms)" } th { "P95 |error| (ms)" } }
            @for e in r.events.iter().chain(&r.events_by_group) {
                @let s = &e.summary;
                tr {
                    td { (e.group) } td { (e.event) } td { (e.side) }
                    td.num { (s.n_ldh) } td.num { (s.n_reference) } td.num { (s.n_matched) }
                    td.num { (fmt(s.recall, 3)) } td.num { (fmt(s.precision, 3)) } td.num { (fmt(s.f1, 3)) }
                    td.num { (ms(s.bias_s)) } td.num { (ms(s.sd_s)) } td.num { (ms(s.mae_s)) } td.num { (ms(s.p95_abs_s)) }
                }
            }
        }
    }
}

/// Unmatched events per system, event kind and side.
fn unmatched(r: &AgreementReport) -> Markup {
    let count = |system: System, event: EventKind, side: Side| {
        r.unmatched_events
            .iter()
            .filter(|u| u.system == system && u.event == event && u.side == side)
            .count()
    };
    html! {
        p { "Unmatched events: " (r.unmatched_events.iter().filter(|u| u.system == System::Reference).count())
            " reference events missed by ldh, " (r.unmatched_events.iter().filter(|u| u.system == System::Ldh).count())
            " ldh events without a reference partner (every one is listed in agreement.json)." }
        table {
            tr { th { "event" } th { "side" } th { "reference events missed" } th { "ldh events unpaired" } }
            @for ev in EVENT_KINDS { @for side in [Side::Left, Side::Right] {
                tr { td { (ev) } td { (side) } td.num { (count(System::Reference, ev, side)) } td.num { (count(System::Ldh, ev, side)) } }
            } }
        }
    }
}

/// The timing histograms of HS and TO.
fn histograms(r: &AgreementReport) -> Result<Markup> {
    let mut figs = Vec::new();
    for ev in EVENT_KINDS {
        let e: Vec<f64> = r
            .event_pairs
            .iter()
            .filter(|p| p.event == ev)
            .map(|p| p.error_s * 1e3)
            .collect();
        if e.is_empty() {
            continue;
        }
        let svg =
            plots::timing_histogram_svg(&format!("Timing error of the {}", event_name(ev)), &e)?;
        let (w, _) = plots::histogram_bins(&e, 1.0);
        figs.push(figure(
            &svg,
            &format!(
                "Timing error of the {} {} matched {}, ldh − reference (ms), both sides and every subject; bars: events per {w} ms bin; solid line: the bias; dashed line: 0.",
                e.len(),
                ev,
                event_name(ev)
            ),
            &[plots::TIMING_X_LABEL, plots::TIMING_Y_LABEL],
            plots::TIMING_PRINT,
        ));
    }
    Ok(html! { @for f in figs { (f) } })
}

/// The parameter table.
fn parameter_table(r: &AgreementReport) -> Markup {
    html! {
        table {
            tr { th { "level" } th { "parameter" } th { "n" } th { "bias [95 % CI]" } th { "limits of agreement" }
                 th { "MAE (relative)" } th { "ICC(2,1) [95 % CI]" } th { "ICC(3,1)" } th { "r" } }
            @for p in &r.parameters {
                @let (name, unit) = name_unit(&p.parameter);
                tr {
                    td { (p.level) } td { (name) " (" (unit) ")" }
                    @match &p.agreement {
                        Some(a) => {
                            td.num { (a.n_pairs) }
                            td.num { (format!("{:+.4} [{:+.4}, {:+.4}]", a.limits.bias, a.limits.bias_ci.0, a.limits.bias_ci.1)) }
                            td.num { (format!("{:+.4} to {:+.4}", a.limits.lower, a.limits.upper)) }
                            td.num { (format!("{:.4} ({:.1} %)", a.mae, a.relative_mae * 100.0)) }
                            td.num { (format!("{:.3} [{:.3}, {:.3}]", a.icc.icc_2_1.value, a.icc.icc_2_1.ci_low, a.icc.icc_2_1.ci_high)) }
                            td.num { (fmt(Some(a.icc.icc_3_1.value), 3)) }
                            td.num { (fmt(Some(a.pearson_r), 3)) }
                        }
                        None => {
                            td.num { (p.pairs.len()) }
                            td.nm colspan="6" { "not computed: " (p.not_computed.as_deref().unwrap_or("")) }
                        }
                    }
                }
            }
        }
    }
}

/// The points of a parameter's Bland–Altman plot, one series per side.
pub fn bland_altman_points(p: &ParameterResult) -> Vec<plots::BlandAltmanSeries> {
    [Side::Left, Side::Right]
        .iter()
        .map(|side| {
            let pts = p
                .pairs
                .iter()
                .filter(|q| q.side == *side)
                .filter_map(|q| Some(((q.ldh? + q.reference?) / 2.0, q.ldh? - q.reference?)))
                .collect();
            (plots::SeriesName::of_side(*side, side.to_string()), pts)
        })
        .filter(|s: &plots::BlandAltmanSeries| !s.1.is_empty())
        .collect()
}

/// One Bland–Altman figure per parameter whose agreement was computed.
fn bland_altman(r: &AgreementReport) -> Result<Markup> {
    let mut figs = Vec::new();
    for p in &r.parameters {
        let Some(a) = &p.agreement else { continue };
        let (name, unit) = name_unit(&p.parameter);
        let x = format!("mean of ldh and reference ({unit})");
        let y = format!("ldh − reference ({unit})");
        let series = bland_altman_points(p);
        let what = if p.level == Level::Stride {
            "stride"
        } else {
            "recording (one leg of one trial)"
        };
        let svg = plots::bland_altman_svg(
            &format!("{name}, per {}", p.level),
            &x,
            &y,
            &series,
            &a.limits,
        )?;
        figs.push(figure(
            &svg,
            &format!(
                "Bland–Altman plot of the {name} ({unit}), one dot per {what} ({} pairs; left blue, right orange): bias {:+.4} (solid line, grey band its 95 % CI), limits of agreement {:+.4} to {:+.4} (bias ± {} SD, dashed lines, blue bands their 95 % CIs).",
                a.n_pairs, a.limits.bias, a.limits.lower, a.limits.upper, r.params.loa_sd_multiplier
            ),
            &[&x, &y],
            plots::BLAND_ALTMAN_PRINT,
        ));
    }
    Ok(html! { @for f in figs { (f) } })
}

/// The file names of the reference files (no machine's folders).
fn file_names(r: &AgreementReport) -> String {
    r.reference_files
        .iter()
        .map(|f| crate::html::base_name(f))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `agreement.html` for a report.
pub fn agreement_html(r: &AgreementReport) -> Result<String> {
    let body = html! {
        h1 { "Agreement with the reference" } "\n"
        p.meta { "Reference: " (file_names(r)) ". Events match within " (r.params.tolerance_s) " s. Differences are ldh − reference. "
                 @if !r.groups.is_empty() { "Subjects: " (r.groups.iter().map(|g| format!("{} {}", g.subjects, g.group)).collect::<Vec<_>>().join(", ")) "." } } "\n"
        (summary(r)) "\n"
        @if r.offsets.iter().any(|o| o.source != OffsetSource::None) {
            h2 { "Clock offsets" }
            table {
                tr { th { "subject" } th { "trial" } th { "ldh − reference clock (s)" } th { "source" } }
                @for o in &r.offsets { tr { td { (o.subject_id) } td { (o.trial_id) } td.num { (format!("{:+.4}", o.offset_s)) } td { (o.source) } } }
            }
        }
        @if !r.events.is_empty() {
            h2 { "Events" } "\n"
            (event_table(r)) "\n"
            (unmatched(r)) "\n"
            (histograms(r)?) "\n"
        }
        @if !r.parameters.is_empty() {
            h2 { "Parameters" } "\n"
            p { (r.strides_matched) " of " (r.reference_strides) " reference strides matched an ldh stride." }
            (parameter_table(r)) "\n"
            (bland_altman(r)?) "\n"
        }
        h2 { "Methods" }
        p.meta { "Events are matched one to one (mutual nearest within the tolerance, gaitmap's rule); recall = matched / reference events, precision = matched / ldh events. Limits of agreement: bias ± " (r.params.loa_sd_multiplier) " SD of the differences, with approximate confidence intervals (Bland & Altman 1999). ICC(2,1): absolute agreement (Shrout & Fleiss 1979); ≥ 0.75 is 'good' (Koo & Li 2016). Formulas and their pingouin / scipy parity: docs/agreement.md." }
    };
    Ok(page("ldh agree: agreement with the reference", body))
}
