//! Newton's method for R(x) = λ P on the free coordinates at a fixed load factor (crate
//! docs): K(x) δq = λ P − R(x), x ← x + δx, until the largest residual force component is
//! within the tolerance ([`tolerance`]).

use crate::dofs::Dofs;
use crate::error::{PathError, Result};
use crate::factor::Factored;
use crate::forces::{member_states, resisting_forces, MemberState};
use crate::model::ElasticModel;
use nalgebra::{DVector, Vector3};

/// Newton iterations before giving up.
pub const MAX_ITERATIONS: usize = 50;

/// The relative residual accepted: 10⁻¹⁰ of the force scale (the load and the members'
/// tensions).
pub const RELATIVE_TOLERANCE: f64 = 1e-10;

/// An equilibrium: positions, load factor, member states and the residual left.
#[derive(Debug, Clone, PartialEq)]
pub struct Equilibrium {
    /// Node positions (m).
    pub x: Vec<Vector3<f64>>,
    /// The load factor λ.
    pub lambda: f64,
    /// Every member's state.
    pub states: Vec<MemberState>,
    /// The largest residual force component on a free coordinate (N).
    pub residual: f64,
}

/// The residual force on the free coordinates, D + λ P − R(x), at node positions `x` with
/// the member `states` there (D the dead load, [`crate::model::Drivers::dead_load`]; R the
/// members' and the springs' resisting forces, [`Dofs::spring_forces`]).
pub fn residual(
    model: &ElasticModel,
    dofs: &Dofs,
    x: &[Vector3<f64>],
    states: &[MemberState],
    lambda: f64,
) -> DVector<f64> {
    let r = resisting_forces(model, states);
    let springs = dofs.spring_forces(&model.nodes, x, lambda);
    let f: Vec<Vector3<f64>> = (0..r.len())
        .map(|i| model.load[i] * lambda + model.dead_load(i) - r[i] - springs[i])
        .collect();
    dofs.reduce(&f)
}

/// The largest absolute component of the residual `r` (N); infinite when a component is not
/// finite, so that a residual that left double precision never passes as converged (a
/// maximum that skipped NaN would).
///
/// ```
/// use nalgebra::dvector;
/// use tensegrity_path::newton::largest_residual;
/// assert_eq!(largest_residual(&dvector![1.0, -3.0]), 3.0);
/// assert_eq!(largest_residual(&dvector![1.0, f64::NAN]), f64::INFINITY);
/// ```
pub fn largest_residual(r: &DVector<f64>) -> f64 {
    if r.iter().all(|v| v.is_finite()) {
        r.amax()
    } else {
        f64::INFINITY
    }
}

/// The residual accepted at load factor `lambda` (N): [`RELATIVE_TOLERANCE`] of the larger of
/// |λ| ‖P‖∞ and the largest |tension|, and never below what double precision resolves on
/// the stiffest member or spring, 64 ε · max(EA/L₀, k) · max‖x‖ (a spring's force is
/// balanced by the load and the tensions, so they bound it).
pub fn tolerance(
    model: &ElasticModel,
    states: &[MemberState],
    x: &[Vector3<f64>],
    lambda: f64,
) -> f64 {
    let dead = model
        .drivers
        .dead_load
        .iter()
        .map(|d| d.amax())
        .fold(0.0, f64::max);
    let load = model.load.iter().map(|p| p.amax()).fold(0.0, f64::max) * lambda.abs() + dead;
    let tension = states.iter().map(|s| s.tension.abs()).fold(0.0, f64::max);
    let springs = model.supports.iter().filter_map(|s| s.stiffness);
    let stiff = model
        .members
        .iter()
        .zip(states)
        .map(|(m, s)| m.ea / s.rest_length)
        .chain(springs)
        .chain(model.clusters.iter().map(|c| c.stiffness))
        .fold(0.0, f64::max);
    let size = x.iter().map(|v| v.norm()).fold(1e-3, f64::max);
    (RELATIVE_TOLERANCE * load.max(tension)).max(64.0 * f64::EPSILON * stiff * size)
}

/// ∂(λP − R)/∂λ on the free coordinates at fixed free coordinates: the reference load less
/// what the drivers do to the resisting forces ([`crate::forces::driven_forces`]) — the
/// right-hand side of the path's tangent, K v = dλ this.
pub fn load_rate(model: &ElasticModel, dofs: &Dofs, states: &[MemberState]) -> DVector<f64> {
    let mut driven = crate::forces::driven_forces(model, states, &dofs.held_motion);
    crate::clusters::add_driven_forces(model, states, &dofs.held_motion, &mut driven);
    let mut f: Vec<Vector3<f64>> = model.load.iter().zip(&driven).map(|(p, d)| p - d).collect();
    // a spring whose anchor moves: its resisting force k d d·(u − λ a) falls by k d (d·a)
    for s in &dofs.springs {
        f[s.node] += s.direction * (s.stiffness * s.direction.dot(&s.anchor));
    }
    dofs.reduce(&f)
}

/// Refuses a load factor at which a driven rest length is no longer positive.
pub fn check_rest_lengths(model: &ElasticModel, lambda: f64) -> Result<()> {
    // the item's name is only written for the error (this runs at every Newton iteration)
    let members = (0..model.members.len()).map(|k| ("member", k, model.rest_length(k, lambda)));
    let clusters =
        (0..model.clusters.len()).map(|c| ("cluster", c, model.cluster_rest_length(c, lambda)));
    for (kind, k, l0) in members.chain(clusters) {
        if l0.is_nan() || l0 <= 0.0 {
            return Err(PathError::model(
                format!("{kind} {k}"),
                format!(
                    "its driven rest length L0 + λ ΔL0 = {l0} m is not positive at λ = {lambda}"
                ),
            ));
        }
    }
    Ok(())
}

/// Newton at load factor `lambda` from `x0`, an equilibrium (or guess) at `lambda0`: the
/// held nodes first moved by their motion over λ − λ₀.
pub fn solve(
    model: &ElasticModel,
    dofs: &Dofs,
    x0: &[Vector3<f64>],
    lambda0: f64,
    lambda: f64,
) -> Result<Equilibrium> {
    check_rest_lengths(model, lambda)?;
    let mut x = dofs.drive(x0, lambda - lambda0);
    for iteration in 0..=MAX_ITERATIONS {
        let states = member_states(model, &x, lambda);
        let r = residual(model, dofs, &x, &states, lambda);
        let worst = largest_residual(&r);
        let tol = tolerance(model, &states, &x, lambda);
        if worst <= tol {
            return Ok(Equilibrium {
                x,
                lambda,
                states,
                residual: worst,
            });
        }
        if iteration == MAX_ITERATIONS || !worst.is_finite() {
            // the last iteration or a residual that left double precision (no NaN in the
            // error: the tolerance of a state that is not finite is not one)
            return Err(PathError::NotConverged {
                lambda,
                residual: worst,
                tolerance: if tol.is_finite() { tol } else { 0.0 },
                iterations: iteration,
                hint: if worst.is_finite() {
                    "; smaller load steps, or the arc-length path if a limit point lies on the way"
                } else {
                    "; the iteration left double precision: smaller load steps, or the arc-length path if a limit point lies on the way"
                }
                .into(),
            });
        }
        let dq = Factored::of(model, dofs, &states)
            .and_then(|mut k| k.solve(&r))
            .ok_or(PathError::Singular { lambda })?;
        for (u, xi) in dofs.expand(&dq, x.len()).iter().zip(x.iter_mut()) {
            *xi += u;
        }
    }
    Err(PathError::Singular { lambda })
}
