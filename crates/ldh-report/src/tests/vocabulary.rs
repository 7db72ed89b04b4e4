//! One parameter, one definition (issue 48): every place that names a gait parameter — the
//! column dictionary (`ldh columns`, docs/columns.md), the tables' headers, the report's rows and
//! the reliability table — takes its code, column, name and unit from
//! `ldh_core::domain::Parameter::definition`, so a parameter has one name and one unit.
//!
//! Adding a parameter is its variant and definition (`domain/parameter.rs`, in `Parameter::ALL`
//! and `TABLE_ORDER`) and its computation (`gait/side.rs`); values are stored by `Parameter`
//! (`PerParameter`), so the tables, the dictionary, the reliability table, Table 3 of the
//! statistics, the classifiers' feature list, the report's change-between-visits table and its
//! parameter page (`verdict::quantities`: a line of `verdict::QUANTITIES` says how the page
//! lays a parameter out — decimals, scope, companion —, a parameter without one follows with
//! the default layout) carry it with no further edit (docs/vocabulary.md "Adding a parameter";
//! ldh-core's `cohort/dummy_parameter.rs` shows it). The test below checks, for every
//! parameter, that each of these places says what its definition says.

use ldh_core::cohort::{ReliabilityRow, ReliabilityTable};
use ldh_core::domain::Parameter;
use ldh_core::output::columns::{columns, Table};

use super::super::verdict::{quantities, QUANTITIES};

#[test]
fn every_parameter_is_named_from_its_one_definition_everywhere() {
    let reliability = ReliabilityTable {
        rows: Parameter::ALL
            .iter()
            .map(|&p| ReliabilityRow::withheld(p, 0, 0, "no repeated trials".into()))
            .collect(),
    };
    let md = reliability.to_markdown(0.95);
    for p in Parameter::ALL {
        let d = p.definition();
        // The column dictionary, both tables.
        let doc = columns()
            .iter()
            .find(|c| c.table == Table::Recordings && c.name == d.column)
            .unwrap_or_else(|| panic!("{p:?} not in the dictionary"));
        assert_eq!(doc.unit, d.unit.as_str(), "{p:?}");
        assert_eq!(
            doc.meaning,
            format!("{} ({}): {}", d.code, d.name, d.description)
        );
        let per_stride = columns()
            .iter()
            .find(|c| c.table == Table::Strides && c.name == d.column);
        assert_eq!(
            per_stride.map(|c| c.meaning.as_ref()),
            d.per_stride,
            "{p:?}"
        );
        // The report's rows: every parameter is one, or a row's companion.
        let q = quantities()
            .iter()
            .find(|q| q.parameter == p || q.companion == Some(p));
        assert!(q.is_some(), "{p:?} not on the report's page");
        if let Some(q) = q.filter(|q| q.parameter == p) {
            assert_eq!(q.label(), p.label());
            assert_eq!((q.scale(), q.unit()), d.display);
        }
        // The reliability table (reliability.csv and its Markdown).
        let row = reliability.row(p).unwrap();
        assert_eq!(
            (row.code.as_str(), row.unit.as_str()),
            (d.code, d.unit.as_str())
        );
        assert!(
            md.contains(&format!("| {} ({}, {}) |", d.name, d.code, d.unit)),
            "{p:?}: {md}"
        );
    }
    // Every report row is a parameter's, named by it.
    assert!(QUANTITIES.iter().all(|q| q.label() == q.parameter.label()));
    assert_eq!(Parameter::Speed.label(), "Walking speed");
    assert_eq!(
        Parameter::StanceRatio.display(),
        (100.0, "% of the gait cycle")
    );
}

/// The tables' headers hold each parameter's column once, where the dictionary puts it (that
/// the writers emit exactly the dictionary's columns is `output::columns`'s own test).
#[test]
fn the_tables_headers_are_the_dictionarys() {
    let header = |t: Table| -> Vec<&'static str> {
        columns()
            .iter()
            .filter(|c| c.table == t)
            .map(|c| c.name)
            .collect()
    };
    let rec = header(Table::Recordings);
    for p in Parameter::ALL {
        assert_eq!(rec.iter().filter(|c| **c == p.column()).count(), 1, "{p:?}");
    }
    assert_eq!(
        header(Table::Strides),
        ldh_core::output::STRIDE_COLUMNS.to_vec()
    );
}
