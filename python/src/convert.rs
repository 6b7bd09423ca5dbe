//! Python values <-> TOML values. A case given as a dict is written as TOML text and parsed
//! by the same function as a case file (`tribo::case::parse`), so that a dict and a file
//! holding the same values give the same case, digit for digit (TOML writes floats in their
//! shortest exact form).

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use toml::Value;

/// A Python value as TOML; `at` is its address in the case ("contact.0.friction").
pub fn to_toml(v: &Bound<'_, PyAny>, at: &str) -> PyResult<Value> {
    let key = |k: &str| {
        if at.is_empty() {
            k.to_string()
        } else {
            format!("{at}.{k}")
        }
    };
    // bool before int: a Python bool is an int
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(Value::Boolean(b.is_true()));
    }
    if v.is_instance_of::<PyInt>() {
        return Ok(Value::Integer(v.extract::<i64>()?));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(Value::Float(v.extract::<f64>()?));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(Value::String(s.extract::<String>()?));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut t = toml::Table::new();
        for (k, x) in d.iter() {
            let Ok(k) = k.extract::<String>() else {
                return Err(PyTypeError::new_err(format!(
                    "case: {}: the keys of a table are strings, got {}",
                    if at.is_empty() { "top level" } else { at },
                    k.repr()?
                )));
            };
            let value = to_toml(&x, &key(&k))?;
            t.insert(k, value);
        }
        return Ok(Value::Table(t));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let mut a = vec![];
        for (i, x) in v.try_iter()?.enumerate() {
            a.push(to_toml(&x?, &key(&i.to_string()))?);
        }
        return Ok(Value::Array(a));
    }
    // numpy scalars and other numbers: an exact integer, else a float
    if let Ok(i) = v.extract::<i64>() {
        return Ok(Value::Integer(i));
    }
    if let Ok(x) = v.extract::<f64>() {
        return Ok(Value::Float(x));
    }
    Err(PyTypeError::new_err(format!(
        "case: {at}: a {} has no TOML equivalent (use a bool, int, float, str, list or dict)",
        v.get_type().name()?
    )))
}

/// A TOML value as Python (tables as dicts, arrays as lists, dates as strings).
pub fn to_py<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::String(s) => s.into_pyobject(py)?.into_any(),
        Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        Value::Float(x) => x.into_pyobject(py)?.into_any(),
        Value::Boolean(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Value::Datetime(d) => d.to_string().into_pyobject(py)?.into_any(),
        Value::Array(a) => {
            let l = PyList::empty(py);
            for x in a {
                l.append(to_py(py, x)?)?;
            }
            l.into_any()
        }
        Value::Table(t) => {
            let d = PyDict::new(py);
            for (k, x) in t {
                d.set_item(k, to_py(py, x)?)?;
            }
            d.into_any()
        }
    })
}
