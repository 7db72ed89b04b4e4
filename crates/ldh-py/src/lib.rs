#![doc = include_str!("../README.md")]
//!
//! ## Layout
//!
//! Python bindings of ldh-core: the native module `ldh._ldh`, laid out like tokenizers'
//! `bindings/python` — one file per area of the core:
//!
//! * [`io`]: reading recordings, filters, demo and simulator;
//! * [`pipeline`]: the analysis of paths or arrays;
//! * [`stats`]: the scipy.stats look-alikes;
//! * [`nonlinear`]: the nolds look-alikes (Lyapunov exponents);
//! * [`ml`]: cross-validation, training, prediction;
//! * [`monitor`]: `ldh.monitor`, days of free-living recordings;
//! * [`agreement`]: `ldh.agree`, an analysis against a laboratory's reference files, and
//!   `ldh.reliability`, the test–retest table of repeated trials;
//! * [`errors`]: core errors as the `ldh` exception family; [`convert`]: values in and out.
//!
//! Conversion only: numpy arrays and typed records in and out (never JSON text for results),
//! the GIL released (`py.detach`) around every computation, and every default taken from the
//! core (`None` here means "the core's default"; [`defaults`] lists them for the Python layer
//! and its tests). No algorithm code.

use pyo3::prelude::*;
use pyo3::types::PyDict;

mod agreement;
mod convert;
mod errors;
mod io;
mod ml;
mod monitor;
mod nonlinear;
mod pipeline;
mod stats;

/// The core's default of every parameter the Python API exposes, by function and Python name
/// (and `analysis_params`: the whole `params` dict of `ldh.analyze`).
#[pyfunction]
fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    agreement::defaults(py, &d)?;
    io::defaults(py, &d)?;
    nonlinear::defaults(py, &d)?;
    pipeline::defaults(py, &d)?;
    Ok(d)
}

#[pymodule]
fn _ldh(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(defaults, m)?)?;
    m.add_function(wrap_pyfunction!(io::read_recording, m)?)?;
    m.add_function(wrap_pyfunction!(io::butter_filtfilt, m)?)?;
    m.add_function(wrap_pyfunction!(io::preprocess, m)?)?;
    m.add_function(wrap_pyfunction!(io::write_demo, m)?)?;
    m.add_function(wrap_pyfunction!(io::simulate_cohort, m)?)?;
    m.add_function(wrap_pyfunction!(pipeline::analyze, m)?)?;
    m.add_function(wrap_pyfunction!(monitor::monitor, m)?)?;
    m.add_function(wrap_pyfunction!(pipeline::analyze_pair, m)?)?;
    m.add_function(wrap_pyfunction!(pipeline::analyze_recording, m)?)?;
    m.add_function(wrap_pyfunction!(nonlinear::lyap_r, m)?)?;
    m.add_function(wrap_pyfunction!(nonlinear::lyap_e, m)?)?;
    m.add_function(wrap_pyfunction!(stats::shapiro, m)?)?;
    m.add_function(wrap_pyfunction!(stats::mannwhitneyu, m)?)?;
    m.add_function(wrap_pyfunction!(stats::ttest_ind, m)?)?;
    m.add_function(wrap_pyfunction!(stats::ttest_rel, m)?)?;
    m.add_function(wrap_pyfunction!(stats::ttest_1samp, m)?)?;
    m.add_function(wrap_pyfunction!(stats::wilcoxon, m)?)?;
    m.add_function(wrap_pyfunction!(stats::f_oneway, m)?)?;
    m.add_function(wrap_pyfunction!(stats::kruskal, m)?)?;
    m.add_function(wrap_pyfunction!(stats::pearsonr, m)?)?;
    m.add_function(wrap_pyfunction!(stats::holm, m)?)?;
    m.add_function(wrap_pyfunction!(stats::confidence_interval, m)?)?;
    m.add_function(wrap_pyfunction!(ml::cross_validate, m)?)?;
    m.add_function(wrap_pyfunction!(ml::train, m)?)?;
    m.add_function(wrap_pyfunction!(ml::predict, m)?)?;
    m.add_function(wrap_pyfunction!(agreement::agree, m)?)?;
    m.add_function(wrap_pyfunction!(agreement::reliability, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
