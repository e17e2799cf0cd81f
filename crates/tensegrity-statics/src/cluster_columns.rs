//! The columns of clustered strings ([`Cluster`]) in the statics: one column of the
//! equilibrium matrix per cluster, after the bars and the strings.
//!
//! **Column.** A cluster c through the nodes n₀ … n_p has the segments i = (n_i, n_{i+1}) of
//! lengths l_i, unit vectors e_i = (x_{n_{i+1}} − x_{n_i}) / l_i and the total length
//! L_c = Σ_i l_i. Frictionless, its tension t_c is the same in every segment, so its only
//! unknown is t_c; the statics takes the force density on the whole length,
//!
//! > q_c = t_c / L_c  (N/m),  t_c = q_c L_c,
//!
//! so that its column has the units of a member's (m): Σ_i (L_c / l_i) m_i with
//! m_i = x_b − x_a distributed onto the segment's nodes as a string's column is (−m_i scaled
//! at a, +m_i scaled at b), i.e. the column is L_c g with g = ∂L_c/∂x, the stacked unit
//! vectors (−e_i at the start of segment i, +e_i at its end, summed where two segments meet
//! at a pulley). A_c q_c puts t_c e_i on the start of segment i and −t_c e_i on its end, as
//! a string of tension t_c does.
//!
//! **Order.** Every per-member array of the statics (the force densities, member forces,
//! self-stress vectors, the prestress, the sizing) has one entry per column: the bars, then
//! the strings, then the clusters ([`n_columns`], [`column_name`]: `cluster 0`, …); a
//! cluster's force is its tension t_c = q_c L_c ([`column_lengths`]: L_c).
//!
//! **Stiffness.** With axial stiffness k_c (of the whole cluster, EA/L₀; 0 when slack) and
//! tension t_c, the cluster's tangent stiffness is the Hessian of its energy,
//!
//! > K_c = k_c g gᵀ + t_c ∇²L_c,  ∇²L_c = Σ_i (1/l_i) [[P_i, −P_i], [−P_i, P_i]],
//! > P_i = I₃ − e_i e_iᵀ,
//!
//! the material part coupling every node of the cluster (a pulley passes length from one
//! segment to the next), the geometric part one block per segment
//! ([`ClusterGeometry::stiffness_blocks`]). The stress matrix of the prestress-stability
//! test takes the geometric part t_c ∇²L_c: the Hessian of the constraint L_c = const
//! weighted by its multiplier t_c (for a member, q I differs from (t/l) P on the member's
//! axis only, which a first-order flex does not move; a flex of a cluster may lengthen one
//! segment and shorten the next, so the projected form is the one that holds).
//!
//! **Friction.** The columns take every cluster frictionless; a cluster with pulley
//! `friction` is analysed so, with a note in the report ([`friction_note`]).
//!
//! **Back-ends.** The dense SVD models clusters; the sparse QR, the nested dissection and
//! the cyclic blocks do not, and refuse a structure with clusters naming the first one
//! ([`refuse_clusters_in`]).

use nalgebra::{Matrix3, Vector3};
use tensegrity_core::error::{ModelError, Result};
use tensegrity_core::structure::{MemberId, Structure};
use tensegrity_core::Cluster;

/// Number of columns of the equilibrium matrix: bars, strings, then clusters.
///
/// ```
/// use tensegrity_core::{Cluster, Structure};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [2.0, 0.0, 0.0]])
///     .cluster(Cluster::new([0, 1, 2]))
///     .build()
///     .unwrap();
/// assert_eq!((s.n_members(), tensegrity_statics::n_columns(&s)), (0, 1));
/// ```
pub fn n_columns(structure: &Structure) -> usize {
    structure.n_members() + structure.clusters().len()
}

/// The name of column `k`: `bar i`, `string i` or `cluster c` (module docs: the order).
///
/// ```
/// use tensegrity_core::{Cluster, StringMember, Structure};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [2.0, 0.0, 0.0], [3.0, 0.0, 0.0]])
///     .string(StringMember::new(2, 3))
///     .cluster(Cluster::new([0, 1, 2]))
///     .build()
///     .unwrap();
/// assert_eq!(tensegrity_statics::column_name(&s, 0), "string 0");
/// assert_eq!(tensegrity_statics::column_name(&s, 1), "cluster 0");
/// ```
pub fn column_name(structure: &Structure, k: usize) -> String {
    match k.checked_sub(structure.n_members()) {
        Some(c) => format!("cluster {c}"),
        None => structure.member_id(k).to_string(),
    }
}

/// The member of column `k`, `None` for a cluster's column.
pub fn column_member(structure: &Structure, k: usize) -> Option<MemberId> {
    (k < structure.n_members()).then(|| structure.member_id(k))
}

/// The length of every column (m): the members' lengths, then each cluster's total length
/// L_c (a column's force is q times it).
pub fn column_lengths(structure: &Structure) -> Vec<f64> {
    let mut lengths = structure.member_lengths();
    lengths.extend(
        structure
            .clusters()
            .iter()
            .map(|c| c.length(structure.nodes())),
    );
    lengths
}

/// Whether column `k` is tension-only (a string or a cluster).
pub fn is_tension_only(structure: &Structure, k: usize) -> bool {
    k >= structure.n_bars()
}

/// One segment of a cluster at the structure's geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Its start and end nodes.
    pub nodes: [usize; 2],
    /// Its length l_i (m).
    pub length: f64,
    /// Its unit vector e_i, start to end.
    pub unit: Vector3<f64>,
}

/// A cluster at the structure's geometry: its segments and total length (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct ClusterGeometry {
    /// The segments in order.
    pub segments: Vec<Segment>,
    /// The total length L_c = Σ l_i (m).
    pub length: f64,
}

impl ClusterGeometry {
    /// The geometry of `cluster` at the node positions `x`.
    pub fn of(cluster: &Cluster, x: &[Vector3<f64>]) -> Self {
        let segments: Vec<Segment> = cluster
            .segments()
            .map(|[a, b]| {
                let m = x[b] - x[a];
                let length = m.norm();
                Segment {
                    nodes: [a, b],
                    length,
                    unit: m / length,
                }
            })
            .collect();
        let length = segments.iter().map(|s| s.length).sum();
        Self { segments, length }
    }

    /// The gradient g = ∂L_c/∂x as (node, vector) pairs: −e_i at the start of segment i,
    /// +e_i at its end (a pulley appears twice; the pairs add).
    pub fn gradient(&self) -> Vec<(usize, Vector3<f64>)> {
        self.segments
            .iter()
            .flat_map(|s| [(s.nodes[0], -s.unit), (s.nodes[1], s.unit)])
            .collect()
    }

    /// The column of A on every node, as (node, vector) pairs: L_c g.
    pub fn column(&self) -> Vec<(usize, Vector3<f64>)> {
        self.gradient()
            .into_iter()
            .map(|(n, g)| (n, g * self.length))
            .collect()
    }

    /// The first-order change of length δL_c = gᵀ u for nodal displacements `u`.
    pub fn length_change(&self, u: &[Vector3<f64>]) -> f64 {
        self.gradient().iter().map(|(n, g)| g.dot(&u[*n])).sum()
    }

    /// The cluster's tangent stiffness with axial stiffness `k` and tension `t`, as 3×3
    /// blocks (row node, column node, block) that add up to K_c (module docs): k g_a g_bᵀ for
    /// every pair of gradient entries, then (t/l_i) P_i ± per segment.
    pub fn stiffness_blocks(&self, k: f64, t: f64) -> Vec<(usize, usize, Matrix3<f64>)> {
        let g = self.gradient();
        let mut blocks = Vec::with_capacity(g.len() * g.len() + 4 * self.segments.len());
        if k != 0.0 {
            for (a, ga) in &g {
                for (b, gb) in &g {
                    blocks.push((*a, *b, ga * gb.transpose() * k));
                }
            }
        }
        for s in &self.segments {
            let p = (Matrix3::identity() - s.unit * s.unit.transpose()) * (t / s.length);
            let [a, b] = s.nodes;
            blocks.extend([(a, a, p), (b, b, p), (a, b, -p), (b, a, -p)]);
        }
        blocks
    }
}

/// The geometry of every cluster of `structure`, in order.
pub fn cluster_geometries(structure: &Structure) -> Vec<ClusterGeometry> {
    structure
        .clusters()
        .iter()
        .map(|c| ClusterGeometry::of(c, structure.nodes()))
        .collect()
}

/// Refuses a structure with clusters for a back-end that does not model them (`back_end`,
/// e.g. `sparse QR`), naming the first cluster and the dense SVD that does.
///
/// ```
/// use tensegrity_core::{Cluster, Structure};
/// use tensegrity_statics::cluster_columns::refuse_clusters_in;
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [2.0, 0.0, 0.0]])
///     .cluster(Cluster::new([0, 1, 2]))
///     .build()
///     .unwrap();
/// let e = refuse_clusters_in(&s, "sparse QR").unwrap_err().to_string();
/// assert!(e.starts_with("cluster 0: the sparse QR back-end of the statics does not model clustered strings"), "{e}");
/// ```
pub fn refuse_clusters_in(structure: &Structure, back_end: &str) -> Result<()> {
    if !structure.has_clusters() {
        return Ok(());
    }
    Err(ModelError::InvalidCluster {
        cluster: 0,
        reason: format!(
            "the {back_end} back-end of the statics does not model clustered strings: use the dense SVD (`method = dense`), which does"
        ),
    }
    .into())
}

/// A per-column array (members, then clusters) spread onto the drawn lines (members, then
/// each cluster's segments in order): a cluster's force t_c on each of its segments, or with
/// `density` its force density q_c on its total length as each segment's t_c / l_i =
/// q_c L_c / l_i. `None` when `values` has not one entry per column.
///
/// ```
/// use tensegrity_core::{Cluster, Structure};
/// use tensegrity_statics::cluster_columns::per_segment;
/// // segments of 5 m and 2 m: q_c = 10/7 N/m is 2 N/m and 5 N/m on them
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [4.0, 0.0, 3.0], [4.0, 0.0, 1.0]])
///     .cluster(Cluster::new([0, 1, 2]))
///     .build()
///     .unwrap();
/// assert_eq!(per_segment(&s, &[10.0], false), Some(vec![10.0, 10.0]));
/// let q = per_segment(&s, &[10.0 / 7.0], true).unwrap();
/// assert!((q[0] - 2.0).abs() < 1e-15 && (q[1] - 5.0).abs() < 1e-15);
/// ```
pub fn per_segment(structure: &Structure, values: &[f64], density: bool) -> Option<Vec<f64>> {
    let nm = structure.n_members();
    if values.len() != n_columns(structure) {
        return None;
    }
    let mut out = values[..nm].to_vec();
    for (c, g) in cluster_geometries(structure).iter().enumerate() {
        let v = values[nm + c];
        out.extend(g.segments.iter().map(|s| match density {
            true => v * g.length / s.length,
            false => v,
        }));
    }
    Some(out)
}

/// The note of a report whose clusters have pulley friction (`friction`, not all zero): the
/// statics takes every cluster frictionless (one tension in all its segments), a special
/// case of the equilibria friction admits (tensions differing across a pulley up to the
/// capstan factor e^{μθ}). `None` when every cluster is frictionless.
///
/// ```
/// use tensegrity_core::{Cluster, Structure};
/// use tensegrity_statics::cluster_columns::friction_note;
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 1.0], [2.0, 0.0, 0.0]])
///     .cluster(Cluster::new([0, 1, 2]).friction([0.2]))
///     .build()
///     .unwrap();
/// assert!(friction_note(&s).unwrap().starts_with("cluster 0 has pulley friction"));
/// ```
pub fn friction_note(structure: &Structure) -> Option<String> {
    let with: Vec<String> = (structure.clusters().iter().enumerate())
        .filter(|(_, c)| !c.is_frictionless())
        .map(|(k, _)| format!("cluster {k}"))
        .collect();
    (!with.is_empty()).then(|| {
        format!(
            "{} has pulley friction: the statics takes it frictionless (one tension in all its segments), one of the equilibria friction admits (tensions differing across a pulley up to the capstan factor e^(μθ))",
            with.join(", ")
        )
    })
}
