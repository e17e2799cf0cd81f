//! What a form-finding run returns.

use crate::method::Method;
use nalgebra::Vector3;
use serde::Serialize;

/// A found form: geometry, force densities and the statics of the self-stress.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FormFound {
    /// The method that found it.
    pub method: Method,
    /// One position per node (m), serialised as `[x, y, z]` rows.
    #[serde(serialize_with = "rows")]
    pub nodes: Vec<Vector3<f64>>,
    /// Force density per member (N/m, tension-positive), bars then strings in topology order,
    /// normalised as documented by the method.
    pub force_density: Vec<f64>,
    /// Dimension of the self-stress space of the found geometry.
    pub self_stress_dim: usize,
    /// Whether a self-stress with every string in tension and every bar in compression exists.
    pub prestressable: bool,
    /// Whether the prestressed structure is stable (positive-definite stiffness on the
    /// non-rigid motions).
    pub prestress_stable: bool,
    /// ‖A q + p‖ / ‖q‖ at the found geometry (A the equilibrium matrix without the rows of
    /// fixed nodes, q the force densities, p the loads: zero without).
    pub residual: f64,
    /// Iterations of the method (1 for a direct solve).
    pub iterations: usize,
    /// The convergence tolerance the iterative method stopped at: the one asked for, or for
    /// dynamic relaxation the floor double precision reaches at the members' stiffness when
    /// that is larger (`None` for a direct solve; see the `dr` module docs).
    pub tolerance: Option<f64>,
    /// What method `auto` chose and why (`None` unless `auto` was asked for): a front end
    /// shows it as a warning.
    pub choice: Option<String>,
    /// The loads the form carries, one per loaded node in node order (N): the point loads
    /// summed per node plus the members' lumped self-weight at the found lengths (empty
    /// without loads).
    pub loads: Vec<NodeForce>,
    /// The reaction r_i = (D X)_i − p_i at each fixed node, in the topology's `fixed` order
    /// (N, in the units of `force_density` times m; empty without fixed nodes): with the
    /// loads, Σ r + Σ p = 0.
    pub reactions: Vec<NodeForce>,
    /// The relative equilibrium residual of the free nodes, ‖(D X)_f − P_f‖ / ‖F_f‖ with
    /// F_i = Σ_k∋i |q_k| L_k + ‖p_i‖ the size of the forces meeting at node i (`None`
    /// without fixed nodes).
    pub equilibrium_residual: Option<f64>,
    /// Each clustered string at the found form: its tension, length and its segments' lengths
    /// and force densities t / l_i (empty without clusters; the `cluster` module).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub clusters: Vec<crate::ClusterState>,
}

/// A force at a node: a load or a reaction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NodeForce {
    /// The node index.
    pub node: usize,
    /// The force [x, y, z] (N).
    pub force: [f64; 3],
}

impl FormFound {
    /// The size of the form: the diagonal of the nodes' bounding box (m).
    pub fn structure_size(&self) -> f64 {
        crate::analysis::size(&self.nodes)
    }

    /// The nodes as `[x, y, z]` rows (the JSON `nodes`).
    pub fn node_rows(&self) -> Vec<[f64; 3]> {
        self.nodes.iter().map(|p| [p.x, p.y, p.z]).collect()
    }
}

/// Serialises points as `[x, y, z]` rows (independent of nalgebra's serde feature).
fn rows<S: serde::Serializer>(nodes: &[Vector3<f64>], s: S) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeSeq;
    let mut seq = s.serialize_seq(Some(nodes.len()))?;
    for p in nodes {
        seq.serialize_element(&[p.x, p.y, p.z])?;
    }
    seq.end()
}
