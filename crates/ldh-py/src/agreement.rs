//! `ldh.agree`: an `ldh analyze` output folder against reference files
//! ([`ldh_core::agreement::run`]); the report as dicts and lists, and its flat table (the rows
//! of `agreement.csv`) ready for `pandas.DataFrame`.

use std::path::PathBuf;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use ldh_core::agreement::{self, AgreementParams, LdhResults, OffsetMode};
use ldh_core::LdhError;

use crate::convert::{to_py, value_of, Opts};
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
    let v = py
        .detach(move || -> Result<serde_json::Value, LdhError> {
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
            let table = value_of(&agreement::write::rows(&report))?;
            if let serde_json::Value::Object(m) = &mut v {
                m.insert("table".into(), table);
            }
            Ok(v)
        })
        .or_raise(py)?;
    to_py(py, &v, Opts::default())
}

/// The core's default of `ldh.agree`'s `tolerance_s`.
pub(crate) fn defaults(py: Python<'_>, d: &Bound<'_, PyDict>) -> PyResult<()> {
    let a = PyDict::new(py);
    a.set_item("tolerance_s", AgreementParams::default().tolerance_s)?;
    d.set_item("agree", a)?;
    Ok(())
}
