//! `ldh agree` in ldh-core: reference files refused with file and line, and the equivalence
//! with `ldh evaluate` on a simulated cohort whose truth is exported as a reference.

use std::path::Path;

use super::reference::parse_reference;
use super::{run, AgreementParams, LdhResults, OffsetMode, Reference, ReferenceError};
use crate::agreement::ValidAgreementParams;
use crate::evaluate::TruthScope;
use crate::pipeline::SubjectResult;
use crate::LdhError;

/// Results of subjects whose legs failed (no events or strides): enough for the reader's
/// subject, trial and range checks. `trials`: (subject, trial, duration s).
pub(super) fn fake_results(trials: &[(&str, &str, f64)]) -> LdhResults {
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

fn parse(text: &str, results: &LdhResults) -> Result<Reference, ReferenceError> {
    let mut into = Reference::default();
    parse_reference(
        text,
        Path::new("ref.csv"),
        results,
        &ValidAgreementParams::default(),
        &mut into,
    )
    .map(|()| into)
    .map_err(|e| match e {
        LdhError::Reference(b) => *b,
        other => panic!("not a reference error: {other}"),
    })
}

/// The error's message, which must name the file and the line.
fn refused(text: &str, line: u64) -> (ReferenceError, String) {
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
    assert!(matches!(e, ReferenceError::Empty { .. }), "{e}");
    let (e, _) = refused(h, 0);
    assert!(matches!(e, ReferenceError::Empty { .. }), "{e}");
    let (e, m) = refused(&format!("{h}S01,left,HS,1\nS09,left,HS,2\n"), 3);
    assert!(matches!(e, ReferenceError::UnknownSubject { .. }), "{e}");
    assert!(m.contains("S09") && m.starts_with("ref.csv:3:1"), "{m}");
    let (e, _) = refused(&format!("{h}S02,left,HS,1\n"), 2);
    assert!(matches!(e, ReferenceError::AmbiguousTrial { .. }), "{e}");
    let (e, m) = refused(&format!("{h}S01,left,HS,1\nS01,left,HS,40\n"), 3);
    assert!(matches!(e, ReferenceError::OutOfRange { .. }), "{e}");
    assert!(m.starts_with("ref.csv:3:4") && m.contains("40"), "{m}");
    let (e, m) = refused(
        &format!("{h}S01,left,HS,2\nS01,right,HS,1\nS01,left,HS,1.5\n"),
        4,
    );
    assert!(matches!(e, ReferenceError::OutOfOrder { .. }), "{e}");
    assert!(m.contains("line 2"), "{m}");
    let (e, m) = refused(&format!("{h}S01,left,HS,2\nS01,left,HS,2\n"), 3);
    assert!(matches!(e, ReferenceError::Duplicate { .. }), "{e}");
    assert!(m.contains("line 2"), "{m}");
    let (e, m) = refused(&format!("{h}S01,left,IC,2\n"), 2);
    assert!(
        matches!(
            e,
            ReferenceError::BadValue {
                column: "event",
                ..
            }
        ),
        "{e}"
    );
    assert!(m.starts_with("ref.csv:2:3") && m.contains("'IC'"), "{m}");
    let (e, _) = refused(&format!("{h}S01,middle,HS,2\n"), 2);
    assert!(
        matches!(e, ReferenceError::BadValue { column: "side", .. }),
        "{e}"
    );
    let (e, m) = refused(&format!("{h}S01,left,HS,1.2s\n"), 2);
    assert!(
        matches!(
            e,
            ReferenceError::BadValue {
                column: "time_s",
                ..
            }
        ),
        "{e}"
    );
    assert!(m.contains("'1.2s'"), "{m}");
    let (e, _) = refused(&format!("{h}S01,left,HS,inf\n"), 2);
    assert!(matches!(e, ReferenceError::BadValue { .. }), "{e}");
    let (e, m) = refused("subject_id,side,stride_tme_s\nS01,left,1\n", 1);
    assert!(matches!(e, ReferenceError::UnknownColumn { .. }), "{e}");
    assert!(
        m.contains("stride_tme_s") && m.contains("stride_time_s"),
        "{m}"
    );
    let (e, _) = refused("subject_id,side\nS01,left\n", 1);
    assert!(matches!(e, ReferenceError::MissingColumn { .. }), "{e}");
    let (e, _) = refused("subject_id,side,time_s,stride_time_cv\nS01,left,1,0.1\n", 1);
    assert!(matches!(e, ReferenceError::UnknownColumn { .. }), "{e}");
    let (e, _) = refused(
        "subject_id,side,stride_time_s\nS01,left,1\nS01,left,1.1\n",
        3,
    );
    assert!(matches!(e, ReferenceError::Duplicate { .. }), "{e}");
    let (e, _) = refused(
        "subject_id,side,stride,stride_time_s\nS01,left,3,1\nS01,left,3,1\n",
        3,
    );
    assert!(matches!(e, ReferenceError::Duplicate { .. }), "{e}");
    let (e, _) = refused(&format!("{h}S01,left,HS,2,9\n"), 2);
    assert!(matches!(e, ReferenceError::Unreadable { .. }), "{e}");
    let (e, m) = refused(
        "subject_id,side,event,time_s,offset_s\nS01,left,HS,1,0.1\nS01,left,HS,2,0.2\n",
        3,
    );
    assert!(matches!(e, ReferenceError::OffsetConflict { .. }), "{e}");
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

/// A small simulated cohort analysed in memory, and its truth.
pub(super) fn simulated() -> (Vec<SubjectResult>, Vec<crate::simulate::SubjectTruth>) {
    use crate::io::{FormatSpec, ReadParams};
    let dir = tempfile::tempdir().unwrap();
    let c = crate::simulate::CohortParams {
        healthy: 2,
        ldh: 2,
        seed: 38,
        ..Default::default()
    };
    crate::simulate::write_cohort(&c, dir.path(), &FormatSpec::default(), &|| {}).unwrap();
    let subjects = crate::pipeline::discover(&[dir.path().to_path_buf()]).unwrap();
    let truths = subjects
        .iter()
        .map(|s| crate::simulate::read_truth(dir.path().join(&s.subject_id).join("truth.json")))
        .collect::<crate::Result<Vec<_>>>()
        .unwrap();
    let params = crate::pipeline::AnalysisParams::default()
        .with_options(None, None, None, Some(false))
        .unwrap();
    let read = ReadParams::default().check().unwrap();
    let results = crate::pipeline::analyze_many(&subjects, &params, None, &read);
    (results, truths)
}

pub(super) fn agree_with(
    results: &LdhResults,
    events: &str,
    strides: &str,
    mode: OffsetMode,
) -> super::AgreementReport {
    let p = AgreementParams {
        tolerance_s: crate::evaluate::MATCH_WINDOW_S,
        ..Default::default()
    }
    .check()
    .unwrap();
    let mut reference = Reference::default();
    parse_reference(events, Path::new("ev.csv"), results, &p, &mut reference).unwrap();
    parse_reference(strides, Path::new("st.csv"), results, &p, &mut reference).unwrap();
    run(results, &reference, &p, mode).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
}

/// `ldh agree` against the exported truth gives `ldh evaluate`'s figures: the numbers of
/// steady strides and missed events, the HS/TO MAE and bias, the stride time MAE, the stance
/// ratio MAE and bias, and every stride length figure (withheld, MAE, bias, SD, worst, > 15 %).
/// Equal to rounding (the errors are summed in the same order; evaluate's are in ms, scaled
/// per value). Not compared: the 95th percentile (evaluate takes the nearest rank, agreement
/// numpy's linear interpolation) — a difference of definition, documented.
#[test]
fn agreement_with_the_exported_truth_reproduces_evaluate() {
    let (results, truths) = simulated();
    let acc = crate::evaluate::evaluate(&results, &truths);
    let ldh = LdhResults::from_results(&results);
    let (ev, st) = crate::evaluate::truth_reference(&truths, TruthScope::Steady, 0.0);
    let rep = agree_with(&ldh, &ev, &st, OffsetMode::None);
    let event = |kind: &str| {
        rep.events
            .iter()
            .find(|e| e.event == kind && e.side == "both")
            .unwrap()
            .summary
    };
    let (hs, to) = (event("HS"), event("TO"));
    assert!(hs.n_reference > 50, "{hs:?}");
    let missed = (hs.n_reference - hs.n_matched) + (to.n_reference - to.n_matched);
    assert_eq!(missed, acc.missed_events);
    assert!(
        close(hs.mae_s.unwrap() * 1e3, acc.hs_mae_ms),
        "{hs:?} {acc:?}"
    );
    assert!(close(hs.bias_s.unwrap() * 1e3, acc.hs_bias_ms));
    assert!(close(to.mae_s.unwrap() * 1e3, acc.to_mae_ms));
    assert!(close(to.bias_s.unwrap() * 1e3, acc.to_bias_ms));
    assert_eq!(rep.strides_matched, acc.strides);
    let param = |name: &str| {
        rep.parameters
            .iter()
            .find(|p| p.level == "stride" && p.parameter == name)
            .unwrap()
    };
    let time = param("stride_time_s").agreement.clone().unwrap();
    assert_eq!(time.n_pairs, acc.strides);
    assert!(close(time.mae * 1e3, acc.stride_time_mae_ms));
    let stance = param("stance_ratio").agreement.clone().unwrap();
    assert!(close(stance.mae, acc.stance_ratio_mae));
    assert!(close(stance.limits.bias, acc.stance_ratio_bias));
    let length = param("stride_length_m");
    let la = length.agreement.clone().unwrap();
    assert_eq!(la.n_dropped, acc.stride_length_withheld);
    let pct: Vec<f64> = length
        .pairs
        .iter()
        .filter_map(|p| Some((p.ldh? - p.reference?) / p.reference? * 100.0))
        .collect();
    assert_eq!(pct.len(), la.n_pairs);
    let mean = pct.iter().sum::<f64>() / pct.len() as f64;
    let mae = pct.iter().map(|x| x.abs()).sum::<f64>() / pct.len() as f64;
    let sd = (pct.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (pct.len() - 1) as f64).sqrt();
    assert!(close(mae, acc.stride_length_mae_pct));
    assert!(close(mean, acc.stride_length_bias_pct));
    assert!(close(sd, acc.stride_length_sd_pct));
    let worst = pct.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(close(worst, acc.stride_length_max_pct));
    assert_eq!(
        pct.iter().filter(|x| x.abs() > 15.0).count(),
        acc.stride_length_over_15pct
    );
    let rec = rep
        .parameters
        .iter()
        .find(|p| p.level == "recording" && p.parameter == "stride_time_s")
        .unwrap();
    assert_eq!(rec.pairs.len(), 2 * truths.len(), "one pair per leg");

    let dir = tempfile::tempdir().unwrap();
    let files = super::write_report(dir.path(), &rep).unwrap();
    assert_eq!(files.len(), 4);
    let csv = std::fs::read_to_string(dir.path().join("agreement.csv")).unwrap();
    assert_eq!(
        csv.lines().count(),
        1 + rep.events.len() + rep.events_by_group.len() + rep.parameters.len()
    );
    assert!(
        csv.lines().any(|l| l.starts_with("events,HS,both,")),
        "{csv}"
    );
    let json: super::AgreementReport =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("agreement.json")).unwrap())
            .unwrap();
    assert_eq!(json.strides_matched, rep.strides_matched);
    let md = std::fs::read_to_string(dir.path().join("agreement.md")).unwrap();
    assert!(md.contains("| stride | stride_time_s |"), "{md}");
}

/// A reference clock started 0.75 s before ldh's: the offset is found (within one grid step)
/// and removed (the same matches as without the shift). Estimated from the whole walk's
/// events; from the steady strides alone (a reference that sees part of the walk, like a
/// walkway) an offset one stride away matches as many events, and the estimate is refused as
/// ambiguous — given with `OffsetMode::Fixed`, it removes the shift as well.
#[test]
fn a_clock_offset_of_0_75_s_is_found_and_removed() {
    let (results, truths) = simulated();
    let ldh = LdhResults::from_results(&results);
    let (ev, st) = crate::evaluate::truth_reference(&truths, TruthScope::All, 0.0);
    let plain = agree_with(&ldh, &ev, &st, OffsetMode::None);
    let (ev_s, st_s) = crate::evaluate::truth_reference(&truths, TruthScope::All, 0.75);
    let shifted = agree_with(&ldh, &ev_s, &st_s, OffsetMode::Estimate);
    assert_eq!(shifted.offsets.len(), truths.len());
    for o in &shifted.offsets {
        assert_eq!(o.source, "estimated");
        assert!(!o.estimate.unwrap().ambiguous, "{o:?}");
        assert!(
            (o.offset_s + 0.75).abs() <= shifted.params.clock_offset_step_s,
            "{o:?}"
        );
    }
    let matches = |r: &super::AgreementReport| -> Vec<(usize, usize, usize)> {
        r.events
            .iter()
            .map(|e| (e.summary.n_ldh, e.summary.n_reference, e.summary.n_matched))
            .collect()
    };
    assert!(plain.events.iter().all(|e| e.summary.n_matched > 20));
    assert_eq!(matches(&plain), matches(&shifted));
    assert_eq!(plain.strides_matched, shifted.strides_matched);

    let (ev_s, st_s) = crate::evaluate::truth_reference(&truths, TruthScope::Steady, 0.75);
    let p = ValidAgreementParams::default();
    let mut reference = Reference::default();
    parse_reference(&ev_s, Path::new("ev.csv"), &ldh, &p, &mut reference).unwrap();
    parse_reference(&st_s, Path::new("st.csv"), &ldh, &p, &mut reference).unwrap();
    match run(&ldh, &reference, &p, OffsetMode::Estimate) {
        Err(LdhError::Reference(e)) => {
            assert!(matches!(*e, ReferenceError::Offset { .. }), "{e}");
            assert!(e.to_string().contains("ambiguous"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    let (ev, st) = crate::evaluate::truth_reference(&truths, TruthScope::Steady, 0.0);
    let steady = agree_with(&ldh, &ev, &st, OffsetMode::None);
    let given = agree_with(&ldh, &ev_s, &st_s, OffsetMode::Fixed(-0.75));
    assert_eq!(matches(&steady), matches(&given));
}

/// A per-stride reference keyed by ldh's stride number pairs each row with that stride; the
/// per-recording reference is the mean of the leg's reference strides.
#[test]
fn strides_by_number_pair_with_that_stride_and_recordings_use_the_mean_of_a_leg() {
    let (results, _) = simulated();
    let ldh = LdhResults::from_results(&results);
    let mut text = String::from("subject_id,side,stride,stride_time_s\n");
    let mut shifts = Vec::new();
    for s in ldh.strides.iter().filter(|s| s.values[0].is_finite()) {
        let shift = 0.001 * (s.stride_index % 5) as f64;
        shifts.push(shift);
        let v = s.values[0] - shift;
        text.push_str(&format!(
            "{},{},{},{v}\n",
            s.subject_id, s.side, s.stride_index
        ));
    }
    let p = ValidAgreementParams::default();
    let mut reference = Reference::default();
    parse_reference(&text, Path::new("st.csv"), &ldh, &p, &mut reference).unwrap();
    let rep = run(&ldh, &reference, &p, OffsetMode::None).unwrap();
    assert_eq!(rep.strides_matched, shifts.len());
    let st = rep
        .parameters
        .iter()
        .find(|x| x.level == "stride" && x.parameter == "stride_time_s")
        .unwrap();
    let a = st.agreement.as_ref().unwrap();
    assert_eq!(a.n_pairs, shifts.len());
    let mean_shift = shifts.iter().sum::<f64>() / shifts.len() as f64;
    assert!(
        (a.limits.bias - mean_shift).abs() < 1e-12,
        "{}",
        a.limits.bias
    );
    let rec = rep
        .parameters
        .iter()
        .find(|x| x.level == "recording" && x.parameter == "stride_time_s")
        .unwrap();
    for pair in &rec.pairs {
        let leg: Vec<f64> = reference
            .strides
            .iter()
            .filter(|v| v.subject_id == pair.subject_id && v.side.as_str() == pair.side)
            .map(|v| v.values[0].1)
            .collect();
        let mean = leg.iter().sum::<f64>() / leg.len() as f64;
        assert!((pair.reference.unwrap() - mean).abs() < 1e-12, "{pair:?}");
    }
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

/// A cohort of two groups (2 healthy, 2 LDH): the event rows per group are the rows of a run
/// whose reference holds that group's subjects alone (equal, not merely close: the same
/// matchings summarised in the same order), their counts add up to the pooled rows, and the
/// CSV and Markdown carry them.
#[test]
fn event_agreement_is_summarised_per_group() {
    let (results, truths) = simulated();
    let ldh = LdhResults::from_results(&results);
    let (ev, st) = crate::evaluate::truth_reference(&truths, TruthScope::Steady, 0.0);
    let rep = agree_with(&ldh, &ev, &st, OffsetMode::None);
    let groups: Vec<(&str, usize, usize)> = rep
        .groups
        .iter()
        .map(|g| (g.group.as_str(), g.subjects, g.trials))
        .collect();
    assert_eq!(groups, [("healthy", 2, 2), ("ldh", 2, 2)]);
    assert_eq!(
        rep.events_by_group.len(),
        2 * 2 * 3,
        "groups × kinds × sides"
    );
    for e in &rep.events {
        assert_eq!(e.group, "all");
        let parts: Vec<_> = rep
            .events_by_group
            .iter()
            .filter(|g| g.event == e.event && g.side == e.side)
            .collect();
        assert_eq!(parts.len(), 2);
        let sum = |f: fn(&super::MatchSummary) -> usize| -> usize {
            parts.iter().map(|g| f(&g.summary)).sum()
        };
        assert_eq!(sum(|s| s.n_matched), e.summary.n_matched);
        assert_eq!(sum(|s| s.n_reference), e.summary.n_reference);
        assert_eq!(sum(|s| s.n_ldh), e.summary.n_ldh);
    }
    for group in ["healthy", "ldh"] {
        let of_group: Vec<_> = truths
            .iter()
            .filter(|t| {
                results.iter().any(|r| {
                    r.subject_id == t.subject_id
                        && r.group.as_ref().map(|g| g.as_str()) == Some(group)
                })
            })
            .cloned()
            .collect();
        assert_eq!(of_group.len(), 2);
        let (ev, st) = crate::evaluate::truth_reference(&of_group, TruthScope::Steady, 0.0);
        let alone = agree_with(&ldh, &ev, &st, OffsetMode::None);
        assert_eq!(alone.groups.len(), 1);
        assert!(alone.events_by_group.is_empty(), "one group: no group rows");
        let mine: Vec<_> = rep
            .events_by_group
            .iter()
            .filter(|e| e.group == group)
            .map(|e| (e.event.clone(), e.side.clone(), e.summary))
            .collect();
        let theirs: Vec<_> = alone
            .events
            .iter()
            .map(|e| (e.event.clone(), e.side.clone(), e.summary))
            .collect();
        assert_eq!(mine, theirs, "{group}");
    }
    assert!(rep
        .unmatched_events
        .iter()
        .all(|u| u.group == "healthy" || u.group == "ldh"));
    let csv = super::write::rows(&rep);
    assert_eq!(csv.iter().filter(|r| r.level == "events").count(), 6 + 12);
    assert!(csv
        .iter()
        .any(|r| r.level == "events" && r.group == "ldh" && r.side == "both"));
    let md = super::write::markdown(&rep);
    assert!(md.contains("## Events per group"), "{md}");
    assert!(md.contains("| ldh | HS | both |"), "{md}");
}
