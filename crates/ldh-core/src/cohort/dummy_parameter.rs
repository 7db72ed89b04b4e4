//! The proof that a gait parameter is one definition plus its computation (issue 48): with the
//! test-only feature `dummy-parameter`, `Parameter::Dummy` exists with only its definition
//! (`domain/parameter.rs`) and its computation (`gait/side.rs`, twice the mean stride time),
//! and nothing else was edited for it. These tests find it in recordings.csv's header and
//! rows, recordings.json, the column dictionary and the reliability table.
//!
//! `cargo test --profile ci -p ldh-core --features dummy-parameter --lib dummy_parameter`

use crate::cohort::reliability_table;
use crate::domain::Parameter;
use crate::output::columns::{columns, markdown, Table};
use crate::output::{recording_rows, to_csv, RecordingRow};
use crate::pipeline::{discover, Analysis, AnalysisParams};
use crate::stats::agreement::ValidAgreementParams;

/// Both legs' rows of the first demo subject, analysed without STA.
fn demo_rows() -> Vec<RecordingRow> {
    let inputs = discover(&[]).unwrap();
    let mut p = AnalysisParams::default();
    p.compute_sta = false;
    let r = Analysis::new(p.check().unwrap()).subject(&inputs[0]);
    recording_rows(&[r])
}

#[test]
fn dummy_parameter_reaches_the_tables_the_dictionary_and_the_reliability_table() {
    let d = Parameter::Dummy;
    let rows = demo_rows();
    // recordings.csv: its column after BDK's (its place in TABLE_ORDER), its value in each row.
    let csv = to_csv(&rows, &[]).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at = header
        .iter()
        .position(|c| *c == "dummy_s")
        .expect("dummy_s in the header");
    assert_eq!(header[at - 1], "bdk_deg");
    for (row, line) in rows.iter().zip(lines) {
        let st = row.value(Parameter::StrideTime).unwrap();
        let v = row.value(d).expect("a dummy value");
        assert!((v - 2.0 * st).abs() < 2e-4, "{v} {st}");
        assert_eq!(
            line.split(',').nth(at),
            Some(format!("{v}").as_str()),
            "{line}"
        );
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
