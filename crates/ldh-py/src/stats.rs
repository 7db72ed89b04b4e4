//! The scipy.stats look-alikes: each function returns the core result's fields as a dict
//! (`statistic`, `pvalue`, and `df`, `method`… where the core has them); the Python layer
//! builds scipy-shaped result objects from them.

use pyo3::prelude::*;
use serde::Serialize;

use ldh_core::stats::{self, Alternative, NanOutcome, NanPolicy};
use ldh_core::LdhError;

use crate::convert::{from_py, to_py, value_of, Opts};
use crate::errors::OrRaise;

fn alt(a: Option<&str>) -> Result<Alternative, LdhError> {
    Ok(a.map(str::parse).transpose()?.unwrap_or_default())
}

/// Apply `nan_policy` (scipy's spelling; default `"propagate"`) to `samples` and run `f` on what
/// is left, without the GIL; the result's fields as a dict, or `{"statistic": nan, "pvalue":
/// nan}` when a NaN propagates.
fn run<'py, R: Serialize + Send>(
    py: Python<'py>,
    test: &'static str,
    samples: Vec<Vec<f64>>,
    paired: bool,
    nan_policy: Option<String>,
    f: impl FnOnce(Vec<Vec<f64>>) -> Result<R, LdhError> + Send,
) -> PyResult<Bound<'py, PyAny>> {
    let r = py
        .detach(move || -> Result<Option<serde_json::Value>, LdhError> {
            let policy: NanPolicy = match nan_policy {
                Some(p) => p.parse()?,
                None => NanPolicy::default(),
            };
            match stats::apply_nan_policy(test, samples, paired, policy)? {
                NanOutcome::Propagate => Ok(None),
                NanOutcome::Run(s) => Ok(Some(value_of(&f(s)?)?)),
            }
        })
        .or_raise(py)?;
    let v = r.unwrap_or_else(|| serde_json::json!({"statistic": null, "pvalue": null}));
    let nan = Opts {
        null_as_nan: true,
        ..Opts::default()
    };
    to_py(py, &v, nan)
}

/// The first two samples (the caller passed exactly two).
fn two(s: Vec<Vec<f64>>) -> (Vec<f64>, Vec<f64>) {
    let mut it = s.into_iter();
    (it.next().unwrap_or_default(), it.next().unwrap_or_default())
}

/// `scipy.stats.shapiro`.
#[pyfunction]
#[pyo3(signature = (x, nan_policy=None))]
pub(crate) fn shapiro(
    py: Python<'_>,
    x: Vec<f64>,
    nan_policy: Option<String>,
) -> PyResult<Bound<'_, PyAny>> {
    run(py, "shapiro", vec![x], false, nan_policy, |s| {
        Ok(stats::shapiro(&s[0])?)
    })
}

/// `scipy.stats.mannwhitneyu` (statistic: U of `x`).
#[pyfunction]
#[pyo3(signature = (x, y, alternative=None, nan_policy=None))]
pub(crate) fn mannwhitneyu(
    py: Python<'_>,
    x: Vec<f64>,
    y: Vec<f64>,
    alternative: Option<String>,
    nan_policy: Option<String>,
) -> PyResult<Bound<'_, PyAny>> {
    run(py, "mannwhitneyu", vec![x, y], false, nan_policy, |s| {
        let (x, y) = two(s);
        Ok(stats::mannwhitneyu(&x, &y, alt(alternative.as_deref())?)?)
    })
}

/// `scipy.stats.ttest_ind` (Student, or Welch with `equal_var=False`).
#[pyfunction]
#[pyo3(signature = (a, b, equal_var=None, alternative=None, nan_policy=None))]
pub(crate) fn ttest_ind(
    py: Python<'_>,
    a: Vec<f64>,
    b: Vec<f64>,
    equal_var: Option<bool>,
    alternative: Option<String>,
    nan_policy: Option<String>,
) -> PyResult<Bound<'_, PyAny>> {
    run(py, "ttest_ind", vec![a, b], false, nan_policy, |s| {
        let (a, b) = two(s);
        let alt = alt(alternative.as_deref())?;
        Ok(stats::ttest_ind(&a, &b, equal_var.unwrap_or(true), alt)?)
    })
}

/// `scipy.stats.ttest_rel`.
#[pyfunction]
#[pyo3(signature = (a, b, alternative=None, nan_policy=None))]
pub(crate) fn ttest_rel(
    py: Python<'_>,
    a: Vec<f64>,
    b: Vec<f64>,
    alternative: Option<String>,
    nan_policy: Option<String>,
) -> PyResult<Bound<'_, PyAny>> {
    run(py, "ttest_rel", vec![a, b], true, nan_policy, |s| {
        let (a, b) = two(s);
        Ok(stats::ttest_rel(&a, &b, alt(alternative.as_deref())?)?)
    })
}

/// `scipy.stats.ttest_1samp`.
#[pyfunction]
#[pyo3(signature = (a, popmean, alternative=None, nan_policy=None))]
pub(crate) fn ttest_1samp(
    py: Python<'_>,
    a: Vec<f64>,
    popmean: f64,
    alternative: Option<String>,
    nan_policy: Option<String>,
) -> PyResult<Bound<'_, PyAny>> {
    run(py, "ttest_1samp", vec![a], false, nan_policy, |s| {
        let alt = alt(alternative.as_deref())?;
        Ok(stats::ttest_1samp(&s[0], popmean, alt)?)
    })
}

/// `scipy.stats.wilcoxon` of `x` (the differences) or of `x − y`.
#[pyfunction]
#[pyo3(signature = (x, y=None, alternative=None, nan_policy=None))]
pub(crate) fn wilcoxon(
    py: Python<'_>,
    x: Vec<f64>,
    y: Option<Vec<f64>>,
    alternative: Option<String>,
    nan_policy: Option<String>,
) -> PyResult<Bound<'_, PyAny>> {
    let paired = y.is_some();
    let samples = match y {
        None => vec![x],
        Some(y) => vec![x, y],
    };
    run(py, "wilcoxon", samples, paired, nan_policy, move |s| {
        let alt = alt(alternative.as_deref())?;
        Ok(if paired {
            let (x, y) = two(s);
            stats::wilcoxon_paired(&x, &y, alt)?
        } else {
            stats::wilcoxon(&s[0], alt)?
        })
    })
}

/// `scipy.stats.f_oneway`.
#[pyfunction]
#[pyo3(signature = (samples, nan_policy=None))]
pub(crate) fn f_oneway(
    py: Python<'_>,
    samples: Vec<Vec<f64>>,
    nan_policy: Option<String>,
) -> PyResult<Bound<'_, PyAny>> {
    run(py, "f_oneway", samples, false, nan_policy, |s| {
        let g: Vec<&[f64]> = s.iter().map(Vec::as_slice).collect();
        Ok(stats::f_oneway(&g)?)
    })
}

/// `scipy.stats.kruskal`.
#[pyfunction]
#[pyo3(signature = (samples, nan_policy=None))]
pub(crate) fn kruskal(
    py: Python<'_>,
    samples: Vec<Vec<f64>>,
    nan_policy: Option<String>,
) -> PyResult<Bound<'_, PyAny>> {
    run(py, "kruskal", samples, false, nan_policy, |s| {
        let g: Vec<&[f64]> = s.iter().map(Vec::as_slice).collect();
        Ok(stats::kruskal(&g)?)
    })
}

/// `scipy.stats.pearsonr`.
#[pyfunction]
#[pyo3(signature = (x, y, alternative=None))]
pub(crate) fn pearsonr(
    py: Python<'_>,
    x: Vec<f64>,
    y: Vec<f64>,
    alternative: Option<String>,
) -> PyResult<Bound<'_, PyAny>> {
    run(py, "pearsonr", vec![x, y], true, None, |s| {
        let (x, y) = two(s);
        Ok(stats::pearsonr(&x, &y, alt(alternative.as_deref())?)?)
    })
}

/// The confidence interval of a t-test or a Pearson result (`kind`: `"ttest"` or
/// `"pearsonr"`; `fields`: the dict the test returned) at `confidence_level`, as scipy's
/// `result.confidence_interval(confidence_level)`; (low, high).
#[pyfunction]
pub(crate) fn confidence_interval(
    py: Python<'_>,
    kind: &str,
    fields: &Bound<'_, PyAny>,
    confidence_level: f64,
) -> PyResult<(f64, f64)> {
    let v = from_py(fields)?;
    let kind = kind.to_string();
    py.detach(move || -> Result<(f64, f64), LdhError> {
        let bad = |e: serde_json::Error| LdhError::param("result", "dict", e.to_string());
        match kind.as_str() {
            "ttest" => {
                let r: stats::TTestResult = serde_json::from_value(v).map_err(bad)?;
                Ok(r.confidence_interval(confidence_level)?)
            }
            "pearsonr" => {
                let r: stats::PearsonRResult = serde_json::from_value(v).map_err(bad)?;
                Ok(r.confidence_interval(confidence_level)?)
            }
            other => Err(LdhError::param(
                "kind",
                other,
                "expected 'ttest' or 'pearsonr'",
            )),
        }
    })
    .or_raise(py)
}

/// Holm-adjusted p-values.
#[pyfunction]
pub(crate) fn holm(py: Python<'_>, pvalues: Vec<f64>) -> PyResult<Vec<f64>> {
    stats::holm(&pvalues).or_raise(py)
}
