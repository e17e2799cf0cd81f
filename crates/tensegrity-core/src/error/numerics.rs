//! [`NumericsError`]: a numerical kernel that failed (a factorisation, an iteration that did
//! not converge, the LP solver), with [`FactorizationFailure`] saying why a factorisation did.

use crate::request::{Categorized, Category};
use thiserror::Error;

/// A failure of the numerical kernels (the factorisations of `tensegrity-linalg`), the
/// eigensolvers and the LP.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum NumericsError {
    /// A numerical kernel failed to converge.
    #[error("{operation} did not converge")]
    NoConvergence {
        /// The operation, e.g. `SVD of the equilibrium matrix`.
        operation: &'static str,
    },
    /// The optimisation solver failed.
    #[error("{problem}: the LP solver stopped with status {status}")]
    SolverFailed {
        /// The problem solved.
        problem: &'static str,
        /// The solver's status, as text.
        status: String,
    },
    /// A dense or sparse factorisation of `tensegrity-linalg` failed (its `LinalgError`).
    #[error("{operation} failed: {reason}")]
    Factorization {
        /// The factorisation, e.g. `SVD` or `sparse LU (numeric)`.
        operation: &'static str,
        /// Why it failed.
        reason: FactorizationFailure,
    },
}

impl Categorized for NumericsError {
    /// A workspace that could not be allocated (or indexed) is a problem too large
    /// ([`Category::Resource`]); every other failure is numerical.
    fn category(&self) -> Category {
        match self {
            Self::Factorization {
                reason: FactorizationFailure::OutOfMemory | FactorizationFailure::IndexOverflow,
                ..
            } => Category::Resource,
            _ => Category::Numerical,
        }
    }
}

pub use tensegrity_linalg::FactorizationFailure;
