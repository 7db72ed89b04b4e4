//! HuGaDB stride length across clipped heel strikes (issue 20 item 1) and without a sensor
//! height (issue 20, `sensor_height_unknown`): on the five files with two clean shank
//! gyroscopes, read through the built-in format maps (the CLI's path, ±2 g accelerometers
//! clipping in 3-21 % of the samples), analysed without a sensor height (as a manifest that
//! leaves the column out) and with the height HuGaDB's README documents.
//!
//! Without a height every leg that has a length carries `sensor_height_unknown`: a warning
//! that withholds its stride length, speed and SV (every stride's length with the reason) when
//! the leg median moves by more than 15 % over 0.05-0.35 m, else a note and the length reported.
//! With the README's height nothing is said about the height. Either way, a leg that reports
//! its length has a median that agrees with the other leg's within 10 % when that one reports
//! too (issue 20's criterion) and lies in the range of healthy young adults' strides, and a
//! leg that does not says why.

use super::super::codes;
use super::hugadb::{hugadb_dir, read_hugadb_map, HUGADB_CLEAN};
use crate::domain::Parameter;
use crate::pipeline::{
    memory_report, Analysis, AnalysisParams, LegResult, LoadedLeg, Severity, SubjectInput,
};

/// HuGaDB's shin sensors sit "around the middle of the shinbone at the level where the calf
/// ends" (README); no distance is given, so the height is half the shank, 0.5 × 0.246 × body
/// height (Winter 2009, Fig. 4.1), with each participant's body height from the README's
/// Table 2 (01: 177 cm, 06: 168, 08: 176, 10: 183, 11: 203): 0.21-0.25 m.
fn readme_sensor_height_m(file: &str) -> f64 {
    let body_m = match &file[..2] {
        "01" => 1.77,
        "06" => 1.68,
        "08" => 1.76,
        "10" => 1.83,
        "11" => 2.03,
        other => panic!("no body height for participant {other}"),
    };
    0.5 * 0.246 * body_m
}

/// Median of the finite values, NaN when there are none.
fn median(mut v: Vec<f64>) -> f64 {
    v.retain(|x| x.is_finite());
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        f64::NAN
    } else {
        v[v.len() / 2]
    }
}

/// The leg's median stride length when it reports one (NaN when not), after checking that a
/// length withheld says why and that `sensor_height_unknown` appears exactly when the height
/// was not given (`failures` collects what is wrong).
fn checked_median(name: &str, l: &LegResult, given: bool, failures: &mut Vec<String>) -> f64 {
    let p = &l.parameters;
    let why = p
        .withheld
        .reason(crate::domain::Parameter::StrideLength)
        .unwrap_or_default()
        .to_string();
    let height = l
        .warnings
        .iter()
        .find(|w| w.code == codes::SENSOR_HEIGHT_UNKNOWN);
    let m = median(l.strides.iter().map(|s| s.stride_length_m).collect());
    println!(
        "{name}: stride length {:.3} m, median {m:.3} m, {} of {} valid strides with a length; {why}{}",
        p[Parameter::StrideLength],
        l.strides.iter().filter(|s| s.valid && s.stride_length_m.is_finite()).count(),
        p.strides_valid,
        height.map_or(String::new(), |w| format!("\n    {w}")),
    );
    if p[Parameter::StrideLength].is_nan() && why.is_empty() {
        failures.push(format!("{name}: no stride length and no reason"));
    }
    match (given, height) {
        (true, Some(w)) => failures.push(format!("{name}: height given, yet {w}")),
        (false, None) if p[Parameter::StrideLength].is_finite() => {
            failures.push(format!("{name}: length from an assumed height, not said"))
        }
        (false, Some(w))
            if w.severity == Severity::Warning
                && (p[Parameter::StrideLength].is_finite()
                    || !l.strides.iter().all(|s| s.stride_length_m.is_nan())) =>
        {
            failures.push(format!("{name}: {w}, yet a length is reported"))
        }
        _ => {}
    }
    if p[Parameter::StrideLength].is_finite() {
        m
    } else {
        f64::NAN
    }
}

#[test]
fn hugadb_stride_lengths_are_withheld_or_agree_left_and_right() {
    let Some(dir) = hugadb_dir() else {
        println!("skipped: ../shared/realdata/hugadb not found (set LDH_REALDATA)");
        return;
    };
    let params = AnalysisParams {
        compute_sta: false,
        ..AnalysisParams::default()
    };
    let mut failures = Vec::new();
    let mut reported = [0usize; 2];
    for f in HUGADB_CLEAN {
        for (k, height) in [None, Some(readme_sensor_height_m(f))]
            .into_iter()
            .enumerate()
        {
            let leg = |side: &str| -> LoadedLeg {
                let rec = read_hugadb_map(&dir, f, side);
                let rep = memory_report(&rec);
                Ok((rec, rep, format!("{f}/{side}")))
            };
            let input = SubjectInput {
                subject_id: f.into(),
                sensor_height_m: height,
                ..SubjectInput::default()
            };
            let res =
                Analysis::new(params.check().unwrap()).pair(&input, leg("left"), leg("right"));
            let mut medians = Vec::new();
            for (side, l) in res.legs() {
                let name = format!(
                    "{f} {side} ({})",
                    height.map_or("no height".into(), |h| format!("{h:.3} m"))
                );
                medians.push(checked_median(
                    &name,
                    l.as_ref().unwrap(),
                    height.is_some(),
                    &mut failures,
                ));
            }
            let (l, r) = (medians[0], medians[1]);
            reported[k] += usize::from(l.is_finite()) + usize::from(r.is_finite());
            if l.is_finite() && r.is_finite() {
                if (l - r).abs() > 0.10 * 0.5 * (l + r) {
                    failures.push(format!("{f}: left {l:.3} m vs right {r:.3} m"));
                }
                // healthy young adults: about 1.1-1.6 m at 0.8-1.1 s strides (wide margins)
                if !(0.8..=1.9).contains(&l) || !(0.8..=1.9).contains(&r) {
                    failures.push(format!("{f}: implausible {l:.3} / {r:.3} m"));
                }
            }
        }
    }
    println!(
        "legs reporting a length: {} of 10 without a height, {} of 10 with the README's",
        reported[0], reported[1]
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
