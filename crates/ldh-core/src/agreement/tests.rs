//! `ldh agree`'s reference files: read, or refused with file and line. (Its equivalence with
//! `ldh evaluate` on a simulated cohort is tested in `ldh-sim`, tests/analysis/agreement_run.rs.)

use std::path::Path;

use super::{OffsetMode, Reference, ReferenceError};
use crate::agreement::ValidAgreementParams;
use crate::output::LdhResults;
use crate::pipeline::SubjectResult;
use crate::reference::parse_reference;
use crate::LdhError;

/// Results of subjects whose legs failed (no events or strides): enough for the reader's
/// subject, trial and range checks. `trials`: (subject, trial, duration s).
pub(crate) fn fake_results(trials: &[(&str, &str, f64)]) -> LdhResults {
    let results: Vec<SubjectResult> = trials
        .iter()
        .map(|(s, t, _)| SubjectResult {
            subject_id: s.to_string(),
            trial_id: (!t.is_empty()).then(|| t.to_string()),
            group: None,
            affected_side: None,
            affected_side_unknown: false,
            setting: None,
            belt_speed_mps: None,
            visit: None,
            model: crate::attitude::AttitudeModel::Fusion,
            left: Err("not analysed".into()),
            right: Err("not analysed".into()),
            warnings: Vec::new(),
            timings: Default::default(),
        })
        .collect();
    let mut r = LdhResults::from_results(&results);
    for row in &mut r.recordings {
        row.duration_s = trials
            .iter()
            .find(|(s, t, _)| row.subject_id == *s && row.trial_id == *t)
            .map(|x| x.2);
    }
    r
}

fn parse(text: &str, results: &LdhResults) -> Result<Reference, LdhError> {
    let mut into = Reference::default();
    parse_reference(
        text,
        Path::new("ref.csv"),
        results,
        &ValidAgreementParams::default(),
        &mut into,
    )
    .map(|()| into)
}

/// The reference error inside `e`, when it is one (a table fault is the table reader's).
fn re(e: &LdhError) -> Option<&ReferenceError> {
    match e {
        LdhError::Reference(b) => Some(b),
        _ => None,
    }
}

/// The error's message, which must name the file and the line.
fn refused(text: &str, line: u64) -> (LdhError, String) {
    let results = fake_results(&[("S01", "", 30.0), ("S02", "a", 30.0), ("S02", "b", 30.0)]);
    let e = parse(text, &results).expect_err(text);
    let msg = e.to_string();
    assert!(
        msg.starts_with(&format!("ref.csv:{line}")) || (line == 0 && msg.starts_with("ref.csv")),
        "{msg}"
    );
    (e, msg)
}

#[test]
fn a_good_reference_reads_events_strides_recordings_and_offsets() {
    let results = fake_results(&[("S01", "", 30.0), ("S02", "a", 30.0), ("S02", "b", 30.0)]);
    let ev = "subject_id,trial_id,side,event,time_s,offset_s\n\
              S01,,left,HS,1.0,0.5\nS01,,left,TO,1.6,0.5\nS01,,Left,hs,2.1,\nS02,b,right,HS,1.0,\n";
    let r = parse(ev, &results).unwrap();
    assert_eq!(r.events.len(), 4);
    assert_eq!(r.events[2].side, crate::Side::Left);
    assert_eq!(r.offsets.len(), 1);
    assert_eq!(r.offsets[0].offset_s, 0.5);
    assert_eq!(r.events[3].trial_id, "b");
    let st = "subject_id,side,stride,time_s,stride_time_s,stride_length_m\nS01,left,0,1.0,1.1,\n";
    let r = parse(st, &results).unwrap();
    assert_eq!(r.strides.len(), 1);
    assert_eq!(r.strides[0].stride, Some(0));
    assert!(
        r.strides[0].values[1].1.is_nan(),
        "an empty cell is missing"
    );
    let rec = "subject_id,trial_id,side,speed_mps,stride_length_cv\nS02,a,left,1.2,0.03\n";
    let r = parse(rec, &results).unwrap();
    assert_eq!(r.recordings.len(), 1);
    assert_eq!(r.recordings[0].values.len(), 2);
}

#[test]
fn each_bad_reference_is_refused_naming_file_line_and_column() {
    let h = "subject_id,side,event,time_s\n";
    let (e, _) = refused("", 0);
    assert!(matches!(re(&e), Some(ReferenceError::Empty { .. })), "{e}");
    let (e, _) = refused(h, 0);
    assert!(matches!(re(&e), Some(ReferenceError::Empty { .. })), "{e}");
    let (e, m) = refused(&format!("{h}S01,left,HS,1\nS09,left,HS,2\n"), 3);
    assert!(
        matches!(re(&e), Some(ReferenceError::UnknownSubject { .. })),
        "{e}"
    );
    assert!(m.contains("S09") && m.starts_with("ref.csv:3:1"), "{m}");
    let (e, _) = refused(&format!("{h}S02,left,HS,1\n"), 2);
    assert!(
        matches!(re(&e), Some(ReferenceError::AmbiguousTrial { .. })),
        "{e}"
    );
    let (e, m) = refused(&format!("{h}S01,left,HS,1\nS01,left,HS,40\n"), 3);
    assert!(
        matches!(re(&e), Some(ReferenceError::OutOfRange { .. })),
        "{e}"
    );
    assert!(m.starts_with("ref.csv:3:4") && m.contains("40"), "{m}");
    let (e, m) = refused(
        &format!("{h}S01,left,HS,2\nS01,right,HS,1\nS01,left,HS,1.5\n"),
        4,
    );
    assert!(
        matches!(re(&e), Some(ReferenceError::OutOfOrder { .. })),
        "{e}"
    );
    assert!(m.contains("line 2"), "{m}");
    let (e, m) = refused(&format!("{h}S01,left,HS,2\nS01,left,HS,2\n"), 3);
    assert!(
        matches!(re(&e), Some(ReferenceError::Duplicate { .. })),
        "{e}"
    );
    assert!(m.contains("line 2"), "{m}");
    let (e, m) = refused(&format!("{h}S01,left,IC,2\n"), 2);
    assert!(
        matches!(
            e,
            LdhError::InvalidValue { ref column, .. } if column == "event"
        ),
        "{e}"
    );
    assert!(m.starts_with("ref.csv:2:3") && m.contains("'IC'"), "{m}");
    let (e, _) = refused(&format!("{h}S01,middle,HS,2\n"), 2);
    assert!(
        matches!(e, LdhError::InvalidValue { ref column, .. } if column == "side"),
        "{e}"
    );
    let (e, m) = refused(&format!("{h}S01,left,HS,1.2s\n"), 2);
    assert!(
        matches!(
            e,
            LdhError::NotANumber { ref column, .. } if column == "time_s"
        ),
        "{e}"
    );
    assert!(m.contains("'1.2s'"), "{m}");
    let (e, _) = refused(&format!("{h}S01,left,HS,inf\n"), 2);
    assert!(matches!(e, LdhError::NonFinite { .. }), "{e}");
    let (e, m) = refused("subject_id,side,stride_tme_s\nS01,left,1\n", 1);
    assert!(matches!(e, LdhError::UnknownColumn { .. }), "{e}");
    assert!(
        m.contains("stride_tme_s") && m.contains("stride_time_s"),
        "{m}"
    );
    let (e, _) = refused("subject_id,side\nS01,left\n", 1);
    assert!(matches!(e, LdhError::MissingColumn { .. }), "{e}");
    let (e, _) = refused("subject_id,side,time_s,stride_time_cv\nS01,left,1,0.1\n", 1);
    assert!(matches!(e, LdhError::UnknownColumn { .. }), "{e}");
    let (e, _) = refused(
        "subject_id,side,stride_time_s\nS01,left,1\nS01,left,1.1\n",
        3,
    );
    assert!(
        matches!(re(&e), Some(ReferenceError::Duplicate { .. })),
        "{e}"
    );
    let (e, _) = refused(
        "subject_id,side,stride,stride_time_s\nS01,left,3,1\nS01,left,3,1\n",
        3,
    );
    assert!(
        matches!(re(&e), Some(ReferenceError::Duplicate { .. })),
        "{e}"
    );
    let (e, _) = refused(&format!("{h}S01,left,HS,2,9\n"), 2);
    assert!(matches!(e, LdhError::FieldCount { .. }), "{e}");
    let (e, m) = refused(
        "subject_id,side,event,time_s,offset_s\nS01,left,HS,1,0.1\nS01,left,HS,2,0.2\n",
        3,
    );
    assert!(
        matches!(re(&e), Some(ReferenceError::OffsetConflict { .. })),
        "{e}"
    );
    assert!(m.contains("line 2"), "{m}");
}

#[test]
fn a_file_that_fails_adds_nothing() {
    let results = fake_results(&[("S01", "", 30.0)]);
    let mut into = Reference::default();
    let p = ValidAgreementParams::default();
    let bad = "subject_id,side,event,time_s\nS01,left,HS,1\nS01,left,HS,0.5\n";
    assert!(parse_reference(bad, Path::new("r.csv"), &results, &p, &mut into).is_err());
    assert_eq!(into, Reference::default());
}

/// `--offset-s` and Python's `offset_s=` read one way: `estimate` in any case, or a finite
/// number of seconds; anything else names the argument.
#[test]
fn the_offset_mode_is_read_once() {
    assert_eq!(
        " Estimate ".parse::<OffsetMode>().unwrap(),
        OffsetMode::Estimate
    );
    assert_eq!(
        "-0.75".parse::<OffsetMode>().unwrap(),
        OffsetMode::Fixed(-0.75)
    );
    for bad in ["soon", "inf", "NaN", ""] {
        let e = bad.parse::<OffsetMode>().unwrap_err().to_string();
        assert!(e.contains("offset_s"), "{bad}: {e}");
    }
    assert!(OffsetMode::fixed(f64::INFINITY, "offset_s").is_err());
}
