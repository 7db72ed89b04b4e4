//! Section 2 of the per-subject page: the parameter table (each side against the reference
//! range, ▲/▼ marks, the symmetry index, withheld values as "not measured: reason") and the
//! radar of the subject's z-scores.

use maud::{html, Markup};

use super::Citations;
use crate::cohort::{Parameter, PARAMETERS};
use crate::error::Result;
use crate::output::RecordingRow;
use crate::plots;
use crate::report::html::{decimals, figure, fmt, side_label};
use crate::report::reference::no_published_reason;
use crate::report::{symmetry_index_pct, Reference, ReferenceRange, ReferenceSource};
use crate::report::{SubjectReport, ValidReportParams};

/// `▲`/`▼` when `v` lies above/below the range.
fn out_mark(v: Option<f64>, rr: Option<&ReferenceRange>) -> Option<&'static str> {
    match (v, rr) {
        (Some(v), Some(rr)) => rr.outside(v).filter(|o| *o).map(|_| {
            if rr.low.is_some_and(|l| v < l) {
                "▼"
            } else {
                "▲"
            }
        }),
        _ => None,
    }
}

/// The reference range as the table shows it, with its source; without one, how many healthy
/// subjects the cohort had for it (`min_n` needed).
fn range_text(
    rr: Option<&ReferenceRange>,
    dec: usize,
    citations: &Citations,
    min_n: usize,
) -> String {
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
            format!("{}–{} ({src})", fmt(Some(*l), dec), fmt(Some(*h), dec))
        }
        Some(r) => format!(
            "no reference (n = {} healthy subjects passing every check; {min_n} needed)",
            r.n_reference
        ),
        None => "no reference".into(),
    }
}

/// A side's value of a parameter (`None` for a failed side).
fn side_value(r: &RecordingRow, p: Parameter) -> Option<f64> {
    if r.is_ok() {
        r.value(p)
    } else {
        None
    }
}

/// Section 2: the parameter table, each side against the reference range, and the symmetry
/// index.
pub(super) fn parameter_table(
    sides: &[&RecordingRow],
    reference: &Reference,
    citations: &Citations,
    p: &ValidReportParams,
) -> Markup {
    let left = sides
        .iter()
        .find(|r| r.side == crate::Side::Left && r.is_ok());
    let right = sides
        .iter()
        .find(|r| r.side == crate::Side::Right && r.is_ok());
    let mut out_of_range = 0usize;
    let mut rows: Vec<Markup> = Vec::new();
    for par in PARAMETERS.iter() {
        let rr = reference.range(*par);
        let dec = decimals(par.unit());
        let cells: Vec<(Option<f64>, Option<&str>, Option<&str>)> = sides
            .iter()
            .map(|r| match r.withheld.reason(par.column()) {
                Some(why) => (None, None, Some(why)),
                None => {
                    let v = side_value(r, *par);
                    (v, out_mark(v, rr), None)
                }
            })
            .collect();
        out_of_range += cells.iter().filter(|c| c.1.is_some()).count();
        let si = match (left, right) {
            (Some(l), Some(r)) => match (
                l.value(*par)
                    .filter(|_| l.withheld.reason(par.column()).is_none()),
                r.value(*par)
                    .filter(|_| r.withheld.reason(par.column()).is_none()),
            ) {
                (Some(a), Some(c)) => symmetry_index_pct(a, c),
                _ => None,
            },
            _ => None,
        };
        let flag = si.is_some_and(|v| v.abs() > p.0.asymmetry_flag_pct);
        rows.push(html! {
            tr {
                td { (par.code()) " — " (par.name()) } td { (par.unit()) }
                @for (v, out, why) in &cells {
                    @if let Some(why) = why {
                        td.withheld { "not measured: " (why) }
                    } @else {
                        td.num.out[out.is_some()] { (fmt(*v, dec)) @if let Some(m) = out { " " (m) } }
                    }
                }
                td { (range_text(rr, dec, citations, p.0.min_healthy_subjects)) }
                td.num.flag[flag] { (si.map(|v| format!("{v:+.1}")).unwrap_or("–".into())) }
            }
            "\n"
        });
    }
    html! {
        h2 { "2. Gait parameters" } "\n"
        p.meta {
            "Reference: " (reference.description) " Values outside the reference range are marked ▲ (above) or ▼ (below) and shaded. Symmetry index SI = 100·(L − R)/((L + R)/2) %; |SI| > "
            (format!("{:.0}", p.0.asymmetry_flag_pct)) " % is shaded."
        }
        "\n"
        table {
            "\n"
            tr { th { "parameter" } th { "unit" } @for r in sides { th { (side_label(r)) } } th { "reference range" } th { "SI (%)" } } "\n"
            @for r in &rows { (r) }
        }
        "\n"
        p { (out_of_range) " value(s) lie outside the reference range." (no_published_note(reference)) } "\n"
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

/// Radar of the subject's z-scores against the reference.
pub(super) fn subject_radar(
    s: &SubjectReport,
    sides: &[&RecordingRow],
    reference: &Reference,
) -> Result<Markup> {
    let ranges: Vec<&ReferenceRange> = reference.ranges.iter().filter(|r| r.sd.is_some()).collect();
    let series: Vec<(String, Vec<f64>)> = sides
        .iter()
        .filter(|r| r.is_ok())
        .map(|r| {
            (
                side_label(r),
                ranges
                    .iter()
                    .map(|rr| {
                        Parameter::from_column(&rr.column)
                            .ok()
                            .and_then(|p| r.value(p))
                            .filter(|_| r.withheld.reason(&rr.column).is_none())
                            .and_then(|v| rr.z(v))
                            .unwrap_or(f64::NAN)
                    })
                    .collect(),
            )
        })
        .collect();
    if series.is_empty() || ranges.len() < 3 {
        return Ok(html! {});
    }
    let names: Vec<String> = ranges.iter().map(|r| r.code.clone()).collect();
    let svg = plots::radar_svg(
        &format!(
            "Subject {}: z-scores against the healthy reference",
            s.subject_id
        ),
        &names,
        &series,
    )?;
    Ok(figure(
        &svg,
        &format!("Radar chart of the subject's parameters as z-scores against the reference of section 2 (0 = the reference mean, the black ring); left blue, right orange. A dot with a black edge lies beyond ±{:.2} SD (abnormal); a gap in a polygon is a parameter not measured on that side (never drawn as 0). The scale stops at ±{:.0} SD: a value beyond it is an open triangle on the rim{}.", plots::RADAR_Z_ABNORMAL, plots::RADAR_Z_CLIP, if svg.contains(plots::RADAR_CLIPPED) { " — clipped here, the values are named under the chart" } else { " (none here)" }),
        &[plots::RADAR_SCALE_LABEL],
    ))
}
