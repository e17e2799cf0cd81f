//! [`StaticsError`]: a statics analysis (load solve, sizing, cyclic symmetry) that has no
//! answer for a valid structure, or a symmetry descriptor that does not fit it.

use super::symmetry::SymmetryError;
use crate::member_id::MemberId;
use crate::request::{Categorized, Category};
use thiserror::Error;

/// Everything a statics analysis can fail on, beyond the model and the numerical kernels.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum StaticsError {
    /// Sizing asked of a string that would have to carry compression.
    #[error(
        "{member}: a string cannot carry compression (force {force:.6e} N); sizing is undefined"
    )]
    StringInCompression {
        /// The string.
        member: MemberId,
        /// Its (negative) axial force.
        force: f64,
    },
    /// The structure cannot carry its loads: the least-squares force densities leave an
    /// equilibrium residual (the loads drive a mechanism).
    #[error("the loads cannot be carried: equilibrium residual {residual:.6e} N ({relative_residual:.3e} of the load) at nodes {nodes:?}; the structure is a mechanism for these loads (add members or supports, or ask for the least-squares answer)")]
    LoadNotCarried {
        /// ‖A q − w‖₂ (N).
        residual: f64,
        /// The residual relative to ‖w‖₂.
        relative_residual: f64,
        /// The unbalanced nodes.
        nodes: Vec<usize>,
    },
    /// A linear response asked of a structure whose tangent stiffness is singular on its
    /// free coordinates: mechanisms that neither the prestress nor a spring stiffens (the
    /// small-displacement answer does not exist; `solve` follows the large motion).
    #[error("the linear response has no answer: the tangent stiffness is singular on the free coordinates ({mechanisms} mechanism(s) stiffened neither by prestress nor by a spring; the first moves node {node} most, along [{:.6}, {:.6}, {:.6}]): add supports or members, or prestress the structure", direction[0], direction[1], direction[2])]
    SingularStiffness {
        /// The number of zero eigenvalues of the tangent stiffness on the free coordinates.
        mechanisms: usize,
        /// The node the first mechanism moves most.
        node: usize,
        /// That node's motion in the mechanism (a unit vector).
        direction: [f64; 3],
    },
    /// A cyclic-symmetry descriptor that does not describe the structure (boxed: the
    /// variant names nodes, members and positions).
    #[error(transparent)]
    Symmetry(Box<SymmetryError>),
}

impl From<SymmetryError> for StaticsError {
    fn from(e: SymmetryError) -> Self {
        Self::Symmetry(Box::new(e))
    }
}

impl Categorized for StaticsError {
    /// A descriptor that does not fit the structure is bad input; a load not carried or a
    /// string in compression is the answer of the computation (it failed).
    fn category(&self) -> Category {
        match self {
            Self::Symmetry(_) => Category::Input,
            _ => Category::Numerical,
        }
    }
}

impl Categorized for SymmetryError {
    fn category(&self) -> Category {
        Category::Input
    }
}
