//! # tensegrity-py
//!
//! The native module `tensegrity._native` of the Python package `tensegrity`: a front end as
//! thin as the command line. It lists the engine's registry (every command, its parameters
//! with names, kinds, units, defaults and help: the Python package builds its keyword
//! arguments, signatures and docstrings from them), runs a command on named values — the
//! estimate checked against the limits first, the work on a Rust thread with the GIL released
//! while the caller polls for signals ([`worker`]) — and hands back the report as Python
//! objects built from the engine's values, every vector or matrix a numpy array ([`convert`]:
//! no text crosses, keyword values go in typed). `simulate` and `roll` stream through the
//! library calls the CLI makes ([`runs`]), sweeps run through the sweeps crate ([`sweep`]),
//! and the structure model is built from numpy arrays ([`structure`]: a `Structure` crosses
//! to the engine as data, the dict of its arrays, validated as a scene file is; scene TOML is
//! only its explicit export and import). Errors become the package's
//! exceptions by their category, naming keywords, never flags ([`errors`]). No physics and
//! no second description of a parameter live here.

mod commands;
mod convert;
mod errors;
mod runs;
mod stepping;
mod structure;
mod sweep;
mod worker;

use errors::Failure;
use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use tensegrity_core::request::Category;
use tensegrity_engine::value::{Map, Value};
use worker::Stopped;

/// What `simulate` hands back: the report and the samples ([`samples`]).
type SimulateResult = (Py<PyAny>, Py<PyAny>);

/// Keyword values as the engine's named values ([`convert::named`]).
fn object(values: &Bound<'_, PyDict>) -> Result<Map<String, Value>, Failure> {
    convert::named(values)
}

/// The limits given as keywords (`max_memory`, `max_work`, `max_output`).
fn limits_of(limits: &Bound<'_, PyDict>) -> Result<tensegrity_core::budget::Limits, Failure> {
    convert::named(limits).and_then(|l| commands::limits(&l))
}

/// A report as Python objects ([`convert::to_py`]).
fn report(py: Python<'_>, v: &Value) -> PyResult<Py<PyAny>> {
    Ok(convert::to_py(py, v)?.unbind())
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
fn list_commands(py: Python<'_>) -> PyResult<Py<PyAny>> {
    report(py, &commands::describe())
}

/// Runs the command `name` on `values` (JSON object) under `limits` (JSON object of
/// `max_memory`, `max_work`, `max_output`); `modes`: the commands whose parameters the call
/// offers (`tipover` and its `dynamic`, `rolling` modes), empty for one. The report as JSON.
#[pyfunction]
#[pyo3(signature = (name, values, limits, modes = Vec::new()))]
fn run(
    py: Python<'_>,
    name: &str,
    values: &Bound<'_, PyDict>,
    limits: &Bound<'_, PyDict>,
    modes: Vec<String>,
) -> PyResult<Py<PyAny>> {
    let c = raise(py, commands::find(name))?;
    let values = raise(py, object(values))?;
    let limits = raise(py, limits_of(limits))?;
    if !modes.is_empty() {
        let modes: Vec<_> = raise(py, modes.iter().map(|m| commands::find(m)).collect())?;
        raise(py, commands::check_modes(c, &modes, &values))?;
    }
    raise(py, commands::admit(c, &values, &limits))?;
    match worker::run(py, false, move || commands::run(c, values, limits)) {
        Ok(r) => report(py, &raise(py, r)?),
        Err(s) => Err(stopped(py, s, |_| Ok(py.None()))),
    }
}

/// The bytes of numbers (native endianness, for `numpy.frombuffer`).
fn bytes(py: Python<'_>, xs: &[f64]) -> Py<PyAny> {
    let raw: Vec<u8> = xs.iter().flat_map(|x| x.to_ne_bytes()).collect();
    PyBytes::new(py, &raw).into_any().unbind()
}

/// The samples of a run as a dict of raw f64 bytes and counts (`t`, `nodes`, `n_nodes`, and
/// where recorded `velocities`, `member_forces` with `n_members`, `energy` (kinetic, total
/// per sample), `contact_forces` with `contact_nodes`): `tensegrity._commands._samples`
/// views them as numpy arrays.
fn samples(py: Python<'_>, t: &runs::Trajectory) -> PyResult<Py<PyAny>> {
    let d = PyDict::new(py);
    d.set_item("t", bytes(py, &t.t))?;
    d.set_item("nodes", bytes(py, &t.nodes))?;
    d.set_item("n_nodes", t.n_nodes)?;
    if !t.velocities.is_empty() {
        d.set_item("velocities", bytes(py, &t.velocities))?;
    }
    if t.n_members > 0 {
        d.set_item("member_forces", bytes(py, &t.member_forces))?;
        d.set_item("n_members", t.n_members)?;
    }
    if !t.energy.is_empty() {
        let flat: Vec<f64> = t.energy.iter().flatten().copied().collect();
        d.set_item("energy", bytes(py, &flat))?;
    }
    if !t.contact_nodes.is_empty() {
        d.set_item("contact_forces", bytes(py, &t.contact_forces))?;
        d.set_item("contact_nodes", t.contact_nodes.clone())?;
    }
    Ok(d.into_any().unbind())
}

/// Runs `simulate` on `values` (`trajectory`: keep the samples at the output times, as the
/// CLI's `--out`): (report, [`samples`]).
#[pyfunction]
#[pyo3(signature = (values, limits, trajectory, progress = None))]
fn simulate(
    py: Python<'_>,
    values: &Bound<'_, PyDict>,
    limits: &Bound<'_, PyDict>,
    trajectory: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<SimulateResult> {
    let values = raise(py, object(values))?;
    let limits = raise(py, limits_of(limits))?;
    let prepared = raise(py, runs::prepare_simulation(values, trajectory, &limits))?;
    let watch = progress.map(|cb| worker::Watch::new(prepared.t_end(), cb));
    let counter = watch.as_ref().map(worker::Watch::counter);
    let outcome = worker::run_watched(
        py,
        true,
        move || runs::simulate(prepared, counter),
        watch.as_ref(),
    );
    match outcome {
        Ok(o) => {
            if o.interrupted_at.is_some() {
                let e = Failure::raw(Category::Interrupted, "interrupted").into_pyerr(py);
                let _ = e
                    .value(py)
                    .setattr("partial_raw", samples(py, &o.trajectory)?);
                return Err(e);
            }
            let r = report(py, &raise(py, o.report)?)?;
            Ok((r, samples(py, &o.trajectory)?))
        }
        Err(s) => Err(stopped(py, s, |o| samples(py, &o.trajectory))),
    }
}

/// Runs `roll` on `values` as the CLI does (observed, stopping on Ctrl-C): the report JSON;
/// an interrupted or stopped run raises with the partial report in `partial_raw`.
#[pyfunction]
#[pyo3(signature = (values, limits, progress = None))]
fn roll(
    py: Python<'_>,
    values: &Bound<'_, PyDict>,
    limits: &Bound<'_, PyDict>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Py<PyAny>> {
    let values = raise(py, object(values))?;
    let limits = raise(py, limits_of(limits))?;
    let c = raise(py, commands::find("roll"))?;
    raise(py, commands::admit(c, &values, &limits))?;
    let request = raise(py, runs::roll_request(values))?;
    // the history's rows as raw f64 bytes (`_commands._history` views them)
    let history = |rows: &[[f64; 9]]| {
        let flat: Vec<f64> = rows.iter().flatten().copied().collect();
        bytes(py, &flat)
    };
    let watch = progress.map(|cb| worker::Watch::new(request.t_end, cb));
    let counter = watch.as_ref().map(worker::Watch::counter);
    let outcome = worker::run_watched(
        py,
        true,
        move || runs::roll(request, counter),
        watch.as_ref(),
    );
    match outcome {
        Ok(o) => {
            let r = report(py, &raise(py, o.report)?)?;
            let h = history(&o.history);
            match o.incomplete {
                None => Ok((r, h).into_pyobject(py)?.into_any().unbind()),
                Some(f) => {
                    let e = f.into_pyerr(py);
                    let _ = e.value(py).setattr("partial_raw", (r, h));
                    Err(e)
                }
            }
        }
        Err(s) => Err(stopped(py, s, |o| {
            let r = match o.report.ok() {
                Some(v) => report(py, &v)?,
                None => py.None(),
            };
            Ok((r, history(&o.history))
                .into_pyobject(py)?
                .into_any()
                .unbind())
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
    limits: &Bound<'_, PyDict>,
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
    let limits = raise(py, limits_of(limits))?;
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

/// Validates a structure's data (a dict of its arrays and tables, [`structure::scene`]):
/// errors name the item.
#[pyfunction]
fn structure_check(py: Python<'_>, data: &Bound<'_, PyDict>) -> PyResult<()> {
    let data = raise(py, object(data))?;
    raise(py, structure::scene(&data).map(|_| ()))
}

/// The data of a structure as the engine gives it back (plain lists; [`structure::canonical`]).
#[pyfunction]
fn structure_arrays(py: Python<'_>, data: &Bound<'_, PyDict>) -> PyResult<Py<PyAny>> {
    let data = raise(py, object(data))?;
    let canonical = raise(py, structure::canonical(&data))?;
    Ok(convert::to_plain(py, &canonical)?.unbind())
}

/// Scene TOML of a structure's data (the explicit export, [`structure::scene_text`]).
#[pyfunction]
fn structure_toml(py: Python<'_>, data: &Bound<'_, PyDict>) -> PyResult<String> {
    let data = raise(py, object(data))?;
    raise(py, structure::scene_text(&data))
}

/// The data (a dict of plain lists) of scene TOML; `name` labels its errors.
#[pyfunction]
fn structure_read(py: Python<'_>, text: &str, name: &str) -> PyResult<Py<PyAny>> {
    let data = raise(py, structure::read(text, name))?;
    Ok(convert::to_plain(py, &data)?.unbind())
}

/// C_b, C_s and the equilibrium matrix of a structure's data (a dict).
#[pyfunction]
fn matrices(py: Python<'_>, data: &Bound<'_, PyDict>) -> PyResult<Py<PyAny>> {
    let data = raise(py, object(data))?;
    let m = raise(py, structure::matrices(&data))?;
    Ok(convert::to_plain(py, &m)?.unbind())
}

/// The structure of a topology crate as data (`toroid`, `michell`, `tbar`, `formfind`): a
/// dict of plain lists.
#[pyfunction]
fn topology(py: Python<'_>, kind: &str, values: &Bound<'_, PyDict>) -> PyResult<Py<PyAny>> {
    let values = raise(py, object(values))?;
    let kind = kind.to_string();
    match worker::run(py, false, move || structure::topology(&kind, values)) {
        Ok(r) => Ok(convert::to_plain(py, &raise(py, r)?)?.unbind()),
        Err(s) => Err(stopped(py, s, |_| Ok(py.None()))),
    }
}

/// TOML text of a dict (a sweep spec given as a dict).
#[pyfunction]
fn toml_text(py: Python<'_>, value: &Bound<'_, PyDict>) -> PyResult<String> {
    let v = raise(py, object(value))?;
    raise(py, structure::toml_text(&Value::Object(v)))
}

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(list_commands, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(roll, m)?)?;
    m.add_function(wrap_pyfunction!(run_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(structure_check, m)?)?;
    m.add_function(wrap_pyfunction!(structure_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(structure_toml, m)?)?;
    m.add_function(wrap_pyfunction!(structure_read, m)?)?;
    m.add_function(wrap_pyfunction!(matrices, m)?)?;
    m.add_function(wrap_pyfunction!(topology, m)?)?;
    m.add_function(wrap_pyfunction!(toml_text, m)?)?;
    m.add_class::<stepping::PyStepper>()?;
    m.add_class::<stepping::PyStepperState>()?;
    m.add("POLL_S", worker::POLL.as_secs_f64())?;
    m.add("ROLL_HISTORY_COLUMNS", runs::HISTORY_COLUMNS.to_vec())?;
    Ok(())
}
