//! Exact derivatives of found forms (issue 47, items 1 and 6): with held nodes, the form is
//! the solution X of an equilibrium R(X, θ) = 0 of the free nodes, and the implicit function
//! theorem gives its derivative with respect to any parameter θ from one linear solve with
//! the Jacobian ∂R/∂X the form was found with:
//!
//! - the force density method ([`FdmSensitivity`], `fdm.rs`): R = D_ff X_f + D_fx X_x − P_f,
//!   parameters the force densities, the point loads and the held positions;
//! - dynamic relaxation's fixed point ([`DrSensitivity`], `dr.rs`): R the out-of-balance
//!   forces of members of rest length s0 and axial stiffness EA, parameters s0 and EA.
//!
//! Forward mode solves once per parameter, adjoint mode once per scalar objective whatever
//! the number of parameters. Each file's docs state its equations.

mod dr;
mod fdm;

use crate::error::FormFindError;

/// What the derivatives refuse, naming the topology's `item` (a missing held node, a cluster,
/// a load): the error both kinds of form return.
fn refused<T>(item: &str, reason: impl Into<String>) -> crate::error::Result<T> {
    Err(FormFindError::InvalidTopology {
        item: item.into(),
        reason: reason.into(),
    })
}

pub use dr::{DrDerivative, DrGradient, DrParameter, DrSensitivity};
pub use fdm::{Cotangent, FdmSensitivity, FormDerivative, FormGradient, Parameter};
