//! Python bindings of ldh-core: the native module `ldh._ldh`.
//!
//! Conversion only: numpy arrays in and out, errors mapped onto the `ldh` exception classes
//! (defined in `python/ldh/_errors.py`, subclasses of `ValueError`, `FileNotFoundError` and
//! `OSError`), and the GIL released (`py.detach`) around every computation. No algorithm code.

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use ldh_core::io::{read_recording, FormatSpec, GapPolicy, ReadParams};
use ldh_core::preprocess::{preprocess as core_preprocess, PreprocessParams};
use ldh_core::{ErrorKind, LdhError, Recording};

/// Map a core error onto the `ldh` exception family.
fn to_py(py: Python<'_>, e: LdhError) -> PyErr {
    let class = match e.kind() {
        ErrorKind::NotFound => "LdhFileNotFoundError",
        ErrorKind::Io => "LdhOSError",
        ErrorKind::Param => "LdhParamError",
        ErrorKind::Data => "LdhDataError",
    };
    let msg = e.to_string();
    match py.import("ldh._errors").and_then(|m| m.getattr(class)) {
        Ok(cls) => match cls.call1((msg.clone(),)) {
            Ok(inst) => PyErr::from_value(inst),
            Err(err) => err,
        },
        Err(_) => PyValueError::new_err(msg),
    }
}

fn vec1<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    v.into_pyarray(py)
}

/// Put the six channels into a dict as `acc_x_g` … `gyro_z_dps` numpy arrays.
fn put_channels(
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
fn vecs<const N: usize>(a: &[PyReadonlyArray1<'_, f64>; N]) -> PyResult<[Vec<f64>; N]> {
    let v: Vec<Vec<f64>> = a
        .iter()
        .map(|c| c.as_slice().map(|s| s.to_vec()))
        .collect::<Result<_, _>>()?;
    Ok(v.try_into().expect("N channels in, N out"))
}

/// The result tables of `ldh analyze` as one JSON object for the Python layer.
fn tables_json(results: &[ldh_core::pipeline::SubjectResult]) -> Result<String, LdhError> {
    serde_json::to_string(&ldh_core::output::Tables::of(results))
        .map_err(|e| LdhError::signal("json", e.to_string()))
}

fn recording_dict<'py>(py: Python<'py>, rec: Recording) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("fs_hz", rec.fs_hz)?;
    d.set_item("t0_s", rec.t0_s)?;
    d.set_item("time_s", vec1(py, rec.times_s()))?;
    put_channels(&d, rec.acc_g, rec.gyro_dps)?;
    d.set_item("saturated", rec.saturated.into_pyarray(py))?;
    Ok(d)
}

fn format_of(format: Option<&str>) -> Result<Option<FormatSpec>, LdhError> {
    format.map(FormatSpec::resolve).transpose()
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

/// Simulate a cohort into a folder (as `ldh simulate`); returns the manifest CSV text.
#[pyfunction]
#[pyo3(signature = (out, healthy=2, ldh=2, seconds=25.0, seed=1, rate_hz=100.0, turn=true))]
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
        params.validate()?;
        let fmt = FormatSpec::default();
        let mut rows = Vec::new();
        for i in 0..params.len() {
            let s = params.simulate(i)?;
            s.write(&out.join(&s.params.subject_id), &fmt)?;
            rows.push(ldh_core::simulate::ManifestRow::of(&s));
        }
        let text = ldh_core::simulate::manifest_csv(&rows);
        ldh_core::io::write_atomic(out.join("manifest.csv"), text.as_bytes())?;
        Ok(text)
    })
    .map_err(|e| to_py(py, e))
}

/// Rosenstein's largest Lyapunov exponent with nolds' parameters (`nolds.lyap_r`, fit="poly").
/// Returns (exponent, ks, divergence, [slope, intercept]).
#[pyfunction]
#[pyo3(signature = (data, emb_dim=10, lag=None, min_tsep=None, tau=1.0, min_neighbors=20, trajectory_len=20, fit="poly", fit_offset=0))]
#[allow(clippy::too_many_arguments)]
fn lyap_r<'py>(
    py: Python<'py>,
    data: PyReadonlyArray1<'py, f64>,
    emb_dim: usize,
    lag: Option<usize>,
    min_tsep: Option<usize>,
    tau: f64,
    min_neighbors: usize,
    trajectory_len: usize,
    fit: &str,
    fit_offset: usize,
) -> PyResult<(
    f64,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    (f64, f64),
)> {
    use ldh_core::nonlinear::{Fit, RosensteinParams};
    if fit != "poly" {
        return Err(to_py(
            py,
            LdhError::param(
                "fit",
                fit,
                "only 'poly' is supported (nolds' RANSAC fit is random)",
            ),
        ));
    }
    let x = data.as_slice()?.to_vec();
    let params = RosensteinParams {
        emb_dim,
        lag,
        min_tsep,
        tau,
        min_neighbors,
        trajectory_len,
        fit: Fit::Poly,
        fit_offset,
    };
    let r = py
        .detach(move || -> Result<_, LdhError> {
            let p = params.check()?;
            Ok(ldh_core::nonlinear::lyap_r(&x, &p)?)
        })
        .map_err(|e| to_py(py, e))?;
    let ks: Vec<f64> = r.ks.iter().map(|&k| k as f64).collect();
    Ok((
        r.exponent,
        vec1(py, ks),
        vec1(py, r.divergence),
        (r.slope, r.intercept),
    ))
}

/// Eckmann's Lyapunov spectrum with nolds' parameters (`nolds.lyap_e`).
#[pyfunction]
#[pyo3(signature = (data, emb_dim=10, matrix_dim=4, min_nb=None, min_tsep=0, tau=1.0))]
fn lyap_e<'py>(
    py: Python<'py>,
    data: PyReadonlyArray1<'py, f64>,
    emb_dim: usize,
    matrix_dim: usize,
    min_nb: Option<usize>,
    min_tsep: usize,
    tau: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    use ldh_core::nonlinear::EckmannParams;
    let x = data.as_slice()?.to_vec();
    let params = EckmannParams {
        emb_dim,
        matrix_dim,
        min_nb,
        min_tsep,
        tau,
    };
    let r = py
        .detach(move || -> Result<_, LdhError> {
            let p = params.check()?;
            Ok(ldh_core::nonlinear::lyap_e(&x, &p)?)
        })
        .map_err(|e| to_py(py, e))?;
    Ok(vec1(py, r.exponents))
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
    use ldh_core::pipeline::{analyze_subject, discover_with, InputOptions};
    use rayon::prelude::*;
    let (model, detector, fmt) = (model, detector, format.map(String::from));
    let out = py
        .detach(move || -> Result<String, LdhError> {
            let p = base_params(params_json.as_deref())?.with_options(
                model.as_deref(),
                detector.as_deref(),
                sensor_height_m,
                compute_sta,
            )?;
            let f = format_of(fmt.as_deref())?;
            let read = ReadParams::default().check()?;
            let opts = InputOptions {
                subject_id,
                setting: setting.as_deref().map(str::parse).transpose()?,
            };
            let subjects = discover_with(&inputs, &opts)?;
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n_jobs)
                .build()
                .map_err(|e| LdhError::param("n_jobs", n_jobs, e.to_string()))?;
            let results: Vec<_> = pool.install(|| {
                subjects
                    .par_iter()
                    .map(|s| analyze_subject(s, &p, f.as_ref(), &read))
                    .collect()
            });
            tables_json(&results)
        })
        .map_err(|e| to_py(py, e))?;
    Ok(out)
}

/// The scipy.stats-compatible tests: `name` is the scipy function, `samples` the sample
/// arrays, `alternative` scipy's spelling, `equal_var` for ttest_ind. Returns (statistic, p).
#[pyfunction]
#[pyo3(signature = (name, samples, alternative="two-sided", equal_var=true))]
fn stats_test(
    py: Python<'_>,
    name: &str,
    samples: Vec<Vec<f64>>,
    alternative: &str,
    equal_var: bool,
) -> PyResult<(f64, f64)> {
    use ldh_core::stats;
    let (name, alt) = (name.to_string(), alternative.to_string());
    py.detach(move || -> Result<(f64, f64), LdhError> {
        let alt: stats::Alternative = alt.parse()?;
        let two = |n: usize| -> Result<(), LdhError> {
            if samples.len() == n {
                Ok(())
            } else {
                Err(LdhError::param(
                    "samples",
                    samples.len(),
                    format!("{name} takes {n} sample(s)"),
                ))
            }
        };
        Ok(match name.as_str() {
            "shapiro" => {
                two(1)?;
                let r = stats::shapiro(&samples[0])?;
                (r.statistic, r.pvalue)
            }
            "mannwhitneyu" => {
                two(2)?;
                let r = stats::mannwhitneyu(&samples[0], &samples[1], alt)?;
                (r.statistic, r.pvalue)
            }
            "ttest_ind" => {
                two(2)?;
                let r = stats::ttest_ind(&samples[0], &samples[1], equal_var, alt)?;
                (r.statistic, r.pvalue)
            }
            "ttest_rel" => {
                two(2)?;
                let r = stats::ttest_rel(&samples[0], &samples[1], alt)?;
                (r.statistic, r.pvalue)
            }
            "wilcoxon" => {
                let r = match samples.len() {
                    1 => stats::wilcoxon(&samples[0], alt)?,
                    _ => {
                        two(2)?;
                        stats::wilcoxon_paired(&samples[0], &samples[1], alt)?
                    }
                };
                (r.statistic, r.pvalue)
            }
            "f_oneway" | "kruskal" => {
                let g: Vec<&[f64]> = samples.iter().map(|v| v.as_slice()).collect();
                if name == "f_oneway" {
                    let r = stats::f_oneway(&g)?;
                    (r.statistic, r.pvalue)
                } else {
                    let r = stats::kruskal(&g)?;
                    (r.statistic, r.pvalue)
                }
            }
            "pearsonr" => {
                two(2)?;
                let r = stats::pearsonr(&samples[0], &samples[1], alt)?;
                (r.statistic, r.pvalue)
            }
            other => return Err(LdhError::param("test", other, "unknown test")),
        })
    })
    .map_err(|e| to_py(py, e))
}

/// Holm-adjusted p-values.
#[pyfunction]
fn holm(py: Python<'_>, pvalues: Vec<f64>) -> PyResult<Vec<f64>> {
    ldh_core::stats::holm(&pvalues).map_err(|e| to_py(py, e.into()))
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
) -> PyResult<(
    String,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
)> {
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
    let (l, r): ([Vec<f64>; 6], [Vec<f64>; 6]) = (vecs(&left)?, vecs(&right)?);
    let (id, model, detector) = (subject_id.to_string(), model, detector);
    py.detach(move || -> Result<String, LdhError> {
        use ldh_core::pipeline::{analyze_pair as core_pair, SubjectInput};
        let p = base_params(params_json.as_deref())?.with_options(
            model.as_deref(),
            detector.as_deref(),
            sensor_height_m,
            compute_sta,
        )?;
        let load = |c: [Vec<f64>; 6], side: ldh_core::Side| -> ldh_core::pipeline::LoadedLeg {
            let [a, b, cc, d, e, f] = c;
            let rec = Recording::new(fs_hz, [a, b, cc], [d, e, f], vec![])
                .map_err(|e| format!("{side}: {e}"))?;
            let report = ldh_core::pipeline::memory_report(&rec);
            Ok((rec, report, format!("<{side} arrays>")))
        };
        let input = SubjectInput {
            subject_id: id,
            ..SubjectInput::default()
        };
        let res = vec![core_pair(
            &input,
            load(l, ldh_core::Side::Left),
            load(r, ldh_core::Side::Right),
            &p,
        )];
        tables_json(&res)
    })
    .map_err(|e| to_py(py, e))
}

/// Analysis parameters from an optional JSON object (the Python `params` dict: the same names,
/// nesting and defaults as the Rust `AnalysisParams`, unknown names refused).
fn base_params(params_json: Option<&str>) -> Result<ldh_core::pipeline::AnalysisParams, LdhError> {
    match params_json {
        None => Ok(ldh_core::pipeline::AnalysisParams::default()),
        Some(j) => {
            serde_json::from_str(j).map_err(|e| LdhError::param("params", "dict", e.to_string()))
        }
    }
}

fn ml_dataset(
    x: numpy::PyReadonlyArray2<'_, f64>,
    y: Vec<usize>,
    groups: Option<Vec<String>>,
    task: &str,
    feature_names: Option<Vec<String>>,
) -> Result<ldh_core::ml::Dataset, LdhError> {
    let task: ldh_core::ml::Task = task.parse()?;
    let x = x.as_array().to_owned();
    if x.nrows() != y.len() {
        return Err(LdhError::param(
            "y",
            y.len(),
            format!("X has {} rows", x.nrows()),
        ));
    }
    let n = y.len();
    let groups = groups.unwrap_or_else(|| (0..n).map(|i| format!("row{i}")).collect());
    if groups.len() != n {
        return Err(LdhError::param(
            "groups",
            groups.len(),
            format!("X has {n} rows"),
        ));
    }
    let names = feature_names.unwrap_or_else(|| (0..x.ncols()).map(|j| format!("x{j}")).collect());
    if names.len() != x.ncols() {
        return Err(LdhError::param(
            "feature_names",
            names.len(),
            format!("X has {} columns", x.ncols()),
        ));
    }
    let ds = ldh_core::ml::Dataset {
        task,
        feature_names: names,
        class_names: task.class_names(),
        x,
        y,
        row_ids: groups
            .iter()
            .enumerate()
            .map(|(i, g)| format!("{g}#{i}"))
            .collect(),
        groups,
        dropped: vec![],
    };
    ds.validate()?;
    Ok(ds)
}

/// Repeated k-fold cross-validation of one classifier on arrays; returns the report as JSON.
#[pyfunction]
#[pyo3(signature = (x, y, groups=None, classifier="rf", task="three-class", k=10, repeats=10, seed=1, kind="grouped", folds=None, top_k=None))]
#[allow(clippy::too_many_arguments)]
fn cross_validate(
    py: Python<'_>,
    x: numpy::PyReadonlyArray2<'_, f64>,
    y: Vec<usize>,
    groups: Option<Vec<String>>,
    classifier: &str,
    task: &str,
    k: usize,
    repeats: usize,
    seed: u64,
    kind: &str,
    folds: Option<Vec<Vec<usize>>>,
    top_k: Option<usize>,
) -> PyResult<String> {
    use ldh_core::ml::{CvKind, CvParams};
    let ds = ml_dataset(x, y, groups, task, None).map_err(|e| to_py(py, e))?;
    let (clf, kind) = (classifier.to_string(), kind.to_string());
    py.detach(move || -> Result<String, LdhError> {
        let kind = match kind.as_str() {
            "grouped" => CvKind::Grouped,
            "stratified" => CvKind::Stratified,
            o => {
                return Err(LdhError::param(
                    "kind",
                    o,
                    "expected 'grouped' or 'stratified'",
                ))
            }
        };
        let c = ldh_core::ml::Classifier::from_name(&clf, seed)?;
        let p = CvParams {
            k,
            repeats,
            seed,
            kind,
            top_k,
            permutation_importance: true,
        };
        let r = match folds {
            Some(f) => ldh_core::ml::cross_validate_with_folds(&ds, &c, &p, &f)?,
            None => ldh_core::ml::cross_validate(&ds, &c, &p)?,
        };
        serde_json::to_string(&r).map_err(|e| LdhError::signal("json", e.to_string()))
    })
    .map_err(|e| to_py(py, e))
}

/// Train a classifier on all rows; returns the model file (JSON) that `ldh predict` reads.
#[pyfunction]
#[pyo3(signature = (x, y, feature_names, classifier="rf", task="three-class", seed=1, attitude_model="fusion"))]
#[allow(clippy::too_many_arguments)]
fn train(
    py: Python<'_>,
    x: numpy::PyReadonlyArray2<'_, f64>,
    y: Vec<usize>,
    feature_names: Vec<String>,
    classifier: &str,
    task: &str,
    seed: u64,
    attitude_model: &str,
) -> PyResult<String> {
    let ds = ml_dataset(x, y, None, task, Some(feature_names)).map_err(|e| to_py(py, e))?;
    let (clf, am) = (classifier.to_string(), attitude_model.to_string());
    py.detach(move || -> Result<String, LdhError> {
        let c = ldh_core::ml::Classifier::from_name(&clf, seed)?;
        let m = ldh_core::ml::ModelFile::train(&ds, &c, &am)?;
        m.to_json()
    })
    .map_err(|e| to_py(py, e))
}

/// Predict with a model file's JSON: (labels, probabilities or None).
#[pyfunction]
#[pyo3(signature = (model_json, x, feature_names=None))]
#[allow(clippy::type_complexity)]
fn predict<'py>(
    py: Python<'py>,
    model_json: &str,
    x: numpy::PyReadonlyArray2<'py, f64>,
    feature_names: Option<Vec<String>>,
) -> PyResult<(Vec<usize>, Option<Bound<'py, numpy::PyArray2<f64>>>)> {
    let x = x.as_array().to_owned();
    let text = model_json.to_string();
    let (labels, proba) = py
        .detach(move || -> Result<_, LdhError> {
            let m = ldh_core::ml::ModelFile::from_json(&text, "<model>")?;
            if let Some(names) = feature_names {
                m.check_features(&names)?;
            }
            m.predict(&x)
        })
        .map_err(|e| to_py(py, e))?;
    Ok((labels, proba.map(|p| p.into_pyarray(py))))
}

#[pymodule]
fn _ldh(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(read_recording_py, m)?)?;
    m.add_function(wrap_pyfunction!(butter_filtfilt, m)?)?;
    m.add_function(wrap_pyfunction!(preprocess, m)?)?;
    m.add_function(wrap_pyfunction!(write_demo, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_cohort, m)?)?;
    m.add_function(wrap_pyfunction!(lyap_r, m)?)?;
    m.add_function(wrap_pyfunction!(lyap_e, m)?)?;
    m.add_function(wrap_pyfunction!(analyze, m)?)?;
    m.add_function(wrap_pyfunction!(stats_test, m)?)?;
    m.add_function(wrap_pyfunction!(holm, m)?)?;
    m.add_function(wrap_pyfunction!(analyze_recording, m)?)?;
    m.add_function(wrap_pyfunction!(cross_validate, m)?)?;
    m.add_function(wrap_pyfunction!(analyze_pair, m)?)?;
    m.add_function(wrap_pyfunction!(train, m)?)?;
    m.add_function(wrap_pyfunction!(predict, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
