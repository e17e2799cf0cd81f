//! The dynamics' sensitivities and system identification in Python: `_native.
//! trajectory_sensitivity` and `_native.identify`, a scene given as `simulate` takes it (a
//! path, its text or a `Structure`), read and checked by the engine
//! ([`tensegrity_engine::sensitivity::scene_dynamics`]), computed by the library
//! (`tensegrity_dynamics::sensitivity`, `::identify`). Arrays cross as raw f64 bytes, which
//! `tensegrity.trajectory_sensitivity` and `tensegrity.identify` view as numpy arrays. No
//! mathematics here.

use crate::errors::Failure;
use nalgebra::Vector3;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use tensegrity_core::request::{Categorized, Category, Request};
use tensegrity_dynamics::sensitivity::DynamicsParameter;
use tensegrity_engine::scene::SceneError;
use tensegrity_engine::sensitivity::{self, IdentifySettings};
use tensegrity_engine::simulate::SimulateCommand;

fn failure(e: &SceneError) -> PyErr {
    Python::attach(|py| Failure::new(e.category(), e.to_string()).into_pyerr(py))
}

/// The scene of `values` (`{"scene": …}`, as `simulate` takes it) and the parameters named.
fn problem(
    py: Python<'_>,
    values: &Bound<'_, PyDict>,
    parameters: &[(String, usize, usize)],
) -> PyResult<(
    tensegrity_core::Structure,
    Option<tensegrity_dynamics::Ground>,
    Vec<DynamicsParameter>,
)> {
    let values = crate::convert::named(values).map_err(|f| f.into_pyerr(py))?;
    let command =
        SimulateCommand::from_values(values).map_err(|e| Failure::invalid(&e).into_pyerr(py))?;
    let Some(scene) = command.scene.as_ref() else {
        return Err(Failure::new(Category::Input, "scene: give a scene").into_pyerr(py));
    };
    let (structure, ground) = sensitivity::scene_dynamics(scene).map_err(|e| failure(&e))?;
    let params = parameters
        .iter()
        .map(|(kind, index, axis)| sensitivity::parameter(kind, *index, *axis))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| failure(&e))?;
    Ok((structure, ground, params))
}

fn raw<'py>(py: Python<'py>, v: impl Iterator<Item = f64>) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = v.flat_map(|x| x.to_ne_bytes()).collect();
    PyBytes::new(py, &bytes)
}

/// Times, nodes (raw, samples × n × 3), node sensitivities (raw, samples × k × n × 3), the
/// events (time, what), the right-hand side evaluations, the bar-length drift and the drift
/// warnings (as `simulate` words them).
type Sensitivities<'py> = (
    Vec<f64>,
    Bound<'py, PyBytes>,
    Bound<'py, PyBytes>,
    Vec<(f64, String)>,
    usize,
    f64,
    Vec<String>,
);

/// The trajectory of a scene by RK4 steps of `dt` to `t_end`, sampled every `every` steps,
/// with its sensitivities to `parameters` (`(kind, index, axis)`).
#[pyfunction]
pub fn trajectory_sensitivity<'py>(
    py: Python<'py>,
    values: &Bound<'_, PyDict>,
    parameters: Vec<(String, usize, usize)>,
    dt: f64,
    t_end: f64,
    every: usize,
) -> PyResult<Sensitivities<'py>> {
    let (structure, ground, params) = problem(py, values, &parameters)?;
    let tr = py
        .detach(|| {
            sensitivity::forward_sensitivities(&structure, ground, &params, dt, t_end, every)
        })
        .map_err(|e| failure(&SceneError::Core(e)))?;
    let nodes = raw(py, tr.nodes.iter().flatten().flat_map(|p| [p.x, p.y, p.z]));
    let sens = raw(
        py,
        tr.node_sensitivities
            .iter()
            .flatten()
            .flatten()
            .flat_map(|p| [p.x, p.y, p.z]),
    );
    let events = tr.events.iter().map(|e| (e.time, e.what.clone())).collect();
    let warnings = tr.warnings.iter().map(|w| w.to_string()).collect();
    Ok((
        tr.times,
        nodes,
        sens,
        events,
        tr.rhs_evaluations,
        tr.bar_length_drift,
        warnings,
    ))
}

/// Identified values, standard errors, rms at the start and the end, iterations, converged,
/// the bar-length drift of the last run and its drift warnings.
type Identification = (Vec<f64>, Vec<f64>, f64, f64, usize, bool, f64, Vec<String>);

/// Identifies `parameters` of a scene from the `measured` positions (flat: samples ×
/// observed × 3) of the `observed` nodes, sampled every `every` RK4 steps of `dt`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn identify(
    py: Python<'_>,
    values: &Bound<'_, PyDict>,
    parameters: Vec<(String, usize, usize)>,
    observed: Vec<usize>,
    measured: Vec<f64>,
    dt: f64,
    every: usize,
    max_iterations: usize,
    tolerance: f64,
) -> PyResult<Identification> {
    let (structure, ground, params) = problem(py, values, &parameters)?;
    let per = 3 * observed.len();
    if per == 0 || !measured.len().is_multiple_of(per) {
        let reason = format!(
            "measured: {} numbers is not samples × {} observed nodes × 3",
            measured.len(),
            observed.len()
        );
        return Err(Failure::new(Category::Input, reason).into_pyerr(py));
    }
    let measured: Vec<Vec<Vector3<f64>>> = measured
        .chunks(per)
        .map(|s| {
            s.chunks(3)
                .map(|c| Vector3::new(c[0], c[1], c[2]))
                .collect()
        })
        .collect();
    let settings = IdentifySettings {
        dt,
        every,
        max_iterations,
        tolerance,
    };
    let id = py
        .detach(|| {
            sensitivity::identify(&structure, ground, &params, &observed, &measured, &settings)
        })
        .map_err(|e| failure(&SceneError::Core(e)))?;
    Ok((
        id.values,
        id.standard_errors,
        id.rms_start,
        id.rms,
        id.iterations,
        id.converged,
        id.bar_length_drift,
        id.warnings.iter().map(|w| w.to_string()).collect(),
    ))
}
