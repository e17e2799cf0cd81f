//! Found forms' exact derivatives in Python: `_native.FormSensitivity` (the force density
//! method) and `_native.RelaxedSensitivity` (dynamic relaxation), built from `formfind`'s
//! values (a topology with held nodes) by the engine
//! ([`tensegrity_engine::formfind::FormfindRequest::sensitivity`] and `relaxed_sensitivity`),
//! differentiated by the library (`formfind::sensitivity`); every vector crosses as raw f64
//! bytes, which the Python classes `tensegrity.FormSensitivity` and
//! `tensegrity.RelaxedSensitivity` view as numpy arrays. No mathematics here.

use crate::errors::Failure;
use nalgebra::Vector3;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use tensegrity_core::request::{Categorized, Category, Request};
use tensegrity_engine::formfind::sensitivity::{
    Cotangent, DrParameter, DrSensitivity, FdmSensitivity, Parameter,
};
use tensegrity_engine::formfind::FormfindRequest;

fn failure(e: &impl std::fmt::Display, category: Category) -> PyErr {
    Python::attach(|py| Failure::new(category, e.to_string()).into_pyerr(py))
}

/// Raw f64 bytes of 3-vectors (x, y, z each).
fn vectors<'py>(py: Python<'py>, v: &[Vector3<f64>]) -> Bound<'py, PyBytes> {
    let raw: Vec<u8> = v
        .iter()
        .flat_map(|p| [p.x, p.y, p.z])
        .flat_map(|x| x.to_ne_bytes())
        .collect();
    PyBytes::new(py, &raw)
}

/// `formfind`'s request of Python's `values` (a bad value: the input error naming it).
fn request(py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<FormfindRequest> {
    let values = crate::convert::named(values).map_err(|f| f.into_pyerr(py))?;
    FormfindRequest::from_values(values).map_err(|e| Failure::invalid(&e).into_pyerr(py))
}

/// A flat list of node derivatives (3 per node) as vectors; another length is the input
/// error naming `dnodes`.
fn node_vectors(dnodes: &[f64]) -> PyResult<Vec<Vector3<f64>>> {
    if !dnodes.len().is_multiple_of(3) {
        return Err(failure(
            &format!("dnodes: {} numbers is not 3 per node", dnodes.len()),
            Category::Input,
        ));
    }
    Ok(dnodes
        .chunks(3)
        .map(|c| Vector3::new(c[0], c[1], c[2]))
        .collect())
}

/// A force density form with held nodes, factored for its derivatives
/// (`tensegrity.FormSensitivity` wraps it).
#[pyclass(unsendable, module = "tensegrity._native", name = "FormSensitivity")]
pub struct PyFormSensitivity {
    inner: FdmSensitivity,
}

/// Three raw f64 byte strings (nodes, then reactions) and two lists (lengths, forces).
type Derivative<'py> = (Bound<'py, PyBytes>, Vec<f64>, Vec<f64>, Bound<'py, PyBytes>);

#[pymethods]
impl PyFormSensitivity {
    /// The form of `formfind`'s values (`topology` or `builtin`, `group`, `ratio`).
    #[new]
    fn new(py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<Self> {
        let inner = request(py, values)?
            .sensitivity()
            .map_err(|e| failure(&e, e.category()))?;
        Ok(Self { inner })
    }

    /// The number of nodes.
    #[getter]
    fn n_nodes(&self) -> usize {
        self.inner.nodes().len()
    }

    /// The held nodes, in the topology's `fixed` order.
    #[getter]
    fn held(&self) -> Vec<usize> {
        self.inner.held().to_vec()
    }

    /// The force densities (bars then strings).
    #[getter]
    fn force_densities(&self) -> Vec<f64> {
        self.inner.force_densities().to_vec()
    }

    /// The form: nodes (raw f64, 3n), member lengths, member forces, reactions (raw f64,
    /// 3 per held node).
    fn form<'py>(&self, py: Python<'py>) -> Derivative<'py> {
        (
            vectors(py, self.inner.nodes()),
            self.inner.lengths(),
            self.inner.forces(),
            vectors(py, &self.inner.reactions()),
        )
    }

    /// The derivative with respect to one parameter: `kind` "force_density" (`index` the
    /// member), "load" (`index` the node, `axis` 0–2) or "fixed" (`index` in `fixed`,
    /// `axis`); as [`PyFormSensitivity::form`].
    #[pyo3(signature = (kind, index, axis = 0))]
    fn forward<'py>(
        &mut self,
        py: Python<'py>,
        kind: &str,
        index: usize,
        axis: usize,
    ) -> PyResult<Derivative<'py>> {
        let parameter = match kind {
            "force_density" => Parameter::ForceDensity(index),
            "load" => Parameter::Load { node: index, axis },
            "fixed" => Parameter::Fixed { index, axis },
            other => {
                return Err(failure(
                    &format!(
                        "parameter: {other:?} is not one of \"force_density\", \"load\", \"fixed\""
                    ),
                    Category::Input,
                ))
            }
        };
        let d = self
            .inner
            .forward(parameter)
            .map_err(|e| failure(&e, e.category()))?;
        Ok((
            vectors(py, &d.nodes),
            d.lengths,
            d.forces,
            vectors(py, &d.reactions),
        ))
    }

    /// The gradient of a scalar objective given its partial derivatives: `dnodes` (3n, by
    /// node) and `dforce_densities` (one per member, at fixed nodes): (df/dq, df/dp as raw
    /// f64 3n, df/dx_fixed as raw f64 3 per held node).
    fn adjoint<'py>(
        &mut self,
        py: Python<'py>,
        dnodes: Vec<f64>,
        dforce_densities: Vec<f64>,
    ) -> PyResult<(Vec<f64>, Bound<'py, PyBytes>, Bound<'py, PyBytes>)> {
        let df = Cotangent {
            nodes: node_vectors(&dnodes)?,
            force_densities: dforce_densities,
        };
        let g = self
            .inner
            .adjoint(&df)
            .map_err(|e| failure(&e, e.category()))?;
        Ok((
            g.force_densities,
            vectors(py, &g.loads),
            vectors(py, &g.fixed),
        ))
    }
}

/// Dynamic relaxation's form with held nodes, factored for its derivatives
/// (`tensegrity.RelaxedSensitivity` wraps it).
#[pyclass(unsendable, module = "tensegrity._native", name = "RelaxedSensitivity")]
pub struct PyRelaxedSensitivity {
    inner: DrSensitivity,
}

#[pymethods]
impl PyRelaxedSensitivity {
    /// The relaxed form of `formfind`'s values (`topology` or `builtin`, `stiffness`,
    /// `tolerance`, `max_iterations`).
    #[new]
    fn new(py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<Self> {
        let inner = request(py, values)?
            .relaxed_sensitivity()
            .map_err(|e| failure(&e, e.category()))?;
        Ok(Self { inner })
    }

    /// The number of nodes.
    #[getter]
    fn n_nodes(&self) -> usize {
        self.inner.nodes().len()
    }

    /// The form: nodes (raw f64, 3n) and the members' tensions (N).
    fn form<'py>(&self, py: Python<'py>) -> (Bound<'py, PyBytes>, Vec<f64>) {
        (
            vectors(py, self.inner.nodes()),
            self.inner.tensions().to_vec(),
        )
    }

    /// The derivatives of the nodes (raw f64, 3n) and tensions with respect to one
    /// parameter: `kind` "rest_length" or "stiffness" of member `index`.
    fn forward<'py>(
        &mut self,
        py: Python<'py>,
        kind: &str,
        index: usize,
    ) -> PyResult<(Bound<'py, PyBytes>, Vec<f64>)> {
        let parameter = match kind {
            "rest_length" => DrParameter::RestLength(index),
            "stiffness" => DrParameter::Stiffness(index),
            other => {
                return Err(failure(
                    &format!("parameter: {other:?} is not one of \"rest_length\", \"stiffness\""),
                    Category::Input,
                ))
            }
        };
        let d = self
            .inner
            .forward(parameter)
            .map_err(|e| failure(&e, e.category()))?;
        Ok((vectors(py, &d.nodes), d.tensions))
    }

    /// The gradient of a scalar objective of the nodes from its partial derivatives
    /// `dnodes` (3n, by node): (df/ds0, df/dEA), one per member.
    fn adjoint(&mut self, dnodes: Vec<f64>) -> PyResult<(Vec<f64>, Vec<f64>)> {
        let dnodes = node_vectors(&dnodes)?;
        let g = self
            .inner
            .adjoint(&dnodes)
            .map_err(|e| failure(&e, e.category()))?;
        Ok((g.rest_lengths, g.stiffnesses))
    }
}

/// A design problem (`design`'s file: a topology with a `[design]` table) compiled for its
/// objective and exact gradient at any force densities (`tensegrity.DesignProblem` wraps it):
/// the engine reads the file ([`tensegrity_engine::design::DesignRequest::problem`]), the
/// library evaluates (`formfind::design::DesignProblem`).
#[pyclass(unsendable, module = "tensegrity._native", name = "DesignProblem")]
pub struct PyDesignProblem {
    inner: tensegrity_engine::formfind::design::DesignProblem,
}

#[pymethods]
impl PyDesignProblem {
    /// The problem of `design`'s values (`design`: the file or its TOML text).
    #[new]
    fn new(py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<Self> {
        use tensegrity_engine::design::DesignRequest;
        let values = crate::convert::named(values).map_err(|f| f.into_pyerr(py))?;
        let request =
            DesignRequest::from_values(values).map_err(|e| Failure::invalid(&e).into_pyerr(py))?;
        let (topology, spec, _) = request.problem().map_err(|e| failure(&e, e.category()))?;
        let inner = tensegrity_engine::formfind::design::DesignProblem::new(&topology, &spec)
            .map_err(|e| failure(&e, e.category()))?;
        Ok(Self { inner })
    }

    /// The variables' start values, lower and upper bounds (±inf for none), and the members
    /// each sets.
    fn variables(&self) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<Vec<usize>>) {
        (
            self.inner.start(),
            self.inner.lower(),
            self.inner.upper(),
            self.inner.members(),
        )
    }

    /// The objective, its gradient and each term's value at `values`.
    fn objective(&self, values: Vec<f64>) -> PyResult<(f64, Vec<f64>, Vec<f64>)> {
        self.inner
            .objective_with_terms(&values)
            .map_err(|e| failure(&e, e.category()))
    }

    /// The residuals at `values` and their Jacobian (raw, residuals × variables, row-major).
    fn residuals<'py>(
        &self,
        py: Python<'py>,
        values: Vec<f64>,
    ) -> PyResult<(Vec<f64>, Bound<'py, PyBytes>)> {
        let (r, j) = self
            .inner
            .residuals(&values)
            .map_err(|e| failure(&e, e.category()))?;
        let bytes: Vec<u8> = (0..j.nrows())
            .flat_map(|i| (0..j.ncols()).map(move |c| (i, c)))
            .flat_map(|(i, c)| j[(i, c)].to_ne_bytes())
            .collect();
        Ok((r, PyBytes::new(py, &bytes)))
    }
}
