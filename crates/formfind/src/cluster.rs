//! Form-finding with clustered strings: one prescribed tension along a string through several
//! nodes over frictionless pulleys or sliding joints ([`crate::ClusterString`]).
//!
//! **One tension, not one force density.** A frictionless cluster c of tension t_c pulls the
//! two nodes of each of its segments i toward each other with t_c e_i (e_i the segment's unit
//! vector, l_i its length): in the force density method's terms each segment has its own
//! force density
//!
//! > q_i = t_c / l_i,
//!
//! which depends on the unknown geometry. One force density along all segments would give
//! tensions q l_i that differ where the segments' lengths differ, which a string running over
//! frictionless pulleys cannot carry; so a topology gives a cluster's tension (`force`, N) and
//! never a force density.
//!
//! **Force density method** (held nodes, with or without loads): the form is the fixed point
//! of the linear force density solve (Schek's force density method with the force constraints
//! l_i q_i = t_c met by iteration, as compas_fd's and jax-fdm's constrained solves do):
//!
//! > q_i ← t_c / l_i(X_k),  D(q) = Cᵀ diag(q) C,  D_ff X_{k+1,f} = P_f(X_k) − D_fx X_x,
//!
//! the members keeping their given force densities and P the point loads plus the lumped
//! self-weight at X_k (the `fdm` module). It starts from the topology's `nodes` (the fixed
//! ones at their positions) or, without them, from q_i = t_c / l_ref with l_ref the size of
//! the fixed nodes (the diagonal of their bounding box) over the number of segments. With
//! δ_k the largest change of a node coordinate in step k relative to the form's size and
//! ρ = δ_k / δ_{k−1} the observed rate of contraction, it stops when both δ_k and the
//! a-posteriori bound δ_k ρ / (1 − ρ) on the remaining distance to the fixed point are at
//! most `tolerance` (the settings', default 10⁻¹²), and fails with
//! [`crate::FormFindError::NotConverged`] (the larger of the two as its residual) after
//! `max_iterations`: never a result that is called converged when it is not. The map
//! contracts slowly where a cluster slides nearly freely (the ring on a clothesline, one free
//! node on a cluster between two held ones under a load W, contracts at about 0.8 for
//! W = t, and 125 steps reach 10⁻¹²); where no equilibrium exists (W ≥ 2 t on the ring) it
//! does not converge and is reported so.
//!
//! **Independent check.** The reported force densities of the segments are t_c / l_i at the
//! returned geometry (not the ones of the last solve), so the reported residuals
//! (`residual`, and with held nodes `equilibrium_residual`: ‖Σ forces‖ at the free nodes
//! relative to the forces meeting there) are those of segment tensions exactly t_c.
//!
//! **Dynamic relaxation** applies the cluster's forces t_c e_i directly (a constant-force
//! element: its geometric stiffness t_c / l_i enters the fictitious masses), the members
//! acting through their rest lengths and stiffnesses as before (the `dr` module).
//!
//! The adaptive method finds force densities and takes no clusters; a free-standing
//! topology with clusters under the force density method is refused (its form is fixed only
//! up to an affine map, which changes the segments' lengths and so their force densities):
//! hold nodes, or give the members rest lengths (dynamic relaxation).
//!
//! **Rest lengths.** At the prestress level the cluster carries α t_c (α the scale of the
//! self-stress, 1 for a loaded form, the `synth` module); with axial stiffness EA (N: its
//! `stiffness`, else E A of its `material` and `area`, else the synthesis' stiffness) and
//! length L = Σ l_i its whole rest length solves α t_c = EA (L − L₀) / L₀:
//!
//! > L₀ = L / (1 + α t_c / EA) = L − α t_c / k,  k = EA / L₀ (N/m, the scene's stiffness).

use crate::error::{FormFindError, Result};
use crate::fdm::{held_positions, member_weights, point_loads, with_weight, FixedSystem};
use crate::method::Settings;
use crate::topology::Topology;
use nalgebra::Vector3;
use serde::Serialize;

/// The state of one cluster in a found form.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClusterState {
    /// The nodes it passes through, in order.
    pub nodes: Vec<usize>,
    /// Its tension t (N): the prescribed `force` (the same on every segment).
    pub tension: f64,
    /// Its length L = Σ l_i in the found form (m).
    pub length: f64,
    /// The length l_i of each segment (m).
    pub segment_length: Vec<f64>,
    /// The force density t / l_i of each segment (N/m).
    pub segment_force_density: Vec<f64>,
}

/// The clusters' states at `nodes`.
pub(crate) fn states(topology: &Topology, nodes: &[Vector3<f64>]) -> Vec<ClusterState> {
    let state = |c: &crate::ClusterString| {
        let t = c.force.unwrap_or(0.0);
        let l: Vec<f64> = c
            .segments()
            .map(|[a, b]| (nodes[b] - nodes[a]).norm())
            .collect();
        ClusterState {
            nodes: c.nodes.clone(),
            tension: t,
            length: l.iter().sum(),
            segment_force_density: l.iter().map(|l| t / l).collect(),
            segment_length: l,
        }
    };
    topology.clusters.iter().map(state).collect()
}

/// The force densities of the members (`q`) followed by t_c / l_i of every segment at
/// `nodes`; a segment of zero or non-finite length is the error.
pub(crate) fn with_segments(
    topology: &Topology,
    q: &[f64],
    nodes: &[Vector3<f64>],
) -> Result<Vec<f64>> {
    let tension = topology.segment_tensions();
    let pairs = topology.force_pairs();
    let nm = topology.n_members();
    let mut out = q[..nm].to_vec();
    for (s, (&[a, b], t)) in pairs[nm..].iter().zip(tension).enumerate() {
        let l = (nodes[b] - nodes[a]).norm();
        if !(l.is_finite() && l > 0.0) {
            return Err(FormFindError::NonFinite {
                method: "fdm".into(),
                item: format!(
                    "the length {l} of {}'s segment (nodes {a}, {b}), its force density t/l",
                    topology.member_name(nm + s)
                ),
            });
        }
        out.push(t / l);
    }
    Ok(out)
}

/// A clustered form of the force density method: nodes, the load on every node (N), the
/// force densities of the members and segments at the nodes, and the iterations.
pub(crate) type Clustered = (Vec<Vector3<f64>>, Vec<Vector3<f64>>, Vec<f64>, usize);

/// The start of the fixed point (module docs): the topology's nodes with the held ones at
/// their positions, or `None` (then q_i = t_c / l_ref for the first solve).
fn start(topology: &Topology) -> Option<Vec<Vector3<f64>>> {
    let mut x = topology.initial_nodes()?;
    for f in &topology.fixed {
        x[f.node] = Vector3::from(f.position);
    }
    let pairs = topology.force_pairs();
    let ok = pairs[topology.n_members()..]
        .iter()
        .all(|&[a, b]| (x[b] - x[a]).norm() > 0.0);
    ok.then_some(x)
}

/// The force density method with clusters on held nodes (module docs): the fixed point of
/// q_i ← t_c / l_i, D_ff X_f = P_f − D_fx X_x, the members' force densities `q` kept.
pub(crate) fn fixed_point(
    topology: &Topology,
    q: &[f64],
    settings: &Settings,
) -> Result<Clustered> {
    let fixed = held_positions(topology);
    let point = point_loads(topology);
    let weights = member_weights(topology);
    let mut x = start(topology);
    let (mut change, mut bound, mut done) = (f64::INFINITY, f64::INFINITY, 0);
    for iteration in 1..=settings.max_iterations {
        done = iteration;
        let (q_all, p) = match &x {
            Some(x) => (
                with_segments(topology, q, x)
                    .map_err(|_| diverged(iteration, settings.tolerance))?,
                with_weight(topology, &point, &weights, x),
            ),
            None => (first_guess(topology, q), point.clone()),
        };
        let scale = q_all
            .iter()
            .fold(0.0f64, |a, v| a.max(v.abs()))
            .max(f64::MIN_POSITIVE);
        let unit: Vec<f64> = q_all.iter().map(|v| v / scale).collect();
        let p: Vec<Vector3<f64>> = p.iter().map(|f| f / scale).collect();
        let next = FixedSystem::new(topology, &unit, &fixed)?.solve(&p)?;
        let size = crate::analysis::size(&next).max(f64::MIN_POSITIVE);
        if !size.is_finite() {
            return Err(diverged(iteration, settings.tolerance));
        }
        let previous = change;
        change = x.as_ref().map_or(f64::INFINITY, |x| {
            let d = next
                .iter()
                .zip(x)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).amax()));
            d / size
        });
        x = Some(next);
        if change.is_nan() {
            break;
        }
        // the distance to the fixed point of a map contracting at the rate ρ is at most
        // change · ρ / (1 − ρ), ρ estimated from the last two changes
        let rate = change / previous;
        bound = if rate < 1.0 {
            change * rate / (1.0 - rate)
        } else {
            f64::INFINITY
        };
        if change == 0.0 || (change <= settings.tolerance && bound <= settings.tolerance) {
            let x = x.unwrap_or_default();
            let q_all = with_segments(topology, q, &x)?;
            let p = with_weight(topology, &point, &weights, &x);
            return Ok((x, p, q_all, iteration));
        }
    }
    Err(FormFindError::NotConverged {
        method: "fdm (the clusters' fixed point q_i = t/l_i)".into(),
        iterations: done,
        residual: change.max(bound),
        tolerance: settings.tolerance,
    })
}

/// The fixed point ran off to infinity in step `iteration` (a node or a segment's length
/// overflowed): no equilibrium with these tensions and loads.
fn diverged(iteration: usize, tolerance: f64) -> FormFindError {
    FormFindError::NotConverged {
        method: "fdm (the clusters' fixed point q_i = t/l_i diverged: the form ran off to \
                 infinity, so there is no equilibrium with these tensions, force densities \
                 and loads — e.g. a load beyond what the clusters' tensions carry)"
            .into(),
        iterations: iteration,
        residual: f64::INFINITY,
        tolerance,
    }
}

/// q_i = t_c / l_ref on every segment (module docs), after the members' `q`.
fn first_guess(topology: &Topology, q: &[f64]) -> Vec<f64> {
    let held: Vec<Vector3<f64>> = topology.fixed.iter().map(|f| f.position.into()).collect();
    let size = crate::analysis::size(&held);
    let segments = topology.n_segments().max(1) as f64;
    let l_ref = if size > 0.0 { size / segments } else { 1.0 };
    let mut out = q[..topology.n_members()].to_vec();
    out.extend(topology.segment_tensions().iter().map(|t| t / l_ref));
    out
}
