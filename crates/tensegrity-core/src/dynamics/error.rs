//! The error type of the dynamics module.
//!
//! Kept separate from [`CoreError`] for now (the lead may merge it); every variant carries
//! structured fields that name the time, member or node concerned.

use crate::error::CoreError;
use crate::structure::MemberId;
use thiserror::Error;

/// Everything that can go wrong when setting up or integrating a dynamic simulation.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DynamicsError {
    /// A member lacks a property that dynamics needs (bar mass, string stiffness).
    #[error("{member}: dynamics needs its {property}, which is not given")]
    MissingProperty {
        /// The member.
        member: MemberId,
        /// The missing property, e.g. `mass` or `stiffness`.
        property: &'static str,
    },
    /// A node that no bar touches and that is not fixed in all three directions: it would
    /// be a massless free point, which rigid-bar dynamics cannot integrate.
    #[error("node {node}: no bar ends at it and it is not fixed in all three directions (massless free node)")]
    MasslessNode {
        /// The node.
        node: usize,
    },
    /// The initial velocities violate a constraint (a fixed direction moves, or a bar changes
    /// length).
    #[error("{item}: initial velocity is inconsistent with the constraints ({reason}, residual {residual:e})")]
    InconsistentVelocity {
        /// The offending node or bar, e.g. `node 3` or `bar 1`.
        item: String,
        /// What is violated.
        reason: &'static str,
        /// The size of the violation.
        residual: f64,
    },
    /// The adaptive integrator needed a step smaller than its minimum.
    #[error("step size fell below the minimum {h_min:e} s at t = {t} s")]
    StepSizeTooSmall {
        /// Time at which the step was rejected.
        t: f64,
        /// The minimum step size.
        h_min: f64,
    },
    /// A NaN or infinity appeared in the state.
    #[error("non-finite state at t = {t} s in {member}")]
    NonFinite {
        /// Time of the step that produced it.
        t: f64,
        /// The bar owning the offending node.
        member: MemberId,
    },
    /// A node moved implausibly far (the run diverged).
    #[error("blow-up at t = {t} s: {member} moved {distance:e} m (limit {limit:e} m)")]
    BlowUp {
        /// Time of detection.
        t: f64,
        /// The bar owning the offending node.
        member: MemberId,
        /// Distance from the initial position.
        distance: f64,
        /// The blow-up limit.
        limit: f64,
    },
    /// The constraint (Ω or RATTLE) system is singular: redundant or conflicting constraints,
    /// e.g. a bar pinned at both ends.
    #[error("the constraint system is singular: pivot {rank} of {expected} is not positive (redundant constraints, e.g. a bar fixed at both ends?)")]
    SingularConstraint {
        /// Number of pivots that succeeded (a lower bound on the numerical rank).
        rank: usize,
        /// The size of the system.
        expected: usize,
    },
    /// The RATTLE position solve did not converge.
    #[error("RATTLE constraint iteration did not converge at t = {t} s (residual {residual:e})")]
    ConstraintNotConverged {
        /// Time of the step.
        t: f64,
        /// Remaining constraint residual.
        residual: f64,
    },
    /// An invalid numerical parameter of the simulation.
    #[error("{name} = {value}: {reason}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// Why it is invalid.
        reason: &'static str,
    },
    /// An invalid scene specification (ground, actuation table, ...).
    #[error("{item}: {reason}")]
    InvalidSpec {
        /// The offending item, e.g. `actuation 2`.
        item: String,
        /// What is wrong.
        reason: String,
    },
    /// An error from the core model.
    #[error(transparent)]
    Core(#[from] CoreError),
}
