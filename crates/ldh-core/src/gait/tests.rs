//! Unit tests of the per-leg stride-length rules of evidence (`gait::side_parameters`,
//! `gait::withhold_unvouched_lengths`).

use super::*;
use crate::domain::Parameter;

/// `n` valid 1.1 s strides of which the first `with_length` have a 1.30 m length.
fn side(n: usize, with_length: usize) -> SideParameters {
    side_parameters(&leg(n, with_length), None)
}

#[test]
fn survivors_of_an_unvouched_leg_lose_their_lengths_too() {
    let mut st = leg(127, 4);
    withhold_unvouched_lengths(&mut st);
    assert!(st
        .iter()
        .all(|s| s.stride_length_m.is_nan() && s.speed_mps.is_nan()));
    assert!(st.iter().all(|s| s.valid), "timing stays valid");
    assert!(st[0]
        .reason
        .contains("only 4 of the leg's 127 valid strides pass the integration checks"));
    let p = side_parameters(&st, None);
    assert!(p[Parameter::StrideLength].is_nan());
    // the leg's reason still counts the survivors as having passed their own checks
    assert_eq!(
        p.withheld.reason(Parameter::StrideLength).unwrap(),
        "stride length passed its checks on only 4 of 127 strides (most often: velocity drift)"
    );
    // a vouched leg is left alone
    let mut st = leg(20, 12);
    withhold_unvouched_lengths(&mut st);
    assert_eq!(
        st.iter().filter(|s| s.stride_length_m.is_finite()).count(),
        12
    );
}

fn leg(n: usize, with_length: usize) -> Vec<Stride> {
    (0..n)
        .map(|k| Stride {
            stride_index: k,
            hs_time_s: 1.1 * k as f64,
            to_time_s: 1.1 * k as f64 + 0.66,
            next_hs_time_s: 1.1 * (k + 1) as f64,
            stride_time_s: 1.1,
            stance_ratio: 0.6,
            double_support_ratio: f64::NAN,
            stride_length_m: if k < with_length { 1.3 } else { f64::NAN },
            speed_mps: if k < with_length { 1.3 / 1.1 } else { f64::NAN },
            wqk_deg: 30.0,
            pbi_deg: 45.0,
            bdk_deg: 8.0,
            heading_change_deg: 0.0,
            bout: 0,
            valid: true,
            reason: String::new(),
            findings: Vec::new(),
            vertical_m: f64::NAN,
        })
        .map(|mut s| {
            if !s.stride_length_m.is_finite() {
                s.push(StrideFinding::new(
                    StrideCode::Length(LengthCheck::Drift),
                    "stride length withheld: velocity drift 2.00 m/s over the stride",
                ));
            }
            s
        })
        .collect()
}

#[test]
fn a_side_length_needs_most_strides_vouched_for() {
    // 4 of 127 passing (HuGaDB 06_00's right leg): survivors, not a sample
    let p = side(127, 4);
    assert!(p[Parameter::StrideLength].is_nan() && p[Parameter::Speed].is_nan());
    assert_eq!(
        p.withheld.reason(Parameter::StrideLength).unwrap(),
        "stride length passed its checks on only 4 of 127 strides (most often: velocity drift)"
    );
    assert!(
        (p[Parameter::StrideTime] - 1.1).abs() < 1e-12,
        "timing stays"
    );
    // half of them: reported
    let p = side(20, 10);
    assert!((p[Parameter::StrideLength] - 1.3).abs() < 1e-12 && p.withheld.is_empty());
    // short legs: half, and at least one
    assert!((side(4, 2)[Parameter::StrideLength] - 1.3).abs() < 1e-12);
    assert!(side(4, 1)[Parameter::StrideLength].is_nan());
    assert!(side(10, 3)[Parameter::StrideLength].is_nan());
}

#[test]
fn a_side_length_blanked_by_a_finding_names_the_finding() {
    // The pair's left/right check blanked every stride's length (quality::apply_to_strides).
    let mut st = leg(10, 0);
    for s in st.iter_mut() {
        s.replace_findings(StrideFinding::new(
            StrideCode::Finding {
                code: crate::domain::codes::LR_DISAGREEMENT,
                effect: super::FindingEffect::Length,
            },
            "stride length withheld: the two legs disagree",
        ));
    }
    let p = side_parameters(&st, None);
    assert_eq!(
        p.withheld.reason(Parameter::StrideLength).unwrap(),
        "the two legs disagree"
    );
    // A length that was simply not finite, with no reason, is "not integrable".
    for s in st.iter_mut() {
        s.findings.clear();
    }
    let p = side_parameters(&st, None);
    assert_eq!(
        p.withheld.reason(Parameter::StrideLength).unwrap(),
        "not integrable"
    );
}

/// A leg's parameters are written (Python's `analyze_recording(...)["parameters"]`) with the keys
/// and in the order they had as named fields, and read back.
#[test]
fn side_parameters_keep_their_keys_and_order() {
    let mut p = side(8, 8);
    p.withhold(
        Parameter::Sta,
        crate::domain::Reason::read("too short"),
        true,
    );
    let json = serde_json::to_string(&p).unwrap();
    let keys: Vec<&str> = json
        .split('"')
        .collect::<Vec<_>>()
        .windows(3)
        .filter(|w| w[2].starts_with(':') && !w[1].is_empty())
        .map(|w| w[1])
        .collect();
    assert_eq!(
        keys,
        [
            "strides_total",
            "strides_valid",
            "stride_time_s",
            "step_time_s",
            "step_frequency_hz",
            "stance_ratio",
            "swing_ratio",
            "double_support_ratio",
            "stride_length_m",
            "speed_mps",
            "stride_length_cv",
            "stride_time_cv",
            "sta_per_s",
            "sta_per_stride",
            "sta_status",
            "wqk_deg",
            "pbi_deg",
            "bdk_deg",
            "withheld",
            "sta_per_s",
            "sta_per_stride"
        ]
    );
    let back: SideParameters = serde_json::from_str(&json).unwrap();
    assert_eq!(back.withheld, p.withheld);
    assert_eq!(back[Parameter::StrideTime], p[Parameter::StrideTime]);
    assert_eq!(back.sta_status, p.sta_status);
    assert!(!serde_json::to_string(&side(8, 8))
        .unwrap()
        .contains("withheld"));
}
