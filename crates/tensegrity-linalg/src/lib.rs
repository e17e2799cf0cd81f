//! # tensegrity-linalg
//!
//! Linear algebra: every dense and sparse factorisation of the workspace, and the only crate
//! that imports faer.
//!
//! faer changes its API with each minor release; it is pinned in the workspace manifest and
//! kept behind this module, whose functions take and return nalgebra matrices, plain slices
//! and the small sparse types of [`sparse`] (never a faer type). Its errors are converted in
//! one place (this crate's private `failed`) into a [`LinalgError`] with a
//! [`FactorizationFailure`] reason.
//!
//! # Layout
//!
//! - [`dense`]: the SVD A = U Σ Vᵀ ([`svd()`], [`orthonormal_basis`]), the symmetric
//!   eigendecomposition A = Q Λ Qᵀ ([`symmetric_eigen`]) and an in-place dense Cholesky
//!   A = L Lᵀ for small SPD systems given in sparse form ([`DenseCholesky`]) and an in-place
//!   dense LU P A = L U with partial pivoting ([`DenseLu`], the implicit integrator's Newton
//!   matrix);
//! - [`sparse`]: compressed-column storage ([`CscPattern`], [`CscMatrix`]), the fill-reducing
//!   ordering ([`amd_ordering`]), sparse Cholesky A = L Lᵀ with symbolic reuse (the in-house
//!   [`StaticCholesky`] with a precomputed schedule, and the general [`SparseCholesky`]) and
//!   sparse LU with partial pivoting P A Q = L U ([`SparseLu`], [`lu_solve`]);
//! - [`complex`]: the complex SVD A = U Σ Vᴴ of the small per-representation blocks of the
//!   symmetry-adapted statics ([`complex_svd`], [`complex_singular_values`]).
//!
//! Where a factorisation is repeated with a fixed pattern (the Ω system of the dynamics is
//! refactored every step), the symbolic analysis is done once by a constructor and the numeric
//! `factor` / `solve_in_place` calls work in preallocated storage, without allocating. One-shot
//! callers use the allocating functions ([`svd()`], [`lu_solve`], [`cholesky_solve`]).
//!
//! # Rank tolerance
//!
//! Rank decisions use [`rank_tolerance`]: a singular value σ counts as zero when
//! σ ≤ max(m, n) · ε · σ_max (the MATLAB/NumPy convention), unless the caller supplies its own
//! relative tolerance r, in which case σ ≤ r · σ_max. Rank, null spaces and least squares come
//! from the SVD (never from a QR-based least-squares solve, which is unsafe on rank-deficient
//! equilibrium matrices).
//!
//! # Threads
//!
//! faer runs sequentially (`Par::Seq`, and its `rayon` feature is off): parallelism belongs to
//! the parameter sweeps that call these kernels.

#![warn(missing_docs)]
#![allow(non_snake_case)]

pub mod complex;
pub mod dense;
pub mod error;
pub mod sparse;

pub use complex::{complex_singular_values, complex_svd, ComplexSvd};
pub use dense::{
    orthonormal_basis, rank_tolerance, svd, symmetric_eigen, DenseCholesky, DenseLu, Svd,
};
pub use error::{FactorizationFailure, LinalgError, Result};
pub use sparse::{
    amd_ordering, cholesky_solve, lu_solve, Block3Cholesky, CscMatrix, CscPattern, FrontalQr,
    RankRevealingQr, SparseCholesky, SparseLu, StaticCholesky,
};

/// A faer error that can be stated as a [`FactorizationFailure`].
trait FaerFailure {
    /// The reason, for a matrix of order `dim`.
    fn reason(self, dim: usize) -> FactorizationFailure;
}

impl FaerFailure for faer::linalg::svd::SvdError {
    fn reason(self, _dim: usize) -> FactorizationFailure {
        FactorizationFailure::NoConvergence
    }
}

impl FaerFailure for faer::linalg::evd::EvdError {
    fn reason(self, _dim: usize) -> FactorizationFailure {
        FactorizationFailure::NoConvergence
    }
}

impl FaerFailure for faer::sparse::FaerError {
    fn reason(self, _dim: usize) -> FactorizationFailure {
        match self {
            faer::sparse::FaerError::IndexOverflow => FactorizationFailure::IndexOverflow,
            _ => FactorizationFailure::OutOfMemory,
        }
    }
}

impl FaerFailure for faer::dyn_stack::mem::AllocError {
    fn reason(self, _dim: usize) -> FactorizationFailure {
        FactorizationFailure::OutOfMemory
    }
}

impl FaerFailure for faer::linalg::cholesky::llt::factor::LltError {
    fn reason(self, dim: usize) -> FactorizationFailure {
        let faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } = self;
        FactorizationFailure::NonPositivePivot { pivot: index, dim }
    }
}

impl FaerFailure for faer::sparse::linalg::LuError {
    fn reason(self, dim: usize) -> FactorizationFailure {
        match self {
            faer::sparse::linalg::LuError::SymbolicSingular { index } => {
                FactorizationFailure::StructurallySingular { step: index, dim }
            }
            faer::sparse::linalg::LuError::Generic(e) => e.reason(dim),
        }
    }
}

/// The one conversion of faer's errors: `map_err(failed("sparse LU (numeric)", n))`.
fn failed<E: FaerFailure>(operation: &'static str, dim: usize) -> impl FnOnce(E) -> LinalgError {
    move |e| LinalgError {
        operation,
        reason: e.reason(dim),
    }
}

/// A failure of an in-house kernel (no faer error involved).
fn failure(operation: &'static str, reason: FactorizationFailure) -> LinalgError {
    LinalgError { operation, reason }
}

/// The README's examples, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
