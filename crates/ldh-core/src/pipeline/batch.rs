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

#[cfg(test)]
mod tests {
    use super::*;

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
