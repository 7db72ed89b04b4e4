//! Units in headers (`units.rs`, `labelled.rs`): the spellings device exports write, each read
//! into the same recording as ldh's own format; unknown, wrong, missing and mixed units refused
//! with file, line and column; a given map keeps its units; the per-column report.

use super::super::units::{split_label, Quantity, Unit};
use crate::recording::STANDARD_GRAVITY_MPS2;

const MPS2: f64 = STANDARD_GRAVITY_MPS2;
const RAD: f64 = std::f64::consts::PI / 180.0;

#[test]
fn unit_spellings_parse_to_their_unit_and_factor() {
    let cases: [(&str, Unit); 24] = [
        ("g", Unit::G),
        ("[g]", Unit::G),
        ("m/s^2", Unit::MetresPerSecond2),
        ("m/s2", Unit::MetresPerSecond2),
        ("m/s²", Unit::MetresPerSecond2),
        ("M/S^2", Unit::MetresPerSecond2),
        ("m s^-2", Unit::MetresPerSecond2),
        ("m/s/s", Unit::MetresPerSecond2),
        ("(m/(s^2))", Unit::MetresPerSecond2),
        ("deg/s", Unit::DegreesPerSecond),
        ("°/s", Unit::DegreesPerSecond),
        ("dps", Unit::DegreesPerSecond),
        ("deg/sec", Unit::DegreesPerSecond),
        ("degrees/s", Unit::DegreesPerSecond),
        ("rad/s", Unit::RadiansPerSecond),
        ("rad s^-1", Unit::RadiansPerSecond),
        ("s", Unit::Seconds),
        ("sec", Unit::Seconds),
        ("ms", Unit::Milliseconds),
        ("msec", Unit::Milliseconds),
        ("us", Unit::Microseconds),
        ("µs", Unit::Microseconds),
        ("μs", Unit::Microseconds),
        (" [usec] ", Unit::Microseconds),
    ];
    for (text, unit) in cases {
        assert_eq!(text.parse::<Unit>(), Ok(unit), "{text}");
    }
    for bad in ["m/s", "mg", "rps", "furlongs", "", "kg"] {
        let e = bad.parse::<Unit>().unwrap_err();
        assert_eq!(e.0, bad, "{bad}");
    }
    assert_eq!(Unit::MetresPerSecond2.to_internal(), 1.0 / MPS2);
    assert_eq!(Unit::RadiansPerSecond.to_internal(), 1.0 / RAD);
    assert_eq!(Unit::Milliseconds.to_internal(), 1e-3);
    assert_eq!(Unit::Microseconds.to_internal(), 1e-6);
    assert_eq!(Unit::G.to_internal(), 1.0);
    assert_eq!(Unit::RadiansPerSecond.quantity(), Quantity::AngularRate);
    assert_eq!(Unit::Microseconds.internal(), Unit::Seconds);
}

#[test]
fn labels_are_cut_into_name_and_unit() {
    let cases = [
        ("Acc_X [m/s^2]", ("Acc_X", Some("m/s^2"))),
        ("acc_x (g)", ("acc_x", Some("g"))),
        ("GyrX/deg/s", ("GyrX", Some("deg/s"))),
        ("gyro_x / rad/s", ("gyro_x", Some("rad/s"))),
        ("AccX [m/s²]", ("AccX", Some("m/s²"))),
        ("Gyr_X (°/s)", ("Gyr_X", Some("°/s"))),
        ("acc_x (m/(s^2))", ("acc_x", Some("m/(s^2)"))),
        ("time_[ms]", ("time", Some("ms"))),
        ("acc_x", ("acc_x", None)),
        ("[g]", ("[g]", None)),
        ("acc_x/", ("acc_x/", None)),
    ];
    for (cell, want) in cases {
        assert_eq!(split_label(cell), want, "{cell}");
    }
}
