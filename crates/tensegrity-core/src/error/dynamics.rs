//! [`DynamicsError`]: a rigid-bar dynamics model that cannot be set up (bad input) or a run
//! that failed on the way (numerical: a step too small, a blow-up, a divergence).

use crate::member_id::MemberId;
use crate::request::{Categorized, Category};
use thiserror::Error;

/// Everything that can go wrong in building or integrating a dynamics model.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum DynamicsError {
    /// A node that no bar touches and that is not fixed in all three directions. It would be
    /// a massless free point (all mass is in the bars), which rigid-bar dynamics cannot
    /// integrate.
    #[error("node {node}: no bar ends at it and it is not fixed in all three directions (massless free node)")]
    FreeNodeWithoutBar {
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
    /// Rigid-bar dynamics needs at least one bar (all the mass is in the bars).
    #[error("structure: rigid-bar dynamics needs at least one bar (all mass is in the bars)")]
    NoBars,
    /// A ground contact candidate names a node that does not exist.
    #[error("ground node {index}: node {node} does not exist ({n_nodes} nodes)")]
    GroundNodeOutOfRange {
        /// Position in the list of contact candidates.
        index: usize,
        /// The node named.
        node: usize,
        /// Number of nodes of the structure.
        n_nodes: usize,
    },
    /// The ground's normal is zero or not finite.
    #[error("ground: normal must be a finite non-zero vector, got [{x}, {y}, {z}]")]
    InvalidGroundNormal {
        /// x component.
        x: f64,
        /// y component.
        y: f64,
        /// z component.
        z: f64,
    },
    /// The adaptive integrator needed a step smaller than its minimum.
    #[error("step size fell below the minimum {h_min:e} s at t = {t:?} s")]
    StepSizeTooSmall {
        /// Time at which the step was rejected.
        t: f64,
        /// The minimum step size.
        h_min: f64,
    },
    /// The run needed more accepted steps than allowed.
    #[error("more than {max_steps} steps needed: stopped at t = {t:?} s")]
    MaxStepsExceeded {
        /// Time reached when the limit was hit.
        t: f64,
        /// The limit on accepted steps.
        max_steps: u64,
    },
    /// A NaN or infinity appeared in the state or the forces.
    #[error("non-finite state at t = {t:?} s in {member}{hint}")]
    NonFiniteState {
        /// Time of the step that produced it.
        t: f64,
        /// The bar owning the offending node.
        member: MemberId,
        /// The remedy, from the run's integrator (filled in by the simulation).
        hint: StepHint,
    },
    /// A node moved implausibly far (the run diverged).
    #[error("blow-up at t = {t:?} s: {member} moved {distance:e} m (limit {limit:e} m){hint}")]
    BlowUp {
        /// Time of detection.
        t: f64,
        /// The bar owning the offending node.
        member: MemberId,
        /// Distance from the initial position.
        distance: f64,
        /// The blow-up limit.
        limit: f64,
        /// The remedy, from the run's integrator (filled in by the simulation).
        hint: StepHint,
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
    /// The state ran away during the run (a constraint system that factored at the start
    /// became singular, or the RATTLE iteration failed): the step is too large for the
    /// stiffness.
    #[error("the integration diverged at t = {t:?} s ({what}): the step is too large for the stiffness of the strings or the ground; use a smaller `dt`, `integrator = rk45` (adaptive) or `integrator = sdirk` (implicit, for stiff strings and contact)")]
    Diverged {
        /// Time of the last accepted state (s).
        t: f64,
        /// What failed.
        what: &'static str,
    },
    /// The elastic (node-mass) dynamics ran away: a force became non-finite. Its remedy names
    /// what an elastic model can run (a smaller step, the implicit Newmark method), not the
    /// rigid-bar integrators.
    #[error("the elastic dynamics diverged at t = {t:?} s ({what}): the step ({dt:?} s) is likely too large for the members' stiffness or damping; use a smaller `dt`, or `integrator = newmark` (implicit, stable at any step)")]
    ElasticDiverged {
        /// Time of the last accepted state (s).
        t: f64,
        /// The step (s).
        dt: f64,
        /// What failed.
        what: &'static str,
    },
    /// A RATTLE step whose constraint iteration failed: the step moved the bars so far that the
    /// Newton iteration on their lengths (and N P = D) did not converge, or its matrix
    /// G M⁻¹ Gᵀ lost rank on the way. The constraints themselves are fine (they factored at the
    /// start): the step is too large for the motion.
    #[error("the RATTLE step from t = {t:?} s (step {dt:?} s) failed: {}: the step is too large for the motion; use a smaller `dt`, `integrator = rk45` (adaptive) or `integrator = sdirk` (implicit, for stiff strings and contact)", rattle_cause(.residual))]
    RattleStepFailed {
        /// Time at the start of the failed step (s).
        t: f64,
        /// The step (s), to 12 significant digits.
        dt: f64,
        /// The constraint residual max |g| where the iteration stopped; `None` when the
        /// iteration converged but the matrix G M⁻¹ Gᵀ lost rank at the new positions.
        residual: Option<f64>,
    },
    /// The constraint projection (positions back onto the bar lengths) did not converge.
    #[error("the constraint projection did not converge at t = {t:?} s (residual {residual:e})")]
    ConstraintNotConverged {
        /// Time of the step.
        t: f64,
        /// Remaining constraint residual.
        residual: f64,
    },
    /// An explicit method's step above its stability limit on the stiffest axial mode of an
    /// elastic model (RK4: h ω_max ≤ 2√2 on the imaginary axis): the run would blow up.
    #[error("the step {dt:.3e} s of `{integrator}` exceeds its stability limit {limit:.3e} s on the stiffest axial mode (ω = {omega:.4e} rad/s, period {period:.4e} s): use `integrator = newmark` (implicit, stable at any step) or a `dt` of at most {limit:.3e} s")]
    StepAboveStabilityLimit {
        /// The step (s).
        dt: f64,
        /// The largest stable step (s).
        limit: f64,
        /// The highest angular frequency of the model (rad/s).
        omega: f64,
        /// Its period 2π/ω (s).
        period: f64,
        /// The integrator's name.
        integrator: &'static str,
    },
    /// An implicit step whose Newton iteration did not reach equilibrium.
    #[error("the implicit step from t = {t:?} s (step {dt:?} s) did not converge: the force residual stayed at {residual:e} N after {iterations} Newton iterations: use a smaller `dt`")]
    ImplicitStepFailed {
        /// Time at the start of the step (s).
        t: f64,
        /// The step (s).
        dt: f64,
        /// The largest residual force component left (N).
        residual: f64,
        /// The iterations made.
        iterations: usize,
    },
    /// An action of a stepped simulation that cannot be applied: a non-finite rest length or
    /// rate (its actuator named, counted from 0 in the simulation's actuator list).
    #[error("actuator {actuator}: action {value:?} {reason}")]
    InvalidAction {
        /// The actuator.
        actuator: usize,
        /// The value given.
        value: f64,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// An actuator of a stepped simulation that cannot be built: an unknown string or
    /// cluster, a bad limit.
    #[error("actuator {actuator}: {reason}")]
    InvalidActuator {
        /// The actuator.
        actuator: usize,
        /// What is wrong, and what to give.
        reason: String,
    },
    /// A setting a model does not take (an integrator of rigid bars on an elastic model, …).
    #[error("{item}: {reason}")]
    Unsupported {
        /// The setting (`integrator = rattle`, …).
        item: String,
        /// Why, and what to use.
        reason: String,
    },
}

impl Categorized for DynamicsError {
    /// A model that cannot be set up (a massless free node, inconsistent initial velocities,
    /// no bar, a bad ground) is bad input; a run that fails on the way is numerical.
    fn category(&self) -> Category {
        match self {
            Self::FreeNodeWithoutBar { .. }
            | Self::InconsistentVelocity { .. }
            | Self::NoBars
            | Self::GroundNodeOutOfRange { .. }
            | Self::InvalidGroundNormal { .. }
            | Self::StepAboveStabilityLimit { .. }
            | Self::InvalidAction { .. }
            | Self::InvalidActuator { .. }
            | Self::Unsupported { .. } => Category::Input,
            _ => Category::Numerical,
        }
    }
}

/// The remedy a run-away state (a blow-up, a NaN) names, chosen by the run's integrator. The
/// error is raised where the state is checked; the simulation, which knows the integrator,
/// fills this in ([`StepHint::Unknown`] until then).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub enum StepHint {
    /// Not known: no remedy is named.
    #[default]
    Unknown,
    /// A fixed-step integrator (`rk4`, `rattle`) at step `dt` (s): the usual cause is a step
    /// too large for the stiffness.
    FixedStep {
        /// The step (s).
        dt: f64,
    },
    /// An adaptive integrator (`rk45`, `sdirk`): the step follows the error estimate, so the
    /// motion itself ran away.
    Adaptive,
    /// The elastic (node-mass) dynamics at step `dt` (s): its remedies are a smaller step and
    /// the implicit Newmark method (the rigid-bar integrators do not run it).
    Elastic {
        /// The step (s).
        dt: f64,
    },
}

impl std::fmt::Display for StepHint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Unknown => Ok(()),
            Self::FixedStep { dt } => write!(
                f,
                "; the step ({dt:?} s) is likely too large for the stiffness of the strings or the ground: use a smaller `dt`, or `integrator = sdirk` (implicit, for stiff strings and contact) or `integrator = rk45` (adaptive)"
            ),
            Self::Elastic { dt } => write!(
                f,
                "; the step ({dt:?} s) is likely too large for the members' stiffness or damping: use a smaller `dt`, or `integrator = newmark` (implicit, stable at any step)"
            ),
            Self::Adaptive => write!(
                f,
                "; the adaptive step followed the motion, so the motion itself ran away: check the loads, the supports and the ground"
            ),
        }
    }
}

/// What failed in a RATTLE step.
fn rattle_cause(residual: &Option<f64>) -> String {
    match residual {
        Some(r) => format!(
            "its constraint iteration did not converge (constraint residual {r:e} after 100 iterations)"
        ),
        None => "its constraint matrix G M⁻¹ Gᵀ lost rank at the new positions".into(),
    }
}
