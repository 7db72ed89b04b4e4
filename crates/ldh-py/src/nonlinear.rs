//! Lyapunov exponents with nolds' names (`ldh.lyap_r`, `ldh.lyap_e`); `None` takes the core's
//! default, which is nolds 0.6.2's.

use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use ldh_core::nonlinear::{EckmannParams, RosensteinParams};
use ldh_core::LdhError;

use crate::convert::{choice, opt_uint, value_of, vec1};
use crate::errors::OrRaise;

type LyapR<'py> = (
    f64,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    (f64, f64),
);

/// Rosenstein's largest Lyapunov exponent (`nolds.lyap_r`): (exponent, ks, divergence,
/// (slope, intercept)).
#[pyfunction]
#[pyo3(signature = (data, emb_dim=None, lag=None, min_tsep=None, tau=None, min_neighbors=None, trajectory_len=None, fit=None, fit_offset=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn lyap_r<'py>(
    py: Python<'py>,
    data: PyReadonlyArray1<'py, f64>,
    emb_dim: Option<i64>,
    lag: Option<i64>,
    min_tsep: Option<i64>,
    tau: Option<f64>,
    min_neighbors: Option<i64>,
    trajectory_len: Option<i64>,
    fit: Option<String>,
    fit_offset: Option<i64>,
) -> PyResult<LyapR<'py>> {
    let counts = || -> Result<_, LdhError> {
        Ok((
            opt_uint::<usize>("emb_dim", emb_dim)?,
            opt_uint::<usize>("lag", lag)?,
            opt_uint::<usize>("min_tsep", min_tsep)?,
            opt_uint::<usize>("min_neighbors", min_neighbors)?,
            opt_uint::<usize>("trajectory_len", trajectory_len)?,
            opt_uint::<usize>("fit_offset", fit_offset)?,
        ))
    };
    let (emb_dim, lag, min_tsep, min_neighbors, trajectory_len, fit_offset) =
        counts().or_raise(py)?;
    let x = data.as_slice()?.to_vec();
    let r = py
        .detach(move || -> Result<_, LdhError> {
            let d = RosensteinParams::nolds();
            let params = RosensteinParams {
                emb_dim: emb_dim.unwrap_or(d.emb_dim),
                lag: lag.or(d.lag),
                min_tsep: min_tsep.or(d.min_tsep),
                tau: tau.unwrap_or(d.tau),
                min_neighbors: min_neighbors.unwrap_or(d.min_neighbors),
                trajectory_len: trajectory_len.unwrap_or(d.trajectory_len),
                fit: match fit {
                    Some(f) => choice("fit", &f)?,
                    None => d.fit,
                },
                fit_offset: fit_offset.unwrap_or(d.fit_offset),
            };
            let p = params.check()?;
            Ok(ldh_core::nonlinear::lyap_r(&x, &p)?)
        })
        .or_raise(py)?;
    let ks: Vec<f64> = r.ks.iter().map(|&k| k as f64).collect();
    Ok((
        r.exponent,
        vec1(py, ks),
        vec1(py, r.divergence),
        (r.slope, r.intercept),
    ))
}

/// Eckmann's Lyapunov spectrum (`nolds.lyap_e`).
#[pyfunction]
#[pyo3(signature = (data, emb_dim=None, matrix_dim=None, min_nb=None, min_tsep=None, tau=None))]
pub(crate) fn lyap_e<'py>(
    py: Python<'py>,
    data: PyReadonlyArray1<'py, f64>,
    emb_dim: Option<i64>,
    matrix_dim: Option<i64>,
    min_nb: Option<i64>,
    min_tsep: Option<i64>,
    tau: Option<f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let counts = || -> Result<_, LdhError> {
        Ok((
            opt_uint::<usize>("emb_dim", emb_dim)?,
            opt_uint::<usize>("matrix_dim", matrix_dim)?,
            opt_uint::<usize>("min_nb", min_nb)?,
            opt_uint::<usize>("min_tsep", min_tsep)?,
        ))
    };
    let (emb_dim, matrix_dim, min_nb, min_tsep) = counts().or_raise(py)?;
    let x = data.as_slice()?.to_vec();
    let r = py
        .detach(move || -> Result<_, LdhError> {
            let d = EckmannParams::default();
            let params = EckmannParams {
                emb_dim: emb_dim.unwrap_or(d.emb_dim),
                matrix_dim: matrix_dim.unwrap_or(d.matrix_dim),
                min_nb: min_nb.or(d.min_nb),
                min_tsep: min_tsep.unwrap_or(d.min_tsep),
                tau: tau.unwrap_or(d.tau),
            };
            let p = params.check()?;
            Ok(ldh_core::nonlinear::lyap_e(&x, &p)?)
        })
        .or_raise(py)?;
    Ok(vec1(py, r.exponents))
}

/// The core defaults of `lyap_r` and `lyap_e`, by Python name.
pub(crate) fn defaults(py: Python<'_>, d: &Bound<'_, PyDict>) -> PyResult<()> {
    let r = RosensteinParams::nolds();
    let lr = PyDict::new(py);
    lr.set_item("emb_dim", r.emb_dim)?;
    lr.set_item("lag", r.lag)?;
    lr.set_item("min_tsep", r.min_tsep)?;
    lr.set_item("tau", r.tau)?;
    lr.set_item("min_neighbors", r.min_neighbors)?;
    lr.set_item("trajectory_len", r.trajectory_len)?;
    lr.set_item("fit", value_of(&r.fit).or_raise(py)?.as_str())?;
    lr.set_item("fit_offset", r.fit_offset)?;
    d.set_item("lyap_r", lr)?;
    let e = EckmannParams::default();
    let le = PyDict::new(py);
    le.set_item("emb_dim", e.emb_dim)?;
    le.set_item("matrix_dim", e.matrix_dim)?;
    le.set_item("min_nb", e.min_nb)?;
    le.set_item("min_tsep", e.min_tsep)?;
    le.set_item("tau", e.tau)?;
    d.set_item("lyap_e", le)?;
    Ok(())
}
