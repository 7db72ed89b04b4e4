//! The scipy.stats look-alikes (core `stats`).

use pyo3::prelude::*;

use ldh_core::LdhError;

use crate::errors::to_py;

/// Register this module's functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(stats_test, m)?)?;
    m.add_function(wrap_pyfunction!(holm, m)?)?;
    Ok(())
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
