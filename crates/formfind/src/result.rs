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
    /// Dimension of the self-stress space of the found geometry (`None`: not analysed, see
    /// [`crate::Settings::analyse`] and [`FormFound::analyse`]).
    pub self_stress_dim: Option<usize>,
    /// Whether a self-stress with every string in tension and every bar in compression exists
    /// (`None`: not analysed).
    pub prestressable: Option<bool>,
    /// Whether the prestressed structure is stable (positive-definite stiffness on the
    /// non-rigid motions; `None`: not analysed).
    pub prestress_stable: Option<bool>,
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
    /// Whether the statics of the form are in it (found with [`crate::Settings::analyse`], or
    /// added by [`FormFound::analyse`]).
    pub fn is_analysed(&self) -> bool {
        self.self_stress_dim.is_some()
    }

    /// Adds the statics of the form (self-stress dimension, prestressability, prestress
    /// stability: the `analysis` module) where they are missing, from the form, its force
    /// densities (the clusters' segments at t / l_i of the found lengths), and its loads, all
    /// scaled by max|q| as the form-finding does; `topology` is the one it was found from.
    /// Nothing is recomputed where they are present.
    pub fn analyse(&mut self, topology: &crate::Topology) -> crate::Result<()> {
        if self.is_analysed() {
            return Ok(());
        }
        let segments = self.clusters.iter().flat_map(|c| &c.segment_force_density);
        let q: Vec<f64> = self.force_density.iter().chain(segments).copied().collect();
        let scale = q.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let unit: Vec<f64> = q.iter().map(|x| x / scale.max(f64::MIN_POSITIVE)).collect();
        let mut loads = Vec::new();
        if !self.loads.is_empty() {
            loads = vec![Vector3::zeros(); self.nodes.len()];
            for f in &self.loads {
                loads[f.node] = Vector3::from(f.force) / scale.max(f64::MIN_POSITIVE);
            }
        }
        let a = crate::analysis::analyse(topology, &self.nodes, &unit, &loads)?;
        self.self_stress_dim = Some(a.self_stress_dim);
        self.prestressable = Some(a.prestressable);
        self.prestress_stable = Some(a.prestress_stable);
        Ok(())
    }

    /// The form with the statics `a`.
    pub(crate) fn with_analysis(self, a: &crate::analysis::Analysis) -> Self {
        FormFound {
            self_stress_dim: Some(a.self_stress_dim),
            prestressable: Some(a.prestressable),
            prestress_stable: Some(a.prestress_stable),
            ..self
        }
    }

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
