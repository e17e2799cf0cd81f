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
//! library calls the CLI makes ([`runs`]), the files the CLI writes beside its reports
//! (`tipover`'s and `tbar roll`'s histories, the friction grid, the T-bar studies, the
//! exports and the project's figures) come from the same library calls ([`studies`]),
//! sweeps run through the sweeps crate ([`sweep`]); the long calls (`simulate`, `roll`,
//! `tbar roll`, `tipover`'s timed runs, sweeps) report their progress to a Python callback
//! ([`worker::Watch`]),
//! and the structure model is built from numpy arrays ([`structure`]: a `Structure` crosses
//! to the engine as data, the dict of its arrays, validated as a scene file is; scene TOML is
//! only its explicit export and import). Errors become the package's
//! exceptions by their category, naming keywords, never flags ([`errors`]). No physics and
//! no second description of a parameter live here.

mod commands;
mod convert;
mod dynamics_sensitivity;
mod errors;
mod runs;
mod sensitivity;
mod statics_sensitivity;
mod stepping;
mod structure;
mod studies;
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

/// The spec of `spec`: a path (`is_path`) or TOML text.
fn sweep_source(spec: &str, is_path: bool) -> sweep::Source {
    if is_path {
        sweep::Source::Path(spec.into())
    } else {
        sweep::Source::Text(spec.to_string())
    }
}

/// Runs a sweep: `spec` is a path (`is_path`) or TOML text; the rows go to `out` (read back
/// by the caller); `progress(done, total)`: the cases in the file of the shard's cases
/// ([`worker::Watch`]). Returns the number of rows in the file.
#[pyfunction(name = "sweep")]
#[pyo3(signature = (spec, is_path, out, limits, threads = None, shard = None, resume = false, units = false, progress = None))]
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
    progress: Option<Py<PyAny>>,
) -> PyResult<usize> {
    let source = sweep_source(spec, is_path);
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
    let (shard, cases) = raise(py, sweep::admit(&spec, &opts))?;
    let out = std::path::PathBuf::from(out);
    let watch = progress.map(|cb| worker::Watch::new(cases as f64, cb));
    let counter = watch.as_ref().map(worker::Watch::counter);
    let outcome = worker::run_watched(
        py,
        true,
        move || sweep::run(&spec, &what, &out, shard, &opts, counter),
        watch.as_ref(),
    );
    match outcome {
        Ok(rows) => raise(py, rows),
        Err(s) => Err(stopped(py, s, |_| Ok(py.None()))),
    }
}

/// The columns of a sweep's CSV with their units (`""` where none): `spec` a path
/// (`is_path`) or TOML text.
#[pyfunction]
fn sweep_columns(py: Python<'_>, spec: &str, is_path: bool) -> PyResult<Vec<(String, String)>> {
    let (spec, _) = raise(py, sweep::spec(&sweep_source(spec, is_path)))?;
    Ok(sweep::columns(&spec))
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

/// Runs `tipover` in its dynamic mode (`rolling`: its rolling mode) as the CLI does, the call
/// offering the parameters of `modes`: (report, the rows of its `--out` history as raw f64
/// bytes: [`studies::TIPOVER_DYNAMIC_COLUMNS`] or [`studies::TIPOVER_ROLLING_COLUMNS`]);
/// `progress(done, total)`: simulated seconds of the end time, paced by the estimate while
/// the run goes on ([`worker::Watch::paced`]), the run's end once it ran.
#[pyfunction]
#[pyo3(signature = (rolling, values, limits, modes, progress = None))]
fn tipover_history(
    py: Python<'_>,
    rolling: bool,
    values: &Bound<'_, PyDict>,
    limits: &Bound<'_, PyDict>,
    modes: Vec<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
    let name = if rolling {
        "tipover_rolling"
    } else {
        "tipover_dynamic"
    };
    let c = raise(py, commands::find(name))?;
    let values = raise(py, object(values))?;
    let limits = raise(py, limits_of(limits))?;
    let modes: Vec<_> = raise(py, modes.iter().map(|m| commands::find(m)).collect())?;
    raise(py, commands::check_modes(c, &modes, &values))?;
    let work_s = raise(py, commands::admit(c, &values, &limits))?;
    let watch = match progress {
        Some(cb) => {
            let t_end = raise(py, studies::tipover_t_end(rolling, &values))?;
            Some(worker::Watch::paced(t_end, work_s, cb))
        }
        None => None,
    };
    let counter = watch.as_ref().map(worker::Watch::counter);
    let outcome = worker::run_watched(
        py,
        false,
        move || studies::tipover(rolling, values, counter),
        watch.as_ref(),
    );
    match outcome {
        Ok(r) => {
            let (r, rows) = raise(py, r)?;
            Ok((report(py, &r)?, bytes(py, &rows)))
        }
        Err(s) => Err(stopped(py, s, |_| Ok(py.None()))),
    }
}

/// `tipover --grid`: F_f/F_e over `grid_points` × `grid_points` (σ, ε) points, ε up to
/// `eps_max`, its estimate checked against `limits`: the rows (σ, ε, F_f/F_e; σ outer) as
/// raw f64 bytes.
#[pyfunction]
fn friction_grid(
    py: Python<'_>,
    grid_points: usize,
    eps_max: f64,
    limits: &Bound<'_, PyDict>,
) -> PyResult<Py<PyAny>> {
    let limits = raise(py, limits_of(limits))?;
    raise(py, studies::admit_friction_grid(grid_points, &limits))?;
    match worker::run(py, false, move || {
        studies::friction_grid(grid_points, eps_max)
    }) {
        Ok(r) => Ok(bytes(py, &raise(py, r)?)),
        Err(s) => Err(stopped(py, s, |_| Ok(py.None()))),
    }
}

/// The T-bar studies of `tbar`'s parameters `values`: `study` = `loop_study` (the six cases)
/// or `mass_sweep` (over `complexities` × `deltas`); the rows as `--json` prints them.
#[pyfunction]
#[pyo3(signature = (study, values, complexities = Vec::new(), deltas = Vec::new()))]
fn tbar_study(
    py: Python<'_>,
    study: &str,
    values: &Bound<'_, PyDict>,
    complexities: Vec<usize>,
    deltas: Vec<f64>,
) -> PyResult<Py<PyAny>> {
    let values = raise(py, object(values))?;
    let work: Box<dyn FnOnce() -> Result<Value, Failure> + Send> = match study {
        "loop_study" => Box::new(move || studies::loop_study(values)),
        "mass_sweep" => Box::new(move || studies::mass_sweep(values, &complexities, &deltas)),
        other => {
            let p = tensegrity_core::request::InvalidParameter::raw(
                "study",
                other,
                "one of loop_study, mass_sweep",
            );
            return Err(Failure::invalid(&p).into_pyerr(py));
        }
    };
    match worker::run(py, false, work) {
        Ok(r) => report(py, &raise(py, r)?),
        Err(s) => Err(stopped(py, s, |_| Ok(py.None()))),
    }
}

/// Runs `tbar roll` on `values` as the CLI does, the T-bar run of its first row observed:
/// (report, that run's samples as raw f64 bytes, rows of `ROLL_HISTORY_COLUMNS`);
/// `progress(done, total)`: simulated seconds over every row's T-bar run
/// ([`studies::tbar_roll`]).
#[pyfunction]
#[pyo3(signature = (values, limits, progress = None))]
fn tbar_roll(
    py: Python<'_>,
    values: &Bound<'_, PyDict>,
    limits: &Bound<'_, PyDict>,
    progress: Option<Py<PyAny>>,
) -> PyResult<(Py<PyAny>, Py<PyAny>)> {
    let c = raise(py, commands::find("tbar_roll"))?;
    let values = raise(py, object(values))?;
    let limits = raise(py, limits_of(limits))?;
    raise(py, commands::admit(c, &values, &limits))?;
    let request = raise(py, studies::tbar_roll_request(values))?;
    let watch = progress.map(|cb| worker::Watch::new(studies::tbar_roll_total(&request), cb));
    let counter = watch.as_ref().map(worker::Watch::counter);
    let outcome = worker::run_watched(
        py,
        false,
        move || studies::tbar_roll(request, counter),
        watch.as_ref(),
    );
    match outcome {
        Ok((r, rows)) => {
            let flat: Vec<f64> = rows.iter().flatten().copied().collect();
            Ok((report(py, &raise(py, r)?)?, bytes(py, &flat)))
        }
        Err(s) => Err(stopped(py, s, |_| Ok(py.None()))),
    }
}

/// The scene of `values["scene"]` (a path, TOML or JSON text, or a Structure) as the
/// engine's value.
fn scene_value(py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<Value> {
    let mut values = raise(py, object(values))?;
    match values.remove("scene") {
        Some(v) => Ok(v),
        None => {
            let p = tensegrity_core::request::InvalidParameter::raw(
                "scene",
                "(unset)",
                "must be given",
            );
            Err(Failure::invalid(&p).into_pyerr(py))
        }
    }
}

/// `export mjcf`: the MJCF text of `values["scene"]`; `source` names it in the model.
#[pyfunction]
#[pyo3(signature = (values, source, timestep, ground_height = None))]
fn export_mjcf(
    py: Python<'_>,
    values: &Bound<'_, PyDict>,
    source: String,
    timestep: f64,
    ground_height: Option<f64>,
) -> PyResult<String> {
    let scene = scene_value(py, values)?;
    raise(py, studies::mjcf(scene, source, timestep, ground_height))
}

/// `export json`: the JSON text of `values["scene"]`.
#[pyfunction]
fn export_json(py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<String> {
    let scene = scene_value(py, values)?;
    raise(py, studies::scene_json(scene))
}

/// `export schema`: the JSON Schema of scene files (text).
#[pyfunction]
fn export_schema(py: Python<'_>) -> PyResult<String> {
    raise(py, studies::schema())
}

/// Builds the figure `name` (`3.10`, `fig_3_10`) and writes it to `path` (SVG, PNG or PDF by
/// its extension), its data table to `data` if given, its sweeps' CSVs into `data_dir`.
#[pyfunction]
#[pyo3(signature = (name, path, data, data_dir, quick, limits, size = None, dpi = None))]
#[allow(clippy::too_many_arguments)]
fn figure(
    py: Python<'_>,
    name: &str,
    path: std::path::PathBuf,
    data: Option<std::path::PathBuf>,
    data_dir: std::path::PathBuf,
    quick: bool,
    limits: &Bound<'_, PyDict>,
    size: Option<String>,
    dpi: Option<f64>,
) -> PyResult<()> {
    let limits = raise(py, limits_of(limits))?;
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    let (spec, options) = raise(
        py,
        studies::figure_spec(name, quick, size.as_deref(), dpi, png, &limits),
    )?;
    match worker::run(py, false, move || {
        studies::write_figure(spec, options, quick, &path, data.as_deref(), &data_dir)
    }) {
        Ok(r) => raise(py, r),
        Err(s) => Err(stopped(py, s, |_| Ok(py.None()))),
    }
}

/// The project's figures: (number, description, file stem) each.
#[pyfunction]
fn figures() -> Vec<(&'static str, &'static str, String)> {
    studies::figure_catalog()
}

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(list_commands, m)?)?;
    m.add_function(wrap_pyfunction!(run, m)?)?;
    m.add_function(wrap_pyfunction!(
        dynamics_sensitivity::trajectory_sensitivity,
        m
    )?)?;
    m.add_function(wrap_pyfunction!(dynamics_sensitivity::identify, m)?)?;
    m.add_function(wrap_pyfunction!(
        statics_sensitivity::stiffness_sensitivity,
        m
    )?)?;
    m.add_function(wrap_pyfunction!(
        statics_sensitivity::margin_sensitivity,
        m
    )?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(roll, m)?)?;
    m.add_function(wrap_pyfunction!(run_sweep, m)?)?;
    m.add_function(wrap_pyfunction!(sweep_columns, m)?)?;
    m.add_function(wrap_pyfunction!(structure_check, m)?)?;
    m.add_function(wrap_pyfunction!(structure_arrays, m)?)?;
    m.add_function(wrap_pyfunction!(structure_toml, m)?)?;
    m.add_function(wrap_pyfunction!(structure_read, m)?)?;
    m.add_function(wrap_pyfunction!(matrices, m)?)?;
    m.add_function(wrap_pyfunction!(topology, m)?)?;
    m.add_function(wrap_pyfunction!(toml_text, m)?)?;
    m.add_function(wrap_pyfunction!(tipover_history, m)?)?;
    m.add_function(wrap_pyfunction!(friction_grid, m)?)?;
    m.add_function(wrap_pyfunction!(tbar_study, m)?)?;
    m.add_function(wrap_pyfunction!(tbar_roll, m)?)?;
    m.add_function(wrap_pyfunction!(export_mjcf, m)?)?;
    m.add_function(wrap_pyfunction!(export_json, m)?)?;
    m.add_function(wrap_pyfunction!(export_schema, m)?)?;
    m.add_function(wrap_pyfunction!(figure, m)?)?;
    m.add_function(wrap_pyfunction!(figures, m)?)?;
    m.add_class::<stepping::PyStepper>()?;
    m.add_class::<stepping::PyStepperState>()?;
    m.add_class::<sensitivity::PyFormSensitivity>()?;
    m.add_class::<sensitivity::PyRelaxedSensitivity>()?;
    m.add_class::<sensitivity::PyDesignProblem>()?;
    m.add("POLL_S", worker::POLL.as_secs_f64())?;
    m.add("ROLL_HISTORY_COLUMNS", runs::HISTORY_COLUMNS.to_vec())?;
    m.add(
        "TIPOVER_DYNAMIC_COLUMNS",
        studies::TIPOVER_DYNAMIC_COLUMNS.to_vec(),
    )?;
    m.add(
        "TIPOVER_ROLLING_COLUMNS",
        studies::TIPOVER_ROLLING_COLUMNS.to_vec(),
    )?;
    m.add(
        "FRICTION_GRID_COLUMNS",
        studies::FRICTION_GRID_COLUMNS.to_vec(),
    )?;
    m.add("MJCF_TIMESTEP", tensegrity_io::mjcf::DEFAULT_TIMESTEP)?;
    // the defaults of the studies, the CLI's flags' own
    m.add("FRICTION_GRID_POINTS", sweeps::grids::FRICTION_GRID_POINTS)?;
    m.add(
        "FRICTION_GRID_EPS_MAX",
        sweeps::grids::FRICTION_GRID_EPS_MAX,
    )?;
    m.add(
        "MASS_SWEEP_COMPLEXITIES",
        tbar_wheel::MASS_SWEEP_COMPLEXITIES.to_vec(),
    )?;
    m.add(
        "MASS_SWEEP_OFFSETS",
        tbar_wheel::MASS_SWEEP_OFFSETS.to_vec(),
    )?;
    Ok(())
}
