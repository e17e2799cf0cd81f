//! The statics' sensitivities in Python: `_native.stiffness_sensitivity` (the smallest
//! nonzero eigenvalue of the tangent stiffness and the lowest natural frequencies, with their
//! derivatives) and `_native.margin_sensitivity` (the prestress margin's), a scene given as
//! `statics` takes it, computed by the library (`tensegrity_statics::sensitivity`). Arrays
//! cross as raw f64 bytes or lists, which `tensegrity.stiffness_sensitivity` and
//! `tensegrity.margin_sensitivity` view as numpy arrays. No mathematics here.

use crate::errors::Failure;
use nalgebra::Vector3;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use tensegrity_core::request::{Categorized, Category, Request};
use tensegrity_core::Structure;
use tensegrity_engine::scene::SceneError;
use tensegrity_engine::statics::StaticsCommand;
use tensegrity_statics::sensitivity::{
    natural_frequencies, prestress_margin, smallest_stiffness_eigenvalue, EigenDerivative,
    EquilibriumState, MarginSmoothness,
};

fn failure(e: &SceneError) -> PyErr {
    Python::attach(|py| Failure::new(e.category(), e.to_string()).into_pyerr(py))
}

/// The structure of the scene of `values` (`{"scene": …}`, as `statics` takes it).
fn structure(py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<Structure> {
    let values = crate::convert::named(values).map_err(|f| f.into_pyerr(py))?;
    let command =
        StaticsCommand::from_values(values).map_err(|e| Failure::invalid(&e).into_pyerr(py))?;
    let Some(scene) = command.scene.as_ref() else {
        return Err(Failure::new(Category::Input, "scene: give a scene").into_pyerr(py));
    };
    let scene = scene.load().map_err(|e| failure(&SceneError::Io(e)))?;
    Ok(scene.structure)
}

fn raw<'py>(py: Python<'py>, v: &[Vector3<f64>]) -> Bound<'py, PyBytes> {
    let bytes: Vec<u8> = v
        .iter()
        .flat_map(|p| [p.x, p.y, p.z])
        .flat_map(|x| x.to_ne_bytes())
        .collect();
    PyBytes::new(py, &bytes)
}

/// value, multiplicity, d/dq, d/da, d/dα, d/dx (raw, n × 3; empty when repeated).
type Eigen<'py> = (
    f64,
    usize,
    Vec<f64>,
    Vec<f64>,
    Option<f64>,
    Bound<'py, PyBytes>,
);

fn eigen<'py>(py: Python<'py>, d: &EigenDerivative) -> Eigen<'py> {
    (
        d.value,
        d.multiplicity,
        d.force_densities.clone(),
        d.axial_stiffnesses.clone(),
        d.prestress_level,
        raw(py, &d.nodes),
    )
}

/// The force densities, the axial stiffnesses, the smallest nonzero eigenvalue, the `modes`
/// lowest nonzero natural frequencies, the balance residual (N) and the warnings.
type Stiffness<'py> = (
    Vec<f64>,
    Vec<f64>,
    Option<Eigen<'py>>,
    Vec<Eigen<'py>>,
    f64,
    Vec<String>,
);

/// The derivatives of the smallest nonzero eigenvalue of a scene's tangent stiffness and of
/// its `modes` lowest nonzero natural frequencies, about the library's
/// [`EquilibriumState`] (with its warning when that state is out of balance).
#[pyfunction]
pub fn stiffness_sensitivity<'py>(
    py: Python<'py>,
    values: &Bound<'_, PyDict>,
    modes: usize,
) -> PyResult<Stiffness<'py>> {
    let s = structure(py, values)?;
    let core = |e| failure(&SceneError::Core(e));
    let state = EquilibriumState::of(&s).map_err(core)?;
    let (q, axial) = (&state.force_densities, &state.axial_stiffnesses);
    let smallest = smallest_stiffness_eigenvalue(&s, q, axial).map_err(core)?;
    let frequencies = if modes > 0 {
        natural_frequencies(&s, q, axial).map_err(core)?
    } else {
        Vec::new()
    };
    Ok((
        q.iter().copied().collect(),
        axial.clone(),
        smallest.as_ref().map(|d| eigen(py, d)),
        frequencies
            .iter()
            .filter(|f| f.value > 0.0)
            .take(modes)
            .map(|f| eigen(py, f))
            .collect(),
        state.residual,
        state.warning().into_iter().collect(),
    ))
}

/// margin, smoothness, its numbers (at_margin/at_bound/unknowns, mechanisms/coupling or
/// directions), stress, at_margin, at_bound, d/dx (raw; empty when not differentiable),
/// d/dα, d/da.
type Margin<'py> = (
    f64,
    &'static str,
    Vec<f64>,
    Vec<f64>,
    Vec<usize>,
    Vec<usize>,
    Bound<'py, PyBytes>,
    f64,
    Vec<f64>,
);

/// The prestress margin of a scene and its derivatives (the Rust crate
/// `tensegrity-statics`, module `sensitivity::margin`).
#[pyfunction]
pub fn margin_sensitivity<'py>(
    py: Python<'py>,
    values: &Bound<'_, PyDict>,
) -> PyResult<Margin<'py>> {
    let s = structure(py, values)?;
    let d = prestress_margin(&s).map_err(|e| failure(&SceneError::Core(e)))?;
    let (kind, numbers) = match &d.smoothness {
        MarginSmoothness::Differentiable => ("differentiable", vec![]),
        MarginSmoothness::NoSelfStress => ("no_self_stress", vec![]),
        MarginSmoothness::AtZero => ("at_zero", vec![]),
        MarginSmoothness::Tie {
            at_margin,
            at_bound,
            unknowns,
        } => (
            "tie",
            vec![*at_margin as f64, *at_bound as f64, *unknowns as f64],
        ),
        MarginSmoothness::NotUnique { directions } => ("not_unique", vec![*directions as f64]),
        MarginSmoothness::SpecialGeometry {
            mechanisms,
            coupling,
        } => ("special_geometry", vec![*mechanisms as f64, *coupling]),
    };
    Ok((
        d.margin,
        kind,
        numbers,
        d.stress.iter().copied().collect(),
        d.at_margin.clone(),
        d.at_bound.clone(),
        raw(py, &d.nodes),
        d.prestress_level,
        d.axial_stiffnesses.clone(),
    ))
}
