//! Reading recordings, filters, the demo cohort and the simulator (core `io`, `preprocess`,
//! `demo`, `simulate`).

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use ldh_core::io::{read_recording, FormatSpec, GapPolicy, ReadParams};
use ldh_core::preprocess::{preprocess as core_preprocess, PreprocessParams};
use ldh_core::{LdhError, Recording};

use crate::convert::{format_of, put_channels, recording_dict, vec1, vecs};
use crate::errors::to_py;

/// Register this module's functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(read_recording_py, m)?)?;
    m.add_function(wrap_pyfunction!(butter_filtfilt, m)?)?;
    m.add_function(wrap_pyfunction!(preprocess, m)?)?;
    m.add_function(wrap_pyfunction!(write_demo, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_cohort, m)?)?;
    Ok(())
}

/// Read one sensor CSV. See `ldh.read_recording`.
#[pyfunction(name = "read_recording")]
#[pyo3(signature = (path, format=None, max_gap_s=0.2, gap_policy="split", min_duration_s=4.0, check_units=true))]
fn read_recording_py<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    format: Option<&str>,
    max_gap_s: f64,
    gap_policy: &str,
    min_duration_s: f64,
    check_units: bool,
) -> PyResult<(Bound<'py, PyDict>, String)> {
    let policy = match gap_policy {
        "split" => GapPolicy::Split,
        "reject" => GapPolicy::Reject,
        other => {
            return Err(to_py(
                py,
                LdhError::param("gap_policy", other, "expected 'split' or 'reject'"),
            ))
        }
    };
    let params = ReadParams {
        max_gap_s,
        gap_policy: policy,
        min_duration_s,
        check_units,
        ..ReadParams::default()
    };
    let fmt = format.map(String::from);
    let out = py.detach(move || {
        let p = params.check()?;
        let f = format_of(fmt.as_deref())?;
        read_recording(&path, f.as_ref(), &p)
    });
    let (rec, report) = out.map_err(|e| to_py(py, e))?;
    let report =
        serde_json::to_string(&report).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok((recording_dict(py, rec)?, report))
}

/// Zero-phase Butterworth low-pass (scipy's sosfiltfilt of butter(order, cutoff_hz, fs=fs_hz)).
#[pyfunction]
#[pyo3(signature = (x, cutoff_hz, fs_hz, order=4))]
fn butter_filtfilt<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    cutoff_hz: f64,
    fs_hz: f64,
    order: usize,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let v = x.as_slice()?.to_vec();
    let y = py
        .detach(move || ldh_core::preprocess::butter_filtfilt(&v, order, cutoff_hz, fs_hz))
        .map_err(|e| to_py(py, e))?;
    Ok(vec1(py, y))
}

/// Preprocess six channels (paper §3.1). Returns a dict of filtered channels.
#[pyfunction]
#[pyo3(signature = (acc_g, gyro_dps, fs_hz, cutoff_hz=10.0, filter_order=4, outlier_sd=3.0, replace_outliers=true, outlier_channels="acc"))]
#[allow(clippy::too_many_arguments)]
fn preprocess<'py>(
    py: Python<'py>,
    acc_g: [PyReadonlyArray1<'py, f64>; 3],
    gyro_dps: [PyReadonlyArray1<'py, f64>; 3],
    fs_hz: f64,
    cutoff_hz: f64,
    filter_order: usize,
    outlier_sd: f64,
    replace_outliers: bool,
    outlier_channels: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let outlier_channels = match outlier_channels {
        "acc" => ldh_core::preprocess::OutlierChannels::Acc,
        "all" => ldh_core::preprocess::OutlierChannels::All,
        o => {
            return Err(to_py(
                py,
                LdhError::param("outlier_channels", o, "expected 'acc' or 'all'"),
            ))
        }
    };
    let acc: [Vec<f64>; 3] = vecs(&acc_g)?;
    let gyro: [Vec<f64>; 3] = vecs(&gyro_dps)?;
    let params = PreprocessParams {
        cutoff_hz,
        filter_order,
        outlier_sd,
        replace_outliers,
        outlier_channels,
    };
    let out = py
        .detach(move || {
            let rec = Recording::new(fs_hz, acc, gyro, vec![])?;
            let p = params.check(fs_hz)?;
            core_preprocess(&rec, &p)
        })
        .map_err(|e| to_py(py, e))?;
    let d = PyDict::new(py);
    put_channels(&d, out.acc_g, out.gyro_dps)?;
    d.set_item("acc_norm_g", vec1(py, out.acc_norm_g))?;
    d.set_item(
        "replaced",
        out.replaced
            .into_iter()
            .map(|i| i as i64)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    d.set_item("fs_hz", out.fs_hz)?;
    Ok(d)
}

/// Write the embedded demo cohort to a folder; returns the number of files.
#[pyfunction]
fn write_demo(py: Python<'_>, out: std::path::PathBuf) -> PyResult<usize> {
    py.detach(move || ldh_core::demo::write_to(&out))
        .map_err(|e| to_py(py, e))
}

/// Simulate a cohort into a folder (as `ldh simulate`: the subjects' files, `manifest.csv` and
/// `cohort.json`); returns the manifest CSV text.
#[pyfunction]
#[pyo3(signature = (out, healthy=2, ldh=2, seconds=25.0, seed=1, rate_hz=100.0, turn=true))]
#[allow(clippy::too_many_arguments)]
fn simulate_cohort(
    py: Python<'_>,
    out: std::path::PathBuf,
    healthy: usize,
    ldh: usize,
    seconds: f64,
    seed: u64,
    rate_hz: f64,
    turn: bool,
) -> PyResult<String> {
    let params = ldh_core::simulate::CohortParams {
        healthy,
        ldh,
        duration_s: seconds,
        fs_hz: rate_hz,
        seed,
        turn,
        ..Default::default()
    };
    py.detach(move || -> Result<String, LdhError> {
        let rows = ldh_core::simulate::write_cohort(&params, &out, &FormatSpec::default(), &|| {})?;
        Ok(ldh_core::simulate::manifest_csv(&rows))
    })
    .map_err(|e| to_py(py, e))
}
