//! Force propagation: member force densities and support reactions of a loaded truss, by the
//! recursive method of joints ([`crate::recursive`], default) or by one global sparse solve
//! ([`crate::global`], an independent check). This module is the one place that dispatches on
//! [`Method`]; neither solver imports the other.

use crate::error::Result;
use crate::global;
use crate::loads::NodalLoads;
use crate::recursive;
use crate::truss::MichellTruss;
use nalgebra::Vector3;

pub use crate::recursive::{propagate_recursive, SINGULAR_RTOL};
pub use crate::solution::{ForceSolution, Method};

/// Solves the member forces with the chosen method.
pub fn propagate(
    truss: &MichellTruss,
    loads: &NodalLoads,
    method: Method,
) -> Result<ForceSolution> {
    match method {
        Method::Recursive => recursive::propagate_recursive(truss, loads),
        Method::Global => global::solve_global(truss, loads),
    }
}

/// Force densities for unit tip loads along ι̂₁, ι̂₂, ι̂₃ (for a planar truss the first is all
/// zeros). By linearity the response to a tip load w is Σ_a w_a q^(a).
pub fn unit_tip_responses(truss: &MichellTruss, method: Method) -> Result<[Vec<f64>; 3]> {
    let solve = |e: Vector3<f64>| -> Result<Vec<f64>> {
        Ok(propagate(truss, &NodalLoads::tip(e), method)?.force_density)
    };
    let x = if truss.is_planar() {
        vec![0.0; truss.members().len()]
    } else {
        solve(Vector3::x())?
    };
    Ok([x, solve(Vector3::y())?, solve(Vector3::z())?])
}
