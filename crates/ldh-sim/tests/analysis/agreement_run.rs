//! `ldh agree` against `ldh evaluate` on a simulated cohort whose truth is exported as a
//! reference: the two agree, clock offsets are found, strides pair by number, groups are kept.

use std::path::Path;

use ldh_core::agreement::run::Level;
use ldh_core::agreement::ValidAgreementParams;
use ldh_core::agreement::{run, OffsetMode, Reference, ReferenceError};
use ldh_core::domain::{EventKind, Legs};
use ldh_core::output::LdhResults;
use ldh_core::reference::parse_reference;
use ldh_core::LdhError;
use ldh_sim::evaluate::TruthScope;
use ldh_test_support::{agree_with, simulated};

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
    let acc = ldh_sim::evaluate::evaluate(&results, &truths);
    let ldh = LdhResults::from_results(&results);
    let (ev, st) = ldh_sim::evaluate::truth_reference(&truths, TruthScope::Steady, 0.0);
    let rep = agree_with(&ldh, &ev, &st, OffsetMode::None);
    let event = |kind: EventKind| {
        rep.events
            .iter()
            .find(|e| e.event == kind && e.side == Legs::Both)
            .unwrap()
            .summary
    };
    let (hs, to) = (event(EventKind::HeelStrike), event(EventKind::ToeOff));
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
            .find(|p| p.level == Level::Stride && p.parameter == name)
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
        .find(|p| p.level == Level::Recording && p.parameter == "stride_time_s")
        .unwrap();
    assert_eq!(rec.pairs.len(), 2 * truths.len(), "one pair per leg");

    let dir = tempfile::tempdir().unwrap();
    let files = ldh_core::agreement::write_report(dir.path(), &rep, &[]).unwrap();
    assert_eq!(files.len(), 3);
    let csv = std::fs::read_to_string(dir.path().join("agreement.csv")).unwrap();
    assert_eq!(
        csv.lines().count(),
        1 + rep.events.len() + rep.events_by_group.len() + rep.parameters.len()
    );
    assert!(
        csv.lines().any(|l| l.starts_with("events,HS,both,")),
        "{csv}"
    );
    let json: ldh_core::agreement::AgreementReport =
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
    let (ev, st) = ldh_sim::evaluate::truth_reference(&truths, TruthScope::All, 0.0);
    let plain = agree_with(&ldh, &ev, &st, OffsetMode::None);
    let (ev_s, st_s) = ldh_sim::evaluate::truth_reference(&truths, TruthScope::All, 0.75);
    let shifted = agree_with(&ldh, &ev_s, &st_s, OffsetMode::Estimate);
    assert_eq!(shifted.offsets.len(), truths.len());
    for o in &shifted.offsets {
        assert_eq!(o.source, run::OffsetSource::Estimated);
        assert!(!o.estimate.unwrap().ambiguous, "{o:?}");
        assert!(
            (o.offset_s + 0.75).abs() <= shifted.params.clock_offset_step_s,
            "{o:?}"
        );
    }
    let matches = |r: &ldh_core::agreement::AgreementReport| -> Vec<(usize, usize, usize)> {
        r.events
            .iter()
            .map(|e| (e.summary.n_ldh, e.summary.n_reference, e.summary.n_matched))
            .collect()
    };
    assert!(plain.events.iter().all(|e| e.summary.n_matched > 20));
    assert_eq!(matches(&plain), matches(&shifted));
    assert_eq!(plain.strides_matched, shifted.strides_matched);

    let (ev_s, st_s) = ldh_sim::evaluate::truth_reference(&truths, TruthScope::Steady, 0.75);
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
    let (ev, st) = ldh_sim::evaluate::truth_reference(&truths, TruthScope::Steady, 0.0);
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
        .find(|x| x.level == Level::Stride && x.parameter == "stride_time_s")
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
        .find(|x| x.level == Level::Recording && x.parameter == "stride_time_s")
        .unwrap();
    for pair in &rec.pairs {
        let leg: Vec<f64> = reference
            .strides
            .iter()
            .filter(|v| v.subject_id == pair.subject_id && v.side == pair.side)
            .map(|v| v.values[0].1)
            .collect();
        let mean = leg.iter().sum::<f64>() / leg.len() as f64;
        assert!((pair.reference.unwrap() - mean).abs() < 1e-12, "{pair:?}");
    }
}

/// A cohort of two groups (2 healthy, 2 LDH): the event rows per group are the rows of a run
/// whose reference holds that group's subjects alone (equal, not merely close: the same
/// matchings summarised in the same order), their counts add up to the pooled rows, and the
/// CSV and Markdown carry them.
#[test]
fn event_agreement_is_summarised_per_group() {
    let (results, truths) = simulated();
    let ldh = LdhResults::from_results(&results);
    let (ev, st) = ldh_sim::evaluate::truth_reference(&truths, TruthScope::Steady, 0.0);
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
        let sum = |f: fn(&ldh_core::agreement::MatchSummary) -> usize| -> usize {
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
        let (ev, st) = ldh_sim::evaluate::truth_reference(&of_group, TruthScope::Steady, 0.0);
        let alone = agree_with(&ldh, &ev, &st, OffsetMode::None);
        assert_eq!(alone.groups.len(), 1);
        assert!(alone.events_by_group.is_empty(), "one group: no group rows");
        let mine: Vec<_> = rep
            .events_by_group
            .iter()
            .filter(|e| e.group == group)
            .map(|e| (e.event, e.side, e.summary))
            .collect();
        let theirs: Vec<_> = alone
            .events
            .iter()
            .map(|e| (e.event, e.side, e.summary))
            .collect();
        assert_eq!(mine, theirs, "{group}");
    }
    assert!(rep
        .unmatched_events
        .iter()
        .all(|u| u.group == "healthy" || u.group == "ldh"));
    let csv = ldh_core::agreement::write::rows(&rep);
    assert_eq!(csv.iter().filter(|r| r.level == "events").count(), 6 + 12);
    assert!(csv
        .iter()
        .any(|r| r.level == "events" && r.group == "ldh" && r.side == "both"));
    let md = ldh_core::agreement::write::markdown(&rep);
    assert!(md.contains("## Events per group"), "{md}");
    assert!(md.contains("| ldh | HS | both |"), "{md}");
}
