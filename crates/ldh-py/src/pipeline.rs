//! The analysis of paths or arrays (core `pipeline`): whole subjects as `ldh analyze` does,
//! a subject's two legs given as arrays, one leg given as arrays.

use numpy::PyReadonlyArray1;
use pyo3::prelude::*;

use ldh_core::io::ReadParams;
use ldh_core::{LdhError, Recording};

use crate::convert::{base_params, format_of, tables_json, vec1, vecs, Array1};
use crate::errors::to_py;

/// Register this module's functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(analyze, m)?)?;
    m.add_function(wrap_pyfunction!(analyze_pair, m)?)?;
    m.add_function(wrap_pyfunction!(analyze_recording, m)?)?;
    Ok(())
}

/// Analyse subjects as `ldh analyze` does; returns JSON text of
/// {"strides": [...], "recordings": [...], "events": [...]} rows.
#[pyfunction]
#[pyo3(signature = (inputs, model=None, detector=None, format=None, compute_sta=None, sensor_height_m=None, n_jobs=1, params_json=None, subject_id=None, setting=None))]
#[allow(clippy::too_many_arguments)]
fn analyze(
    py: Python<'_>,
    inputs: Vec<std::path::PathBuf>,
    model: Option<String>,
    detector: Option<String>,
    format: Option<&str>,
    compute_sta: Option<bool>,
    sensor_height_m: Option<f64>,
    n_jobs: usize,
    params_json: Option<String>,
    subject_id: Option<String>,
    setting: Option<String>,
) -> PyResult<String> {
    let (model, detector, fmt) = (model, detector, format.map(String::from));
    py.detach(move || -> Result<String, LdhError> {
        let p = base_params(params_json.as_deref())?.with_options(
            model.as_deref(),
            detector.as_deref(),
            sensor_height_m,
            compute_sta,
        )?;
        let f = format_of(fmt.as_deref())?;
        let read = ReadParams::default().check()?;
        let opts = ldh_core::pipeline::InputOptions {
            subject_id,
            setting: setting.as_deref().map(str::parse).transpose()?,
        };
        let subjects = ldh_core::pipeline::discover_with(&inputs, &opts)?;
        let results =
            ldh_core::pipeline::analyze_many_on(&subjects, &p, f.as_ref(), &read, n_jobs)?;
        tables_json(&results)
    })
    .map_err(|e| to_py(py, e))
}

/// Analyse one recording given as arrays; returns JSON text with the alignment, events,
/// strides and parameters, and the attitude (pitch, roll, yaw in deg) as numpy arrays.
#[pyfunction]
#[pyo3(signature = (acc_g, gyro_dps, fs_hz, side="left", model=None, detector=None, sensor_height_m=None, compute_sta=None, params_json=None))]
#[allow(clippy::too_many_arguments)]
fn analyze_recording<'py>(
    py: Python<'py>,
    acc_g: [PyReadonlyArray1<'py, f64>; 3],
    gyro_dps: [PyReadonlyArray1<'py, f64>; 3],
    fs_hz: f64,
    side: &str,
    model: Option<String>,
    detector: Option<String>,
    sensor_height_m: Option<f64>,
    compute_sta: Option<bool>,
    params_json: Option<String>,
) -> PyResult<(String, Array1<'py>, Array1<'py>, Array1<'py>)> {
    let acc: [Vec<f64>; 3] = vecs(&acc_g)?;
    let gyro: [Vec<f64>; 3] = vecs(&gyro_dps)?;
    let side = side.to_string();
    let (json, att) = py
        .detach(
            move || -> Result<(String, ldh_core::attitude::Attitude), LdhError> {
                let side: ldh_core::Side = side.parse()?;
                let p = base_params(params_json.as_deref())?.with_options(
                    model.as_deref(),
                    detector.as_deref(),
                    sensor_height_m,
                    compute_sta,
                )?;
                let rec = Recording::new(fs_hz, acc, gyro, vec![])?.with_side(side);
                let (leg, _) = ldh_core::pipeline::analyze_leg(&rec, side, &p, None)?;
                let att = leg
                    .attitude
                    .clone()
                    .expect("analyze_leg keeps the attitude");
                let json = serde_json::json!({
                    "alignment": leg.alignment,
                    "events": leg.events,
                    "strides": leg.strides,
                    "parameters": leg.parameters,
                    "outliers_replaced": leg.outliers_replaced,
                    "warnings": leg.warnings,
                })
                .to_string();
                Ok((json, att))
            },
        )
        .map_err(|e| to_py(py, e))?;
    Ok((
        json,
        vec1(py, att.pitch_deg),
        vec1(py, att.roll_deg),
        vec1(py, att.yaw_deg),
    ))
}

/// Analyse a subject's two recordings given as arrays (6 channels each); returns the JSON of
/// {"strides", "recordings", "events"} rows as `analyze` does.
#[pyfunction]
#[pyo3(signature = (left, right, fs_hz, subject_id="subject", model=None, detector=None, sensor_height_m=None, compute_sta=None, params_json=None))]
#[allow(clippy::too_many_arguments)]
fn analyze_pair<'py>(
    py: Python<'py>,
    left: [PyReadonlyArray1<'py, f64>; 6],
    right: [PyReadonlyArray1<'py, f64>; 6],
    fs_hz: f64,
    subject_id: &str,
    model: Option<String>,
    detector: Option<String>,
    sensor_height_m: Option<f64>,
    compute_sta: Option<bool>,
    params_json: Option<String>,
) -> PyResult<String> {
    use ldh_core::pipeline::{analyze_pair as core_pair, bare_subject, leg_from_arrays};
    use ldh_core::Side;
    let (l, r): ([Vec<f64>; 6], [Vec<f64>; 6]) = (vecs(&left)?, vecs(&right)?);
    let (id, model, detector) = (subject_id.to_string(), model, detector);
    py.detach(move || -> Result<String, LdhError> {
        let p = base_params(params_json.as_deref())?.with_options(
            model.as_deref(),
            detector.as_deref(),
            sensor_height_m,
            compute_sta,
        )?;
        let leg = |c: [Vec<f64>; 6], side: Side| {
            let [a, b, cc, d, e, f] = c;
            leg_from_arrays(fs_hz, [a, b, cc], [d, e, f], side)
        };
        let input = bare_subject(&id);
        let res = [core_pair(
            &input,
            leg(l, Side::Left),
            leg(r, Side::Right),
            &p,
        )];
        tables_json(&res)
    })
    .map_err(|e| to_py(py, e))
}
