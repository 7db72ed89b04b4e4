//! The quality layer on the simulator and on synthetic strides (the HuGaDB checks are in
//! `tests/hugadb.rs`).

mod height;
pub(crate) mod hugadb;
mod hugadb_faults;
mod stride_length;

use super::*;

pub(crate) fn stride(i: usize, t: f64, stance: f64) -> crate::gait::Stride {
    crate::gait::Stride {
        stride_index: i,
        hs_time_s: i as f64 * t,
        to_time_s: i as f64 * t + stance * t,
        next_hs_time_s: (i + 1) as f64 * t,
        stride_time_s: t,
        stance_ratio: stance,
        double_support_ratio: f64::NAN,
        stride_length_m: 1.4,
        speed_mps: 1.4 / t,
        wqk_deg: 40.0,
        pbi_deg: 20.0,
        bdk_deg: 8.0,
        heading_change_deg: 0.0,
        bout: 0,
        valid: true,
        reason: String::new(),
        findings: Vec::new(),
        vertical_m: f64::NAN,
    }
}

/// A leg-level finding that withholds the angles and stride length blanks them per stride and
/// says why in the stride's reason; one that withholds everything invalidates the stride.
#[test]
fn blanked_stride_cells_carry_the_findings_reason() {
    let mut st: Vec<crate::gait::Stride> = (0..3).map(|i| stride(i, 1.0, 0.6)).collect();
    st[1].stride_length_m = f64::NAN;
    st[1].push(crate::gait::StrideFinding::new(
        crate::gait::StrideCode::Length(crate::gait::LengthCheck::Drift),
        "stride length withheld: velocity drift 1.00 m/s over the stride",
    ));
    let w = Warning::new(
        codes::ATTITUDE_DIVERGENCE,
        Severity::Warning,
        "the shank attitude drifts",
    )
    .withholding(&[
        Parameter::Wqk,
        Parameter::Pbi,
        Parameter::Bdk,
        Parameter::StrideLength,
        Parameter::Speed,
    ]);
    apply_to_strides(&mut st, std::slice::from_ref(&w));
    assert!(st.iter().all(|s| s.valid && s.wqk_deg.is_nan()));
    assert!(st.iter().all(|s| s.stride_length_m.is_nan()));
    assert_eq!(
        st[0].reason,
        "angles and stride length withheld: the sensor's tilt estimate drifts"
    );
    assert_eq!(
        st[1].reason,
        "stride length withheld: velocity drift 1.00 m/s over the stride; angles withheld: the sensor's tilt estimate drifts"
    );
    // applied twice (leg, then pair): one reason
    apply_to_strides(&mut st, &[w]);
    assert_eq!(
        st[0].reason,
        "angles and stride length withheld: the sensor's tilt estimate drifts"
    );
    let all = Warning::new(
        codes::GYRO_SCALE_FAULT,
        Severity::Fault,
        "gyroscope scale fault",
    )
    .withholding(&params::ALL);
    apply_to_strides(&mut st, &[all]);
    assert!(st.iter().all(|s| !s.valid && s.reason == "gyroscope fault"));
}
