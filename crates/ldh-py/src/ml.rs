//! Cross-validation, training and prediction on arrays (core `ml`).

use numpy::IntoPyArray;
use pyo3::prelude::*;

use ldh_core::LdhError;

use crate::errors::to_py;

/// Register this module's functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(cross_validate, m)?)?;
    m.add_function(wrap_pyfunction!(train, m)?)?;
    m.add_function(wrap_pyfunction!(predict, m)?)?;
    Ok(())
}

/// The rows of `x` with labels `y` as a core dataset (checks in `Dataset::from_arrays`).
fn ml_dataset(
    x: numpy::PyReadonlyArray2<'_, f64>,
    y: Vec<usize>,
    groups: Option<Vec<String>>,
    task: &str,
    feature_names: Option<Vec<String>>,
) -> Result<ldh_core::ml::Dataset, LdhError> {
    let task: ldh_core::ml::Task = task.parse()?;
    ldh_core::ml::Dataset::from_arrays(x.as_array().to_owned(), y, groups, task, feature_names)
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
