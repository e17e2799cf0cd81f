//! [`LinalgError`]: the one error of this crate, a factorisation that failed, with
//! [`FactorizationFailure`] saying why. The layers above wrap it in their own error (the core's
//! `NumericsError::Factorization` carries the same two fields).

use thiserror::Error;

/// Result alias of this crate.
pub type Result<T, E = LinalgError> = std::result::Result<T, E>;

/// A dense or sparse factorisation that failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Error)]
#[error("{operation} failed: {reason}")]
pub struct LinalgError {
    /// The factorisation, e.g. `SVD` or `sparse LU (numeric)`.
    pub operation: &'static str,
    /// Why it failed.
    pub reason: FactorizationFailure,
}

/// Why a factorisation failed (the reason of a [`LinalgError`]).
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
