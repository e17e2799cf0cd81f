//! Load solve: the minimal-norm force densities q with A q = w (w = free rows of the external
//! force matrix W, loads plus bar weights), member forces q·l, support reactions and the
//! equilibrium residual.
//!
//! The reaction at a fixed degree of freedom is whatever the support must supply so that the
//! node balances: r = (A_full q − w) at that row; at a node held along directions of any
//! orientation, the node's unbalance projected on the span of its held directions (the
//! reaction lies in that span: [`reaction_components`] gives it along each held direction).
//! An elastic support counts as a support here (its spring carries the reaction). When w is not in the range of A (the load
//! drives a mechanism), the least-squares q is returned and the residual ‖A q − w‖ says by how
//! much equilibrium fails. A load counts as carried when ‖A q − w‖₂ ≤
//! [`LOAD_RESIDUAL_TOLERANCE`]·‖w‖₂; otherwise [`LoadSolution::unbalanced`] names the nodes whose
//! residual force exceeds that tolerance.

use super::{DofMap, Statics};
use nalgebra::{DVector, Matrix3, Vector3};
use tensegrity_core::structure::{Structure, Support};

/// Relative equilibrium residual ‖A q − w‖₂ / ‖w‖₂ above which a load is not carried (the
/// minimal-norm solve of a consistent system leaves round-off of order κ(A)·ε).
pub const LOAD_RESIDUAL_TOLERANCE: f64 = 1e-8;

/// The solution of a load problem.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadSolution {
    /// Force densities q (N/m, tension positive), bars, strings, then clusters (q_c = t_c /
    /// L_c).
    pub force_density: DVector<f64>,
    /// Axial forces q·l (N, tension positive; a cluster's tension t_c = q_c L_c).
    pub member_force: DVector<f64>,
    /// `(node, reaction)` for every supported node, in support order (free directions of a
    /// partially supported node carry 0).
    pub reactions: Vec<(usize, Vector3<f64>)>,
    /// ‖A q − w‖₂ over the free degrees of freedom (N).
    pub residual: f64,
    /// The residual relative to ‖w‖₂ (0 when w = 0).
    pub relative_residual: f64,
    /// `(node, residual force)` of every node whose unbalanced force A q − w exceeds
    /// [`LOAD_RESIDUAL_TOLERANCE`]·‖w‖₂ (empty when the load is carried).
    pub unbalanced: Vec<(usize, Vector3<f64>)>,
}

impl LoadSolution {
    /// Whether the structure carries the load: relative residual within
    /// [`LOAD_RESIDUAL_TOLERANCE`].
    pub fn load_carried(&self) -> bool {
        self.relative_residual <= LOAD_RESIDUAL_TOLERANCE
    }
}

impl Statics<'_> {
    /// Solves for the structure's own loads (nodal loads plus gravity on bar masses).
    pub fn solve_loads(&self) -> LoadSolution {
        self.solve_nodal_forces(&self.structure().W())
    }

    /// Solves A q = w for an arbitrary 3×n nodal force matrix `w_nodes`.
    pub fn solve_nodal_forces(&self, w_nodes: &nalgebra::Matrix3xX<f64>) -> LoadSolution {
        let w = self.dofs().gather(w_nodes);
        let q = self.solve_min_norm(&w);
        let r = self.matrix() * &q - &w;
        assemble_solution(self.structure(), self.dofs(), w_nodes, q, r)
    }
}

/// The load solution for force densities `q` with equilibrium residual `r` = A q − w on the
/// free rows: member forces, reactions, residual norms and unbalanced nodes.
pub(super) fn assemble_solution(
    structure: &Structure,
    dofs: &DofMap,
    w_nodes: &nalgebra::Matrix3xX<f64>,
    q: DVector<f64>,
    r: DVector<f64>,
) -> LoadSolution {
    let w_norm = dofs.gather(w_nodes).norm();
    let lengths = crate::column_lengths(structure);
    let member_force = DVector::from_iterator(q.len(), q.iter().zip(&lengths).map(|(q, l)| q * l));
    let residual = r.norm();
    let relative_residual = if w_norm > 0.0 { residual / w_norm } else { 0.0 };
    let unbalanced = unbalanced_nodes(structure, dofs, &r, LOAD_RESIDUAL_TOLERANCE * w_norm);

    // (A_full q) node by node, one member at a time: −q m at the start, +q m at the end
    let mut internal = vec![Vector3::zeros(); structure.n_nodes()];
    for (k, [i, j]) in structure.member_nodes().into_iter().enumerate() {
        let t = structure.member_vector(k) * q[k];
        internal[i] -= t;
        internal[j] += t;
    }
    // a cluster's column: q_c L_c g (−t e_i at a segment's start, +t e_i at its end)
    let nm = structure.n_members();
    for (c, g) in crate::cluster_columns::cluster_geometries(structure)
        .iter()
        .enumerate()
    {
        for (node, v) in g.column() {
            internal[node] += v * q[nm + c];
        }
    }
    // the node's unbalance projected on its held axes (x, y, z, or its frame's held ones)
    let reactions = structure
        .supports()
        .iter()
        .map(|s| {
            let f = internal[s.node] - Vector3::from(w_nodes.column(s.node));
            let r: Vector3<f64> = (0..3)
                .filter(|&a| dofs.row[s.node][a].is_none())
                .map(|a| dofs.axis(s.node, a) * dofs.component(s.node, a, &f))
                .sum();
            (s.node, r)
        })
        .collect();
    LoadSolution {
        force_density: q,
        member_force,
        reactions,
        residual,
        relative_residual,
        unbalanced,
    }
}

/// The reaction `reaction` of `support` as forces along each of its held directions
/// ([`Support::held_directions`]: the flagged axes, then the `along` directions), r = Σ a_h
/// d_h, solved on the Gram matrix of the directions (independent: the builder checks it).
///
/// ```
/// use nalgebra::Vector3;
/// use tensegrity_core::Support;
/// use tensegrity_statics::reaction_components;
/// let s = Support::along(0, [[0.6, 0.8, 0.0]]);
/// let a = reaction_components(&s, &Vector3::new(3.0, 4.0, 0.0));
/// assert!((a[0] - 5.0).abs() < 1e-15);
/// ```
pub fn reaction_components(support: &Support, reaction: &Vector3<f64>) -> Vec<f64> {
    let d = support.held_directions();
    let k = d.len();
    let mut g = Matrix3::identity();
    let mut b = Vector3::zeros();
    for a in 0..k {
        b[a] = d[a].dot(reaction);
        for c in 0..k {
            g[(a, c)] = d[a].dot(&d[c]);
        }
    }
    let x = g.lu().solve(&b).unwrap_or(b);
    (0..k).map(|a| x[a]).collect()
}

/// Nodes whose residual force (free directions of `r`, node by node) exceeds `tol`.
fn unbalanced_nodes(
    structure: &Structure,
    dofs: &DofMap,
    r: &DVector<f64>,
    tol: f64,
) -> Vec<(usize, Vector3<f64>)> {
    let mut per_node = vec![Vector3::zeros(); structure.n_nodes()];
    for (row, &(node, d)) in dofs.free.iter().enumerate() {
        per_node[node] += dofs.axis(node, d) * r[row];
    }
    per_node
        .into_iter()
        .enumerate()
        .filter(|(_, f)| f.norm() > tol)
        .collect()
}
