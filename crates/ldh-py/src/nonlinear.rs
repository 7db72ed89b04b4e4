//! The nolds look-alikes: Rosenstein's and Eckmann's Lyapunov exponents (core `nonlinear`).

use numpy::PyReadonlyArray1;
use pyo3::prelude::*;

use ldh_core::LdhError;

use crate::convert::{vec1, Array1};
use crate::errors::to_py;

/// Register this module's functions.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(lyap_r, m)?)?;
    m.add_function(wrap_pyfunction!(lyap_e, m)?)?;
    Ok(())
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
) -> PyResult<(f64, Array1<'py>, Array1<'py>, (f64, f64))> {
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
) -> PyResult<Array1<'py>> {
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
