//! The error type of the core crate, [`CoreError`], split by concern: one enum per concern
//! in its own file, each wrapped by a variant of [`CoreError`] with `#[from]`, so `?` works on
//! any of them and a construction reads `DynamicsError::NoBars.into()`.
//!
//! | concern | enum | category |
//! |---|---|---|
//! | the structure: nodes, members, supports, materials, what an analysis needs | [`ModelError`] | input |
//! | statics without an answer (load not carried, sizing), symmetry descriptors | [`StaticsError`] | numerical (descriptors: input) |
//! | dynamics: model set-up, then the run (step, blow-up, divergence) | [`DynamicsError`] | input, then numerical |
//! | numerical kernels: factorisations, convergence, the LP solver | [`NumericsError`] | numerical (allocation: resource) |
//! | a bad parameter value | [`InvalidParameter`] | input |
//! | a problem above the memory budget ([`CoreError::TooLarge`]) | — | resource |
//! | an analysis a back-end does not offer ([`CoreError::Unsupported`]) | — | input |
//! | a run stopped by its sink ([`CoreError::Interrupted`]) | — | interrupted |
//!
//! Every variant carries structured fields naming the offending item, so a caller can both
//! print a clear message and react programmatically; every enum is [`Categorized`], so a front
//! end decides its reaction (the CLI's exit code) from the [`Category`] alone. The enums are
//! `#[non_exhaustive]`: other crates match them with a wildcard arm, so that new conditions
//! can be added without breaking them. Messages name the library's own parameters, in backticks
//! (`` `dt` ``, `` `integrator = rk45` ``), never a front end's spelling of them; a front end
//! may rewrite them (the CLI writes `--dt`, `--integrator rk45`).

mod dynamics;
mod model;
mod numerics;
mod statics;
mod symmetry;

pub use crate::number::short_number;
pub use dynamics::{DynamicsError, StepHint};
pub use model::ModelError;
pub use numerics::{FactorizationFailure, NumericsError};
pub use statics::{node_list, StaticsError};
pub use symmetry::SymmetryError;

use crate::request::{Categorized, Category, InvalidParameter};
use thiserror::Error;

/// Result alias used throughout the core.
pub type Result<T, E = CoreError> = std::result::Result<T, E>;

/// Everything that can go wrong when building, analysing or simulating a structure: one
/// variant per concern, each its own enum (module docs).
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum CoreError {
    /// An invalid structure, or one lacking what an analysis needs.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A statics analysis without an answer (a load not carried, sizing a compressed
    /// string), or a symmetry descriptor that does not fit.
    #[error(transparent)]
    Statics(#[from] StaticsError),
    /// A dynamics model that cannot be set up, or a run that failed on the way.
    #[error(transparent)]
    Dynamics(#[from] DynamicsError),
    /// A numerical kernel that failed: a factorisation, a convergence, the LP solver.
    #[error(transparent)]
    Numerics(#[from] NumericsError),
    /// An invalid analysis parameter.
    #[error("{0}")]
    InvalidParameter(#[from] InvalidParameter),
    /// A problem too large for the memory budget, refused before allocating.
    #[error("{what} ({rows} × {cols}) needs about {:.1} GiB, above the limit of {:.1} GiB: use a smaller structure (e.g. fewer `sides` or a lower `complexity`)", bytes / 1073741824.0, limit / 1073741824.0)]
    TooLarge {
        /// The computation refused.
        what: &'static str,
        /// Rows of the matrix.
        rows: usize,
        /// Columns of the matrix.
        cols: usize,
        /// Estimated peak memory (bytes).
        bytes: f64,
        /// The budget (bytes).
        limit: f64,
    },
    /// A computation whose cost, estimated once part of it ran (e.g. the sparse statics once
    /// its rank is known), is above a limit of its settings; refused before the rest runs.
    #[error(transparent)]
    OverBudget(Box<crate::budget::OverBudget>),
    /// A statics back-end was asked for something it does not compute (e.g. the load solve of
    /// the cyclic back-end, whose loads need not be symmetric).
    #[error("{analysis} is not available from the {backend} statics")]
    Unsupported {
        /// What was asked, e.g. `the load solve`.
        analysis: &'static str,
        /// The back-end, e.g. `cyclic (symmetry-adapted blocks)`.
        backend: &'static str,
    },
    /// The run was interrupted (a sample sink asked to stop, e.g. on Ctrl-C).
    #[error("interrupted at t = {t:?} s")]
    Interrupted {
        /// Time of the last sample handed out (s).
        t: f64,
    },
}

impl Categorized for CoreError {
    fn category(&self) -> Category {
        match self {
            Self::Model(e) => e.category(),
            Self::Statics(e) => e.category(),
            Self::Dynamics(e) => e.category(),
            Self::Numerics(e) => e.category(),
            Self::InvalidParameter(e) => e.category(),
            Self::TooLarge { .. } | Self::OverBudget(_) => Category::Resource,
            Self::Unsupported { .. } => Category::Input,
            Self::Interrupted { .. } => Category::Interrupted,
        }
    }
}

impl CoreError {
    /// Shorthand for [`CoreError::InvalidParameter`].
    ///
    /// ```
    /// use tensegrity_core::CoreError;
    /// let e = CoreError::invalid_parameter("dt", -1.0, "must be positive and finite");
    /// assert_eq!(e.to_string(), "dt = -1: must be positive and finite");
    /// ```
    pub fn invalid_parameter(name: &'static str, value: f64, reason: impl Into<String>) -> Self {
        Self::InvalidParameter(crate::request::InvalidParameter::new(name, value, reason))
    }
}

impl From<SymmetryError> for CoreError {
    fn from(e: SymmetryError) -> Self {
        Self::Statics(e.into())
    }
}

impl From<tensegrity_linalg::LinalgError> for NumericsError {
    fn from(e: tensegrity_linalg::LinalgError) -> Self {
        Self::Factorization {
            operation: e.operation,
            reason: e.reason,
        }
    }
}

impl From<tensegrity_linalg::LinalgError> for CoreError {
    fn from(e: tensegrity_linalg::LinalgError) -> Self {
        Self::Numerics(e.into())
    }
}
