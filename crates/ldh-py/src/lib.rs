//! Python bindings of ldh-core: the native module `ldh._ldh`, laid out like tokenizers'
//! `bindings/python`, one file per area of the core:
//!
//! * [`io`]: reading recordings, filters, the demo cohort and the simulator;
//! * [`pipeline`]: the analysis of paths or arrays;
//! * [`stats`]: the scipy.stats look-alikes;
//! * [`nonlinear`]: the nolds look-alikes (Lyapunov exponents);
//! * [`ml`]: cross-validation, training, prediction;
//! * [`errors`]: core errors as the `ldh` exception family; [`convert`]: values in and out.
//!
//! Conversion only: numpy arrays in and out, errors mapped onto the `ldh` exception classes,
//! and the GIL released (`py.detach`) around every computation. No algorithm code: this file
//! only registers the modules' functions.

use pyo3::prelude::*;

mod convert;
mod errors;
mod io;
mod ml;
mod nonlinear;
mod pipeline;
mod stats;

#[pymodule]
fn _ldh(m: &Bound<'_, PyModule>) -> PyResult<()> {
    io::register(m)?;
    pipeline::register(m)?;
    nonlinear::register(m)?;
    stats::register(m)?;
    ml::register(m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
