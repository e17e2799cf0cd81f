//! The stepped simulation in Python: `_native.Stepper`, built from `simulate`'s values (the
//! scene, as a path, text or a `Structure`'s data, and its overrides) by the engine
//! ([`tensegrity_engine::simulate::stepped`]), stepped with actions as floats, observed as
//! one buffer of raw f64 (the Python class `tensegrity.Simulator` views it as numpy arrays
//! without copying it again). No physics here.

use crate::errors::Failure;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use tensegrity_core::request::{Categorized, Category, Request};
use tensegrity_dynamics::{Action, ActuatorTarget, Stepper, StepperState};
use tensegrity_engine::simulate::{stepped, SimulateCommand};

fn failure(e: &impl std::fmt::Display, category: Category) -> PyErr {
    Python::attach(|py| Failure::new(category, e.to_string()).into_pyerr(py))
}

fn core(e: tensegrity_core::CoreError) -> PyErr {
    failure(&e, e.category())
}

/// A rigid-bar simulation advanced one control period at a time (`tensegrity.Simulator`
/// wraps it).
#[pyclass(unsendable, module = "tensegrity._native", name = "Stepper")]
pub struct PyStepper {
    inner: Stepper,
    n_nodes: usize,
}

/// A saved state of a `Stepper`.
#[pyclass(
    unsendable,
    module = "tensegrity._native",
    name = "StepperState",
    frozen
)]
pub struct PyStepperState(StepperState);

#[pymethods]
impl PyStepperState {
    /// Time (s).
    #[getter]
    fn t(&self) -> f64 {
        self.0.t
    }

    /// The actuators' rest lengths (m).
    #[getter]
    fn rest_lengths(&self) -> Vec<f64> {
        self.0.rest_lengths.clone()
    }
}

#[pymethods]
impl PyStepper {
    /// A stepped simulation of `simulate`'s values (`scene` and its overrides).
    #[new]
    fn new(py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<Self> {
        let values = crate::convert::named(values).map_err(|f| f.into_pyerr(py))?;
        let command = SimulateCommand::from_values(values)
            .map_err(|e| Failure::invalid(&e).into_pyerr(py))?;
        let (scene, inner) = stepped::stepper(&command)
            .map_err(|e| Failure::new(e.category(), e.to_string()).into_pyerr(py))?;
        Ok(Self {
            inner,
            n_nodes: scene.structure.n_nodes(),
        })
    }

    /// Back to t = 0, turned by `angle` (rad) about the vertical when given.
    #[pyo3(signature = (angle = None))]
    fn reset(&mut self, angle: Option<f64>) -> PyResult<()> {
        match angle {
            Some(a) => self.inner.reset_turned(a),
            None => self.inner.reset(),
        }
        .map_err(core)
    }

    /// One period of `n_steps` ticks: `mode` "hold", "rest_lengths" or "rates".
    fn step(&mut self, mode: &str, values: Vec<f64>, n_steps: u64) -> PyResult<()> {
        let action = match mode {
            "hold" => Action::Hold,
            "rest_lengths" => Action::RestLengths(&values),
            "rates" => Action::Rates(&values),
            other => {
                return Err(failure(
                    &format!("mode: {other:?} is not one of \"rest_lengths\", \"rates\", \"hold\""),
                    Category::Input,
                ))
            }
        };
        self.inner.step(action, n_steps).map_err(core)
    }

    /// The observation as raw f64: nodes (3n), velocities (3n), member forces (bars,
    /// strings, clusters), contact forces (3n), rest lengths (one per actuator), kinetic and
    /// total energy.
    fn observe<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let forces = self.inner.member_forces().map_err(core)?;
        let contact = self.inner.contact_forces();
        let (ke, e) = self.inner.energy();
        let mut out: Vec<f64> = Vec::with_capacity(9 * self.n_nodes + forces.len() + 8);
        out.extend(self.inner.nodes().iter().flat_map(|p| [p.x, p.y, p.z]));
        out.extend(self.inner.velocities().iter().flat_map(|p| [p.x, p.y, p.z]));
        out.extend(&forces);
        out.extend(contact.iter().flat_map(|p| [p.x, p.y, p.z]));
        out.extend(self.inner.rest_lengths());
        out.extend([ke, e]);
        let bytes: Vec<u8> = out.iter().flat_map(|x| x.to_ne_bytes()).collect();
        Ok(PyBytes::new(py, &bytes))
    }

    /// The node positions alone as raw f64 (3n): the cheap observation.
    fn nodes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let bytes: Vec<u8> = self
            .inner
            .nodes()
            .iter()
            .flat_map(|p| [p.x, p.y, p.z])
            .flat_map(|x| x.to_ne_bytes())
            .collect();
        PyBytes::new(py, &bytes)
    }

    /// The current state.
    fn get_state(&mut self) -> PyStepperState {
        PyStepperState(self.inner.state())
    }

    /// Restores a state of this simulation.
    fn set_state(&mut self, state: &PyStepperState) -> PyResult<()> {
        self.inner.set_state(&state.0).map_err(core)
    }

    /// Time (s).
    #[getter]
    fn t(&self) -> f64 {
        self.inner.time()
    }

    /// The control tick (s).
    #[getter]
    fn dt(&self) -> f64 {
        self.inner.dt()
    }

    /// Node count.
    #[getter]
    fn n_nodes(&self) -> usize {
        self.n_nodes
    }

    /// The actuators: (kind "string" or "cluster", index, min_length, max_length, max_rate).
    #[getter]
    fn actuators(&self) -> Vec<(&'static str, usize, f64, f64, f64)> {
        self.inner
            .actuators()
            .iter()
            .map(|a| {
                let (kind, k) = match a.target {
                    ActuatorTarget::String(k) => ("string", k),
                    ActuatorTarget::Cluster(k) => ("cluster", k),
                };
                (kind, k, a.min_length, a.max_length, a.max_rate)
            })
            .collect()
    }

    /// The drift warnings since the last reset, as text.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.inner
            .warnings()
            .iter()
            .map(|w| w.to_string())
            .collect()
    }

    /// Accepted steps, rejected steps and right-hand-side evaluations since the last reset.
    #[getter]
    fn stats(&self) -> (u64, u64, u64) {
        let s = self.inner.stats();
        (s.steps, s.rejected_steps, s.rhs_evals)
    }
}
