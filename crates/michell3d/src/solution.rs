//! The result of a force solve and the choice of solver, shared by the recursive method of
//! joints ([`crate::recursive`]) and the global sparse solve ([`crate::global`]); the dispatch
//! on [`Method`] is [`crate::propagation::propagate`].

use crate::truss::MichellTruss;
use nalgebra::Vector3;
use serde::Serialize;

/// Which solver to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Level-by-level method of joints (default).
    #[default]
    Recursive,
    /// One sparse LU solve of the assembled equilibrium ([`crate::global`]).
    Global,
}

/// Member force densities and support reactions.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceSolution {
    /// Tension-positive force density q of each member (N/m), in member order.
    pub force_density: Vec<f64>,
    /// Reaction on each support node (N), in node order (support k is node `n_free + k`).
    pub reactions: Vec<Vector3<f64>>,
}

impl ForceSolution {
    /// Axial member forces f = q·l (N, tension positive).
    pub fn forces(&self, truss: &MichellTruss) -> Vec<f64> {
        self.force_density
            .iter()
            .zip(truss.members())
            .map(|(q, m)| q * m.length)
            .collect()
    }
}
