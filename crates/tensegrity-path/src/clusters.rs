//! Clustered strings in the elastic model ([`ElasticCluster`]): one continuous string
//! through the nodes n₀, n₁, …, n_p over frictionless pulleys at its inner nodes, so one
//! tension acts along all its segments (issue 44; the scene's `[[clusters]]`,
//! `tensegrity_core::Cluster`).
//!
//! **Tension.** With the segments' lengths l_i = ‖x_{n_{i+1}} − x_{n_i}‖, unit vectors e_i
//! and the cluster's length L = Σ_i l_i,
//!
//! > t = k (L − L₀) (+ c L̇ in the dynamics) when L > L₀, else 0 (slack),
//!
//! k the stiffness of the whole cluster (N/m; EA = k L₀), L₀ its rest length and c its
//! damping (N·s/m, on L̇ = Σ_i e_iᵀ(ẋ_{n_{i+1}} − ẋ_{n_i}); the total clipped at zero, as a
//! string's). On each segment t pulls its two nodes toward each other (t e_i on n_i, −t e_i
//! on n_{i+1}): the resisting force is R = t g with g = ∂L/∂x, the stacked segment unit
//! vectors (−e_i at n_i, +e_i at n_{i+1}, summed at a node two segments share).
//!
//! **Tangent.** dR/dx = k g gᵀ + Σ_i (t/l_i)(I − e_i e_iᵀ) on the segment's two nodes: the
//! material part couples every segment (a pulley passes length from one to the next), the
//! geometric part is a string's per segment; a slack cluster adds nothing. The strain
//! energy is ½ k (L − L₀)² (taut), conserved with the kinetic energy and the loads'
//! potential; frictionless pulleys dissipate nothing.
//!
//! **States.** [`crate::forces::member_states`] gives the members' states, then one state
//! per segment of each cluster in order (its length l_i and direction e_i; the cluster's
//! tension, rest length L₀ and slackness shared by its segments): the forces, tangents and
//! dashpots of the members run over the segments unchanged beside the material part k g gᵀ
//! here. Reports give one tension per member, then one per cluster
//! ([`ElasticModel::reported`]): index `members.len() + c` is cluster c (also in the slack
//! lists and events of a load path).
//!
//! Pulley friction (the capstan law) is not modelled: a cluster with a friction coefficient
//! is refused ([`ElasticModel::from_structure`]).

use crate::dofs::Dofs;
use crate::forces::MemberState;
use crate::model::ElasticModel;
use nalgebra::{Matrix3, Vector3};

/// The length L of cluster `c` from its segments' `states` (all the states).
pub fn cluster_length(model: &ElasticModel, c: usize, states: &[MemberState]) -> f64 {
    states[model.cluster_states(c)]
        .iter()
        .map(|s| s.length)
        .sum()
}

/// The rate L̇ = Σ_i e_iᵀ(v_b − v_a) of cluster `c` at node velocities `v`.
pub fn cluster_rate(
    model: &ElasticModel,
    c: usize,
    states: &[MemberState],
    v: &[Vector3<f64>],
) -> f64 {
    model.clusters[c]
        .segments()
        .zip(&states[model.cluster_states(c)])
        .map(|([a, b], s)| s.direction.dot(&(v[b] - v[a])))
        .sum()
}

/// g = ∂L/∂x of cluster `c` per node it passes (node, vector), summed where two segments
/// share a node.
fn gradient(model: &ElasticModel, c: usize, states: &[MemberState]) -> Vec<(usize, Vector3<f64>)> {
    let mut g: Vec<(usize, Vector3<f64>)> = Vec::new();
    let mut add = |node: usize, v: Vector3<f64>| match g.iter_mut().find(|(i, _)| *i == node) {
        Some((_, w)) => *w += v,
        None => g.push((node, v)),
    };
    for ([a, b], s) in model.clusters[c]
        .segments()
        .zip(&states[model.cluster_states(c)])
    {
        add(a, -s.direction);
        add(b, s.direction);
    }
    g
}

/// The clusters' rank-one blocks `scale(c) g gᵀ` (c the cluster; `None`: nothing) on the
/// free coordinates, as triplets: the material stiffness k g gᵀ of the taut clusters, or
/// the dashpots' c g gᵀ of the implicit dynamics.
pub fn rank_one_triplets(
    model: &ElasticModel,
    dofs: &Dofs,
    states: &[MemberState],
    scale: impl Fn(usize) -> Option<f64>,
) -> Vec<(usize, usize, f64)> {
    let mut t = Vec::new();
    for c in 0..model.clusters.len() {
        let Some(w) = scale(c) else {
            continue;
        };
        // g on the free coordinates
        let mut reduced: Vec<(usize, f64)> = Vec::new();
        for (node, g) in gradient(model, c, states) {
            let (p0, pc) = dofs.of_node[node];
            reduced.extend((0..pc).map(|r| (p0 + r, dofs.free[p0 + r].1.dot(&g))));
        }
        for &(r, gr) in &reduced {
            for &(col, gc) in &reduced {
                t.push((r, col, w * gr * gc));
            }
        }
    }
    t
}

/// The clusters' tangent stiffness as triplets on the free coordinates (module docs):
/// k g gᵀ per taut cluster and (t/l_i)(I − e_i e_iᵀ) per segment of one.
pub fn cluster_triplets(
    model: &ElasticModel,
    dofs: &Dofs,
    states: &[MemberState],
) -> Vec<(usize, usize, f64)> {
    let taut = |c: usize| !states[model.cluster_states(c).start].slack;
    let mut t = rank_one_triplets(model, dofs, states, |c| {
        taut(c).then_some(model.clusters[c].stiffness)
    });
    let nodes: Vec<[usize; 2]> = model.state_nodes().collect();
    for (k, s) in states.iter().enumerate().skip(model.members.len()) {
        if s.slack {
            continue;
        }
        let nn = s.direction * s.direction.transpose();
        let local = (Matrix3::identity() - nn) * (s.tension / s.length);
        push_block(&mut t, dofs, nodes[k], &local);
    }
    t
}

/// [[B, −B], [−B, B]] on the nodes `[a, b]`, projected onto their free directions.
fn push_block(
    t: &mut Vec<(usize, usize, f64)>,
    dofs: &Dofs,
    [a, b]: [usize; 2],
    local: &Matrix3<f64>,
) {
    for (p, sp) in [(a, 1.0), (b, -1.0)] {
        let (p0, pc) = dofs.of_node[p];
        for (q, sq) in [(a, 1.0), (b, -1.0)] {
            let (q0, qc) = dofs.of_node[q];
            for r in 0..pc {
                let kr = local * dofs.free[p0 + r].1;
                for c in 0..qc {
                    t.push((p0 + r, q0 + c, sp * sq * dofs.free[q0 + c].1.dot(&kr)));
                }
            }
        }
    }
}

/// What moving the held nodes by `held_motion` (per unit load factor) does to the clusters'
/// resisting forces: their tangent applied to the motion, into `r`.
pub fn add_driven_forces(
    model: &ElasticModel,
    states: &[MemberState],
    held_motion: &[Vector3<f64>],
    r: &mut [Vector3<f64>],
) {
    for (c, cluster) in model.clusters.iter().enumerate() {
        let range = model.cluster_states(c);
        if states[range.start].slack {
            continue;
        }
        let segs: Vec<[usize; 2]> = cluster.segments().collect();
        let rate: f64 = segs
            .iter()
            .zip(&states[range.clone()])
            .map(|([a, b], s)| s.direction.dot(&(held_motion[*b] - held_motion[*a])))
            .sum();
        for ([a, b], s) in segs.iter().zip(&states[range]) {
            let rel = held_motion[*b] - held_motion[*a];
            let nn = s.direction * s.direction.transpose();
            let f = (Matrix3::identity() - nn) * rel * (s.tension / s.length)
                + s.direction * (cluster.stiffness * rate);
            r[*a] -= f;
            r[*b] += f;
        }
    }
}

/// The clusters' strain energy Σ ½ k (L − L₀)² over the taut ones (J).
pub fn strain_energy(model: &ElasticModel, states: &[MemberState]) -> f64 {
    (0..model.clusters.len())
        .map(|c| {
            let e = cluster_length(model, c, states) - model.clusters[c].rest_length;
            if e > 0.0 {
                0.5 * model.clusters[c].stiffness * e * e
            } else {
                0.0
            }
        })
        .sum()
}
