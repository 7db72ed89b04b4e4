//! The first screen of a subject's page: the clinical headline ([`super::headline`]) and a
//! clinical summary in a clinician's words and units (cadence in steps/min, speed m/s, stride
//! length m, stance % of the gait cycle, variability as CV %, left-right asymmetry %), each
//! value beside the normal range it was judged against and that range's source, a
//! plain-language flag ("below normal", "within normal", …) and ▲/▼ for values outside it,
//! and "not measured: <reason>" — never a number, never a mark — for what a quality check
//! withheld or could not be computed. Every verdict comes from [`super::verdict`], made once.
//!
//! The asymmetry is the symmetry index of Robinson et al. (J Manipulative Physiol Ther
//! 1987;10(4):172–176), flagged above [`super::ReportParams::asymmetry_flag_pct`].

use maud::{html, Markup};

use super::html::fmt;
use super::reference::no_published_reason;
use super::reference::Citations;
use super::verdict::{Asymmetry, Cell, Quantity, Row, Scope, Verdicts};
use super::{ReferenceRange, ReferenceSource, ValidReportParams};

/// The range in clinical units and where it comes from.
fn range_cells(
    rr: Option<&ReferenceRange>,
    m: &Quantity,
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
                    format!("published [{}]", citations.number(c))
                }
                ReferenceSource::None => String::new(),
            };
            (
                format!(
                    "{}–{}",
                    fmt(Some(l * m.scale()), d),
                    fmt(Some(h * m.scale()), d)
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

/// Why values were not measured, each reason numbered once per page: a cell says "not
/// measured [n]" and the reason is written once under the first table that cites it (issue 36:
/// each note said once per page; a real walk with withheld values otherwise repeats one long
/// reason in a dozen cells).
#[derive(Default)]
pub(crate) struct WhyNotes(std::cell::RefCell<Vec<String>>);

impl WhyNotes {
    /// The number of `why` (1-based), given it on first use.
    pub(crate) fn cite(&self, why: &str) -> usize {
        let mut v = self.0.borrow_mut();
        match v.iter().position(|w| w == why) {
            Some(i) => i + 1,
            None => {
                v.push(why.to_string());
                v.len()
            }
        }
    }

    /// How many reasons are numbered so far.
    pub(crate) fn len(&self) -> usize {
        self.0.borrow().len()
    }

    /// The reasons numbered since `from` (= [`Self::len`] before a table), one line each.
    pub(crate) fn list_from(&self, from: usize) -> Markup {
        let v = self.0.borrow();
        html! {
            @if v.len() > from {
                div.meta.why {
                    @for (i, w) in v.iter().enumerate().skip(from) {
                        div { "[" (i + 1) "] not measured: " (w) }
                    }
                }
                "\n"
            }
        }
    }
}

/// One value's cell: the value with its mark and plain words, or "not measured [n]" with the
/// reason numbered in `why`.
pub(crate) fn value_cell(c: &Cell, q: &Quantity, colspan: usize, notes: &WhyNotes) -> Markup {
    match c {
        Cell::NotMeasured(why) => {
            html! { td.nm colspan=[(colspan > 1).then_some(colspan)] { "not measured [" (notes.cite(why)) "]" } }
        }
        Cell::Value { v, judgement, note } => {
            let mark = judgement.mark();
            html! {
                td.num.out[mark.is_some()] colspan=[(colspan > 1).then_some(colspan)] {
                    (fmt(Some(*v), q.decimals)) @if let Some(k) = mark { " " (k) }
                    " " span.flagword { (judgement.words()) @if let Some(n) = note { "; " (n) } }
                }
            }
        }
    }
}

/// The value cells of a row: one spanning both sides for a whole-walk quantity.
pub(crate) fn value_cells(row: &Row, notes: &WhyNotes) -> Markup {
    match row.q.scope {
        Scope::Walk => value_cell(&row.cells[0], row.q, 2, notes),
        // Both legs not measured for the same reason: said once, across both.
        Scope::Side => match row.cells.as_slice() {
            [Cell::NotMeasured(a), Cell::NotMeasured(b)] if a == b => {
                html! { td.nm colspan="2" { "not measured (both legs) [" (notes.cite(a)) "]" } }
            }
            cells => html! { @for c in cells { (value_cell(c, row.q, 1, notes)) } },
        },
    }
}

/// An asymmetry's cell: the SI with ◆ and "asymmetric"/"symmetric" when judged, "not judged"
/// for a shank angle without a reference range.
pub(crate) fn asymmetry_cell(a: &Asymmetry, colspan: usize, notes: &WhyNotes) -> Markup {
    match a {
        Asymmetry::NotMeasured(why) => {
            html! { td.nm colspan=[(colspan > 1).then_some(colspan)] { "not measured [" (notes.cite(why)) "]" } }
        }
        Asymmetry::Value(v, judged) => {
            let flag = *judged == Some(true);
            let words = match judged {
                Some(true) => "asymmetric",
                Some(false) => "symmetric",
                None => "not judged: no reference range",
            };
            html! {
                td.num.out[flag] colspan=[(colspan > 1).then_some(colspan)] {
                    (format!("{v:+.1}")) @if flag { " ◆" } " " span.flagword { (words) }
                }
            }
        }
    }
}

/// The clinical summary (first screen of the subject page), rendered from the page's verdicts.
pub(crate) fn clinical_summary(
    v: &Verdicts,
    reference: &super::Reference,
    citations: &Citations,
    p: &ValidReportParams,
    notes: &WhyNotes,
) -> Markup {
    let limit = p.0.asymmetry_flag_pct;
    let first_note = notes.len();
    let rows = || v.rows.iter().filter(|r| r.q.in_summary);
    // Every cell "not measured": one sentence, not a grid of them.
    if let Some(why) = v.all_withheld(|r| r.q.in_summary) {
        return html! {
            p { "No value of this summary was measured on either leg, so its table is left out: " (why.join("; ")) "." } "\n"
        };
    }
    html! {
        table.summary {
            "\n"
            tr { th { "measure (unit)" } th { "left" } th { "right" } th { "normal range" } th { "judged against" } } "\n"
            @for row in rows() {
                @let rr = reference.range(row.q.parameter);
                @let (range, src) = range_cells(rr, row.q, citations);
                tr {
                    td { b { (row.q.label()) } " (" (row.q.unit()) ")" }
                    (value_cells(row, notes))
                    td.num { (range) } td { (src) }
                }
                "\n"
            }
            @if let Some(why) = &v.no_pair {
                // no asymmetry can be computed: one row says why, not one per measure
                tr {
                    td { b { "Left–right asymmetry" } " (SI %)" }
                    td.nm colspan="2" { "not measured [" (notes.cite(why)) "]" }
                    td.num { "|SI| ≤ " (format!("{limit:.0}")) }
                    td { "Robinson 1987" }
                }
                "\n"
            }
            @for row in rows().filter(|_| v.no_pair.is_none()) {
                @if let Some(a) = &row.asymmetry {
                    tr {
                        td { b { (row.q.label()) " asymmetry" } " (SI %)" }
                        (asymmetry_cell(a, 2, notes))
                        td.num { "|SI| ≤ " (format!("{limit:.0}")) }
                        td { "Robinson 1987" }
                    }
                    "\n"
                }
            }
        }
        "\n"
        (notes.list_from(first_note))
        p.meta {
            "▲ above, ▼ below the normal range (bounds included, compared as shown); ◆ asymmetry beyond the threshold (also shaded): the legs compared with each other, with or without a normal range. "
            "Cadence, walking speed and stride time are one value for the walk, from both legs (one cell across both): cadence counts the steps of both legs, 60·(1/stride time left + 1/stride time right). "
            "SI = 100·(L − R)/((L + R)/2) %: positive when the left value is larger. "
            "The shank angles (WQK, PBI, BDK) and gait stability (STA) are in section 2 with their own reference."
        }
        "\n"
    }
}
