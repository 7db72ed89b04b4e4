//! Training on what was measured: candidate rows, default-feature selection, the folds a small
//! class allows, and the one refusal when nothing remains.

use super::*;
use crate::ml::{train, TrainParams};
use crate::output::{RecordingRow, Status};

fn cand(subject: &str, label: usize, values: &[Option<f64>]) -> Candidate {
    Candidate {
        values: values.to_vec(),
        label,
        subject: subject.into(),
        what: "x".into(),
    }
}

const F: [Parameter; 3] = [
    Parameter::ALL[0],
    Parameter::ALL[7], // stride_length_cv
    Parameter::ALL[9],
];

#[test]
fn a_feature_measured_in_too_few_rows_is_dropped_and_named() {
    // 10 rows with something measured: F[0] in all, F[1] in none, F[2] in 9 of 10; one row empty.
    let mut c: Vec<Candidate> = (0..10)
        .map(|i| {
            cand(
                &format!("S{i}"),
                i % 2,
                &[Some(1.0), None, (i != 3).then_some(2.0)],
            )
        })
        .collect();
    c.push(cand("E1", 0, &[None, None, None]));
    let (kept, rows, notes) = select_measured(c.clone(), &F, 0.9).unwrap();
    assert_eq!(kept, vec![F[0], F[2]]);
    assert_eq!(rows.len(), 10);
    assert!(rows.iter().all(|r| r.values.len() == 2));
    assert_eq!(
        notes[0],
        TrainNote::NothingMeasured {
            rows: vec!["E1/x".into()]
        }
    );
    let TrainNote::FeaturesDropped { features, .. } = &notes[1] else {
        panic!("{notes:?}")
    };
    assert_eq!(features.len(), 1);
    assert_eq!((features[0].measured, features[0].rows), (0, 10));
    let text = notes[1].to_string();
    assert!(
        text.contains("stride_length_cv (measured in 0 of 10 rows)") && text.contains("90 %"),
        "{text}"
    );
    // Every row measured: a 9-of-10 feature goes too.
    let (kept, _, notes) = select_measured(c, &F, 1.0).unwrap();
    assert_eq!(kept, vec![F[0]]);
    assert!(
        notes[1].to_string().contains("measured in 9 of 10 rows"),
        "{}",
        notes[1]
    );
}

#[test]
fn nothing_measured_is_one_error_that_says_why() {
    let c = vec![
        cand("A", 0, &[None, None, None]),
        cand("B", 1, &[None, None, None]),
    ];
    let e = select_measured(c, &F, 0.9).unwrap_err().to_string();
    assert!(
        e.contains("nothing to train on")
            && e.contains("none of the 2 rows")
            && e.contains("A/x, B/x"),
        "{e}"
    );
}

#[test]
fn k_is_lowered_to_the_smallest_class_with_a_note() {
    let names = Task::ThreeClass.class_names();
    assert_eq!(folds_for(&[12, 12, 12], &names, 10).unwrap(), (10, None));
    let (k, note) = folds_for(&[3, 0, 6], &names, 10).unwrap();
    assert_eq!(k, 3);
    let note = note.unwrap();
    assert_eq!(
        note.to_string(),
        "k lowered from 10 to 3: the smallest class (LDHH) has 3 rows"
    );
    let e = folds_for(&[1, 4, 6], &names, 10).unwrap_err().to_string();
    assert!(
        e.contains("(LDHH) has 1 row") && e.contains("1 LDHH, 4 LDHE, 6 H"),
        "{e}"
    );
}

/// Six subjects per group, both legs measured in every parameter but SV; one LDH subject's
/// affected leg has no valid stride.
fn short_walk_cohort() -> Vec<RecordingRow> {
    let mut rows = Vec::new();
    for (g, n) in [("healthy", "H"), ("ldh", "L")] {
        for i in 0..6 {
            for side in ["left", "right"] {
                let x = i as f64 * 0.01
                    + if g == "ldh" && side == "left" {
                        0.3
                    } else {
                        0.0
                    };
                let mut r = crate::output::test_rows::row(&format!("{n}{i}"), g, side, 1.0 + x);
                r.affected_side = (g == "ldh").then(|| crate::output::Label::parse("left"));
                for p in Parameter::ALL {
                    if p.column() != "stride_length_cv" {
                        r.set_value(p, Some(1.0 + x));
                    }
                }
                if g == "ldh" && i == 0 && side == "left" {
                    for p in Parameter::ALL {
                        r.set_value(p, None);
                    }
                    r.strides_valid = Some(0);
                    r.status = Status::NoValidStrides.into();
                }
                rows.push(r);
            }
        }
    }
    rows
}

#[test]
fn a_short_walk_cohort_trains_on_what_was_measured_with_notes() {
    let p = TrainParams {
        repeats: 1,
        classifiers: vec![crate::ml::ClassifierKind::Rf],
        ..TrainParams::default()
    };
    let out = train(&short_walk_cohort(), &p).unwrap();
    assert_eq!(out.k, 5, "{:?}", out.notes);
    let text: Vec<String> = out.notes.iter().map(|n| n.to_string()).collect();
    assert!(text[0].contains("L0/affected"), "{text:?}");
    assert!(text[1].contains("stride_length_cv"), "{text:?}");
    assert!(
        text[2].contains("k lowered from 10 to 5: the smallest class (LDHE)"),
        "{text:?}"
    );
    assert!(out.markdown.contains("Notes:") && out.markdown.contains(&text[2]));
    assert!(!out.reports[0]
        .permutation_importance
        .iter()
        .any(|(f, _)| f == "stride_length_cv"));
    // Asked for by name, SV is not measured anywhere: one error saying so.
    let named = TrainParams {
        features: Some(vec!["stride_length_cv".into()]),
        ..p.clone()
    };
    let e = train(&short_walk_cohort(), &named).unwrap_err().to_string();
    assert!(e.contains("stride_length_cv on"), "{e}");
    // Parameters are checked first.
    let bad = TrainParams {
        min_feature_coverage: 0.0,
        ..p
    };
    assert!(train(&short_walk_cohort(), &bad)
        .unwrap_err()
        .to_string()
        .contains("min_feature_coverage"));
}
