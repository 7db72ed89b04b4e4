//! Reading recordings, the filters, the demo and the simulator (`ldh.read_recording`,
//! `ldh.butter_filtfilt`, `ldh.preprocess`, `ldh.write_demo`, `ldh.simulate_cohort`).
//! Parameters left as `None` take the core's defaults.

use std::path::PathBuf;

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use ldh_core::io::{read_recording as core_read, FormatSpec, ReadParams};
use ldh_core::preprocess::{preprocess as core_preprocess, PreprocessParams};
use ldh_core::{LdhError, Recording};

use crate::convert::{choice, opt_uint, to_py, value_of, vec1, vecs, Opts};
use crate::errors::OrRaise;

const CHANNELS: [&str; 6] = [
    "acc_x_g",
    "acc_y_g",
    "acc_z_g",
    "gyro_x_dps",
    "gyro_y_dps",
    "gyro_z_dps",
];

/// Put the six channels into a dict as `acc_x_g` … `gyro_z_dps` numpy arrays.
fn put_channels(
    d: &Bound<'_, PyDict>,
    acc_g: [Vec<f64>; 3],
    gyro_dps: [Vec<f64>; 3],
) -> PyResult<()> {
    for (k, v) in CHANNELS.into_iter().zip(acc_g.into_iter().chain(gyro_dps)) {
        d.set_item(k, vec1(d.py(), v))?;
    }
    Ok(())
}

fn recording_dict(py: Python<'_>, rec: Recording) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("fs_hz", rec.fs_hz)?;
    d.set_item("t0_s", rec.t0_s)?;
    d.set_item("time_s", vec1(py, rec.times_s()))?;
    put_channels(&d, rec.acc_g, rec.gyro_dps)?;
    d.set_item("saturated", rec.saturated.into_pyarray(py))?;
    Ok(d)
}

/// The reader's defaults with the size limits given (`None`: the core's default).
pub(crate) fn read_limits(max_file_size_mb: Option<f64>, max_samples: Option<usize>) -> ReadParams {
    let d = ReadParams::default();
    ReadParams {
        max_file_size_mb: max_file_size_mb.unwrap_or(d.max_file_size_mb),
        max_samples: max_samples.unwrap_or(d.max_samples),
        ..d
    }
}

/// A format name or TOML column map, or detection when `None`.
pub(crate) fn format_of(format: Option<&str>) -> Result<Option<FormatSpec>, LdhError> {
    format.map(FormatSpec::resolve).transpose()
}

/// Read one sensor CSV: (recording dict of numpy channels, read report dict).
#[pyfunction]
#[pyo3(signature = (path, format=None, max_gap_s=None, gap_policy=None, min_duration_s=None, check_units=None, max_file_size_mb=None, max_samples=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn read_recording<'py>(
    py: Python<'py>,
    path: PathBuf,
    format: Option<String>,
    max_gap_s: Option<f64>,
    gap_policy: Option<String>,
    min_duration_s: Option<f64>,
    check_units: Option<bool>,
    max_file_size_mb: Option<f64>,
    max_samples: Option<i64>,
) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyAny>)> {
    let max_samples = opt_uint("max_samples", max_samples).or_raise(py)?;
    let (rec, report) = py
        .detach(move || -> Result<_, LdhError> {
            let d = ReadParams::default();
            let params = ReadParams {
                max_gap_s: max_gap_s.unwrap_or(d.max_gap_s),
                gap_policy: match gap_policy {
                    Some(g) => choice("gap_policy", &g)?,
                    None => d.gap_policy,
                },
                min_duration_s: min_duration_s.unwrap_or(d.min_duration_s),
                check_units: check_units.unwrap_or(d.check_units),
                ..read_limits(max_file_size_mb, max_samples)
            };
            let p = params.check()?;
            let f = format_of(format.as_deref())?;
            let (rec, report) = core_read(&path, f.as_ref(), &p)?;
            Ok((rec, value_of(&report)?))
        })
        .or_raise(py)?;
    Ok((
        recording_dict(py, rec)?,
        to_py(py, &report, Opts::default())?,
    ))
}

/// Zero-phase Butterworth low-pass (scipy's sosfiltfilt of butter(order, cutoff_hz, fs=fs_hz)).
#[pyfunction]
#[pyo3(signature = (x, cutoff_hz, fs_hz, order=None))]
pub(crate) fn butter_filtfilt<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
    cutoff_hz: f64,
    fs_hz: f64,
    order: Option<i64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let order = opt_uint("order", order).or_raise(py)?;
    let v = x.as_slice()?.to_vec();
    let order = order.unwrap_or(PreprocessParams::default().filter_order);
    let y = py
        .detach(move || ldh_core::preprocess::butter_filtfilt(&v, order, cutoff_hz, fs_hz))
        .or_raise(py)?;
    Ok(vec1(py, y))
}

/// Preprocess six channels (paper §3.1); a dict of filtered channels.
#[pyfunction]
#[pyo3(signature = (acc_g, gyro_dps, fs_hz, cutoff_hz=None, filter_order=None, outlier_sd=None, replace_outliers=None, outlier_channels=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn preprocess<'py>(
    py: Python<'py>,
    acc_g: [PyReadonlyArray1<'py, f64>; 3],
    gyro_dps: [PyReadonlyArray1<'py, f64>; 3],
    fs_hz: f64,
    cutoff_hz: Option<f64>,
    filter_order: Option<i64>,
    outlier_sd: Option<f64>,
    replace_outliers: Option<bool>,
    outlier_channels: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let filter_order = opt_uint("filter_order", filter_order).or_raise(py)?;
    let (acc, gyro) = (vecs(&acc_g)?, vecs(&gyro_dps)?);
    let out = py
        .detach(move || {
            let d = PreprocessParams::default();
            let params = PreprocessParams {
                cutoff_hz: cutoff_hz.unwrap_or(d.cutoff_hz),
                filter_order: filter_order.unwrap_or(d.filter_order),
                outlier_sd: outlier_sd.unwrap_or(d.outlier_sd),
                replace_outliers: replace_outliers.unwrap_or(d.replace_outliers),
                outlier_channels: match outlier_channels {
                    Some(c) => choice("outlier_channels", &c)?,
                    None => d.outlier_channels,
                },
            };
            let rec = Recording::new(fs_hz, acc, gyro, vec![])?;
            let p = params.check(fs_hz)?;
            core_preprocess(&rec, &p)
        })
        .or_raise(py)?;
    let d = PyDict::new(py);
    put_channels(&d, out.acc_g, out.gyro_dps)?;
    d.set_item("acc_norm_g", vec1(py, out.acc_norm_g))?;
    let replaced: Vec<i64> = out.replaced.into_iter().map(|i| i as i64).collect();
    d.set_item("replaced", replaced.into_pyarray(py))?;
    d.set_item("fs_hz", out.fs_hz)?;
    Ok(d)
}

/// Write the embedded demo cohort to a folder; returns the number of files.
#[pyfunction]
pub(crate) fn write_demo(py: Python<'_>, out: PathBuf) -> PyResult<usize> {
    py.detach(move || ldh_core::demo::write_to(&out))
        .or_raise(py)
}

/// Simulate a cohort into a folder as `ldh simulate` does; returns the manifest CSV text.
#[pyfunction]
#[pyo3(signature = (out, healthy=None, ldh=None, seconds=None, seed=None, rate_hz=None, turn=None, slow_ldh=None, acc_range_g=None, ramp_s=None, trials=None, day_to_day_sd_fraction=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn simulate_cohort(
    py: Python<'_>,
    out: PathBuf,
    healthy: Option<i128>,
    ldh: Option<i128>,
    seconds: Option<f64>,
    seed: Option<i128>,
    rate_hz: Option<f64>,
    turn: Option<bool>,
    slow_ldh: Option<i128>,
    acc_range_g: Option<f64>,
    ramp_s: Option<f64>,
    trials: Option<i128>,
    day_to_day_sd_fraction: Option<f64>,
) -> PyResult<String> {
    let counts = || -> Result<_, LdhError> {
        Ok((
            opt_uint::<usize>("healthy", healthy)?,
            opt_uint::<usize>("ldh", ldh)?,
            opt_uint::<u64>("seed", seed)?,
            opt_uint::<usize>("slow_ldh", slow_ldh)?,
            opt_uint::<usize>("trials", trials)?,
        ))
    };
    let (healthy, ldh, seed, slow_ldh, trials) = counts().or_raise(py)?;
    let d = ldh_sim::CohortParams::default();
    let trials = trials.unwrap_or(d.trials);
    let sensor = match acc_range_g {
        Some(g) => d.sensor.clone().acc_range_g(g),
        None => d.sensor.clone(),
    };
    let params = ldh_sim::CohortParams {
        healthy: healthy.unwrap_or(d.healthy),
        ldh: ldh.unwrap_or(d.ldh),
        duration_s: seconds.unwrap_or(d.duration_s),
        fs_hz: rate_hz.unwrap_or(d.fs_hz),
        seed: seed.unwrap_or(d.seed),
        turn: turn.unwrap_or(d.turn),
        slow_ldh: slow_ldh.unwrap_or(d.slow_ldh),
        ramp_s: ramp_s.unwrap_or(d.ramp_s),
        trials,
        day_to_day_sd_fraction: ldh_sim::retest::day_to_day_sd_fraction_or_default(
            trials,
            day_to_day_sd_fraction,
        ),
        sensor,
        ..d
    };
    py.detach(move || -> Result<String, LdhError> {
        let rows = ldh_sim::write_cohort(&params, &out, &FormatSpec::default(), &|| {})?;
        Ok(ldh_sim::manifest_csv(&rows))
    })
    .or_raise(py)
}

/// The core defaults of the reading, filtering and simulation functions, by Python name.
pub(crate) fn defaults(py: Python<'_>, d: &Bound<'_, PyDict>) -> PyResult<()> {
    let r = ReadParams::default();
    let read = PyDict::new(py);
    read.set_item("max_gap_s", r.max_gap_s)?;
    read.set_item("gap_policy", value_of(&r.gap_policy).or_raise(py)?.as_str())?;
    read.set_item("min_duration_s", r.min_duration_s)?;
    read.set_item("check_units", r.check_units)?;
    read.set_item("max_file_size_mb", r.max_file_size_mb)?;
    read.set_item("max_samples", r.max_samples)?;
    d.set_item("read_recording", read)?;
    // The size limits of the functions that read recordings from paths (`analyze`).
    let limits = PyDict::new(py);
    limits.set_item("max_file_size_mb", r.max_file_size_mb)?;
    limits.set_item("max_samples", r.max_samples)?;
    d.set_item("read_limits", limits)?;
    let p = PreprocessParams::default();
    let pre = PyDict::new(py);
    pre.set_item("cutoff_hz", p.cutoff_hz)?;
    pre.set_item("filter_order", p.filter_order)?;
    pre.set_item("outlier_sd", p.outlier_sd)?;
    pre.set_item("replace_outliers", p.replace_outliers)?;
    let oc = value_of(&p.outlier_channels).or_raise(py)?;
    pre.set_item("outlier_channels", oc.as_str())?;
    d.set_item("preprocess", pre)?;
    let bf = PyDict::new(py);
    bf.set_item("order", p.filter_order)?;
    d.set_item("butter_filtfilt", bf)?;
    let c = ldh_sim::CohortParams::default();
    let sim = PyDict::new(py);
    sim.set_item("healthy", c.healthy)?;
    sim.set_item("ldh", c.ldh)?;
    sim.set_item("seconds", c.duration_s)?;
    sim.set_item("seed", c.seed)?;
    sim.set_item("rate_hz", c.fs_hz)?;
    sim.set_item("turn", c.turn)?;
    sim.set_item("slow_ldh", c.slow_ldh)?;
    sim.set_item("acc_range_g", c.sensor.acc_range_g)?;
    sim.set_item("ramp_s", c.ramp_s)?;
    sim.set_item("trials", c.trials)?;
    d.set_item("simulate_cohort", sim)?;
    Ok(())
}
