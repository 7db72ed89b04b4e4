//! What a clinician's reading of pages not read before found untrue or unclear (docs/reports.md
//! "2026-12-03, evening reading"): TRIPOD's slowest treadmill run alone, whose belt speed was
//! "the walking speed" and yet "could not be measured" and never judged; a simulated slow
//! hemiparetic walker whose to-do asked for a longer walk although the value it answered was
//! withheld because the other leg's stride length failed its checks.

use super::headline::{leg, leg_of, page_parts, warn};
use ldh_core::domain::Parameter;
use ldh_core::pipeline::{Severity, Warning};

/// TRIPOD `Sub_FZ` PWS−20 alone: belt 0.83 m/s, no sensor height, so the sensors' walking speed
/// is withheld. The belt's speed is the walking speed and is judged against the published range
/// (below 1.00–1.60 m/s); "Could not be measured" does not list the walking speed the sentence
/// above it gives.
#[test]
fn a_belt_speed_is_judged_and_not_listed_as_not_measured() {
    let mut recs = vec![leg("FZ", "left", 0.725), leg("FZ", "right", 0.725)];
    for r in recs.iter_mut() {
        r.setting = Some(ldh_core::Setting::Treadmill.into());
        r.belt_speed_mps = Some(0.833);
        warn(
            r,
            "sensor_height_unknown",
            &["stride_length_m", "speed_mps", "stride_length_cv"],
        );
    }
    let (html, _, h) = page_parts(recs);
    let belt = "On a treadmill, belt at 0.83 m/s: the walking speed is the belt's, below normal (normal 1.00–1.60 m/s); the sensors could not estimate it.";
    assert_eq!(h.belt.as_deref(), Some(belt));
    assert!(html.contains(belt));
    assert_eq!(
        h.not_measured.as_deref(),
        Some("Could not be measured: stride length, stride length variability.")
    );
    // Without a belt speed the sensors' missing estimate is listed as before.
    let mut recs = vec![leg("G", "left", 0.725), leg("G", "right", 0.725)];
    for r in recs.iter_mut() {
        warn(
            r,
            "sensor_height_unknown",
            &["stride_length_m", "speed_mps", "stride_length_cv"],
        );
    }
    let (_, _, h) = page_parts(recs);
    assert_eq!(
        h.not_measured.as_deref(),
        Some("Could not be measured: walking speed, stride length, stride length variability.")
    );
}

/// The `sv_unchecked` warning, as the pipeline writes it, on `r` (its stride length
/// variability withheld).
fn unchecked(r: &mut ldh_core::output::RecordingRow, why: &str) {
    let w = ldh_core::pipeline::quality::unchecked_warning(0.04, why);
    r.set_value(Parameter::StrideLengthCv, None);
    r.withheld
        .0
        .insert(Parameter::StrideLengthCv, w.withheld_reason());
    r.warnings.0.push(w);
}

/// Family B's slow hemiparetic walker (90 s on a treadmill, 55 s steady): the left stride
/// length passed its checks on too few strides (a reason that asks for nothing), so the right
/// leg's stride length variability could not be checked against the left's (`sv_unchecked`).
/// The page asked to "Record a longer walk (at least 30 s of straight walking)"; a longer walk
/// changes neither. Both legs unchecked because the walk was short still ask for it.
#[test]
fn a_variability_unchecked_for_want_of_the_other_leg_does_not_ask_for_a_longer_walk() {
    let mut recs = vec![leg_of("BP", "left", 0.77), leg_of("BP", "right", 0.77)];
    // Left: stride length withheld by its own checks (no finding), so no variability either.
    for p in [
        Parameter::StrideLength,
        Parameter::Speed,
        Parameter::StrideLengthCv,
    ] {
        recs[0].set_value(p, None);
        recs[0].withheld.0.insert(
            p,
            ldh_core::domain::Reason::new(
                ldh_core::domain::ReasonCode::LengthNotVouched,
                "stride length passed its checks on only 16 of 35 strides (most often: velocity drift)",
            ),
        );
    }
    unchecked(
        &mut recs[1],
        "the left leg reports no stride length variability",
    );
    let (_, _, h) = page_parts(recs.clone());
    assert_eq!(h.to_do, None, "{h:?}");
    // A walk too short to pair the legs' strides: both unchecked, a longer walk helps.
    let mut short = vec![leg_of("S", "left", 0.525), leg_of("S", "right", 0.525)];
    for r in short.iter_mut() {
        unchecked(r, "too few strides");
    }
    let (_, _, h) = page_parts(short);
    assert_eq!(
        h.to_do.as_deref(),
        Some("Record a longer walk (at least 30 s of straight walking).")
    );
    // A note on the left leg alone changes nothing.
    recs[0].warnings.0.push(Warning::new(
        ldh_core::pipeline::quality::codes::SENSOR_HEIGHT_UNKNOWN,
        Severity::Note,
        "the sensor height was not given, so 0.10 m above the ankle was assumed",
    ));
    assert_eq!(page_parts(recs).2.to_do, None);
}

/// HuGaDB P08 analysed with `--no-sta`: STA's cell read "not measured: not computed: turned off
/// for this run (--no-sta, or compute_sta=False in Python)" on the clinical part, and its
/// technical fact "not computed: not computed: …". Now the cell says "turned off for this run"
/// once, without the command-line switch, and the fact says "not computed" once.
#[test]
fn sta_turned_off_is_said_once_in_plain_words() {
    let mut recs = vec![leg("N", "left", 0.525), leg("N", "right", 0.525)];
    for r in recs.iter_mut() {
        r.parameters.sta_status = ldh_core::pipeline::STA_TURNED_OFF.into();
    }
    assert_eq!(
        super::super::measured::not_measured(&recs[0], Parameter::Sta).as_deref(),
        Some("turned off for this run")
    );
    let (html, _, _) = page_parts(recs);
    assert!(html.contains("turned off for this run"), "no STA reason");
    assert!(!html.contains("--no-sta") && !html.contains("compute_sta"));
    assert!(!html.contains("not computed: not computed"));
    assert!(!html.contains("not measured: not computed"));
}
