//! Section 2 of the per-subject page: the parameter table (each side against the reference
//! range, ▲/▼ marks, the symmetry index, withheld values as "not measured: reason") and the
//! radar of the subject's z-scores.

use maud::{html, Markup};

use super::Citations;
use crate::html::{counted, figure, fmt, side_label};
use crate::plots;
use crate::reference::no_published_reason;
use crate::summary::{asymmetry_cell, value_cells, WhyNotes};
use crate::verdict::{Cell, Quantity, Scope, Verdicts};
use crate::{Reference, ReferenceRange, ReferenceSource};
use crate::{SubjectReport, ValidReportParams};
use ldh_core::cohort::Parameter;
use ldh_core::error::Result;
use ldh_core::output::RecordingRow;

/// The reference range as the table shows it, with its source; without one, how many healthy
/// subjects the cohort had for it (`min_n` needed).
fn range_text(
    rr: Option<&ReferenceRange>,
    q: &Quantity,
    citations: &Citations,
    min_n: usize,
) -> String {
    let dec = q.decimals;
    match rr {
        Some(ReferenceRange {
            low: Some(l),
            high: Some(h),
            source,
            ..
        }) => {
            let src = match source {
                ReferenceSource::Cohort { n_subjects } => {
                    format!("cohort healthy, n = {n_subjects}")
                }
                ReferenceSource::Published(c) => format!("published [{}]", citations.number(c)),
                ReferenceSource::None => String::new(),
            };
            format!(
                "{}–{} ({src})",
                fmt(Some(l * q.scale()), dec),
                fmt(Some(h * q.scale()), dec)
            )
        }
        // "n" is said once in the paragraph above the table (four rows repeated it).
        Some(r) => format!("no reference (n = {} of {min_n} needed)", r.n_reference),
        None => "no reference".into(),
    }
}

/// A side's companion value (the inverse or complement shown beside a quantity), in its own
/// unit, never judged.
fn companion(r: &RecordingRow, p: Parameter) -> Option<String> {
    let v = r
        .value(p)
        .filter(|_| r.is_ok() && r.withheld.reason(p).is_none())?;
    Some(match p {
        Parameter::StepFrequency => format!("{v:.2} steps/s"),
        _ => format!("{:.1} %", 100.0 * v),
    })
}

/// Section 2: every quantity, each side against the reference range, and the symmetry index,
/// rendered from the page's verdicts (the same as the summary's); `radar` (its chart, or
/// nothing) stands between the section's note and the table.
pub(super) fn parameter_table(
    v: &Verdicts,
    sides: &[&RecordingRow],
    reference: &Reference,
    citations: &Citations,
    p: &ValidReportParams,
    notes: &WhyNotes,
    radar: Markup,
) -> Markup {
    let first_note = notes.len();
    let find = |s: ldh_core::Side| sides.iter().find(|r| r.side == s);
    let (left, right) = (find(ldh_core::Side::Left), find(ldh_core::Side::Right));
    let label = |s: ldh_core::Side| match find(s) {
        Some(r) => side_label(r),
        None => s.to_string(),
    };
    // Every cell "not measured": one sentence, not a table of them (the radar has nothing
    // to draw either).
    if let Some(why) = v.all_withheld(|_| true) {
        return html! {
            h2 { "2. Gait parameters" } "\n"
            p { "No gait parameter was measured on either leg, so the table is left out: " (why.join("; ")) "." } "\n"
        };
    }
    html! {
        h2 { "2. Gait parameters" } "\n"
        p.meta {
            "Reference: " (reference.description) " A range without a reference says how many healthy subjects passing every check the cohort has (n) of those it needs. Values outside the reference range are marked ▲ (above) or ▼ (below) and shaded (bounds included, compared as shown). Cadence, walking speed and stride time are one value per walk, from both legs; step frequency (the inverse of step time) and swing (the complement of stance) are shown beside them and judged with them. Symmetry index SI = 100·(L − R)/((L + R)/2) %; |SI| > "
            (format!("{:.0}", p.0.asymmetry_flag_pct)) " % is shaded for step time, stance and stride length (the legs compared with each other, with or without a range) and for the shank angles when they have a reference range."
        }
        "\n"
        // The figure kept whole before the table whose rows may break across pages, so
        // the table fills the printed page around it (a figure after the table left a third
        // of a page blank where it did not fit).
        div.beside { (radar) } "\n"
        table.params {
            "\n"
            tr { th { "parameter" } th { "unit" } th { (label(ldh_core::Side::Left)) } th { (label(ldh_core::Side::Right)) } th { "reference range" } th { "SI (%)" } } "\n"
            @for row in &v.rows {
                @let q = row.q;
                tr {
                    td {
                        (q.parameter.code()) " — " (q.label())
                        @if let Some(c) = q.companion {
                            " (with " (c.code()) ": "
                            (left.and_then(|r| companion(r, c)).unwrap_or("–".into())) " / "
                            (right.and_then(|r| companion(r, c)).unwrap_or("–".into())) ")"
                        }
                    }
                    td { (q.unit()) }
                    (value_cells(row, notes))
                    td { (range_text(reference.range(q.parameter), q, citations, p.0.min_healthy_subjects)) }
                    @match &row.asymmetry {
                        Some(a) => (asymmetry_cell(a, 1, notes)),
                        None => td.num { "–" },
                    }
                }
                "\n"
            }
        }
        "\n"
        (notes.list_from(first_note))
        p { (counted(v.outside(), "value lies", "values lie")) " outside the reference range; " (counted(v.asymmetric(), "asymmetry", "asymmetries")) " beyond the threshold." (no_published_note(reference)) } "\n"
    }
}

/// One sentence on why the parameters without a range here have no published range (none when
/// every parameter has a range).
fn no_published_note(reference: &Reference) -> String {
    let mut why: Vec<(&str, Vec<&str>)> = Vec::new();
    for r in reference.ranges.iter().filter(|r| r.low.is_none()) {
        if let Some(w) = no_published_reason(&r.column) {
            match why.iter_mut().find(|(x, _)| *x == w) {
                Some((_, codes)) => codes.push(&r.code),
                None => why.push((w, vec![&r.code])),
            }
        }
    }
    if why.is_empty() {
        return String::new();
    }
    let parts: Vec<String> = why
        .iter()
        .map(|(w, codes)| format!("{}: {w}", codes.join(", ")))
        .collect();
    format!(" No published range stands in for {}.", parts.join("; "))
}

/// The radar's axes and polygons: the values of the page's verdicts (section 2's table, as
/// shown) as z-scores against their ranges with an SD. A whole-walk quantity (cadence,
/// walking speed, stride time, double support) is one value, drawn on both legs' polygons; a
/// companion (step frequency per leg, swing) is no axis of its own. Issue 50: the "cadence"
/// axis drew each leg's step frequency (z = −4.5 on the right) beside a table whose walk
/// cadence was within normal.
pub(crate) fn radar_series(
    v: &Verdicts,
    sides: &[&RecordingRow],
    reference: &Reference,
) -> (Vec<String>, Vec<(plots::SeriesName, Vec<f64>)>) {
    let axes: Vec<(&crate::verdict::Row, &ReferenceRange)> = v
        .rows
        .iter()
        .filter_map(|row| {
            let rr = reference.range(row.q.parameter)?;
            rr.sd.is_some().then_some((row, rr))
        })
        .collect();
    let series = sides
        .iter()
        .filter(|r| r.is_ok())
        .map(|r| {
            let i = usize::from(r.side == ldh_core::Side::Right);
            let z = axes
                .iter()
                .map(|(row, rr)| {
                    let c = match row.q.scope {
                        Scope::Walk => row.cells.first(),
                        Scope::Side => row.cells.get(i),
                    };
                    match c {
                        Some(Cell::Value { v, .. }) => rr.z(v / row.q.scale()),
                        _ => None,
                    }
                    .unwrap_or(f64::NAN)
                })
                .collect();
            (
                plots::SeriesName {
                    text: side_label(r),
                    side: r.side.known(),
                },
                z,
            )
        })
        .collect();
    let codes = axes
        .iter()
        .map(|(row, _)| row.q.parameter.code().to_string())
        .collect();
    (codes, series)
}

/// Radar of the subject's z-scores against the reference ([`radar_series`]).
pub(super) fn subject_radar(
    s: &SubjectReport,
    v: &Verdicts,
    sides: &[&RecordingRow],
    reference: &Reference,
) -> Result<Markup> {
    let (names, series) = radar_series(v, sides, reference);
    // A shape needs three measured axes on a side: with fewer, the radar shows nothing the
    // table does not (and a real page with a faulty leg printed on a fourth A4 page).
    let shaped = series
        .iter()
        .any(|(_, z)| z.iter().filter(|v| v.is_finite()).count() >= 3);
    if !shaped || names.len() < 3 {
        return Ok(html! {});
    }
    // Name the reference that exists: the cohort's healthy subjects (n > 0) or, without
    // them, the published values (never "the healthy reference" of n = 0, issue 50).
    let cohort_n = reference
        .ranges
        .iter()
        .filter(|r| r.sd.is_some())
        .filter_map(|r| match r.source {
            ReferenceSource::Cohort { n_subjects } => Some(n_subjects),
            _ => None,
        })
        .max();
    let against = match cohort_n {
        Some(n) => format!("this cohort's healthy subjects (n = {n})"),
        None => "published normal values".to_string(),
    };
    let svg = plots::radar_svg(
        &format!("Subject {}: z-scores against {against}", s.subject_id),
        &names,
        &series,
    )?;
    Ok(figure(
        &svg,
        &format!("Radar chart of the values of section 2's table{} as z-scores against its reference (0 = the reference mean, the black ring); left blue, right orange. Cadence, walking speed, stride time and double support are one value per walk, drawn on both legs' polygons. A dot with a black edge lies beyond ±{:.2} SD (abnormal); a gap in a polygon is a parameter not measured on that side (never drawn as 0). The scale stops at ±{:.0} SD: a value beyond it is an open triangle on the rim{}.", mean_of(sides), plots::RADAR_Z_ABNORMAL, plots::RADAR_Z_CLIP, if svg.contains(plots::RADAR_CLIPPED) { " — clipped here, the values are named under the chart" } else { " (none here)" }),
        &[plots::RADAR_SCALE_LABEL],
        plots::RADAR_PRINT,
    ))
}

/// " (the mean of 3 trials (…))" when the page's values are a mean of trials, else "".
fn mean_of(sides: &[&RecordingRow]) -> String {
    sides
        .iter()
        .find_map(|r| r.trial_mean.as_ref())
        .map_or_else(String::new, |t| format!(" (the {t})"))
}
