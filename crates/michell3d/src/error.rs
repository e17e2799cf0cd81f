//! The error type of the crate: every failure names the offending parameter, node or item.

use tensegrity_core::request::{Categorized, Category};
use thiserror::Error;

/// Result alias of the crate.
pub type Result<T> = std::result::Result<T, MichellError>;

/// Everything that can go wrong when building, solving or sizing a Michell truss.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum MichellError {
    /// A user parameter is outside its valid range.
    #[error("{0}")]
    InvalidParameter(#[from] tensegrity_core::request::InvalidParameter),
    /// The three (or, in the plane, two) child members of a node are (nearly) linearly
    /// dependent, so the node equilibrium has no unique solution.
    #[error("node {node:?} is singular: its child members are linearly dependent (relative determinant {relative_det:.3e})")]
    SingularNode {
        /// The node tuple: `[U, D, L, R]`, or `[i, k]` for a planar truss.
        node: Vec<usize>,
        /// |det| divided by the product of the member lengths.
        relative_det: f64,
    },
    /// The operation needs a 3-D truss but was given a planar one.
    #[error("{what} need a 3-D truss: a planar truss carries only in-plane loads")]
    NeedsThreeD {
        /// What was asked for, e.g. `extra strings`.
        what: &'static str,
    },
    /// A load on a planar truss (y–z plane) has an out-of-plane component w_x.
    #[error("a planar truss (y–z plane) cannot carry the out-of-plane component w_x = {w_x} on node {node}; use azimuth = ±π/2 or polar = 0 or π")]
    OutOfPlaneLoad {
        /// The loaded node (index).
        node: usize,
        /// The out-of-plane component (N).
        w_x: f64,
    },
    /// An angle grid has no points.
    #[error("the {name} grid needs at least one angle")]
    EmptyGrid {
        /// The grid's angle, `azimuth` or `polar`.
        name: &'static str,
    },
    /// A force density overflowed (a load or radius ratio far outside the f64 range).
    #[error("force densities overflow at node {node:?}: reduce the load or the complexity")]
    NonFinite {
        /// The node tuple whose child members overflowed.
        node: Vec<usize>,
    },
    /// The assembled global equilibrium system factorised, but its solution fails the
    /// residual check: the matrix is numerically singular.
    #[error("global equilibrium solve failed: relative residual {relative_residual:.3e} (matrix numerically singular)")]
    SingularSystem {
        /// ‖A q − w‖₁ / (max|A| ‖q‖₁ + ‖w‖₁).
        relative_residual: f64,
    },
    /// A member index is out of range.
    #[error("member {index} does not exist (the truss has {count} members)")]
    UnknownMember {
        /// Requested index.
        index: usize,
        /// Number of members.
        count: usize,
    },
    /// A node index is out of range.
    #[error("node {index} does not exist (the truss has {count} nodes)")]
    UnknownNode {
        /// Requested index.
        index: usize,
        /// Number of nodes.
        count: usize,
    },
    /// No prestress of the extra strings keeps these members from changing sign over the
    /// nominal region (an `auto` prestress has no value; give one to analyse it).
    #[error("no extra-string prestress keeps members {members:?} from changing sign over the nominal region: give the prestress (N) to analyse a chosen one")]
    NoExtraPrestress {
        /// The members no prestress holds (base member indices).
        members: Vec<usize>,
    },
    /// An error from the core crate (e.g. an unknown material name).
    #[error(transparent)]
    Core(#[from] tensegrity_core::CoreError),
}

/// Shorthand for [`MichellError::InvalidParameter`].
pub(crate) fn invalid(name: &'static str, value: f64, reason: impl Into<String>) -> MichellError {
    MichellError::InvalidParameter(tensegrity_core::request::InvalidParameter::new(
        name, value, reason,
    ))
}

impl From<tensegrity_linalg::LinalgError> for MichellError {
    fn from(e: tensegrity_linalg::LinalgError) -> Self {
        Self::Core(e.into())
    }
}

impl Categorized for MichellError {
    /// A parameter, load, grid or index the truss does not take is bad input; a singular
    /// node or system, an overflow or no extra-string prestress is a failed computation; a
    /// core error keeps its own category.
    fn category(&self) -> Category {
        match self {
            Self::InvalidParameter(_)
            | Self::NeedsThreeD { .. }
            | Self::OutOfPlaneLoad { .. }
            | Self::EmptyGrid { .. }
            | Self::UnknownMember { .. }
            | Self::UnknownNode { .. } => Category::Input,
            Self::Core(e) => e.category(),
            _ => Category::Numerical,
        }
    }
}
