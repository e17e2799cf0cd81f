//! The [`Integrator`] trait: one step of a time integrator of y' = f(t, y), driven by
//! [`Simulation::run`](super::Simulation::run).
//!
//! The integrator is generic over the system it advances ([`System`]: the state and its
//! right-hand side f, with [`ConstrainedSystem`](super::ConstrainedSystem) and
//! [`ContactSystem`](super::ContactSystem) for the methods that need the constraints or the
//! contact split); the simulation steps [`Model`](super::Model), whose state y holds the
//! class-1 positions then velocities and whose f is [`Model::rhs`](super::Model::rhs) (or,
//! for RATTLE, the applied forces with the constraint multipliers). One trait covers
//!
//! * fixed-step methods ([`Rk4`](super::Rk4), [`Rattle`](super::Rattle)): every step is
//!   accepted and the driver places the steps on the grid t_k = k·dt, shortened to land on
//!   output times;
//! * adaptive methods ([`Dopri5`](super::Dopri5)): a step may be rejected, and every outcome
//!   carries the step the method proposes next; the driver caps it at the maximum step and the
//!   end time;
//! * constraint-preserving methods ([`Rattle`](super::Rattle)): they keep ‖b_k‖ = l_k and
//!   N P = D themselves, so the driver does not project their states;
//! * dense output: a method that can evaluate its solution inside the last accepted step
//!   ([`Integrator::interpolate`]) gets output samples and events located through it; without
//!   it the driver lands on output times and the event module interpolates linearly.
//!
//! The counters (accepted and rejected steps, right-hand-side evaluations) are kept by the
//! driver and the system's workspace; see [`IntegratorStats`]. The implicit, L-stable
//! [`Sdirk`](super::Sdirk) fits the same trait: its Newton failures become rejected steps with
//! a smaller proposal.

pub use super::kind::IntegratorKind;
use super::system::System;
use serde::Serialize;
use std::fmt;
use tensegrity_core::error::CoreError;

/// What one attempted step did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepOutcome {
    /// The step was accepted: the state now holds y(t + h). A rejected step leaves the state
    /// untouched.
    pub accepted: bool,
    /// The step size the method proposes next (after a rejection: the size to retry with).
    /// Fixed-step methods return the step they were given.
    pub h_next: f64,
}

impl StepOutcome {
    /// An accepted step of a fixed-step method.
    pub fn fixed(h: f64) -> Self {
        Self {
            accepted: true,
            h_next: h,
        }
    }
}

/// Work counters of one run: the numbers a performance regression changes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct IntegratorStats {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps (adaptive methods).
    pub rejected_steps: u64,
    /// Right-hand-side (force) evaluations.
    pub rhs_evals: u64,
}

/// One time integrator of the system `S` (module docs).
///
/// The driver calls [`start`](Self::start) once at the initial state, then
/// [`step`](Self::step) until the end time; after it modified an accepted state itself (a
/// projection onto the constraints) it calls [`invalidate`](Self::invalidate).
pub trait Integrator<S: System>: fmt::Debug {
    /// Which integrator this is.
    fn kind(&self) -> IntegratorKind;

    /// Whether the method chooses its own steps (and may reject them).
    fn is_adaptive(&self) -> bool {
        false
    }

    /// Whether the method keeps bar lengths and N P = D itself (no projection needed).
    fn preserves_constraints(&self) -> bool {
        false
    }

    /// Whether [`interpolate`](Self::interpolate) is available.
    fn has_dense_output(&self) -> bool {
        false
    }

    /// Prepares a run from (t, y) and returns the first step to try (at most `h_max`).
    fn start(
        &mut self,
        _system: &S,
        _ws: &mut S::Workspace,
        _t: f64,
        _y: &[f64],
        h_max: f64,
    ) -> Result<f64, CoreError> {
        Ok(h_max)
    }

    /// Attempts one step of size `h` from (t, y), advancing `y` in place when accepted.
    fn step(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<StepOutcome, CoreError>;

    /// Dense output: writes the solution at time `t` inside the last accepted step into
    /// `out` and returns `true`, or returns `false` (leaving `out` alone) when the method has
    /// none.
    fn interpolate(&self, _t: f64, _out: &mut [f64]) -> bool {
        false
    }

    /// Forgets cached stages (the state was changed outside the integrator).
    fn invalidate(&mut self) {}

    /// A copy of this integrator with everything it keeps between steps (stages, Jacobians,
    /// contact memory): a saved state of a stepped simulation restores it, so the restored
    /// run takes the steps the original took. `None`: a method that cannot be copied (its
    /// restore restarts it instead).
    fn boxed_clone(&self) -> Option<Box<dyn Integrator<S>>> {
        None
    }

    /// The largest step the driver lets an adaptive method take in a run of step `dt`
    /// (`dt` itself, except for methods that take multiples of it, e.g. [`Flight`](super::Flight)).
    fn max_step(&self, dt: f64) -> f64 {
        dt
    }

    /// Implicit stage equations solved so far and how many of them ended above their
    /// acceptance residual ([`ImexArk`](super::ImexArk); (0, 0) for methods without such
    /// solves or whose failed solves become rejected steps).
    fn implicit_solves(&self) -> (u64, u64) {
        (0, 0)
    }

    /// Contact node-steps counted so far (a contact node touching the ground at three
    /// consecutive step ends) and how many of them chattered: the node's tangential velocity
    /// changed in the opposite direction to its change over the previous step, by a large
    /// part of its speed ([`Imex`](super::Imex), whose splitting lets a creeping node chatter;
    /// (0, 0) for methods that cannot).
    fn contact_chatter(&self) -> (u64, u64) {
        (0, 0)
    }
}

/// The last stage of the standard starting-step heuristic (Hairer, Nørsett & Wanner, §II.4):
/// from the trial step `h0` and the scaled derivative norms `d1` (of f) and `d2` (of its
/// change over h0), h1 = (0.01 / max(d1, d2))^exponent with exponent = 1/(order + 1); the
/// start is min(100 h0, h1, h_max).
pub(crate) fn starting_step(h0: f64, d1: f64, d2: f64, exponent: f64, h_max: f64) -> f64 {
    let h1 = if d1.max(d2) <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d1.max(d2)).powf(exponent)
    };
    (100.0 * h0).min(h1).min(h_max)
}
