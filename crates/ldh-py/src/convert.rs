//! Values in and out of the binding: numpy channels, recordings as dicts, the result tables,
//! the Python `params` dict. Every conversion of core results to Python goes through here.

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use ldh_core::io::FormatSpec;
use ldh_core::{LdhError, Recording};

/// A 1-D float64 numpy array owned by Python.
pub(crate) type Array1<'py> = Bound<'py, PyArray1<f64>>;

/// A vector as a 1-D float64 numpy array.
pub(crate) fn vec1<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    v.into_pyarray(py)
}

/// Put the six channels into a dict as `acc_x_g` … `gyro_z_dps` numpy arrays.
pub(crate) fn put_channels(
    d: &Bound<'_, PyDict>,
    acc_g: [Vec<f64>; 3],
    gyro_dps: [Vec<f64>; 3],
) -> PyResult<()> {
    let names = [
        "acc_x_g",
        "acc_y_g",
        "acc_z_g",
        "gyro_x_dps",
        "gyro_y_dps",
        "gyro_z_dps",
    ];
    for (k, v) in names.into_iter().zip(acc_g.into_iter().chain(gyro_dps)) {
        d.set_item(k, vec1(d.py(), v))?;
    }
    Ok(())
}

/// Copy N numpy channels (contiguous float64, as the Python layer passes them) into vectors.
pub(crate) fn vecs<const N: usize>(a: &[PyReadonlyArray1<'_, f64>; N]) -> PyResult<[Vec<f64>; N]> {
    let v: Vec<Vec<f64>> = a
        .iter()
        .map(|c| c.as_slice().map(|s| s.to_vec()))
        .collect::<Result<_, _>>()?;
    Ok(v.try_into().expect("N channels in, N out"))
}

/// The result tables of `ldh analyze` as one JSON object for the Python layer.
pub(crate) fn tables_json(
    results: &[ldh_core::pipeline::SubjectResult],
) -> Result<String, LdhError> {
    serde_json::to_string(&ldh_core::output::Tables::of(results))
        .map_err(|e| LdhError::signal("json", e.to_string()))
}

/// A recording as the dict `ldh.read_recording` returns (channels as numpy arrays).
pub(crate) fn recording_dict<'py>(py: Python<'py>, rec: Recording) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("fs_hz", rec.fs_hz)?;
    d.set_item("t0_s", rec.t0_s)?;
    d.set_item("time_s", vec1(py, rec.times_s()))?;
    put_channels(&d, rec.acc_g, rec.gyro_dps)?;
    d.set_item("saturated", rec.saturated.into_pyarray(py))?;
    Ok(d)
}

/// A `format` argument: a preset name or a column spec (see `ldh formats`).
pub(crate) fn format_of(format: Option<&str>) -> Result<Option<FormatSpec>, LdhError> {
    format.map(FormatSpec::resolve).transpose()
}

/// Analysis parameters from an optional JSON object (the Python `params` dict: the same names,
/// nesting and defaults as the Rust `AnalysisParams`, unknown names refused).
pub(crate) fn base_params(
    params_json: Option<&str>,
) -> Result<ldh_core::pipeline::AnalysisParams, LdhError> {
    match params_json {
        None => Ok(ldh_core::pipeline::AnalysisParams::default()),
        Some(j) => {
            serde_json::from_str(j).map_err(|e| LdhError::param("params", "dict", e.to_string()))
        }
    }
}
