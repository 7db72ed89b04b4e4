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
        "ST",
        "stride time (s)",
        &[
            ("LDHH".into(), vec![1.0, 1.1, 1.2, 1.05]),
            ("H".into(), vec![0.9, 1.0, 0.95]),
        ],
    )
    .unwrap();
    assert!(b.contains("stride time (s)") && b.contains("group") && b.contains("LDHH"));
    assert!(boxplot_svg("x", "y", &[("A".into(), vec![])]).is_err());
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
