//! `sensor_height_unknown`: a stride length computed with an assumed sensor height, said
//! (a note) or withheld (a warning) by how much it depends on the height
//! ([`crate::gait::height_sensitivity`]; docs/quality.md; issue 20).

use super::warning::{codes, params, Severity, Warning};
use crate::gait::{HeightSensitivity, MAX_HEIGHT_SPREAD_SHARE};

/// Where a user gives the height (the end of every `sensor_height_unknown` message).
const GIVE_IT: &str =
    "give it (manifest column sensor_height_m, --sensor-height-m, or sensor_height_m= in Python)";

/// The finding about a leg whose stride length used an assumed sensor height: a warning
/// withholding stride length, speed and SV when the leg's median stride length moves by more
/// than [`MAX_HEIGHT_SPREAD_SHARE`] across the range of heights (or an end of the range has no
/// length to bound it), else a note saying the height was assumed, with the movement. Kept
/// short: it is printed in the subject report's box of findings.
pub fn sensor_height_warning(s: &HeightSensitivity) -> Warning {
    let [lo, hi] = s.range_m;
    let ends = match s.at_ends_m {
        [Some(a), Some(b)] => {
            format!("{a:.2} and {b:.2} m with the sensor {lo:.2} and {hi:.2} m above the ankle")
        }
        [a, b] => {
            let one = |m: Option<f64>, h: f64| {
                m.map_or_else(
                    || format!("none (no stride passes the integration checks) at {h:.2} m"),
                    |m| format!("{m:.2} m at {h:.2} m"),
                )
            };
            format!("{} and {} above the ankle", one(a, lo), one(b, hi))
        }
    };
    let tol = MAX_HEIGHT_SPREAD_SHARE * 100.0;
    match s.spread_share() {
        Some(e) if s.vouched() => Warning::new(
            codes::SENSOR_HEIGHT_UNKNOWN,
            Severity::Note,
            format!(
                "the sensor height was not given, so {:.2} m above the ankle was assumed; the median stride length {:.2} m would be {ends}, a movement of {:.1} % (at most {tol:.0} %), so it is reported; {GIVE_IT} to remove this uncertainty",
                s.assumed_m, s.median_m, e * 100.0
            ),
        ),
        spread => Warning::new(
            codes::SENSOR_HEIGHT_UNKNOWN,
            Severity::Warning,
            format!(
                "the sensor height was not given and the stride length depends on it; the median stride length would be {ends}, {:.2} m at the assumed {:.2} m, {}, so stride length, speed and their variability are not measured: {GIVE_IT}",
                s.median_m,
                s.assumed_m,
                spread.map_or_else(
                    || "a movement that cannot be bounded".to_string(),
                    |e| format!("a movement of {:.0} % (more than {tol:.0} %)", e * 100.0)
                ),
            ),
        )
        .withholding(&params::LENGTH),
    }
}
