//! For the library front ends (the Python binding, notebooks): a subject's two legs given as
//! arrays instead of files, a subject without a manifest row. The CLI and the binding only
//! adapt arguments around these and [`Analysis`].

use super::*;
use crate::recording::{Recording, Side};

/// One leg given as arrays (acceleration in g, angular velocity in deg/s, sampled at `fs_hz`),
/// as a [`LoadedLeg`] for [`Analysis::pair`]: an invalid recording becomes that leg's error.
pub fn leg_from_arrays(
    fs_hz: f64,
    acc_g: [Vec<f64>; 3],
    gyro_dps: [Vec<f64>; 3],
    side: Side,
) -> LoadedLeg {
    let rec = Recording::new(fs_hz, acc_g, gyro_dps, vec![])
        .map_err(|e| format!("{side}: {e}"))?
        .with_side(side);
    let report = memory_report(&rec);
    Ok((rec, report, format!("<{side} arrays>")))
}

/// A subject without a manifest row: only its identifier.
pub fn bare_subject(subject_id: &str) -> SubjectInput {
    SubjectInput {
        subject_id: subject_id.to_string(),
        ..SubjectInput::default()
    }
}

/// The clocks of two legs handed over as arrays when the caller says nothing: two, as two files
/// are ([`SubjectInput::clocks`]). Arrays carry no sign of one device (two rates may be given),
/// two separately recorded sensors are the common case, and two clocks only withhold a step
/// asymmetry the legs' own swing times do not back (`two_clocks`), where one clock taken on
/// trust would report an offset as the walker's asymmetry.
pub const ARRAYS_CLOCKS: Clocks = Clocks::Two;

/// A subject whose two legs are handed over as arrays (Python's `analyze_pair`): no files to
/// judge the clocks by, so they are as stated (`clocks`), else [`ARRAYS_CLOCKS`].
pub fn arrays_subject(subject_id: &str, clocks: Option<Clocks>) -> SubjectInput {
    SubjectInput {
        clocks: Some(clocks.unwrap_or(ARRAYS_CLOCKS)),
        ..bare_subject(subject_id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::domain::Parameter;
    use crate::pipeline::quality::codes;

    /// The embedded demo's healthy H01 as arrays, the right sensor's clock `late_s` late.
    fn h01_as_arrays(clocks: Option<Clocks>, late_s: f64) -> SubjectResult {
        let leg = |side: Side| -> LoadedLeg {
            let mut rec = crate::demo::recording(&format!("H01/{side}.csv")).unwrap();
            if side == Side::Right {
                rec.t0_s += late_s;
            }
            let report = memory_report(&rec);
            Ok((rec.with_side(side), report, format!("<{side} arrays>")))
        };
        let p = AnalysisParams {
            compute_sta: false,
            ..Default::default()
        }
        .check()
        .unwrap();
        let input = arrays_subject("H01", clocks);
        Analysis::new(p).pair(&input, leg(Side::Left), leg(Side::Right))
    }

    #[test]
    fn sta_turned_off_is_said_in_plain_words() {
        let r = h01_as_arrays(None, 0.0);
        for (_, leg) in r.legs() {
            let status = &leg.as_ref().unwrap().parameters.sta_status;
            assert_eq!(status, "not computed: turned off for this run");
            assert_eq!(status, STA_TURNED_OFF);
        }
    }

    #[test]
    fn arrays_are_two_clocks_unless_said() {
        assert_eq!(arrays_subject("S", None).clocks(), Some(Clocks::Two));
        let one = arrays_subject("S", Some(Clocks::One));
        assert_eq!(one.clocks(), Some(Clocks::One));
        assert_eq!(one.subject_id, "S");
        // A 55 ms offset (TRIPOD's smallest) on a healthy walker: from two clocks the step
        // time is withheld on both legs; stated as one clock it is reported.
        let fired = |r: &SubjectResult| r.warnings.iter().any(|w| w.code == codes::TWO_CLOCKS);
        let step = |r: &SubjectResult| {
            r.legs()
                .map(|(_, l)| l.as_ref().unwrap().parameters.values[Parameter::StepTime])
        };
        let two = h01_as_arrays(None, 0.055);
        assert!(fired(&two), "{:?}", two.warnings);
        assert!(step(&two).iter().all(|v| v.is_nan()), "{:?}", step(&two));
        let one = h01_as_arrays(Some(Clocks::One), 0.055);
        assert!(!fired(&one), "{:?}", one.warnings);
        assert!(step(&one).iter().all(|v| v.is_finite()), "{:?}", step(&one));
        // Without an offset, two clocks withhold nothing from a symmetric walker.
        let aligned = h01_as_arrays(None, 0.0);
        assert!(!fired(&aligned), "{:?}", aligned.warnings);
    }

    #[test]
    fn the_result_does_not_depend_on_the_number_of_threads() {
        let subjects = demo_inputs().unwrap();
        let p = AnalysisParams {
            compute_sta: false,
            ..Default::default()
        }
        .check()
        .unwrap();
        let on = |n| {
            Analysis::new(p.clone())
                .jobs(n)
                .many(&subjects[..2])
                .results()
                .unwrap()
        };
        let (one, two) = (on(1), on(2));
        // NaN (STA not computed) is not equal to itself: compare the serialised results.
        let json = |r: &[SubjectResult]| serde_json::to_string(r).unwrap();
        assert_eq!(json(&one), json(&two));
        assert_eq!(one[0].subject_id, subjects[0].subject_id);
    }

    #[test]
    fn a_bad_array_is_that_legs_error() {
        let leg = leg_from_arrays(
            100.0,
            [vec![], vec![], vec![]],
            [vec![], vec![], vec![]],
            Side::Left,
        );
        assert!(leg.unwrap_err().starts_with("left: "));
    }
}
