//! Core errors as the `ldh` exception family (classes defined in `python/ldh/_errors.py`:
//! subclasses of `ValueError`, `FileNotFoundError` and `OSError`, all of `ldh.LdhError`).

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use ldh_core::{ErrorKind, LdhError};

/// Map a core error onto the `ldh` exception family by its [`ErrorKind`].
pub(crate) fn to_py(py: Python<'_>, e: LdhError) -> PyErr {
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
