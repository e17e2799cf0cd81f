//! [`NumericsError`]: a numerical kernel that failed (a factorisation, an iteration that did
//! not converge, the LP solver), with [`FactorizationFailure`] saying why a factorisation did.

use crate::request::{Categorized, Category};
use thiserror::Error;

/// A failure of the numerical kernels of [`crate::linalg`], the eigensolvers and the LP.
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
    /// A dense or sparse factorisation of [`crate::linalg`] failed.
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

/// Why a factorisation of [`crate::linalg`] failed (the reason of
/// [`NumericsError::Factorization`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum FactorizationFailure {
    /// An iterative kernel (SVD, eigensolver) reached its iteration limit.
    #[error("the iteration did not converge")]
    NoConvergence,
    /// A Cholesky pivot is zero, negative or NaN: the matrix is not (numerically) positive
    /// definite.
    #[error("pivot {pivot} of {dim} is not positive (matrix not positive definite)")]
    NonPositivePivot {
        /// Number of pivots that succeeded (0-based index of the failing one).
        pivot: usize,
        /// The order of the matrix.
        dim: usize,
    },
    /// No pivot could be found in a column: the matrix is structurally singular.
    #[error("no pivot in step {step} of {dim} (matrix structurally singular)")]
    StructurallySingular {
        /// The elimination step that found no pivot.
        step: usize,
        /// The order of the matrix.
        dim: usize,
    },
    /// A sparse entry lies outside the matrix.
    #[error("entry ({row}, {col}) lies outside the {nrows}×{ncols} matrix")]
    EntryOutOfBounds {
        /// Row of the entry.
        row: usize,
        /// Column of the entry.
        col: usize,
        /// Rows of the matrix.
        nrows: usize,
        /// Columns of the matrix.
        ncols: usize,
    },
    /// A compressed-column pattern is malformed: column pointers not non-decreasing, or the
    /// row indices of a column out of range or not strictly increasing.
    #[error("column {column} of the sparse pattern is malformed")]
    InvalidPattern {
        /// The first malformed column.
        column: usize,
    },
    /// A right-hand side or value array has the wrong length.
    #[error("expected {expected} values, got {found}")]
    DimensionMismatch {
        /// The required length.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// The workspace could not be allocated.
    #[error("out of memory")]
    OutOfMemory,
    /// A sparse index overflowed the index type.
    #[error("sparse index overflow")]
    IndexOverflow,
}
