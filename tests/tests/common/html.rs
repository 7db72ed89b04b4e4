//! Checks of the HTML pages ldh writes (reports, `agreement.html`): well-formed XML,
//! self-contained, figures numbered once each, every figure's axis labels drawn with their
//! units, and no figure text printing under 8 pt.

use std::path::Path;

/// Parse as XML, check self-containment and every figure's declared axis labels.
pub fn check_page(path: &Path) -> usize {
    let src = std::fs::read_to_string(path).unwrap();
    let opt = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(&src, opt)
        .unwrap_or_else(|e| panic!("{} is not well-formed: {e}", path.display()));
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "html");
    assert!(
        root.descendants().any(|n| n.has_tag_name("title")),
        "{}: no title",
        path.display()
    );
    for n in root.descendants().filter(|n| n.is_element()) {
        let t = n.tag_name().name();
        assert!(
            !matches!(t, "script" | "link" | "iframe" | "img"),
            "{}: <{t}> makes the page depend on something else",
            path.display()
        );
        for a in n.attributes() {
            assert!(
                !(a.name() == "src" || (a.name() == "href" && a.value().contains("://"))),
                "{}: external reference {}={}",
                path.display(),
                a.name(),
                a.value()
            );
        }
    }
    check_figure_numbers(path, &src);
    let mut figures = 0;
    for f in root.descendants().filter(|n| {
        n.has_tag_name("figure")
            && n.attribute("class")
                .is_some_and(|c| c.split_whitespace().any(|c| c == "plot"))
    }) {
        figures += 1;
        let svg = f
            .children()
            .find(|c| c.tag_name().name() == "svg")
            .unwrap_or_else(|| panic!("{}: figure without svg", path.display()));
        check_print_text(path, &src, f, svg);
        let texts: Vec<String> = svg
            .descendants()
            .filter(|n| n.tag_name().name() == "text")
            .map(|n| n.descendants().filter_map(|t| t.text()).collect::<String>())
            .collect();
        let labels: Vec<&str> = f
            .attribute("data-axis-labels")
            .unwrap_or("")
            .split('|')
            .filter(|s| !s.is_empty())
            .collect();
        assert!(
            !labels.is_empty(),
            "{}: a figure declares no axis label",
            path.display()
        );
        for l in labels {
            let unit = l
                .find('(')
                .zip(l.rfind(')'))
                .is_some_and(|(a, b)| b > a + 1);
            assert!(unit, "{}: axis label '{l}' has no unit", path.display());
            assert!(
                texts.iter().any(|t| t.contains(l)),
                "{}: axis label '{l}' is not drawn in its figure (texts: {:?})",
                path.display(),
                &texts[..texts.len().min(8)]
            );
        }
    }
    figures
}

/// No text of a figure prints under 8 pt: the figure prints `data-print-width-pt` wide (and the
/// page's print CSS gives its class exactly that width), its SVG is `viewBox` wide, so a text of
/// `font-size` f prints at f × width / viewBox pt.
pub fn check_print_text(path: &Path, src: &str, f: roxmltree::Node, svg: roxmltree::Node) {
    let width_pt: f64 = f
        .attribute("data-print-width-pt")
        .and_then(|w| w.parse().ok())
        .unwrap_or_else(|| panic!("{}: a figure without its print width", path.display()));
    let class = f.attribute("class").unwrap_or("");
    let print_class = class
        .split_whitespace()
        .find(|c| c.starts_with("print-"))
        .unwrap_or_else(|| panic!("{}: a figure without a print class", path.display()));
    let rule = format!("figure.{print_class} {{ width: {width_pt}pt;");
    assert!(
        src.contains(&rule),
        "{}: the print CSS does not give '{print_class}' its width ({rule})",
        path.display()
    );
    let view_w: f64 = svg
        .attribute("viewBox")
        .and_then(|v| v.split_whitespace().nth(2)?.parse().ok())
        .unwrap_or_else(|| panic!("{}: an svg without a viewBox", path.display()));
    for t in svg.descendants().filter(|n| n.has_tag_name("text")) {
        let size: f64 = t
            .attribute("font-size")
            .and_then(|v| v.parse().ok())
            .unwrap_or_else(|| panic!("{}: a figure text without font-size", path.display()));
        let printed = size * width_pt / view_w;
        let txt: String = t.descendants().filter_map(|n| n.text()).collect();
        assert!(
            printed >= 8.0 - 1e-9,
            "{}: '{txt}' prints at {printed:.2} pt (font-size {size} in a {view_w}-wide figure printed {width_pt} pt wide)",
            path.display()
        );
    }
}

/// Figure captions are numbered once each, 1, 2, … in page order.
pub fn check_figure_numbers(path: &Path, src: &str) {
    let numbers: Vec<usize> = src
        .match_indices("<figcaption>Fig. ")
        .map(|(i, m)| {
            let rest = &src[i + m.len()..];
            rest[..rest.find('.').unwrap()].parse().unwrap()
        })
        .collect();
    let expected: Vec<usize> = (1..=numbers.len()).collect();
    assert_eq!(numbers, expected, "{}: figure numbers", path.display());
    assert_eq!(
        src.matches("<figcaption>").count(),
        numbers.len(),
        "{}: a figure without a number",
        path.display()
    );
}
