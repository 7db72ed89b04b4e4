//! `ldh.monitor`: days of free-living recordings (`ldh_core::monitor`), the GIL released;
//! the four tables and the visit changes out as `{name: (columns, rows)}` of text cells (the
//! cells `ldh monitor` writes), typed in Python.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use ldh_core::monitor::write::{change_rows, tables, CHANGE_COLUMNS};
use ldh_core::monitor::{monitor_many, visit_changes, MonitorParams};
use ldh_core::pipeline::{discover_with, InputOptions};
use ldh_core::LdhError;

use crate::convert::from_py;
use crate::errors::OrRaise;

/// Analyse the inputs (as `ldh monitor`): a dict of table name → (columns, rows) (`bouts`,
/// `days`, `summary`, `periods` and `changes`, changes.csv's rows: empty when no person has
/// two periods), plus `notes` and `errors` (one list of strings per person and visit).
#[pyfunction]
#[pyo3(signature = (inputs, subject_id=None, params=None, n_jobs=1))]
pub(crate) fn monitor<'py>(
    py: Python<'py>,
    inputs: Vec<PathBuf>,
    subject_id: Option<String>,
    params: Option<&Bound<'py, PyAny>>,
    n_jobs: i64,
) -> PyResult<Bound<'py, PyDict>> {
    let n_jobs: usize = crate::convert::uint("n_jobs", n_jobs).or_raise(py)?;
    let params = params.map(from_py).transpose()?;
    let (tabs, changes, notes, errors) = py
        .detach(move || -> Result<_, LdhError> {
            let p: MonitorParams = match params {
                None => MonitorParams::default(),
                Some(v) => serde_json::from_value(v)
                    .map_err(|e| LdhError::param("params", "dict", e.to_string()))?,
            };
            let p = p.check()?;
            let inputs = discover_with(
                &inputs,
                &InputOptions {
                    subject_id,
                    ..InputOptions::default()
                },
            )?;
            let jobs = if n_jobs == 0 {
                0
            } else {
                ldh_core::pipeline::bounded_jobs(n_jobs).0
            };
            let results = monitor_many(&inputs, &p, jobs)?;
            let notes: Vec<Vec<String>> = results.iter().map(|r| r.notes.clone()).collect();
            let errors: Vec<Vec<String>> = results.iter().map(|r| r.errors.clone()).collect();
            let changes = change_rows(&visit_changes(&results));
            Ok((tables(&results), changes, notes, errors))
        })
        .or_raise(py)?;
    let d = PyDict::new(py);
    for (name, head, rows) in tabs {
        d.set_item(name.trim_end_matches(".csv"), (head, rows))?;
    }
    d.set_item("changes", (CHANGE_COLUMNS.to_vec(), changes))?;
    d.set_item("notes", notes)?;
    d.set_item("errors", errors)?;
    Ok(d)
}
