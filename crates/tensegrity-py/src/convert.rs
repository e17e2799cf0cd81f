//! Python objects ↔ the engine's values, without text in between.
//!
//! Inward ([`from_py`]): `None`, `bool`, `int`, `float`, `str`, lists and tuples, dicts with
//! string keys, `os.PathLike` (its path), numpy scalars and arrays (their `tolist()`), and an
//! object with `_arrays()` (a `Structure`: the dict of its arrays and tables, which the
//! engine reads as a scene given as data, `SceneSource::Data`; no TOML text is written)
//! become the engine's values; a non-finite float crosses as its text (`nan`, `inf`), which
//! every numeric parameter refuses by name. Anything else is an input error naming the
//! keyword.
//!
//! Outward ([`to_py`]): objects become dicts, strings, booleans and numbers as they are, and
//! every rectangular list of numbers (any depth) a numpy array: int64 when every entry is an
//! integer, bool when every entry is a boolean, float64 otherwise with `null` as NaN. An empty
//! list becomes an empty float array, except under the keys that hold text or records
//! (`warnings`, `errors`, `notes`, `frames`, `impacts`, `rows`, `samples`), where it stays a
//! list.

use crate::errors::Failure;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use tensegrity_core::request::{Category, InvalidParameter};
use tensegrity_engine::value::{Map, Number, Value};

/// Keys whose lists hold text or records even when empty.
const LIST_KEYS: [&str; 7] = [
    "warnings", "errors", "notes", "frames", "impacts", "rows", "samples",
];

/// Why a Python value cannot cross to the engine: what was found (the caller names the
/// keyword).
#[derive(Debug, Clone, PartialEq)]
pub struct Unconvertible(pub String);

impl std::fmt::Display for Unconvertible {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl From<PyErr> for Unconvertible {
    fn from(e: PyErr) -> Self {
        Unconvertible(e.to_string())
    }
}

/// A dict of keyword values as the engine's named values (`None` values left out: the
/// engine then applies its default, as for an absent flag).
pub fn named(values: &Bound<'_, PyDict>) -> Result<Map<String, Value>, Failure> {
    let mut out = Map::new();
    for (k, v) in values.iter() {
        let key: String = k
            .extract()
            .map_err(|_| Failure::new(Category::Input, "keyword names must be strings"))?;
        if v.is_none() {
            continue;
        }
        let value = from_py(&v).map_err(|Unconvertible(reason)| {
            Failure::invalid(&InvalidParameter::raw(key.clone(), "(value)", reason))
        })?;
        out.insert(key, value);
    }
    Ok(out)
}

/// One Python value as the engine's value (module docs); the error is the reason.
pub fn from_py(v: &Bound<'_, PyAny>) -> Result<Value, Unconvertible> {
    if v.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if v.is_instance_of::<PyInt>() {
        if let Ok(i) = v.extract::<i64>() {
            return Ok(Value::from(i));
        }
        if let Ok(u) = v.extract::<u64>() {
            return Ok(Value::from(u));
        }
        return Err(Unconvertible("the integer is out of range".into()));
    }
    if v.is_instance_of::<PyFloat>() {
        let x: f64 = v.extract().map_err(|e: PyErr| Unconvertible::from(e))?;
        return Ok(Number::from_f64(x).map_or_else(|| Value::String(x.to_string()), Value::Number));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(Value::String(s.to_string()));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        let mut out = Map::new();
        for (k, x) in d.iter() {
            let key: String = k
                .extract()
                .map_err(|_| Unconvertible("dict keys must be strings".into()))?;
            out.insert(key, from_py(&x)?);
        }
        return Ok(Value::Object(out));
    }
    if let Ok(l) = v.cast::<PyList>() {
        return l
            .iter()
            .map(|x| from_py(&x))
            .collect::<Result<_, _>>()
            .map(Value::Array);
    }
    if let Ok(t) = v.cast::<PyTuple>() {
        return t
            .iter()
            .map(|x| from_py(&x))
            .collect::<Result<_, _>>()
            .map(Value::Array);
    }
    let py = v.py();
    // a Structure: the dict of its arrays (a scene as data)
    if v.hasattr("_arrays").unwrap_or(false) {
        let data = v.call_method0("_arrays").map_err(Unconvertible::from)?;
        return from_py(&data);
    }
    let os = py.import("os").map_err(Unconvertible::from)?;
    if v.is_instance(&os.getattr("PathLike").map_err(Unconvertible::from)?)
        .unwrap_or(false)
    {
        let path = os
            .call_method1("fspath", (v,))
            .map_err(Unconvertible::from)?;
        return from_py(&path);
    }
    // numpy arrays and scalars: their Python equivalents
    if v.hasattr("tolist").unwrap_or(false) {
        let plain = v.call_method0("tolist").map_err(Unconvertible::from)?;
        return from_py(&plain);
    }
    let kind = v
        .get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_default();
    Err(Unconvertible(format!(
        "a value of type {kind} cannot be passed"
    )))
}

/// The element kind of a rectangular numeric list.
#[derive(Clone, Copy, PartialEq)]
enum Elem {
    Bool,
    Int,
    Float,
}

/// The shape and element kind of a rectangular nested list of scalars, if it is one (an
/// all-null list is not numeric: it stays a list of `None`).
fn shape(v: &Value) -> Option<(Vec<usize>, Elem, bool)> {
    match v {
        Value::Bool(_) => Some((vec![], Elem::Bool, false)),
        Value::Number(n) if n.is_i64() || n.is_u64() => Some((vec![], Elem::Int, false)),
        Value::Number(_) => Some((vec![], Elem::Float, false)),
        Value::Null => Some((vec![], Elem::Float, true)),
        Value::Array(items) if !items.is_empty() => {
            let shapes: Vec<_> = items.iter().map(shape).collect::<Option<_>>()?;
            let first = &shapes[0].0;
            if shapes.iter().any(|s| &s.0 != first) {
                return None;
            }
            let bools = shapes.iter().filter(|s| s.1 == Elem::Bool).count();
            let kind = if bools == shapes.len() {
                Elem::Bool
            } else if bools > 0 {
                return None;
            } else if shapes.iter().all(|s| s.1 == Elem::Int) {
                Elem::Int
            } else {
                Elem::Float
            };
            let all_null = shapes.iter().all(|s| s.2);
            let mut dims = vec![items.len()];
            dims.extend(first);
            Some((dims, kind, all_null))
        }
        _ => None,
    }
}

/// The scalars of a rectangular list, row-major, as Python objects of the element kind.
fn leaves<'py>(py: Python<'py>, v: &Value, kind: Elem, out: &mut Vec<Bound<'py, PyAny>>) {
    match v {
        Value::Array(items) => items.iter().for_each(|x| leaves(py, x, kind, out)),
        Value::Bool(b) => out.push(PyBool::new(py, *b).to_owned().into_any()),
        Value::Number(n) if kind == Elem::Int => {
            let i = n.as_i64().map_or_else(
                || {
                    n.as_u64()
                        .unwrap_or_default()
                        .into_pyobject(py)
                        .unwrap()
                        .into_any()
                },
                |i| i.into_pyobject(py).unwrap().into_any(),
            );
            out.push(i)
        }
        Value::Number(n) => out.push(PyFloat::new(py, n.as_f64().unwrap_or(f64::NAN)).into_any()),
        _ => out.push(PyFloat::new(py, f64::NAN).into_any()),
    }
}

/// One engine value as a Python object (module docs).
pub fn to_py<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    value_at(py, v, "", true)
}

/// One engine value as plain Python objects: lists stay lists (no numpy arrays).
pub fn to_plain<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyAny>> {
    value_at(py, v, "", false)
}

fn value_at<'py>(
    py: Python<'py>,
    v: &Value,
    key: &str,
    arrays: bool,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::Null => py.None().into_bound(py),
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Value::Number(n) => match (n.as_i64(), n.as_u64()) {
            (Some(i), _) => i.into_pyobject(py)?.into_any(),
            (None, Some(u)) => u.into_pyobject(py)?.into_any(),
            _ => PyFloat::new(py, n.as_f64().unwrap_or(f64::NAN)).into_any(),
        },
        Value::String(s) => PyString::new(py, s).into_any(),
        Value::Object(m) => {
            let d = PyDict::new(py);
            for (k, x) in m {
                d.set_item(k, value_at(py, x, k, arrays)?)?;
            }
            d.into_any()
        }
        Value::Array(items) if !arrays => {
            let list = PyList::empty(py);
            for x in items {
                list.append(value_at(py, x, key, false)?)?;
            }
            list.into_any()
        }
        Value::Array(items) => {
            let np = py.import("numpy")?;
            if items.is_empty() {
                return if LIST_KEYS.iter().any(|k| key.ends_with(k)) {
                    Ok(PyList::empty(py).into_any())
                } else {
                    np.call_method1("empty", (0,))
                };
            }
            match shape(v) {
                Some((dims, kind, false)) => {
                    let mut flat = Vec::new();
                    leaves(py, v, kind, &mut flat);
                    let dtype = match kind {
                        Elem::Bool => "bool",
                        Elem::Int => "int64",
                        Elem::Float => "float64",
                    };
                    let list = PyList::new(py, flat)?;
                    let arr = np.call_method1("array", (list, dtype))?;
                    arr.call_method1("reshape", (PyTuple::new(py, dims)?,))?
                }
                _ => {
                    let list = PyList::empty(py);
                    for x in items {
                        list.append(value_at(py, x, key, true)?)?;
                    }
                    list.into_any()
                }
            }
        }
    })
}
