//! Cross-validation, training and prediction on arrays (`ldh.cross_validate`, `ldh.train`,
//! `ldh.predict`).

use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2};
use pyo3::prelude::*;

use ldh_core::ml::{Classifier, CvParams, Dataset, ModelFile};
use ldh_core::LdhError;

use crate::convert::{choice, opt_uint, to_py, uints, value_of, Opts};
use crate::errors::OrRaise;

/// Repeated k-fold cross-validation of one classifier; the report as a dict.
#[pyfunction]
#[pyo3(signature = (x, y, groups=None, classifier="rf", task="three-class", k=None, repeats=None, seed=None, kind=None, folds=None, top_k=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn cross_validate<'py>(
    py: Python<'py>,
    x: PyReadonlyArray2<'py, f64>,
    y: Vec<i64>,
    groups: Option<Vec<String>>,
    classifier: &str,
    task: &str,
    k: Option<i64>,
    repeats: Option<i64>,
    seed: Option<i64>,
    kind: Option<String>,
    folds: Option<Vec<Vec<i64>>>,
    top_k: Option<i64>,
) -> PyResult<Bound<'py, PyAny>> {
    let counts = || -> Result<_, LdhError> {
        Ok((
            uints::<usize>("y", y)?,
            opt_uint::<usize>("k", k)?,
            opt_uint::<usize>("repeats", repeats)?,
            opt_uint::<u64>("seed", seed)?,
            folds
                .map(|f| f.into_iter().map(|v| uints::<usize>("folds", v)).collect())
                .transpose()?,
            opt_uint::<usize>("top_k", top_k)?,
        ))
    };
    let (y, k, repeats, seed, folds, top_k): (Vec<usize>, _, _, _, Option<Vec<Vec<usize>>>, _) =
        counts().or_raise(py)?;
    let x = x.as_array().to_owned();
    let (clf, task) = (classifier.to_string(), task.to_string());
    let report = py
        .detach(move || -> Result<_, LdhError> {
            let ds = Dataset::from_arrays(x, y, groups, task.parse()?, None)?;
            let d = CvParams::default();
            let p = CvParams {
                k: k.unwrap_or(d.k),
                repeats: repeats.unwrap_or(d.repeats),
                seed: seed.unwrap_or(d.seed),
                kind: match kind {
                    Some(s) => choice("kind", &s)?,
                    None => d.kind,
                },
                top_k: top_k.or(d.top_k),
                ..d
            };
            let c = Classifier::from_name(&clf, p.seed)?;
            let r = match folds {
                Some(f) => ldh_core::ml::cross_validate_with_folds(&ds, &c, &p, &f)?,
                None => ldh_core::ml::cross_validate(&ds, &c, &p)?,
            };
            value_of(&r)
        })
        .or_raise(py)?;
    to_py(py, &report, Opts::default())
}

/// Train a classifier on all rows; the model file (the JSON that `ldh predict` reads).
#[pyfunction]
#[pyo3(signature = (x, y, feature_names, classifier="rf", task="three-class", seed=None, attitude_model="fusion"))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn train(
    py: Python<'_>,
    x: PyReadonlyArray2<'_, f64>,
    y: Vec<i64>,
    feature_names: Vec<String>,
    classifier: &str,
    task: &str,
    seed: Option<i64>,
    attitude_model: &str,
) -> PyResult<String> {
    let y: Vec<usize> = uints("y", y).or_raise(py)?;
    let seed: Option<u64> = opt_uint("seed", seed).or_raise(py)?;
    let x = x.as_array().to_owned();
    let (clf, task, am) = (
        classifier.to_string(),
        task.to_string(),
        attitude_model.to_string(),
    );
    py.detach(move || -> Result<String, LdhError> {
        let ds = Dataset::from_arrays(x, y, None, task.parse()?, Some(feature_names))?;
        let c = Classifier::from_name(&clf, seed.unwrap_or(CvParams::default().seed))?;
        let m = ModelFile::train(&ds, &c, &am)?;
        m.to_json()
    })
    .or_raise(py)
}

type Predicted<'py> = (Vec<usize>, Option<Bound<'py, PyArray2<f64>>>);

/// Predict with a model file's text, or with the file at `model_path` (read as `ldh predict`
/// reads it, named in every error): (labels, probabilities or None).
#[pyfunction]
#[pyo3(signature = (model_json, x, feature_names=None, model_path=None))]
pub(crate) fn predict<'py>(
    py: Python<'py>,
    model_json: &str,
    x: PyReadonlyArray2<'py, f64>,
    feature_names: Option<Vec<String>>,
    model_path: Option<std::path::PathBuf>,
) -> PyResult<Predicted<'py>> {
    let x = x.as_array().to_owned();
    let text = model_json.to_string();
    let (labels, proba) = py
        .detach(move || -> Result<_, LdhError> {
            let m = match model_path {
                Some(p) => ldh_core::ml::read_model(&p)?,
                None => ModelFile::from_json(&text, "<model>")?,
            };
            if let Some(names) = feature_names {
                m.check_features(&names)?;
            }
            m.predict(&x)
        })
        .or_raise(py)?;
    Ok((labels, proba.map(|p| p.into_pyarray(py))))
}
