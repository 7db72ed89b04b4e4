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
    assert!(
        r.starts_with("<svg") && r.contains("LDHE") && r.contains("SL") && r.contains("z-score")
    );
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
    assert!(c.contains("clipped at ±4 SD: right SF z = +12.0"), "{c}");
    assert!(c.contains("z = +4.0"), "the scale stops at 4 SD");
    assert!(!c.contains("z = +6.0") && !c.contains("z = +10.0"));
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
fn smallest_printed_pt(svg: &str, print: PrintWidth) -> f64 {
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
    let curve = (
        "left (n = 9 strides)".to_string(),
        cycle.clone(),
        vec![3.0; 101],
    );
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
