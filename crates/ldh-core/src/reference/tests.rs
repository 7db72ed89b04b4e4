//! Walkway exports through a column map: the shipped GAITRite-like example gives the same
//! reference as its long-form equivalent, and every refusal names the export's file, line and
//! column.

use std::path::{Path, PathBuf};

use super::long_form::{parse_reference, Reference};
use super::walkway::{parse_walkway, WalkwayIds};
use super::walkway_map::WalkwayMap;
use super::ReferenceError;
use crate::output::LdhResults;
use crate::stats::agreement::ValidAgreementParams;
use crate::LdhError;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data-fixtures/agreement")
        .join(name)
}

fn results() -> LdhResults {
    crate::agreement::tests::fake_results(&[("S01", "", 30.0)])
}

fn map() -> WalkwayMap {
    let p = fixture("gaitrite-footfalls.toml");
    WalkwayMap::from_toml_str(&std::fs::read_to_string(&p).unwrap(), &p).unwrap()
}

/// A reference without its rows' locations (the two readers name different files).
fn unlocated(mut r: Reference) -> Reference {
    for v in &mut r.strides {
        v.at = crate::error::Location::file("");
    }
    r.files.clear();
    r
}

fn walkway(text: &str, map: &WalkwayMap, ids: &WalkwayIds) -> Result<Reference, LdhError> {
    let mut into = Reference::default();
    let p = ValidAgreementParams::default();
    parse_walkway(
        text,
        Path::new("walk.csv"),
        map,
        ids,
        &results(),
        &p,
        &mut into,
    )?;
    Ok(into)
}

fn refused(text: &str, map: &WalkwayMap, ids: &WalkwayIds) -> (LdhError, String) {
    match walkway(text, map, ids) {
        Err(e) => {
            let m = e.to_string();
            (e, m)
        }
        other => panic!("not refused: {other:?}"),
    }
}

/// The reference error inside `e`, when it is one (a table fault is the table reader's).
fn re(e: &LdhError) -> Option<&ReferenceError> {
    match e {
        LdhError::Reference(b) => Some(b),
        _ => None,
    }
}

/// The example export (two title lines, cm, cm/s, %, strides on the footfall that ends them)
/// read through its map equals the long-form events and strides files written by hand:
/// 8 heel strikes, 7 toe offs (one empty cell), 6 strides (each foot's first footfall ends
/// none), values converted to m, m/s and ratios (to 1e-12: 131.2 / 100 is the double of 1.312
/// up to rounding).
#[test]
fn the_example_export_is_its_long_form_equivalent() {
    let text = std::fs::read_to_string(fixture("gaitrite-footfalls.csv")).unwrap();
    let got = unlocated(walkway(&text, &map(), &WalkwayIds::default()).unwrap());
    let p = ValidAgreementParams::default();
    let mut want = Reference::default();
    for f in [
        "gaitrite-footfalls-events.csv",
        "gaitrite-footfalls-strides.csv",
    ] {
        let t = std::fs::read_to_string(fixture(f)).unwrap();
        parse_reference(&t, Path::new(f), &results(), &p, &mut want).unwrap();
    }
    let want = unlocated(want);
    assert_eq!(got.events, want.events);
    assert_eq!(got.events.len(), 15);
    assert_eq!(got.strides.len(), 6);
    for (g, w) in got.strides.iter().zip(&want.strides) {
        assert_eq!(
            (&g.subject_id, g.side, g.time_s, g.end_time_s),
            (&w.subject_id, w.side, w.time_s, w.end_time_s)
        );
        assert_eq!(g.values.len(), 4);
        for ((pg, vg), (pw, vw)) in g.values.iter().zip(&w.values) {
            assert_eq!(pg, pw);
            assert!(
                (vg - vw).abs() <= 1e-12 || (vg.is_nan() && vw.is_nan()),
                "{pg:?}: {vg} vs {vw}"
            );
        }
    }
    assert_eq!(got.strides[0].time_s, Some(1.0));
    assert_eq!(got.strides[0].end_time_s, Some(2.08));
}

/// The subject from the command line when the map has no column; a start-anchored map gives
/// every footfall with a heel strike a stride starting there.
#[test]
fn ids_from_the_command_line_and_start_anchored_strides() {
    let mut m = map();
    m.subject_column = None;
    m.skip_rows_before_header = 0;
    m.stride_anchor = super::StrideAnchor::Start;
    let text = "Left/Right,First Contact (sec.),Last Contact (sec.),Stride Length (cm.),Stride Time (sec.),Velocity (cm./sec.),Stance %\n\
                L,1.0,1.6,130,1.08,120,60\nR,1.5,2.1,131,1.07,121,61\n";
    let ids = WalkwayIds {
        subject_id: Some("S01".into()),
        trial_id: None,
    };
    let r = walkway(text, &m, &ids).unwrap();
    assert_eq!(r.strides.len(), 2);
    assert_eq!(r.strides[1].time_s, Some(1.5));
    assert_eq!(r.strides[1].end_time_s, None);
    assert_eq!(r.strides[0].values[2].1, 1.3, "stride_length_m from 130 cm");
    let (e, m2) = refused(text, &m, &WalkwayIds::default());
    assert!(matches!(re(&e), Some(ReferenceError::Map { .. })), "{m2}");
    assert!(m2.contains("--subject-id"), "{m2}");
}

/// Each refusal names the export, its line and its column (the export's column, also for the
/// checks of the long-form reader: an unknown subject, times out of order).
#[test]
fn walkway_refusals_name_file_line_and_column() {
    let m = map();
    let ids = WalkwayIds::default();
    let head = "title\ntitle\nID,Left/Right,First Contact (sec.),Last Contact (sec.),Stride Length (cm.),Stride Time (sec.),Velocity (cm./sec.),Stance %\n";
    let (e, msg) = refused(&format!("{head}S01,X,1.0,1.6,,,,\n"), &m, &ids);
    assert!(matches!(e, LdhError::InvalidValue { .. }), "{msg}");
    assert!(
        msg.starts_with("walk.csv:4:2") && msg.contains("Left/Right") && msg.contains("'X'"),
        "{msg}"
    );
    let (_, msg) = refused(&format!("{head}S01,L,1.0,1.6,12x,,,\n"), &m, &ids);
    assert!(
        msg.starts_with("walk.csv:4:5") && msg.contains("Stride Length (cm.)"),
        "{msg}"
    );
    let (e, msg) = refused(
        &format!("{head}S01,L,1.0,1.6,,,,\nS09,L,2.0,2.6,,,,\n"),
        &m,
        &ids,
    );
    assert!(
        matches!(re(&e), Some(ReferenceError::UnknownSubject { .. })),
        "{msg}"
    );
    assert!(msg.starts_with("walk.csv:5:1:"), "{msg}");
    let (e, msg) = refused(
        &format!("{head}S01,L,2.0,2.6,,,,\nS01,R,2.5,3.1,,,,\nS01,L,1.0,1.6,,,,\n"),
        &m,
        &ids,
    );
    assert!(
        matches!(re(&e), Some(ReferenceError::OutOfOrder { .. })),
        "{msg}"
    );
    assert!(
        msg.starts_with("walk.csv:6:3:") && msg.contains("line 4"),
        "{msg}"
    );
    let (e, msg) = refused(&format!("{head}S01,L,1.0,1.6,,,\n"), &m, &ids);
    assert!(matches!(e, LdhError::FieldCount { .. }), "{msg}");
    assert!(msg.starts_with("walk.csv:4"), "{msg}");
    let mut bad = map();
    bad.toe_off.as_mut().unwrap().column = "Toe Off".into();
    let (e, msg) = refused(&format!("{head}S01,L,1.0,1.6,,,,\n"), &bad, &ids);
    assert!(matches!(re(&e), Some(ReferenceError::Map { .. })), "{msg}");
    assert!(
        msg.starts_with("walk.csv:3") && msg.contains("'Toe Off'"),
        "{msg}"
    );
    // The map itself: a unit that does not fit, a TOML error with its line.
    let f = Path::new("m.toml");
    let wrong_unit = "name = \"x\"\n[side]\ncolumn = \"Foot\"\nleft = [\"L\"]\nright = [\"R\"]\n[heel_strike]\ncolumn = \"HS\"\nunit = \"s\"\n[strides]\nstride_time_s = { column = \"T\", unit = \"cm\" }\n";
    let e = WalkwayMap::from_toml_str(wrong_unit, f)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("stride_time_s") && e.contains("does not convert to s"),
        "{e}"
    );
    let typo = wrong_unit.replace("unit = \"s\"", "unit = \"sec\"");
    let e = WalkwayMap::from_toml_str(&typo, f).unwrap_err().to_string();
    assert!(e.starts_with("m.toml:8:"), "{e}");
}
