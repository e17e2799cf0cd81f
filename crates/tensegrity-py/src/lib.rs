//! # tensegrity-py
//!
//! The native module `tensegrity._native` of the Python package `tensegrity`: a front end as
//! thin as the command line. It lists the engine's registry (every command, its parameters
//! with names, kinds, units, defaults and help: the Python package builds its keyword
//! arguments, signatures and docstrings from them), runs a command on named values — the
//! estimate checked against the limits first, the work on a Rust thread with the GIL released
//! while the caller polls for signals ([`worker`]) — and hands back the report as JSON text,
//! which Python turns into dicts and numpy arrays. `simulate` and `roll` stream through the
//! library calls the CLI makes ([`runs`]), sweeps run through the sweeps crate ([`sweep`]),
//! and the structure model crosses as scene TOML through the io crate's reader and writer
//! ([`structure`]). Errors become the package's exceptions by their category, with the
//! command line's message ([`errors`]). No physics and no second description of a parameter
//! live here.

mod commands;
mod errors;
mod runs;
mod structure;
mod sweep;
mod worker;

use errors::Failure;
use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use serde_json::{Map, Value};
use tensegrity_core::request::Category;
use worker::Stopped;

/// Named values from their JSON text (an object).
fn object(text: &str) -> Result<Map<String, Value>, Failure> {
    match serde_json::from_str(text) {
        Ok(Value::Object(m)) => Ok(m),
        Ok(_) => Err(Failure::new(Category::Input, "expected named values")),
        Err(e) => Err(Failure::new(
            Category::Input,
            format!("unreadable values: {e}"),
        )),
    }
}

/// A [`Failure`] raised in Python.
fn raise<T>(py: Python<'_>, r: Result<T, Failure>) -> PyResult<T> {
    r.map_err(|f| f.into_pyerr(py))
}

/// The exception of a run that did not finish: `Interrupted` (a `KeyboardInterrupt`) with
/// `partial_raw` set to what the run handed back, or the signal handler's own exception.
fn stopped<T>(
    py: Python<'_>,
    s: Stopped<T>,
    partial: impl FnOnce(T) -> PyResult<Py<PyAny>>,
) -> PyErr {
    match s {
        Stopped::Panic(msg) => Failure::raw(
            Category::Numerical,
            format!("the computation panicked: {msg}"),
        )
        .into_pyerr(py),
        Stopped::Signal(err, got) => {
            if !err.is_instance_of::<PyKeyboardInterrupt>(py) {
                return err;
            }
            let e = Failure::raw(Category::Interrupted, "interrupted").into_pyerr(py);
            if let Some(value) = got.map(partial).transpose().ok().flatten() {
                let _ = e.value(py).setattr("partial_raw", value);
            }
            e
        }
    }
}

/// Every command of the registry (JSON text).
#[pyfunction(name = "commands")]
fn list_commands() -> String {
    commands::describe().to_string()
}

/// Runs the command `name` on `values` (JSON object) under `limits` (JSON object of
/// `max_memory`, `max_work`, `max_output`); `modes`: the commands whose parameters the call
/// offers (`tipover` and its `dynamic`, `rolling` modes), empty for one. The report as JSON.
#[pyfunction]
#[pyo3(signature = (name, values, limits, modes = Vec::new()))]
fn run(
    py: Python<'_>,
    name: &str,
    values: &str,
    limits: &str,
    modes: Vec<String>,
) -> PyResult<String> {
    let c = raise(py, commands::find(name))?;
    let values = raise(py, object(values))?;
    let limits = raise(py, object(limits).and_then(|l| commands::limits(&l)))?;
    if !modes.is_empty() {
        let modes: Vec<_> = raise(py, modes.iter().map(|m| commands::find(m)).collect())?;
        raise(py, commands::check_modes(c, &modes, &values))?;
    }
    raise(py, commands::admit(c, &values, &limits))?;
    match worker::run(py, false, move || commands::run(c, values, limits)) {
        Ok(report) => raise(py, report),
        Err(s) => Err(stopped(py, s, |_| Ok(py.None()))),
    }
}

/// The bytes of numbers (native endianness, for `numpy.frombuffer`).
fn bytes(py: Python<'_>, xs: &[f64]) -> Py<PyAny> {
    let raw: Vec<u8> = xs.iter().flat_map(|x| x.to_ne_bytes()).collect();
    PyBytes::new(py, &raw).into_any().unbind()
}

/// Runs `simulate` on `values` (`trajectory`: keep the node positions at the output times,
/// as the CLI's `--out`): (report JSON, times bytes, positions bytes, nodes per sample).
#[pyfunction]
fn simulate(
    py: Python<'_>,
    values: &str,
    limits: &str,
    trajectory: bool,
) -> PyResult<(String, Py<PyAny>, Py<PyAny>, usize)> {
    let values = raise(py, object(values))?;
    let limits = raise(py, object(limits).and_then(|l| commands::limits(&l)))?;
    let prepared = raise(py, runs::prepare_simulation(values, trajectory, &limits))?;
    let outcome = worker::run(py, true, move || runs::simulate(prepared));
    let samples = |t: &runs::Trajectory| (bytes(py, &t.t), bytes(py, &t.nodes), t.n_nodes);
    match outcome {
        Ok(o) => {
            if o.interrupted_at.is_some() {
                let e = Failure::raw(Category::Interrupted, "interrupted").into_pyerr(py);
                let _ = e.value(py).setattr("partial_raw", samples(&o.trajectory));
                return Err(e);
            }
            let report = raise(py, o.report)?;
            let (t, x, n) = samples(&o.trajectory);
            Ok((report, t, x, n))
        }
        Err(s) => Err(stopped(py, s, |o| {
            samples(&o.trajectory)
                .into_pyobject(py)
                .map(|b| b.into_any().unbind())
        })),
    }
}

/// Runs `roll` on `values` as the CLI does (observed, stopping on Ctrl-C): the report JSON;
/// an interrupted or stopped run raises with the partial report in `partial_raw`.
#[pyfunction]
fn roll(py: Python<'_>, values: &str, limits: &str) -> PyResult<String> {
    let values = raise(py, object(values))?;
    let limits = raise(py, object(limits).and_then(|l| commands::limits(&l)))?;
    let c = raise(py, commands::find("roll"))?;
    raise(py, commands::admit(c, &values, &limits))?;
    let request = raise(py, runs::roll_request(values))?;
    match worker::run(py, true, move || runs::roll(request)) {
        Ok(o) => {
            let report = raise(py, o.report)?;
            match o.incomplete {
                None => Ok(report),
                Some(f) => {
                    let e = f.into_pyerr(py);
                    let _ = e.value(py).setattr("partial_raw", report);
                    Err(e)
                }
            }
        }
        Err(s) => Err(stopped(py, s, |o| {
            Ok(o.report.ok().into_pyobject(py)?.into_any().unbind())
        })),
    }
}

/// Runs a sweep: `spec` is a path (`is_path`) or TOML text; the rows go to `out` (read back
/// by the caller). Returns the number of rows in the file.
#[pyfunction(name = "sweep")]
#[pyo3(signature = (spec, is_path, out, limits, threads = None, shard = None, resume = false, units = false))]
#[allow(clippy::too_many_arguments)]
fn run_sweep(
    py: Python<'_>,
    spec: &str,
    is_path: bool,
    out: &str,
    limits: &str,
    threads: Option<usize>,
    shard: Option<(usize, usize)>,
    resume: bool,
    units: bool,
) -> PyResult<usize> {
    let source = if is_path {
        sweep::Source::Path(spec.into())
    } else {
        sweep::Source::Text(spec.to_string())
    };
    let limits = raise(py, object(limits).and_then(|l| commands::limits(&l)))?;
    if threads == Some(0) {
        let p = tensegrity_core::request::InvalidParameter::raw("threads", 0, "must be at least 1");
        return Err(Failure::invalid(&p).into_pyerr(py));
    }
    let opts = sweep::Options {
        threads,
        shard,
        resume,
        units,
        limits,
    };
    let (spec, what) = raise(py, sweep::spec(&source))?;
    let shard = raise(py, sweep::admit(&spec, &opts))?;
    let out = std::path::PathBuf::from(out);
    match worker::run(py, true, move || {
        sweep::run(&spec, &what, &out, shard, &opts)
    }) {
        Ok(rows) => raise(py, rows),
        Err(s) => Err(stopped(py, s, |_| Ok(py.None()))),
    }
}

/// Scene TOML of a structure spec (a dict, see [`structure::build`]) and its other tables
/// (`tables`: JSON object).
#[pyfunction]
fn structure_toml(py: Python<'_>, spec: &Bound<'_, PyDict>, tables: &str) -> PyResult<String> {
    let s = raise(py, structure::build(spec)?)?;
    let tables = raise(py, object(tables))?;
    raise(py, structure::scene_text(&s, &tables))
}

/// The structure spec (JSON) of scene TOML; `name` labels its errors.
#[pyfunction]
fn structure_read(py: Python<'_>, text: &str, name: &str) -> PyResult<String> {
    raise(py, structure::read(text, name).map(|v| v.to_string()))
}

/// C_b, C_s and the equilibrium matrix of scene TOML (JSON).
#[pyfunction]
fn matrices(py: Python<'_>, text: &str) -> PyResult<String> {
    raise(py, structure::matrices(text).map(|v| v.to_string()))
}

/// The structure of a topology crate as scene TOML (`toroid`, `michell`, `tbar`).
#[pyfunction]
fn topology(py: Python<'_>, kind: &str, values: &str) -> PyResult<String> {
    let values = raise(py, object(values))?;
    let kind = kind.to_string();
    match worker::run(py, false, move || structure::topology(&kind, values)) {
        Ok(r) => raise(py, r),
        Err(s) => Err(stopped(py, s, |_| Ok(py.None()))),
    }
}

/// TOML text of a JSON object (a sweep spec or scene tables given as a dict).
#[pyfunction]
fn toml_text(py: Python<'_>, value: &str) -> PyResult<String> {
    let v: Value = raise(
        py,
        serde_json::from_str(value).map_err(|e| Failure::new(Category::Input, e.to_string())),
    )?;
    raise(py, structure::toml_text(&v))
}

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(list_commands, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(roll, m)?)?;
    m.add_function(wrap_pyfunction!(run_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(structure_toml, m)?)?;
    m.add_function(wrap_pyfunction!(structure_read, m)?)?;
    m.add_function(wrap_pyfunction!(matrices, m)?)?;
    m.add_function(wrap_pyfunction!(topology, m)?)?;
    m.add_function(wrap_pyfunction!(toml_text, m)?)?;
    m.add("POLL_S", worker::POLL.as_secs_f64())?;
    Ok(())
}
