//! Clustered strings in the elastic model ([`ElasticCluster`]): one continuous string
//! through the nodes n₀, n₁, …, n_p over pulleys at its inner nodes; frictionless, one
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
//! **Pulley friction** (`friction`, one μ per inner node; [`ElasticCluster::friction`]):
//! the cluster's material is a state, each segment's rest length s_i (Σ s_i = L₀; at the
//! start spread in proportion to the segments' lengths: one strain, the frictionless state),
//! and segment i is a string of rigidity EA = k L₀ at rest length s_i: t_i = EA (l_i − s_i)/s_i,
//! tangent (EA/s_i) e eᵀ + (t_i/l_i)(I − e eᵀ), strain energy ½ (EA/s_i)(l_i − s_i)². Material
//! passes a pulley only at the capstan limit t_out = e^{μθ} t_in (θ the wrap angle between
//! the segments' directions): [`slide`] is the return map of that law over an increment
//! (`tensegrity_core::capstan`). A load path follows it by load control (`load_steps`: at
//! each step Newton at fixed rest lengths and the slide alternate until no rest length moves
//! by 10⁻¹⁴ of the cluster; the arc-length path refuses friction, as the sliding depends on
//! the path's history). The dynamics (the string is massless, so it slides at once) slides
//! from the last accepted step's rest lengths at every force evaluation — the force is a
//! continuous function of the positions within a step — and keeps the slide at the step's
//! end; the friction's work, Σ_j |t_j − t_{j−1}| |f_j| over the material f_j passed
//! (trapezoidal in the step), enters the energy balance. A slipping pulley's ratio holds to
//! about 10⁻¹² on a load path; the dynamics' sliding is first order in the step where a
//! pulley switches between stick and slip.

use crate::dofs::Dofs;
use crate::error::{PathError, Result};
use crate::forces::MemberState;
use crate::model::{ElasticCluster, ElasticModel};
use nalgebra::{Matrix3, Vector3};
use tensegrity_core::capstan::{self, Pulley};

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
        let cluster = &model.clusters[c];
        // a driven cluster's stiffness at its rest length now (the states carry it)
        let rest = states[model.cluster_states(c).start].rest_length;
        (taut(c) && cluster.friction.is_none()).then_some(cluster.stiffness_at(rest))
    });
    let nodes: Vec<[usize; 2]> = model.state_nodes().collect();
    for (c, cluster) in model.clusters.iter().enumerate() {
        for k in model.cluster_states(c) {
            if !states[k].slack {
                push_block(
                    &mut t,
                    dofs,
                    nodes[k],
                    &segment_tangent(cluster, &states[k]),
                );
            }
        }
    }
    t
}

/// A taut segment's 3 × 3 tangent: (t/l)(I − e eᵀ), plus (EA/s_i) e eᵀ on a frictional
/// cluster (its stuck material: a string of rest length s_i).
fn segment_tangent(cluster: &ElasticCluster, s: &MemberState) -> Matrix3<f64> {
    let nn = s.direction * s.direction.transpose();
    let geometric = (Matrix3::identity() - nn) * (s.tension / s.length);
    if cluster.friction.is_some() {
        geometric + nn * (cluster.stiffness * cluster.rest_length / s.rest_length)
    } else {
        geometric
    }
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

/// What the load factor's drivers do to the clusters' resisting forces at fixed free
/// coordinates, into `r`: their tangent applied to the held nodes' motion `held_motion` (per
/// unit load factor), and a driven rest length's dt/dλ = −EA L/L₀² ΔL₀ along every segment.
pub fn add_driven_forces(
    model: &ElasticModel,
    states: &[MemberState],
    held_motion: &[Vector3<f64>],
    r: &mut [Vector3<f64>],
) {
    for (c, cluster) in model.clusters.iter().enumerate() {
        let range = model.cluster_states(c);
        if cluster.friction.is_some() {
            for ([a, b], s) in cluster.segments().zip(&states[range]) {
                if !s.slack {
                    let f = segment_tangent(cluster, s) * (held_motion[b] - held_motion[a]);
                    r[a] -= f;
                    r[b] += f;
                }
            }
            continue;
        }
        if states[range.start].slack {
            continue;
        }
        // a driven rest length: t = EA (L − L₀)/L₀, dt/dλ = −EA L/L₀² ΔL₀ on every segment
        let rest = states[range.start].rest_length;
        let length = cluster_length(model, c, states);
        let change = (model.drivers.cluster_rest_length_changes)
            .get(c)
            .copied()
            .unwrap_or(0.0);
        let reel = -cluster.stiffness * cluster.rest_length * length / (rest * rest) * change;
        let k = cluster.stiffness_at(rest);
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
                + s.direction * (k * rate + reel);
            r[*a] -= f;
            r[*b] += f;
        }
    }
}

/// The clusters' strain energy Σ ½ k (L − L₀)² over the taut ones (J).
pub fn strain_energy(model: &ElasticModel, states: &[MemberState]) -> f64 {
    (0..model.clusters.len())
        .map(|c| {
            let cluster = &model.clusters[c];
            if cluster.friction.is_some() {
                let ea = cluster.stiffness * cluster.rest_length;
                return states[model.cluster_states(c)]
                    .iter()
                    .filter(|s| !s.slack)
                    .map(|s| 0.5 * ea / s.rest_length * (s.length - s.rest_length).powi(2))
                    .sum();
            }
            let e = cluster_length(model, c, states) - model.clusters[c].rest_length;
            if e > 0.0 {
                0.5 * model.clusters[c].stiffness * e * e
            } else {
                0.0
            }
        })
        .sum()
}

/// The frictional clusters' segment rest lengths (one list per cluster; empty for a
/// frictionless one): the state that [`slide`] changes.
pub fn friction_rest_lengths(model: &ElasticModel) -> Vec<Vec<f64>> {
    model
        .clusters
        .iter()
        .map(|c| {
            c.friction
                .as_ref()
                .map_or_else(Vec::new, |f| f.rest_lengths.clone())
        })
        .collect()
}

/// Sets the frictional clusters' segment states from the rest lengths `rest` (as
/// [`friction_rest_lengths`] gives them) instead of the model's.
pub fn apply_rest_lengths(model: &ElasticModel, states: &mut [MemberState], rest: &[Vec<f64>]) {
    for (c, cluster) in model.clusters.iter().enumerate() {
        if cluster.friction.is_some() {
            let ea = cluster.stiffness * cluster.rest_length;
            for (s, &r) in states[model.cluster_states(c)].iter_mut().zip(&rest[c]) {
                crate::forces::set_segment(s, ea, r);
            }
        }
    }
}

/// What one increment of pulley friction gives ([`slide`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Slid {
    /// Each cluster's segment rest lengths after the slide (empty for a frictionless one).
    pub rest: Vec<Vec<f64>>,
    /// Each cluster's pulley states (empty for a frictionless one).
    pub pulleys: Vec<Vec<Pulley>>,
    /// The largest change of a rest length (m).
    pub moved: f64,
}

/// One increment of pulley friction (module docs): from the rest lengths `start` (as
/// [`friction_rest_lengths`] gives them) at the increment's start, the rest lengths after
/// sliding to the capstan law at the segments' `states` at its end
/// (`tensegrity_core::capstan::slide`), each pulley's state, and the largest change of a
/// rest length (m). An error names the cluster whose sliding failed.
pub fn slide(model: &ElasticModel, states: &[MemberState], start: &[Vec<f64>]) -> Result<Slid> {
    let mut rest = start.to_vec();
    let mut pulleys = vec![Vec::new(); model.clusters.len()];
    let mut moved = 0.0_f64;
    for (c, cluster) in model.clusters.iter().enumerate() {
        let Some(friction) = &cluster.friction else {
            continue;
        };
        let seg = &states[model.cluster_states(c)];
        let lengths: Vec<f64> = seg.iter().map(|s| s.length).collect();
        let mu_theta: Vec<f64> = friction
            .mu
            .iter()
            .zip(seg.windows(2))
            .map(|(mu, w)| mu * capstan::wrap_angle(&w[0].direction, &w[1].direction))
            .collect();
        let out = capstan::slide(
            &lengths,
            &mut rest[c],
            cluster.stiffness * cluster.rest_length,
            &mu_theta,
        )
        .map_err(|e| PathError::model(format!("cluster {c}"), format!("pulley friction: {e}")))?;
        moved = moved.max(out.moved);
        pulleys[c] = out.pulleys;
    }
    Ok(Slid {
        rest,
        pulleys,
        moved,
    })
}
