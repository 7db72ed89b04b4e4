//! The analysis (`ldh.analyze`, `ldh.analyze_pair`, `ldh.analyze_recording`): paths or arrays
//! in, the result tables out as columns (numpy arrays), with the GIL released during the work.

use std::path::PathBuf;
use std::time::Instant;

use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use ldh_core::output::{self, Tables};
use ldh_core::pipeline::{self as core, AnalysisParams, SubjectResult};
use ldh_core::timings::{Stage, StageTimings};
use ldh_core::{LdhError, Recording, Setting, Side};

use crate::convert::{columns, from_py, to_py, value_of, vec1, vecs, Opts};
use crate::errors::OrRaise;
use crate::io::{format_of, read_limits};

const EVENT_COLUMNS: [&str; 5] = ["subject_id", "time_s", "side", "event", "order"];

/// The analysis options of every entry point, converted before the GIL is released.
struct Options {
    model: Option<String>,
    detector: Option<String>,
    sensor_height_m: Option<f64>,
    compute_sta: Option<bool>,
    params: Option<serde_json::Value>,
}

impl Options {
    /// The core's parameters: the `params` dict (the Rust names, nesting and defaults, unknown
    /// names refused), then the named options on top, checked once.
    fn params(&self) -> Result<AnalysisParams, LdhError> {
        let base: AnalysisParams = match &self.params {
            None => AnalysisParams::default(),
            Some(v) => serde_json::from_value(v.clone())
                .map_err(|e| LdhError::param("params", "dict", e.to_string()))?,
        };
        base.with_options(
            self.model.as_deref(),
            self.detector.as_deref(),
            self.sensor_height_m,
            self.compute_sta,
        )
    }

    /// The per-side heights (`left_sensor_height_m=`, `right_sensor_height_m=`), checked with
    /// `sensor_height_m=` (a leg's own height may not contradict it).
    fn heights(
        &self,
        left_m: Option<f64>,
        right_m: Option<f64>,
    ) -> Result<core::SensorHeights, LdhError> {
        core::SensorHeights {
            both_m: self.sensor_height_m,
            left_m,
            right_m,
        }
        .check()
    }
}

fn options(
    model: Option<String>,
    detector: Option<String>,
    sensor_height_m: Option<f64>,
    compute_sta: Option<bool>,
    params: Option<&Bound<'_, PyAny>>,
) -> PyResult<Options> {
    Ok(Options {
        model,
        detector,
        sensor_height_m,
        compute_sta,
        params: params.map(from_py).transpose()?,
    })
}

/// `setting=` of the analysis functions: `None` (not said: overground), `"overground"` or
/// `"treadmill"`.
fn setting_of(setting: Option<&str>) -> Result<Option<Setting>, LdhError> {
    setting.map(str::parse).transpose()
}

/// The three result tables as a dict of column dicts, plus the wall-clock time and the wall time
/// per stage summed over the recordings (`write_s`: building the tables).
fn tables<'py>(
    py: Python<'py>,
    results: &[SubjectResult],
    seconds: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let mut spent = StageTimings::default();
    results.iter().for_each(|r| spent.add(&r.timings));
    let t = spent.time(Stage::Write, || Tables::of(results));
    let d = PyDict::new(py);
    d.set_item("strides", columns(py, &t.strides, &output::STRIDE_COLUMNS)?)?;
    d.set_item("recordings", columns(py, &t.recordings, &[])?)?;
    d.set_item("events", columns(py, &t.events, &EVENT_COLUMNS)?)?;
    let timings = PyDict::new(py);
    timings.set_item("total_s", seconds)?;
    timings.set_item("subjects", results.len())?;
    timings.set_item("recordings", spent.recordings)?;
    for stage in Stage::ALL {
        timings.set_item(format!("{}_s", stage.as_str()), spent.get(stage))?;
    }
    d.set_item("timings", timings)?;
    Ok(d)
}

/// Analyse subjects as `ldh analyze` does on `n_jobs` threads (0: one per core; more than the
/// cores are lowered to the cores, and `jobs_warning` in the result says so). A missing input
/// path raises before any work; a bad recording is an error row. `subject_id` and `setting`
/// are `ldh analyze --subject` and `--setting`; `max_file_size_mb` and `max_samples` are
/// `--max-file-size-mb` and `--max-samples` (a recording over a limit is an error row naming it).
#[pyfunction]
#[pyo3(signature = (inputs, model=None, detector=None, format=None, compute_sta=None, sensor_height_m=None, n_jobs=1, params=None, subject_id=None, setting=None, max_file_size_mb=None, max_samples=None, left_sensor_height_m=None, right_sensor_height_m=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn analyze<'py>(
    py: Python<'py>,
    inputs: Vec<PathBuf>,
    model: Option<String>,
    detector: Option<String>,
    format: Option<String>,
    compute_sta: Option<bool>,
    sensor_height_m: Option<f64>,
    n_jobs: i64,
    params: Option<&Bound<'py, PyAny>>,
    subject_id: Option<String>,
    setting: Option<String>,
    max_file_size_mb: Option<f64>,
    max_samples: Option<i64>,
    left_sensor_height_m: Option<f64>,
    right_sensor_height_m: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let n_jobs: usize = crate::convert::uint("n_jobs", n_jobs).or_raise(py)?;
    let max_samples = crate::convert::opt_uint("max_samples", max_samples).or_raise(py)?;
    let o = options(model, detector, sensor_height_m, compute_sta, params)?;
    // `n_jobs=10**6` must not spawn a million threads: bounded by the cores, as `-j` is.
    let (jobs, jobs_warning) = match n_jobs {
        0 => (0, None),
        n => core::bounded_jobs(n),
    };
    let start = Instant::now();
    let results = py
        .detach(move || -> Result<Vec<SubjectResult>, LdhError> {
            let p = o.params()?;
            let heights = o.heights(left_sensor_height_m, right_sensor_height_m)?;
            let f = format_of(format.as_deref())?;
            let read = read_limits(max_file_size_mb, max_samples).check()?;
            let opts = core::InputOptions {
                subject_id,
                setting: setting_of(setting.as_deref())?,
                left_sensor_height_m: heights.left_m,
                right_sensor_height_m: heights.right_m,
            };
            let subjects = core::discover_with(&inputs, &opts)?;
            core::Analysis::new(p.check()?)
                .read(read)
                .format(f)
                .jobs(jobs)
                .many(&subjects)
                .results()
        })
        .or_raise(py)?;
    let d = tables(py, &results, start.elapsed().as_secs_f64())?;
    d.set_item("jobs_warning", jobs_warning)?;
    Ok(d)
}

/// One subject's two legs given as arrays (six channels each, each leg at its own rate: the
/// core warns when they differ by more than 0.5 %); the same tables as `analyze`. `clocks`
/// (`"one"`, `"two"`) is read by the core's [`core::Clocks`]; `None` is the core's default for
/// arrays ([`core::arrays_subject`]).
#[pyfunction]
#[pyo3(signature = (left, right, left_fs_hz, right_fs_hz, subject_id="subject", model=None, detector=None, sensor_height_m=None, compute_sta=None, params=None, setting=None, left_sensor_height_m=None, right_sensor_height_m=None, clocks=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn analyze_pair<'py>(
    py: Python<'py>,
    left: [PyReadonlyArray1<'py, f64>; 6],
    right: [PyReadonlyArray1<'py, f64>; 6],
    left_fs_hz: f64,
    right_fs_hz: f64,
    subject_id: &str,
    model: Option<String>,
    detector: Option<String>,
    sensor_height_m: Option<f64>,
    compute_sta: Option<bool>,
    params: Option<&Bound<'py, PyAny>>,
    setting: Option<String>,
    left_sensor_height_m: Option<f64>,
    right_sensor_height_m: Option<f64>,
    clocks: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let o = options(model, detector, sensor_height_m, compute_sta, params)?;
    let (l, r) = (vecs(&left)?, vecs(&right)?);
    let id = subject_id.to_string();
    let start = Instant::now();
    let result = py
        .detach(move || -> Result<SubjectResult, LdhError> {
            let p = o.params()?;
            let heights = o.heights(left_sensor_height_m, right_sensor_height_m)?;
            let clocks = clocks.as_deref().map(str::parse).transpose()?;
            let subject = core::SubjectInput {
                setting: setting_of(setting.as_deref())?,
                left_sensor_height_m: heights.left_m,
                right_sensor_height_m: heights.right_m,
                ..core::arrays_subject(&id, clocks)
            };
            let leg = |c: [Vec<f64>; 6], fs: f64, side| {
                let [a, b, cc, d, e, f] = c;
                core::leg_from_arrays(fs, [a, b, cc], [d, e, f], side)
            };
            Ok(core::Analysis::new(p.check()?).pair(
                &subject,
                leg(l, left_fs_hz, Side::Left),
                leg(r, right_fs_hz, Side::Right),
            ))
        })
        .or_raise(py)?;
    tables(py, &[result], start.elapsed().as_secs_f64())
}

/// The per-recording pipeline on arrays: alignment, events, strides, parameters, attitude and
/// warnings of one leg. `setting="treadmill"`: no stride is a turn
/// ([`AnalysisParams::for_treadmill`]).
#[pyfunction]
#[pyo3(signature = (acc_g, gyro_dps, fs_hz, side="left", model=None, detector=None, sensor_height_m=None, compute_sta=None, params=None, setting=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn analyze_recording<'py>(
    py: Python<'py>,
    acc_g: [PyReadonlyArray1<'py, f64>; 3],
    gyro_dps: [PyReadonlyArray1<'py, f64>; 3],
    fs_hz: f64,
    side: &str,
    model: Option<String>,
    detector: Option<String>,
    sensor_height_m: Option<f64>,
    compute_sta: Option<bool>,
    params: Option<&Bound<'py, PyAny>>,
    setting: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let o = options(model, detector, sensor_height_m, compute_sta, params)?;
    let (acc, gyro) = (vecs(&acc_g)?, vecs(&gyro_dps)?);
    let side = side.to_string();
    let leg = py
        .detach(move || -> Result<core::LegResult, LdhError> {
            let side: Side = side.parse()?;
            let p = match setting_of(setting.as_deref())? {
                Some(Setting::Treadmill) => o.params()?.for_treadmill(),
                _ => o.params()?,
            };
            let rec = Recording::new(fs_hz, acc, gyro, vec![])?.with_side(side);
            let one_leg = core::Analysis::new(p.check()?).one_leg();
            Ok(one_leg.leg(&rec, side, None)?.leg)
        })
        .or_raise(py)?;
    let d = PyDict::new(py);
    d.set_item(
        "alignment",
        to_py(py, &value_of(&leg.alignment).or_raise(py)?, Opts::default())?,
    )?;
    let ev = value_of(&leg.events).or_raise(py)?;
    let arrays = Opts {
        numeric_arrays: true,
        ..Opts::default()
    };
    d.set_item("events", to_py(py, &ev, arrays)?)?;
    d.set_item("strides", columns(py, &leg.strides, &[])?)?;
    let nan = Opts {
        null_as_nan: true,
        ..Opts::default()
    };
    let params = value_of(&leg.parameters).or_raise(py)?;
    d.set_item("parameters", to_py(py, &params, nan)?)?;
    d.set_item("outliers_replaced", leg.outliers_replaced)?;
    d.set_item(
        "warnings",
        to_py(py, &value_of(&leg.warnings).or_raise(py)?, Opts::default())?,
    )?;
    let att = leg.attitude.expect("Analysis::leg keeps the attitude");
    let a = PyDict::new(py);
    a.set_item("pitch_deg", vec1(py, att.pitch_deg))?;
    a.set_item("roll_deg", vec1(py, att.roll_deg))?;
    a.set_item("yaw_deg", vec1(py, att.yaw_deg))?;
    d.set_item("attitude", a)?;
    Ok(d)
}

/// The core defaults of the analysis (the `params` dict in full, and the named options).
pub(crate) fn defaults(py: Python<'_>, d: &Bound<'_, PyDict>) -> PyResult<()> {
    let p = AnalysisParams::default();
    let v = value_of(&p).or_raise(py)?;
    d.set_item("analysis_params", to_py(py, &v, Opts::default())?)?;
    let named = PyDict::new(py);
    named.set_item("model", value_of(&p.attitude.model).or_raise(py)?.as_str())?;
    named.set_item(
        "detector",
        value_of(&p.events.detector).or_raise(py)?.as_str(),
    )?;
    // None: not given (the core assumes 0.10 m and checks the stride length's dependence on
    // it, docs/quality.md `sensor_height_unknown`).
    named.set_item("sensor_height_m", p.strides.sensor_height_m)?;
    named.set_item("compute_sta", p.compute_sta)?;
    d.set_item("analyze", named)?;
    Ok(())
}
