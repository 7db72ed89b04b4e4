//! `ldh.agree`: an `ldh analyze` output folder against reference files
//! ([`ldh_core::agreement::run`]); the report as dicts and lists, and its flat table (the rows
//! of `agreement.csv`) ready for `pandas.DataFrame`. `ldh.reliability`: the test–retest table
//! ([`ldh_core::agreement::reliability_table`]) of a folder or of a recordings table in memory.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use ldh_core::agreement::write::AgreementRow;
use ldh_core::agreement::{self, AgreementParams, OffsetMode};
use ldh_core::cohort::reliability_table::COLUMNS;
use ldh_core::cohort::{self, ReliabilityTable};
use ldh_core::output::{LdhResults, Parameter, RecordingRow};
use ldh_core::LdhError;

use crate::convert::{columns as columns_of, csv_header, from_py, to_py, value_of, Opts};
use crate::errors::OrRaise;

/// `offset_s`: `None` (the clocks agree), a number of seconds, or `"estimate"`.
fn offset_mode(offset_s: Option<&Bound<'_, PyAny>>) -> Result<OffsetMode, LdhError> {
    let Some(o) = offset_s else {
        return Ok(OffsetMode::None);
    };
    if let Ok(s) = o.extract::<String>() {
        return s.parse();
    }
    match o.extract::<f64>() {
        Ok(v) => OffsetMode::fixed(v, "offset_s"),
        Err(_) => Err(LdhError::param(
            "offset_s",
            o.to_string(),
            "expected a finite number of seconds or 'estimate'",
        )),
    }
}

/// `ldh agree RESULTS --reference REF...` without writing files: the report (`offsets`,
/// `events`, `unmatched_events`, `parameters` with their pairs, …) plus `table`, the rows of
/// `agreement.csv`. `write_params`: also write the run's parameters calibrated to this
/// reference there (`ldh agree --write-params`), before returning.
#[pyfunction]
#[pyo3(signature = (results_dir, reference, tolerance_s=None, offset_s=None, write_params=None, reference_system=None))]
pub(crate) fn agree<'py>(
    py: Python<'py>,
    results_dir: PathBuf,
    reference: Vec<PathBuf>,
    tolerance_s: Option<f64>,
    offset_s: Option<&Bound<'py, PyAny>>,
    write_params: Option<PathBuf>,
    reference_system: Option<String>,
) -> PyResult<Bound<'py, PyAny>> {
    let mode = offset_mode(offset_s).or_raise(py)?;
    let (v, rows) = py
        .detach(
            move || -> Result<(serde_json::Value, Vec<AgreementRow>), LdhError> {
                let mut p = AgreementParams::default();
                if let Some(t) = tolerance_s {
                    p.tolerance_s = t;
                }
                let params = p.check()?;
                let results = LdhResults::read(&results_dir)?;
                let reference = agreement::read_reference(&reference, &results, &params)?;
                let report = agreement::run(&results, &reference, &params, mode)?;
                if let Some(f) = write_params {
                    let p = agreement::calibrated_params(
                        &report,
                        results.analysis_params.as_ref(),
                        reference_system.as_deref(),
                    )?;
                    ldh_core::io::write_atomic(f, agreement::params_toml(&p)?.as_bytes())?;
                }
                let mut v = value_of(&report)?;
                let rows = agreement::write::rows(&report);
                let table = value_of(&rows)?;
                if let serde_json::Value::Object(m) = &mut v {
                    m.insert("table".into(), table);
                }
                Ok((v, rows))
            },
        )
        .or_raise(py)?;
    let out = to_py(py, &v, Opts::default())?;
    // The rows of `agreement.csv` as columns in the file's order (`ldh.Agreement.table`).
    let header = csv_header(&AgreementRow::default());
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    out.set_item("table_columns", columns_of(py, &rows, &header)?)?;
    Ok(out)
}

/// The columns of a recordings table the reliability reads: the trial's keys (text) and the
/// parameters (numbers; NaN or None is missing).
const KEYS: [&str; 5] = ["subject_id", "trial_id", "visit", "side", "status"];

/// Per-recording rows from a recordings table given as columns (`{name: list}`, as
/// `ldh.Result` holds them): only what the reliability reads; a missing key column is empty.
fn rows_of(columns: &serde_json::Value) -> Result<Vec<RecordingRow>, LdhError> {
    let col = |name: &str| columns.get(name).and_then(|v| v.as_array());
    let n = col("subject_id").map_or(0, Vec::len);
    let mut rows = Vec::with_capacity(n);
    for i in 0..n {
        let mut m = serde_json::json!({
            "model": "fusion", "group": "", "affected_side": "", "side_role": "", "source": "",
            "error": "", "sta_status": "",
        });
        for k in KEYS {
            let v = col(k)
                .and_then(|c| c.get(i))
                .and_then(|v| v.as_str())
                .unwrap_or("");
            m[k] = v.into();
        }
        for p in Parameter::ALL {
            let v = col(p.column())
                .and_then(|c| c.get(i))
                .and_then(|v| v.as_f64());
            m[p.column()] = v.into();
        }
        let row: RecordingRow = serde_json::from_value(m).map_err(|e| {
            LdhError::param(
                "results",
                format!("row {i}"),
                format!("not a recordings row: {e}"),
            )
        })?;
        rows.push(row);
    }
    Ok(rows)
}

/// `ldh stats --reliability` without writing files: the rows of `reliability.csv` as columns,
/// from an `ldh analyze` folder (`results_dir`) or a recordings table's columns.
#[pyfunction]
#[pyo3(signature = (results_dir=None, recordings=None, confidence_level=None))]
pub(crate) fn reliability<'py>(
    py: Python<'py>,
    results_dir: Option<PathBuf>,
    recordings: Option<&Bound<'py, PyAny>>,
    confidence_level: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let columns = recordings.map(from_py).transpose()?;
    let table = py
        .detach(move || -> Result<ReliabilityTable, LdhError> {
            let mut p = AgreementParams::default();
            if let Some(c) = confidence_level {
                p.confidence_level = c;
            }
            let params = p.check()?;
            let rows = match (&results_dir, &columns) {
                (Some(d), None) => ldh_core::output::read_recordings(d)?,
                (None, Some(c)) => rows_of(c)?,
                _ => {
                    return Err(LdhError::param(
                        "results",
                        "",
                        "give an ldh analyze output folder or a recordings table, one of them",
                    ))
                }
            };
            cohort::require_repeated_trials(&rows)?;
            Ok(cohort::reliability_table(&rows, &params))
        })
        .or_raise(py)?;
    columns_of(py, &table.rows, &COLUMNS)
}

/// The core's defaults of `ldh.agree`'s `tolerance_s` and `ldh.reliability`'s
/// `confidence_level`.
pub(crate) fn defaults(py: Python<'_>, d: &Bound<'_, PyDict>) -> PyResult<()> {
    let a = PyDict::new(py);
    a.set_item("tolerance_s", AgreementParams::default().tolerance_s)?;
    d.set_item("agree", a)?;
    let r = PyDict::new(py);
    r.set_item(
        "confidence_level",
        AgreementParams::default().confidence_level,
    )?;
    d.set_item("reliability", r)?;
    Ok(())
}
