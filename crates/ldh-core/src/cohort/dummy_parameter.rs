//! The proof that a gait parameter is one definition plus its computation (issue 48): with the
//! test-only feature `dummy-parameter`, `Parameter::Dummy` exists with only its definition
//! (`domain/parameter.rs`, with a per-stride meaning), its computation per walk
//! (`gait/side.rs`, twice the mean stride time) and its arm exposing its per-stride value
//! (`gait::Stride::value`, twice the stride time), and nothing else was edited for it. These
//! tests find it in recordings.csv's header and rows, recordings.json, strides.csv's header
//! and rows, strides.json, the column dictionary (both tables) and the reliability table
//! (ldh-report's own test with the feature finds it on the report's pages).
//!
//! `cargo test --profile ci -p ldh-core --features dummy-parameter --lib dummy_parameter`

use crate::cohort::reliability_table;
use crate::domain::Parameter;
use crate::output::columns::{columns, markdown, Table};
use crate::output::{recording_rows, stride_rows, to_csv, RecordingRow, StrideRow, STRIDE_COLUMNS};
use crate::pipeline::{discover, Analysis, AnalysisParams, SubjectResult};
use crate::stats::agreement::ValidAgreementParams;

/// The first demo subject, analysed without STA.
fn demo_subject() -> SubjectResult {
    let inputs = discover(&[]).unwrap();
    let mut p = AnalysisParams::default();
    p.compute_sta = false;
    Analysis::new(p.check().unwrap()).subject(&inputs[0])
}

/// Both legs' rows of the first demo subject, analysed without STA.
fn demo_rows() -> Vec<RecordingRow> {
    recording_rows(&[demo_subject()])
}

#[test]
fn dummy_parameter_reaches_the_tables_the_dictionary_and_the_reliability_table() {
    let d = Parameter::Dummy;
    let rows = demo_rows();
    // recordings.csv: its column after BDK's (its place in TABLE_ORDER), its value in each row.
    let csv = to_csv(&rows, &[]).unwrap();
    // Read as CSV: a cell of text before the parameters may hold a quoted comma (`sta_status`).
    let mut table = csv::Reader::from_reader(csv.as_bytes());
    let header: Vec<String> = table.headers().unwrap().iter().map(String::from).collect();
    let at = header
        .iter()
        .position(|c| c == "dummy_s")
        .expect("dummy_s in the header");
    assert_eq!(header[at - 1], "bdk_deg");
    for (row, record) in rows.iter().zip(table.records()) {
        let record = record.unwrap();
        let st = row.value(Parameter::StrideTime).unwrap();
        let v = row.value(d).expect("a dummy value");
        assert!((v - 2.0 * st).abs() < 2e-4, "{v} {st}");
        assert_eq!(record.get(at), Some(format!("{v}").as_str()), "{record:?}");
    }
    // recordings.json, read back.
    let json = serde_json::to_string(&rows).unwrap();
    assert!(json.contains("\"dummy_s\":"), "{json}");
    let back: Vec<RecordingRow> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, rows);
    // The column dictionary (`ldh columns`, docs/columns.md).
    let doc = columns()
        .iter()
        .find(|c| c.table == Table::Recordings && c.name == "dummy_s")
        .expect("dummy_s in the dictionary");
    assert_eq!(doc.unit, "s");
    assert!(doc.meaning.contains("DUM (dummy)"), "{}", doc.meaning);
    assert!(markdown().contains("`dummy_s`"));
    // The reliability table: three people × two trials.
    let mut trials = Vec::new();
    for (i, k) in [(0, 1.0), (1, 1.1), (2, 0.9)] {
        for (t, e) in [("a", 1.0), ("b", 1.02)] {
            for r in &rows {
                let mut r = r.clone();
                r.subject_id = format!("P{i}");
                r.trial_id = t.into();
                r.set_value(d, r.value(d).map(|v| v * k * e));
                trials.push(r);
            }
        }
    }
    let table = reliability_table(&trials, &ValidAgreementParams::default());
    let row = table.row(d).expect("a reliability row");
    assert_eq!((row.n_subjects, row.k_trials), (3, 2));
    assert!(row.mdc95.is_some(), "{row:?}");
    assert!(table
        .to_markdown(0.95)
        .contains("| dummy (DUM, s) | 3 × 2 |"));
}

#[test]
fn dummy_parameter_reaches_the_stride_table_and_its_dictionary() {
    let d = Parameter::Dummy;
    assert_eq!(Parameter::PER_STRIDE.last(), Some(&d));
    let strides = stride_rows(&[demo_subject()]);
    // strides.csv: its column after BDK's (its place in TABLE_ORDER), before the row's own
    // columns that follow the parameters; its value in each row.
    let csv = to_csv(&strides, &[]).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header, STRIDE_COLUMNS);
    let at = header
        .iter()
        .position(|c| *c == "dummy_s")
        .expect("dummy_s in the header");
    assert_eq!(
        (header[at - 1], header[at + 1]),
        ("bdk_deg", "heading_change_deg")
    );
    let mut measured = 0;
    for (row, line) in strides.iter().zip(lines) {
        // The columns up to dummy_s hold no text with a comma.
        let cell = line.split(',').nth(at).unwrap();
        match (row.value(Parameter::StrideTime), row.value(d)) {
            (Some(st), Some(v)) => {
                assert!((v - 2.0 * st).abs() < 2e-4, "{v} {st}");
                assert_eq!(cell, format!("{v}"), "{line}");
                measured += 1;
            }
            (None, None) => assert_eq!(cell, "", "{line}"),
            other => panic!("{other:?}: {line}"),
        }
    }
    assert!(measured > 10, "{measured} strides");
    // Read back as `ldh agree` and `ldh report` read strides.csv; strides.json.
    let back: Vec<StrideRow> = ::csv::Reader::from_reader(csv.as_bytes())
        .deserialize()
        .collect::<Result<_, _>>()
        .unwrap();
    assert_eq!(back, strides);
    let json = serde_json::to_string(&strides).unwrap();
    assert!(json.contains("\"dummy_s\":"), "{json}");
    // The column dictionary's strides.csv entry, from the definition's `per_stride`.
    let doc = columns()
        .iter()
        .find(|c| c.table == Table::Strides && c.name == "dummy_s")
        .expect("dummy_s in the dictionary's strides.csv");
    assert_eq!(doc.unit, "s");
    assert_eq!(
        doc.meaning,
        "Twice the stride time (a test-only parameter)."
    );
    assert!(markdown().contains("| `dummy_s` | s | Twice the stride time"));
}
