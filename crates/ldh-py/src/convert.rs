//! Conversion of core values into Python objects: numpy arrays for channels and numeric
//! columns, dicts and lists for typed records (through their serde form, never JSON text), and
//! Python values into core parameters. Nothing here decides anything about the data.

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString};
use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::Value;

use ldh_core::LdhError;

/// How [`to_py`] maps JSON-like values.
#[derive(Clone, Copy, Default)]
pub(crate) struct Opts {
    /// `None` becomes `nan` (parameters that could not be measured).
    pub null_as_nan: bool,
    /// A non-empty list of numbers becomes a float64 numpy array.
    pub numeric_arrays: bool,
}

pub(crate) fn vec1(py: Python<'_>, v: Vec<f64>) -> Bound<'_, PyArray1<f64>> {
    v.into_pyarray(py)
}

/// Copy N numpy channels (contiguous float64, as the Python layer passes them) into vectors.
pub(crate) fn vecs<const N: usize>(a: &[PyReadonlyArray1<'_, f64>; N]) -> PyResult<[Vec<f64>; N]> {
    let v: Vec<Vec<f64>> = a
        .iter()
        .map(|c| c.as_slice().map(|s| s.to_vec()))
        .collect::<Result<_, _>>()?;
    Ok(v.try_into().expect("N channels in, N out"))
}

/// The serde form of a core value (a struct becomes a map of its fields).
pub(crate) fn value_of<T: Serialize>(v: &T) -> Result<Value, LdhError> {
    serde_json::to_value(v).map_err(|e| LdhError::signal("conversion", e.to_string()))
}

fn is_number(v: &Value) -> bool {
    v.is_number() || v.is_null()
}

/// A serde value as a Python object (dict, list, float, int, str, bool, None).
pub(crate) fn to_py<'py>(py: Python<'py>, v: &Value, o: Opts) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Null if o.null_as_nan => PyFloat::new(py, f64::NAN).into_any(),
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Value::Number(n) => match (n.as_i64(), n.as_u64()) {
            (Some(i), _) => i.into_pyobject(py)?.into_any(),
            (None, Some(u)) => u.into_pyobject(py)?.into_any(),
            _ => PyFloat::new(py, n.as_f64().unwrap_or(f64::NAN)).into_any(),
        },
        Value::String(s) => PyString::new(py, s).into_any(),
        Value::Array(a) if o.numeric_arrays && !a.is_empty() && a.iter().all(is_number) => {
            let f: Vec<f64> = a.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect();
            vec1(py, f).into_any()
        }
        Value::Array(a) => {
            let l = PyList::empty(py);
            for x in a {
                l.append(to_py(py, x, o)?)?;
            }
            l.into_any()
        }
        Value::Object(m) => {
            let d = PyDict::new(py);
            for (k, x) in m {
                d.set_item(k, to_py(py, x, o)?)?;
            }
            d.into_any()
        }
    })
}

/// A Python value (dict, list, str, number, bool, None) as a serde value, to build core
/// parameters with their own names, defaults and validation (`deny_unknown_fields`).
pub(crate) fn from_py(v: &Bound<'_, PyAny>) -> PyResult<Value> {
    Ok(if v.is_none() {
        Value::Null
    } else if let Ok(b) = v.cast::<PyBool>() {
        Value::Bool(b.is_true())
    } else if v.is_instance_of::<PyInt>() {
        match v.extract::<i64>() {
            Ok(i) => Value::from(i),
            Err(_) => Value::from(v.extract::<u64>()?),
        }
    } else if let Ok(f) = v.extract::<f64>() {
        serde_json::Number::from_f64(f).map_or(Value::Null, Value::Number)
    } else if let Ok(s) = v.extract::<String>() {
        Value::String(s)
    } else if let Ok(d) = v.cast::<PyDict>() {
        let mut m = serde_json::Map::new();
        for (k, x) in d.iter() {
            m.insert(k.str()?.to_string(), from_py(&x)?);
        }
        Value::Object(m)
    } else {
        let items: Vec<Value> = v
            .try_iter()?
            .map(|x| from_py(&x?))
            .collect::<PyResult<_>>()?;
        Value::Array(items)
    })
}

/// A core choice (an enum with serde names: `"split"`, `"grouped"`…) from its name; the error
/// lists the valid names.
pub(crate) fn choice<T: DeserializeOwned>(name: &'static str, s: &str) -> Result<T, LdhError> {
    serde_json::from_value(Value::String(s.to_string()))
        .map_err(|e| LdhError::param(name, s, e.to_string()))
}

/// Column order of a table: the CSV header of its first row (the field order), then any other
/// key of the rows.
fn column_order<T: Serialize>(rows: &[T], maps: &[serde_json::Map<String, Value>]) -> Vec<String> {
    let mut cols: Vec<String> = rows.first().map(csv_header).unwrap_or_default();
    for m in maps {
        for k in m.keys() {
            if !cols.contains(k) {
                cols.push(k.clone());
            }
        }
    }
    cols
}

/// The CSV header a row of a table is written with (its fields in order, as `ldh` writes the
/// file); empty when it cannot be serialised.
pub(crate) fn csv_header<T: Serialize>(row: &T) -> Vec<String> {
    let mut w = csv::WriterBuilder::new().from_writer(Vec::new());
    // Lists (warnings, withheld) are one cell in CSV, as `ldh analyze` writes them.
    if ldh_core::pipeline::quality::flat(|| w.serialize(row)).is_err() {
        return Vec::new();
    }
    let Ok(bytes) = w.into_inner() else {
        return Vec::new();
    };
    let mut r = csv::Reader::from_reader(&bytes[..]);
    r.headers()
        .map(|h| h.iter().map(String::from).collect())
        .unwrap_or_default()
}

/// Rows of a table as columns: numbers (with `None` as NaN) as float64 arrays, booleans as bool
/// arrays, anything else (text, with `None` for missing) as lists. `header` names the columns of
/// an empty table.
pub(crate) fn columns<'py, T: Serialize>(
    py: Python<'py>,
    rows: &[T],
    header: &[&str],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let maps: Vec<serde_json::Map<String, Value>> = rows
        .iter()
        .map(|r| match value_of(r) {
            Ok(Value::Object(m)) => Ok(m),
            Ok(_) => Ok(serde_json::Map::new()),
            Err(e) => Err(e),
        })
        .collect::<Result<_, _>>()
        .map_err(|e| crate::errors::to_py(py, e))?;
    if rows.is_empty() {
        for h in header {
            d.set_item(*h, vec1(py, vec![]))?;
        }
        return Ok(d);
    }
    for c in column_order(rows, &maps) {
        let vals: Vec<&Value> = maps
            .iter()
            .map(|m| m.get(&c).unwrap_or(&Value::Null))
            .collect();
        if vals.iter().all(|v| is_number(v)) {
            let f: Vec<f64> = vals
                .iter()
                .map(|v| v.as_f64().unwrap_or(f64::NAN))
                .collect();
            d.set_item(&c, vec1(py, f))?;
        } else if vals.iter().all(|v| v.is_boolean()) {
            let b: Vec<bool> = vals.iter().map(|v| v.as_bool().unwrap_or(false)).collect();
            d.set_item(&c, b.into_pyarray(py))?;
        } else {
            let l = PyList::empty(py);
            for v in vals {
                l.append(to_py(py, v, Opts::default())?)?;
            }
            d.set_item(&c, l)?;
        }
    }
    Ok(d)
}

/// A Python int given for an unsigned argument (taken as a signed integer, so a negative value
/// is not pyo3's `OverflowError`; `i128` where the whole `u64` range must pass, e.g. a seed)
/// as the core's unsigned type: a negative value, or one beyond the type, is an
/// `LdhParamError` naming the argument.
pub(crate) fn uint<T: TryFrom<i128>>(
    name: &'static str,
    v: impl Into<i128>,
) -> Result<T, LdhError> {
    let v: i128 = v.into();
    T::try_from(v).map_err(|_| {
        LdhError::param(
            name,
            v,
            if v < 0 {
                "must be a non-negative integer"
            } else {
                "is too large"
            },
        )
    })
}

/// [`uint`] of an optional argument.
pub(crate) fn opt_uint<T: TryFrom<i128>>(
    name: &'static str,
    v: Option<impl Into<i128>>,
) -> Result<Option<T>, LdhError> {
    v.map(|v| uint(name, v)).transpose()
}

/// [`uint`] of every element of a list argument (class labels, fold indices).
pub(crate) fn uints<T: TryFrom<i128>>(name: &'static str, v: Vec<i64>) -> Result<Vec<T>, LdhError> {
    v.into_iter().map(|x| uint(name, x)).collect()
}
