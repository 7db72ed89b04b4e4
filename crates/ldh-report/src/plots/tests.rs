//! Unit tests of the SVG figures: titles, axis labels and shapes.

use super::*;

#[test]
fn svgs_have_titles_labels_and_shapes() {
    let r = radar_svg(
        "Fusion",
        &["SF".into(), "SL".into(), "ST".into()],
        &[
            ("LDHE".into(), vec![-1.0, -2.0, 1.5]),
            ("H".into(), vec![0.0; 3]),
        ],
    )
    .unwrap();
    // Axes by the parameters' names (issue 50), the long one on two lines; no label over the
    // reference ring.
    assert!(
        r.starts_with("<svg")
            && r.contains("LDHE")
            && r.contains("\ncadence\n")
            && r.contains("\nstride\n")
            && r.contains("\nlength\n")
            && r.contains("\nstride time\n")
            && r.contains("z-score"),
        "{r}"
    );
    assert!(!r.contains("z = 0") && !r.contains("healthy mean"));
    let b = boxplot_svg(
        "stride time (s)",
        &[
            ("LDHH".into(), vec![1.0, 1.1, 1.2, 1.05]),
            ("H".into(), vec![0.9, 1.0, 0.95]),
        ],
        true,
    )
    .unwrap();
    assert!(b.contains("stride time (s)") && b.contains("LDHH"));
    let no_names =
        boxplot_svg("stride time (s)", &[("LDHH".into(), vec![1.0, 1.2])], false).unwrap();
    assert!(
        !no_names.contains("LDHH"),
        "without the legend the groups go by colour"
    );
    assert!(boxplot_svg("x (s)", &[("A".into(), vec![])], false).is_err());
}

/// The clipped values under the radar are named in words, and a walk value drawn on both legs'
/// polygons (the cadence, one per walk) is named once: a slow hemiparetic walker's page read
/// "left (unaffected) SF z = -4.3, … right (affected) SF z = -4.3".
#[test]
fn the_radars_clipped_values_are_named_in_words_and_a_walk_value_once() {
    use ldh_core::Side;
    let codes: Vec<String> = ["SF", "STP", "SL"].map(String::from).to_vec();
    let c = radar_svg(
        "x",
        &codes,
        &[
            (
                SeriesName::of_side(Side::Left, "left (unaffected)"),
                vec![-4.3, 4.2, 0.5],
            ),
            (
                SeriesName::of_side(Side::Right, "right (affected)"),
                vec![-4.3, 1.0, f64::NAN],
            ),
        ],
    )
    .unwrap();
    let text: String = c
        .split("<text")
        .skip(1)
        .filter_map(|t| t.split_once('>').and_then(|(_, r)| r.split_once("</text>")))
        .map(|(t, _)| format!("{t} "))
        .collect();
    assert!(text.contains("clipped at ±4 SD, z-score:"), "{text}");
    assert!(text.contains("both legs: cadence -4.3"), "{text}");
    assert!(text.contains("left (unaffected): stance +4.2"), "{text}");
    assert!(!text.contains(" SF ") && !text.contains(" STP "), "{text}");
    // No line of the note is only a stray comma after the header (the demo's L02 read
    // "clipped at ±4 SD:," with its first item too long for the line).
    assert!(!text.contains(":,"), "{text}");
    assert_eq!(text.matches("-4.3").count(), 1, "{text}");
}

/// A missing value is a gap (no point, no segment to it), never a point at 0; values beyond
/// ±4 SD are drawn on the rim, marked and named.
#[test]
fn the_radar_leaves_gaps_and_marks_clipping() {
    let codes: Vec<String> = ["SF", "SL", "ST", "WQK"].map(String::from).to_vec();
    let r = radar_svg(
        "x",
        &codes,
        &[("left".into(), vec![0.5, f64::NAN, 1.0, -0.2])],
    )
    .unwrap();
    // Three finite values: three points; segments SF–WQK and ST–WQK only (SL missing).
    assert_eq!(r.matches("<circle").count(), 3, "{r}");
    assert!(!r.contains(RADAR_CLIPPED));
    let all = radar_svg("x", &codes, &[("left".into(), vec![0.5, 0.1, 1.0, -0.2])]).unwrap();
    assert_eq!(all.matches("<circle").count(), 4);
    assert!(all.matches("<polyline").count() > r.matches("<polyline").count());
    let c = radar_svg(
        "x",
        &codes,
        &[("right".into(), vec![12.0, 0.1, -2.5, f64::NAN])],
    )
    .unwrap();
    assert!(c.contains("clipped at ±4 SD, z-score:"), "{c}");
    // A series that is no leg (a group of the cohort page) keeps the code.
    assert!(c.contains("right: SF +12.0"), "{c}");
    assert!(
        c.contains("rings, centre to rim: z = -4.0, -2.0, 0 (black), +2.0, +4.0"),
        "the scale stops at 4 SD: {c}"
    );
    assert!(!c.contains("+6.0,") && !c.contains("+10.0,"));
    // −2.5 is abnormal: the black-edged dot (two circles), 12 a triangle, NaN nothing.
    assert_eq!(c.matches("<circle").count(), 3);
}

#[test]
fn clipping_counts_values_beyond_the_range() {
    let (v, n) = clip_to(&[-100.0, 0.0, f64::NAN, 95.0], -90.0, 90.0);
    assert_eq!(n, 2);
    assert_eq!(v[0], -90.0);
    assert_eq!(v[3], 90.0);
    assert!(v[2].is_nan());
}

/// The smallest text of an SVG drawn by plotters, in pt, when it prints `print` wide: every
/// `font-size` × printed width / viewBox width.
pub(crate) fn smallest_printed_pt(svg: &str, print: PrintWidth) -> f64 {
    let attr = |name: &str, from: &str| -> Vec<f64> {
        from.match_indices(&format!(" {name}=\""))
            .map(|(i, m)| {
                let rest = &from[i + m.len()..];
                rest[..rest.find('"').unwrap()].to_string()
            })
            .flat_map(|v| v.split_whitespace().map(str::to_string).collect::<Vec<_>>())
            .map(|v| v.parse().unwrap())
            .collect()
    };
    let view_w = attr("viewBox", svg)[2];
    let sizes = attr("font-size", svg);
    assert!(!sizes.is_empty(), "no text in {svg}");
    sizes.iter().fold(f64::MAX, |m, s| m.min(*s)) * print.pt() / view_w
}

/// Every figure prints its text at 8 pt or more at the width the report CSS gives it (issue 36:
/// every plot readable on paper), and the sizes meant (8.5 pt labels) are the sizes written.
#[test]
fn every_figure_prints_text_of_at_least_8_pt() {
    let codes: Vec<String> = ["SF", "SL", "ST", "STT", "STP", "SV", "STV", "WQK"]
        .map(String::from)
        .to_vec();
    let z: Vec<f64> = vec![0.5, -1.0, 7.0, 2.5, f64::NAN, -0.4, 1.2, -6.0];
    let cycle: Vec<f64> = (0..101).map(|i| (i as f64 / 16.0).sin() * 30.0).collect();
    let curve = ("left (n = 9 strides)".into(), cycle.clone(), vec![3.0; 101]);
    let signal: Vec<f64> = (0..1000).map(|i| (i as f64 / 20.0).sin()).collect();
    let figures = [
        (
            radar_svg(
                "Subject H01: z-scores against the healthy reference",
                &codes,
                &[("left".into(), z.clone()), ("right".into(), z)],
            )
            .unwrap(),
            RADAR_PRINT,
        ),
        (
            cycle_svg(
                "Subject H01: shank pitch over the gait cycle",
                "shank pitch (deg)",
                std::slice::from_ref(&curve),
                Some(&curve),
            )
            .unwrap(),
            CYCLE_PRINT,
        ),
        (
            stride_series_svg(
                "Stride time",
                "stride time (s)",
                &[("left".into(), vec![(1.0, 1.1, true), (2.1, 1.2, false)])],
            )
            .unwrap(),
            STRIDE_SERIES_PRINT,
        ),
        (
            signals_svg(
                "left shank",
                0.0,
                100.0,
                &[Panel {
                    y_label: "acceleration (g)".into(),
                    series: vec![("x".into(), signal)],
                }],
                None,
            )
            .unwrap(),
            SIGNALS_PRINT,
        ),
        (
            boxplot_svg(
                "STV (CV %)",
                &[
                    ("LDHH".into(), vec![1.0, 2.0, 3.0]),
                    ("H".into(), vec![2.0, 2.5]),
                ],
                true,
            )
            .unwrap(),
            BOX_PRINT,
        ),
        (
            confusion_svg("RF", &["H".into(), "LDH".into()], &[vec![5, 1], vec![2, 4]]).unwrap(),
            CONFUSION_PRINT,
        ),
        (
            timing_histogram_svg("Timing error of the heel strikes", &[-3.0, 1.0, 2.0, 8.0])
                .unwrap(),
            TIMING_PRINT,
        ),
        (
            bland_altman_svg(
                "stride length, per stride",
                "mean of ldh and reference (m)",
                "ldh − reference (m)",
                &[("left".into(), vec![(1.2, 0.01), (1.3, -0.02), (1.25, 0.0)])],
                &ldh_core::agreement::LimitsOfAgreement {
                    bias: 0.0,
                    sd_diff: 0.015,
                    lower: -0.03,
                    upper: 0.03,
                    bias_ci: (-0.01, 0.01),
                    lower_ci: (-0.05, -0.01),
                    upper_ci: (0.01, 0.05),
                },
            )
            .unwrap(),
            BLAND_ALTMAN_PRINT,
        ),
    ];
    for (svg, print) in &figures {
        let pt = smallest_printed_pt(svg, *print);
        assert!(
            (MIN_PRINT_TEXT_PT..9.0).contains(&pt),
            "{:?}: smallest text prints at {pt:.2} pt (8 pt at least, and no needlessly large labels)",
            &svg[..120]
        );
    }
    // The widths: thirds and fifths side by side (4 pt apart) on the A4 text width.
    assert!(3.0 * PrintWidth::Third.pt() + 8.0 <= A4_TEXT_WIDTH_PT);
    assert!(5.0 * PrintWidth::Fifth.pt() + 16.0 <= A4_TEXT_WIDTH_PT);
    assert!(PrintWidth::Full.pt() <= A4_TEXT_WIDTH_PT);
}

/// Bins of 1, 2 or 5 × 10ᵏ, at most 24 over the range, starting at a multiple of the width;
/// empty bins kept; the histogram draws one bar per non-empty bin.
#[test]
fn histogram_bins_and_bars() {
    let v = [-12.0, -3.0, 0.0, 4.0, 4.5, 31.0, f64::NAN];
    let (w, bins) = histogram_bins(&v, 1.0);
    assert_eq!(w, 2.0, "43 / 24 = 1.8 → 2");
    assert_eq!(bins.len(), 22, "-12 … 30");
    assert_eq!(bins[0], (-12.0, 1));
    assert_eq!(bins[4], (-4.0, 1));
    assert_eq!(bins[6], (0.0, 1));
    assert_eq!(bins[8], (4.0, 2));
    assert_eq!(bins[21], (30.0, 1));
    assert_eq!(bins.iter().map(|b| b.1).sum::<usize>(), 6);
    let (w, bins) = histogram_bins(&[1.0, 1.2], 1.0);
    assert_eq!(
        (w, bins),
        (1.0, vec![(1.0, 2)]),
        "at least the minimum width"
    );
    assert!(histogram_bins(&[], 1.0).1.is_empty());
    let svg = timing_histogram_svg("HS", &v).unwrap();
    let c = TIMING_BAR_COLOUR;
    let fill = format!("fill=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
    assert_eq!(svg.matches(&fill).count(), 5, "five non-empty bins");
    assert!(svg.contains(TIMING_X_LABEL) && svg.contains("bias +4.1 ms"));
    assert!(timing_histogram_svg("HS", &[f64::NAN]).is_err());
}

/// A Bland–Altman plot: one dot per finite pair; the bias and the limits are written in the
/// legend.
#[test]
fn bland_altman_draws_every_pair() {
    let limits = ldh_core::agreement::LimitsOfAgreement {
        bias: 0.01,
        sd_diff: 0.02,
        lower: -0.0292,
        upper: 0.0492,
        bias_ci: (0.0, 0.02),
        lower_ci: (-0.04, -0.02),
        upper_ci: (0.04, 0.06),
    };
    let series = [
        ("left".into(), vec![(1.0, 0.01), (1.1, 0.03), (1.2, -0.01)]),
        ("right".into(), vec![(1.05, 0.02), (f64::NAN, 0.0)]),
    ];
    let svg = bland_altman_svg(
        "stride time",
        "mean of ldh and reference (s)",
        "ldh − reference (s)",
        &series,
        &limits,
    )
    .unwrap();
    assert_eq!(
        svg.matches("<circle").count(),
        4,
        "no legend dots: the caption names the sides"
    );
    assert!(svg.contains("bias +0.010") && svg.contains("limits -0.029 to +0.049"));
    assert!(bland_altman_svg("x", "a (s)", "b (s)", &[], &limits).is_err());
}

/// A side's series is drawn in its side's colour whatever its position and text; any other
/// series by its position, whatever its text says.
#[test]
fn a_series_colour_follows_its_side_not_its_text() {
    use super::{colour_of, SeriesName, COLORS};
    use ldh_core::Side;
    assert_eq!(
        colour_of(&SeriesName::of_side(Side::Right, "R"), 0),
        COLORS[1]
    );
    assert_eq!(
        colour_of(&SeriesName::of_side(Side::Left, "L"), 3),
        COLORS[0]
    );
    assert_eq!(colour_of(&"left".into(), 1), COLORS[1]);
    assert_eq!(colour_of(&"right leg".into(), 4), COLORS[0]);
}

/// The x of an SVG `<text>` element whose content is `content` (as escaped in the SVG), px.
fn text_x(svg: &str, content: &str) -> Option<i32> {
    let at = svg.find(&format!(">\n{content}\n</text>"))?;
    let start = svg[..at].rfind("<text")?;
    let tag = &svg[start..at];
    let x = tag.split("x=\"").nth(1)?.split('"').next()?;
    x.parse().ok()
}

/// A long title is broken into lines, not cut at the canvas's edge; the rings' values are said
/// under the chart, not printed on it (issue 50's reading: "…healthy subje", and "z = +4.0"
/// over the next axis's name).
#[test]
fn the_radar_title_wraps_and_its_scale_stays_on_its_axis() {
    let codes: Vec<String> = ["SF", "SL", "ST", "WQK", "STP", "SWP"]
        .map(String::from)
        .to_vec();
    let title = "Subject L01: z-scores against this cohort's healthy subjects (n = 10)";
    let r = radar_svg(
        title,
        &codes,
        &[("left".into(), vec![0.5, 1.0, 3.5, -0.2, 0.1, 0.3])],
    )
    .unwrap();
    assert!(text_x(&r, "Subject L01:").is_some(), "{r}");
    assert!(
        text_x(
            &r,
            "z-scores against this cohort&apos;s healthy subjects (n = 10)"
        )
        .is_some(),
        "{r}"
    );
    let short = radar_svg("Fusion", &codes, &[("left".into(), vec![0.5; 6])]).unwrap();
    assert!(text_x(&short, "Fusion").is_some());
    assert!(
        text_x(&r, "z = +4.0").is_none(),
        "no ring label on the chart"
    );
    assert!(
        text_x(
            &r,
            "rings, centre to rim: z = -4.0, -2.0, 0 (black), +2.0, +4.0"
        )
        .is_some(),
        "{r}"
    );
}

/// The gait-cycle axis is labelled every 20 % in whole numbers ("90.0" and "100" touched).
#[test]
fn the_gait_cycle_axis_reads_in_whole_percent() {
    let s = cycle_svg(
        "cycle",
        "pitch (deg)",
        &[("left".into(), vec![0.0, 10.0, 5.0], vec![1.0, 1.0, 1.0])],
        None,
    )
    .unwrap();
    for tick in ["0", "20", "40", "60", "80", "100"] {
        assert!(text_x(&s, tick).is_some(), "tick {tick}: {s}");
    }
    assert!(text_x(&s, "90.0").is_none() && text_x(&s, "100.0").is_none());
}
