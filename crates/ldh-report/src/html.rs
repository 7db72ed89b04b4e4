//! The page frame and the small pieces every report section uses: the HTML skeleton with its
//! CSS, figures, number formatting.
//!
//! Markup is written with [`maud`]: every spliced value is escaped by construction (`&`, `<`,
//! `>`, `"`), only the fixed CSS, the `<head>` boilerplate and the SVG drawn by
//! [`crate::plots`] are inserted raw ([`PreEscaped`]). The page stays well-formed XML: void
//! elements are only in the fixed head (written `<meta …/>`), and [`page`] replaces control
//! characters (which XML 1.0 forbids) by spaces once for the whole document, so a hostile file
//! name or error message cannot break the page.

use maud::{html, Markup, PreEscaped, DOCTYPE};

use crate::plots::PrintWidth;
use ldh_core::output::RecordingRow;

/// The ldh version written into every page.
pub(crate) const VERSION: &str = env!("CARGO_PKG_VERSION");

pub(crate) const CSS: &str = r#"
body { font-family: "DejaVu Sans", Arial, Helvetica, sans-serif; color: #111; margin: 24px auto; max-width: 860px; line-height: 1.35; font-size: 14px; }
h1 { font-size: 22px; margin: 0 0 4px 0; } h2 { font-size: 17px; border-bottom: 1px solid #999; margin-top: 22px; padding-bottom: 2px; } h3 { font-size: 15px; margin: 14px 0 6px; }
table { border-collapse: collapse; margin: 6px 0 10px; width: 100%; font-size: 12.5px; }
th, td { border: 1px solid #bbb; padding: 3px 5px; text-align: left; vertical-align: top; }
th { background: #eee; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
.out { background: #fde2e2; font-weight: bold; } .flag { background: #fff1c2; }
.note { background: #f3f3f3; border-left: 4px solid #888; padding: 6px 10px; margin: 8px 0; }
.missing { background: #fde2e2; border-left: 4px solid #c00; padding: 6px 10px; margin: 8px 0; }
.support { background: #e8f0fe; border-left: 4px solid #1a56c4; padding: 6px 10px; margin: 8px 0; }
.meta { color: #444; font-size: 12.5px; }
td.nm, td.withheld { color: #555; font-style: italic; }
table.summary { font-size: 13.5px; } table.summary td.num { white-space: nowrap; }
span.flagword { font-weight: normal; font-size: 11.5px; color: #333; }
p.headline, div.headline { font-size: 14.5px; margin: 6px 0; }
figure { margin: 10px 0; page-break-inside: avoid; break-inside: avoid; }
figure svg { width: 100%; height: auto; display: block; }
figure.print-chart { max-width: 560px; margin: 10px auto; }
div.side { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; } div.side > figure { flex: 0 0 auto; margin: 0; } div.side > div { flex: 1 1 200px; }
@media screen { div.side > figure.print-chart { width: 60%; } }
span.g0 { color: #0072b2; } span.g1 { color: #e69f00; } span.g2 { color: #009e73; }
div.figgrid { display: grid; grid-template-columns: repeat(5, 1fr); gap: 8px; } div.figgrid.cols3 { grid-template-columns: repeat(3, 1fr); } div.figgrid figure { margin: 0; }
figcaption { font-size: 12px; color: #333; margin-top: 3px; }
ol.refs { font-size: 11.5px; }
table.triage td.bad { background: #fde2e2; font-weight: bold; }
.print-only { display: none; }
@page { size: A4; margin: 7mm; }
@media print { body { margin: 0; max-width: none; font-size: 8pt; line-height: 1.2; } div.headline p, div.headline ul { margin: 1px 0; } div.headline li { margin: 0; } .missing { padding: 2px 8px; margin: 3px 0; } .missing ul { margin: 1px 0; } .screen-only { display: none; } table.params span.flagword { display: none; } .print-only { display: block; } figcaption { font-size: 8pt; } table { font-size: 8pt; } th, td { padding: 1px 4px; } h1 { font-size: 15pt; } h2 { font-size: 11pt; margin-top: 6px; margin-bottom: 3px; page-break-after: avoid; break-after: avoid; } .note, .missing, .support, figure, tr { page-break-inside: avoid; break-inside: avoid; } .out, .flag, th, td.bad { -webkit-print-color-adjust: exact; print-color-adjust: exact; } }
"#;

/// The whole page around `body`: doctype, head (charset, viewport, generator, title, CSS).
pub(crate) fn page(title: &str, body: Markup) -> String {
    let head = format!(
        "\n<meta charset=\"utf-8\"/>\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\n<meta name=\"generator\" content=\"ldh {VERSION}\"/>\n"
    );
    let m = html! {
        (DOCTYPE) "\n"
        html lang="en" {
            "\n"
            head {
                (PreEscaped(head))
                title { (title) } "\n"
                style { (PreEscaped(CSS)) (PreEscaped(print_figure_css())) } "\n"
            }
            "\n"
            body { "\n" (body) }
            "\n"
        }
        "\n"
    };
    without_control_chars(numbered_figures(m.into_string()))
}

/// The print widths of the figures ([`PrintWidth::pt`]): each figure prints exactly as wide as
/// its fonts were sized for, so no figure text prints under 8 pt.
fn print_figure_css() -> String {
    let mut css = String::from("@media print { ");
    for w in PrintWidth::ALL {
        css += &format!(
            "figure.{} {{ width: {}pt; margin: 2px auto; }} ",
            w.class(),
            w.pt()
        );
    }
    // A chart of a subject page prints with its caption beside it, not under it: the
    // figure, kept whole, is then only as tall as its chart.
    css += &format!(
        "div.beside > figure.{c} {{ width: auto; display: flex; gap: 8pt; align-items: flex-start; margin: 2px 0; }} div.beside > figure.{c} > svg {{ width: {w}pt; flex: 0 0 {w}pt; }} div.beside > figure.{c} > figcaption {{ flex: 1 1 auto; margin-top: 0; }} ",
        c = PrintWidth::Chart.class(),
        w = PrintWidth::Chart.pt()
    );
    css += &format!(
        "div.figgrid {{ grid-template-columns: repeat(5, {}pt); gap: 4pt; }} div.figgrid.cols3 {{ grid-template-columns: repeat(3, {}pt); }} div.figgrid figure.plot {{ margin: 0; }} }}\n",
        PrintWidth::Fifth.pt(),
        PrintWidth::Third.pt()
    );
    css
}

/// Every figure caption of a page numbered in the order of the page ("Fig. 1. …"), so each
/// number is used once. The figures printed come first on every page, the on-screen ones
/// after them, so the printed numbers are 1, 2, … as well. Only [`figure`] writes
/// `<figcaption>` (spliced text is escaped by maud, so no file name or message can add one).
fn numbered_figures(page: String) -> String {
    let mut out = String::with_capacity(page.len() + 64);
    for (k, part) in page.split("<figcaption>").enumerate() {
        if k > 0 {
            out += &format!("<figcaption>Fig. {k}. ");
        }
        out += part;
    }
    out
}

/// Control characters other than tab, line feed and carriage return are not allowed in XML 1.0;
/// a carriage return is replaced too (as the old hand-written escaping did).
fn without_control_chars(s: String) -> String {
    if s.chars()
        .any(|c| (c as u32) < 0x20 && c != '\n' && c != '\t')
    {
        s.chars()
            .map(|c| {
                if (c as u32) < 0x20 && c != '\n' && c != '\t' {
                    ' '
                } else {
                    c
                }
            })
            .collect()
    } else {
        s
    }
}

/// A figure: the SVG inline, its caption, and the axis labels it draws (each with its unit), so
/// a checker can verify them (`data-axis-labels`, separated by `|`); `print` is the width the
/// SVG's fonts were sized for (the plot's `…_PRINT` constant), written as its class and as
/// `data-print-width-pt`.
pub(crate) fn figure(svg: &str, caption: &str, axis_labels: &[&str], print: PrintWidth) -> Markup {
    let svg = svg
        .trim_start_matches("<?xml version=\"1.0\" encoding=\"UTF-8\"?>")
        .trim();
    html! {
        figure.plot.(print.class()) data-axis-labels=(axis_labels.join("|")) data-print-width-pt=(print.pt()) {
            "\n" (PreEscaped(svg)) "\n"
            figcaption { (caption) } "\n"
        }
        "\n"
    }
}

/// `v` with `dec` decimals, an en dash when missing or not finite.
pub(crate) fn fmt(v: Option<f64>, dec: usize) -> String {
    match v {
        Some(x) if x.is_finite() => format!("{x:.dec$}"),
        _ => "–".into(),
    }
}

/// A file's name without the folders before it (a report names no machine's paths); a
/// person's several files (`t1: a/l.csv; t2: b/l.csv`) each by its name.
pub(crate) fn base_name(source: &str) -> String {
    source
        .split("; ")
        .map(|part| {
            let (label, path) = match part.split_once(": ") {
                Some((t, p)) if !t.contains(['/', '\\']) => (Some(t), p),
                _ => (None, part),
            };
            let name = path.rsplit(['/', '\\']).next().unwrap_or(path);
            match label {
                Some(t) => format!("{t}: {name}"),
                None => name.to_string(),
            }
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The word of a count in its number: `plural(1, "person", "people")` is "person", any other
/// count (0 too) takes `many`. The pages' one pluraliser.
pub(crate) fn plural<'a>(n: usize, one: &'a str, many: &'a str) -> &'a str {
    if n == 1 {
        one
    } else {
        many
    }
}

/// A count with its words in the right number: "1 value lies", "4 values lie", "0 strides".
pub(crate) fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", plural(n, one, many))
}

/// An optional count, an en dash when missing.
pub(crate) fn count(v: Option<usize>) -> String {
    v.map(|v| v.to_string()).unwrap_or("–".into())
}

/// `left` or `right`, with the manifest's role when there is one (`right (affected)`).
pub(crate) fn side_label(r: &RecordingRow) -> String {
    use ldh_core::output::{Label, SideRole};
    match &r.side_role {
        None | Some(Label::Known(SideRole::Healthy)) => r.side.to_string(),
        Some(role) => format!("{} ({role})", r.side),
    }
}

/// A red box with a bold title and one bullet per item (nothing when there are no items).
pub(crate) fn red_box(title: &str, items: &[String]) -> Markup {
    html! {
        @if !items.is_empty() {
            div.missing { b { (title) } ul { @for i in items { li { (i) } } } } "\n"
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_take_their_words_in_the_right_number() {
        assert_eq!(plural(1, "person", "people"), "person");
        assert_eq!(plural(0, "person", "people"), "people");
        assert_eq!(plural(2, "value is", "values are"), "values are");
        assert_eq!(counted(1, "value lies", "values lie"), "1 value lies");
        assert_eq!(counted(4, "value lies", "values lie"), "4 values lie");
        assert_eq!(counted(0, "asymmetry", "asymmetries"), "0 asymmetries");
    }
}
