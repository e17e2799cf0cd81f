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
    #[error("the loads cannot be carried: equilibrium residual {residual:.6e} N ({relative_residual:.3e} of the load) at {}; the structure is a mechanism for these loads (add members or supports, or ask for the least-squares answer)", node_list(nodes))]
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
    /// The sparse QR's answer failed its own check (a load solve that left a residual, an LP
    /// that stalled), and the dense SVD that would answer instead is above the work limit.
    #[error("the sparse QR's answer failed its check ({failure}): a mechanism, or the sparse factorisation's round-off; the dense SVD would tell them apart but needs an estimated {dense_work_s:.0} s of work, above the work limit: raise `max_work` (e.g. `max_work = {}`) or give `method = dense`", dense_work_s.ceil())]
    SparseCheckFailed {
        /// What failed, e.g. the load solve's residual.
        failure: String,
        /// The dense SVD's estimated work (s).
        dense_work_s: f64,
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

/// Nodes named in a message: all of them up to ten, else the first ten and the count.
///
/// ```
/// use tensegrity_core::error::node_list;
/// assert_eq!(node_list(&[3, 7]), "nodes [3, 7]");
/// let many: Vec<usize> = (0..25).collect();
/// assert_eq!(node_list(&many), "25 nodes, the first [0, 1, 2, 3, 4, 5, 6, 7, 8, 9]");
/// ```
pub fn node_list(nodes: &[usize]) -> String {
    match nodes.len() {
        0..=10 => format!("nodes {nodes:?}"),
        n => format!("{n} nodes, the first {:?}", &nodes[..10]),
    }
}
