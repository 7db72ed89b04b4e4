//! Core errors as the `ldh` exception family (`python/ldh/_errors.py`): each class is also the
//! built-in exception a Python user catches (`ValueError`, `FileNotFoundError`, `OSError`).

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use ldh_core::{ErrorKind, LdhError};

/// Map a core error onto the `ldh` exception family by [`LdhError::kind`].
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

/// `result.or_raise(py)?`: a core `Result` as a `PyResult` with the `ldh` exception.
pub(crate) trait OrRaise<T> {
    /// The value, or the error as an `ldh` exception.
    fn or_raise(self, py: Python<'_>) -> PyResult<T>;
}

impl<T, E: Into<LdhError>> OrRaise<T> for Result<T, E> {
    fn or_raise(self, py: Python<'_>) -> PyResult<T> {
        self.map_err(|e| to_py(py, e.into()))
    }
}
