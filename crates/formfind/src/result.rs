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
    /// ‖A q‖ / ‖q‖ at the found geometry (A the equilibrium matrix, q the force densities).
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
