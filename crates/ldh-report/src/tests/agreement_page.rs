//! `agreement.html`: the figures hold the expected points and bars, every figure's text prints
//! at 8 pt or more, the summary says which parameters agree, and spliced text is escaped.

use crate::agreement_page::{agreement_html, bland_altman_points, GOOD_ICC};
use crate::plots::tests::smallest_printed_pt;
use crate::plots::{self, PrintWidth, MIN_PRINT_TEXT_PT, TIMING_BAR_COLOUR};
use ldh_core::agreement::OffsetMode;
use ldh_core::domain::{EventKind, Legs};
use ldh_core::output::LdhResults;
use ldh_sim::evaluate::TruthScope;
use ldh_test_support::{agree_with, simulated};

/// The SVG of each `<figure>` of a page, in order.
fn figure_svgs(page: &str) -> Vec<&str> {
    page.split("<figure")
        .skip(1)
        .map(|f| {
            let f = &f[..f.find("</figure>").unwrap()];
            &f[f.find("<svg").unwrap()..f.find("</svg>").unwrap() + 6]
        })
        .collect()
}

fn bar_colour() -> String {
    let c = TIMING_BAR_COLOUR;
    format!("fill=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2)
}

/// On a simulated cohort against its exported truth: two histograms (HS, TO) whose bars are the
/// non-empty bins of the matched errors and add up to the matched events, then one
/// Bland–Altman plot per computed parameter with one dot per complete pair; every figure prints its text at ≥ 8 pt at its print width.
#[test]
fn the_page_draws_every_pair_and_every_matched_event() {
    let (results, truths) = simulated();
    let ldh = LdhResults::from_results(&results);
    let (ev, st) = ldh_sim::evaluate::truth_reference(&truths, TruthScope::Steady, 0.0);
    let rep = agree_with(&ldh, &ev, &st, OffsetMode::None);
    let page = agreement_html(&rep).unwrap();
    let svgs = figure_svgs(&page);
    let computed: Vec<_> = rep
        .parameters
        .iter()
        .filter(|p| p.agreement.is_some())
        .collect();
    assert!(computed.len() >= 6, "{}", computed.len());
    assert_eq!(svgs.len(), 2 + computed.len());
    for (k, ev) in [EventKind::HeelStrike, EventKind::ToeOff]
        .iter()
        .enumerate()
    {
        let errors: Vec<f64> = rep
            .event_pairs
            .iter()
            .filter(|p| p.event == *ev)
            .map(|p| p.error_s * 1e3)
            .collect();
        let matched = rep
            .events
            .iter()
            .find(|e| e.event == *ev && e.side == Legs::Both)
            .unwrap()
            .summary
            .n_matched;
        assert_eq!(errors.len(), matched);
        let (_, bins) = plots::histogram_bins(&errors, 1.0);
        assert_eq!(bins.iter().map(|b| b.1).sum::<usize>(), matched);
        let bars = bins.iter().filter(|b| b.1 > 0).count();
        assert!(bars >= 3, "{bins:?}");
        assert_eq!(svgs[k].matches(&bar_colour()).count(), bars, "{ev}");
    }
    for (p, svg) in computed.iter().zip(&svgs[2..]) {
        let series = bland_altman_points(p);
        let dots: usize = series.iter().map(|s| s.1.len()).sum();
        assert_eq!(
            dots,
            p.agreement.as_ref().unwrap().n_pairs,
            "{}",
            p.parameter
        );
        assert_eq!(
            svg.matches("<circle").count(),
            dots,
            "{} {}",
            p.level,
            p.parameter
        );
    }
    for svg in &svgs {
        let pt = smallest_printed_pt(svg, PrintWidth::Chart);
        assert!((MIN_PRINT_TEXT_PT..9.0).contains(&pt), "{pt}");
    }
    assert!(page.contains("<figcaption>Fig. 1. Timing error of the"));
    assert!(page.contains(&format!("Fig. {}. Bland–Altman plot", 2 + computed.len())));
    // The summary sorts each computed parameter once, by ICC(2,1).
    let head = &page[page.find("div class=\"headline\"").unwrap()..page.find("<h2").unwrap()];
    let good = computed
        .iter()
        .filter(|p| p.agreement.as_ref().unwrap().icc.icc_2_1.value >= GOOD_ICC)
        .count();
    if good > 0 {
        assert!(head.contains("Agree with the reference"), "{head}");
    }
    if good < computed.len() {
        assert!(head.contains("Do not agree"), "{head}");
    }
    assert!(
        head.contains("reference heel strikes were matched"),
        "{head}"
    );
}

/// Subject ids and group labels come from users' files: the page escapes them.
#[test]
fn the_page_escapes_subject_ids_and_groups() {
    let (results, truths) = simulated();
    let ldh = LdhResults::from_results(&results);
    let (ev, st) = ldh_sim::evaluate::truth_reference(&truths, TruthScope::Steady, 0.0);
    let mut rep = agree_with(&ldh, &ev, &st, OffsetMode::None);
    rep.offsets[0].subject_id = "<script>alert(1)</script>".into();
    rep.offsets[0].source = ldh_core::agreement::run::OffsetSource::Given;
    rep.groups[0].group = "a&b\"<i>".into();
    let page = agreement_html(&rep).unwrap();
    assert!(!page.contains("<script>") && !page.contains("<i>"));
    assert!(page.contains("&lt;script&gt;alert(1)&lt;/script&gt;"));
    assert!(page.contains("a&amp;b&quot;&lt;i&gt;"));
}
