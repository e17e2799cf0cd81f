//! The members' tensions and resisting forces at a configuration (crate docs):
//! t_k = EA_k (L_k − L₀,k)/L₀,k, zero for a string shorter than its rest length, and
//! R_i = −Σ t_k n_k over the members leaving node i (n_k the unit vector to the other node),
//! the clusters' segments counted alike with their cluster's tension ([`crate::clusters`]);
//! and what the load factor's drivers do to R at fixed free coordinates ([`driven_forces`]).

use crate::model::{ElasticModel, MemberKind};
use nalgebra::{Matrix3, Vector3};

/// A member's state at a configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MemberState {
    /// Its length L (m).
    pub length: f64,
    /// Its unit vector n from the start to the end node.
    pub direction: Vector3<f64>,
    /// Its rest length L₀ at the load factor of the state (m).
    pub rest_length: f64,
    /// Its tension t (N, compression negative).
    pub tension: f64,
    /// Whether it is a string shorter than its rest length (no force, no stiffness).
    pub slack: bool,
}

/// The state of every member at the node positions `x` and load factor `lambda` (which sets
/// the driven rest lengths, [`ElasticModel::rest_length`]), then of every cluster's segments
/// ([`segment_states`]).
///
/// ```
/// use nalgebra::Vector3;
/// use tensegrity_path::{forces::member_states, ElasticMember, ElasticModel, MemberKind};
/// let string = ElasticMember { nodes: [0, 1], kind: MemberKind::String, ea: 100.0, rest_length: 1.0 };
/// let m = ElasticModel { nodes: vec![Vector3::zeros(), Vector3::x()], members: vec![string],
///     clusters: Vec::new(),
///     supports: vec![], load: vec![Vector3::zeros(); 2], drivers: Default::default() };
/// let s = member_states(&m, &[Vector3::zeros(), Vector3::new(1.1, 0.0, 0.0)], 0.0);
/// assert!((s[0].tension - 10.0).abs() < 1e-12 && !s[0].slack);
/// let s = member_states(&m, &[Vector3::zeros(), Vector3::new(0.9, 0.0, 0.0)], 0.0);
/// assert!(s[0].tension == 0.0 && s[0].slack);
/// ```
pub fn member_states(model: &ElasticModel, x: &[Vector3<f64>], lambda: f64) -> Vec<MemberState> {
    model
        .members
        .iter()
        .enumerate()
        .map(|(k, m)| {
            let [i, j] = m.nodes;
            let d = x[j] - x[i];
            let length = d.norm();
            let rest_length = model.rest_length(k, lambda);
            let stretch = length - rest_length;
            let slack = m.kind == MemberKind::String && stretch <= 0.0;
            MemberState {
                length,
                direction: d / length,
                rest_length,
                tension: if slack {
                    0.0
                } else {
                    m.ea * stretch / rest_length
                },
                slack,
            }
        })
        .chain(segment_states(model, x, lambda))
        .collect()
}

/// The states of the clusters' segments at positions `x` and load factor `lambda` (the
/// driven rest lengths, [`ElasticModel::cluster_rest_length`]; [`crate::clusters`]), in
/// order.
pub fn segment_states(model: &ElasticModel, x: &[Vector3<f64>], lambda: f64) -> Vec<MemberState> {
    let mut out = Vec::new();
    for (k, c) in model.clusters.iter().enumerate() {
        let rest_length = model.cluster_rest_length(k, lambda);
        let start = out.len();
        for [a, b] in c.segments() {
            let d = x[b] - x[a];
            let length = d.norm();
            out.push(MemberState {
                length,
                direction: d / length,
                rest_length,
                tension: 0.0,
                slack: true,
            });
        }
        if let Some(friction) = &c.friction {
            // each segment its own material s_i (crate::clusters): a string of rigidity k L₀
            let ea = c.stiffness * c.rest_length;
            for (s, &rest) in out[start..].iter_mut().zip(&friction.rest_lengths) {
                set_segment(s, ea, rest);
            }
            continue;
        }
        let total: f64 = out[start..].iter().map(|s| s.length).sum();
        let slack = total <= rest_length;
        for s in &mut out[start..] {
            s.slack = slack;
            s.tension = if slack {
                0.0
            } else {
                c.stiffness_at(rest_length) * (total - rest_length)
            };
        }
    }
    out
}

/// A frictional cluster's segment state at its own rest length `rest` (m), the cluster's
/// rigidity `ea` (N): t = EA (l − s)/s, slack when l ≤ s.
pub fn set_segment(s: &mut MemberState, ea: f64, rest: f64) {
    s.rest_length = rest;
    s.slack = s.length <= rest;
    s.tension = tensegrity_core::capstan::segment_tension(ea, s.length, rest);
}

/// The resisting forces R_i at every node (crate docs) from the member states (a cluster's
/// segments pull like strings with the cluster's tension, [`crate::clusters`]).
pub fn resisting_forces(model: &ElasticModel, states: &[MemberState]) -> Vec<Vector3<f64>> {
    let mut r = vec![Vector3::zeros(); model.nodes.len()];
    for ([a, b], s) in model.state_nodes().zip(states) {
        let f = s.direction * s.tension;
        r[a] -= f;
        r[b] += f;
    }
    r
}

/// dR/dλ at fixed free coordinates: what the driven rest lengths (dt/dλ = −EA L ΔL₀/L₀²) and
/// the held nodes' motion (K_k (d_j − d_i) per member, `held_motion` per unit λ) do to the
/// resisting forces; zero without drivers.
pub fn driven_forces(
    model: &ElasticModel,
    states: &[MemberState],
    held_motion: &[Vector3<f64>],
) -> Vec<Vector3<f64>> {
    let mut r = vec![Vector3::zeros(); model.nodes.len()];
    let changes = &model.drivers.rest_length_changes;
    for (k, (m, s)) in model.members.iter().zip(states).enumerate() {
        if s.slack {
            continue;
        }
        let [i, j] = m.nodes;
        let mut f = Vector3::zeros();
        if let Some(&dl0) = changes.get(k) {
            let dt = -m.ea * s.length / (s.rest_length * s.rest_length) * dl0;
            f += s.direction * dt;
        }
        let rel = held_motion[j] - held_motion[i];
        if rel.norm() > 0.0 {
            let nn = s.direction * s.direction.transpose();
            let local =
                nn * (m.ea / s.rest_length) + (Matrix3::identity() - nn) * (s.tension / s.length);
            f += local * rel;
        }
        r[i] -= f;
        r[j] += f;
    }
    r
}
