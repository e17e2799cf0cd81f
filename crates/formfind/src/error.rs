//! Errors of the formfind crate: one enum, structured fields, the core's errors wrapped.

use tensegrity_core::request::{Categorized, Category, InvalidParameter};
use tensegrity_core::CoreError;
use thiserror::Error;

/// Result alias of the formfind crate.
pub type Result<T, E = FormFindError> = std::result::Result<T, E>;

/// Everything that can go wrong when finding a form.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum FormFindError {
    /// A parameter out of its range (a negative stiffness, a prestress of zero, …).
    #[error("{0}")]
    InvalidParameter(#[from] InvalidParameter),
    /// The topology is malformed: `item` names the member, node, group or fixed node.
    #[error("{item}: {reason}")]
    InvalidTopology {
        /// The offending item (`bars[3]`, `strings[0].group`, `fixed[1]`, …).
        item: String,
        /// What is wrong with it.
        reason: String,
    },
    /// An unknown built-in topology name.
    #[error("unknown built-in topology \"{name}\" ({known})")]
    UnknownBuiltin {
        /// The name asked for.
        name: String,
        /// The names and forms that exist.
        known: String,
    },
    /// The force densities give no geometry of the required rank deficiency.
    #[error(
        "the force density matrix has rank deficiency {found}, {required} is required: {hint}"
    )]
    RankDeficiency {
        /// The rank deficiency of D found.
        found: usize,
        /// The rank deficiency required (d + 1 = 4 in 3-D for a free-standing structure).
        required: usize,
        /// What to change.
        hint: String,
    },
    /// A linear system of the method is singular (fixed nodes that do not determine the free
    /// ones, a dynamic relaxation without stiffness, …).
    #[error("singular system: {hint}")]
    SingularSystem {
        /// What is singular and what to change.
        hint: String,
    },
    /// No prestressable (or prestress-stable) self-stress exists for this connectivity.
    #[error("no prestressable self-stress found: {reason}")]
    NoPrestress {
        /// Why (margin, eigenvalues, iterations).
        reason: String,
    },
    /// An iteration did not converge.
    #[error("{method} did not converge in {iterations} iterations (residual {residual:e}, tolerance {tolerance:e})")]
    NotConverged {
        /// The method (`adaptive`, `dr`).
        method: String,
        /// Iterations done.
        iterations: usize,
        /// The residual reached.
        residual: f64,
        /// The tolerance it had to reach (for `dr` the effective one, module `dr`).
        tolerance: f64,
    },
    /// A number of the computation overflowed (or came out NaN); the parameters were
    /// finite, so the method diverged.
    #[error("{method}: {item} came out non-finite (an overflow): scale the force densities, stiffnesses or lengths towards 1")]
    NonFinite {
        /// The method (`fdm`, `adaptive`, `dr`).
        method: String,
        /// What overflowed (`node 3`, `strings[2].force_density`, `the residual`).
        item: String,
    },
    /// Something this crate does not do.
    #[error("not supported: {what}")]
    Unsupported {
        /// What was asked.
        what: String,
    },
    /// An error of the core analyses.
    #[error(transparent)]
    Core(#[from] CoreError),
}

impl From<tensegrity_linalg::LinalgError> for FormFindError {
    fn from(e: tensegrity_linalg::LinalgError) -> Self {
        Self::Core(e.into())
    }
}

impl Categorized for FormFindError {
    /// Bad parameters, topologies and names are bad input; a search that finds no form is a
    /// failed computation; a core error keeps its own category.
    fn category(&self) -> Category {
        match self {
            Self::InvalidParameter(_)
            | Self::InvalidTopology { .. }
            | Self::UnknownBuiltin { .. }
            | Self::Unsupported { .. } => Category::Input,
            Self::RankDeficiency { .. }
            | Self::SingularSystem { .. }
            | Self::NoPrestress { .. }
            | Self::NotConverged { .. }
            | Self::NonFinite { .. } => Category::Numerical,
            Self::Core(e) => e.category(),
        }
    }
}
