//! Flight steps: a fixed-step method at its step `dt` while a ground contact node touches or
//! is about to, and at [`FLIGHT_RATIO`]·dt while every contact node is clear of the ground
//! ([`Flight`]). The step follows the motion: a wheel that hops spends much of its time in
//! the air, where only the strings bound an explicit step, and the ground's stiffness and
//! damping (the reason for a small `dt`) do not act.
//!
//! **Schedule.** Every step lands on the grid t_k = k·dt (a flight step on the coarse grid
//! k·H, H = [`FLIGHT_RATIO`]·dt), so a run's contact phases see exactly the steps the inner
//! method would take at `dt`. From a state where every contact node i has height z_i > 0
//! above the plane, the next step is a flight step to the next coarse grid point, unless a
//! node could reach the plane within it at its current approach speed:
//! z_i + min(0, ż_i)·h·[`APPROACH_SAFETY`] ≤ 0. A flight step is accepted only when no node
//! crossed the plane inside it: with z, ż at both ends of the step (z₀, ż₀, z₁, ż₁), the cubic
//! Hermite interpolant of z over the step (fourth-order accurate, as the inner step) must stay
//! positive. Otherwise the state is left as it was and the step is rejected in favour of a
//! step of `dt`, from which touch-down is resolved at the inner method's own step. A
//! rejected flight step costs one inner step of work; it happens about once per landing.
//!
//! The inner method keeps its order and its stability in each phase: in flight the step is
//! bound by the string stiffness (explicit RK4: ω_max H < 2.8), in contact by the ground's.
//! The error of the whole run is the inner method's at `dt` in contact plus its error at H
//! in flight. The driver sees an adaptive method (a step may be rejected, each outcome
//! proposes the next step; [`Integrator::max_step`] = H), and projects and monitors every
//! accepted step as it does for the inner method.
//!
//! The heights and normal speeds are the [`ContactSystem`]'s: z_i = h(x_i) − h_touch
//! ([`ContactSystem::ground_height`], [`ContactSystem::touch_height`]) and ż_i = n̂·v_i.

use super::integrator::{Integrator, IntegratorKind, StepOutcome};
use super::system::{vec3, ContactSystem};
use std::fmt;
use tensegrity_core::error::CoreError;

/// Flight step over contact step: H = `FLIGHT_RATIO`·dt.
///
/// Measured on the toroid n = 24 on 50° (10 s, RK4 at dt = 10⁻⁴ s, strings 2·10⁴ N/m): 3 and 5
/// keep the energy budget within 5·10⁻³ (RK4 alone: 3·10⁻³), 10 misses by 1.6·10⁻² and 20
/// by 3·10⁻² (RK4 at ω H ≈ 1 damps the string vibrations the impacts excite).
pub const FLIGHT_RATIO: u32 = 5;

/// Safety factor on the approach speed when deciding to try a flight step.
pub const APPROACH_SAFETY: f64 = 1.5;

/// A fixed-step method on the system `S` that takes [`FLIGHT_RATIO`] times its step while no
/// contact node is near the ground (module docs).
pub struct Flight<S> {
    inner: Box<dyn Integrator<S>>,
    kind: IntegratorKind,
    /// The contact step dt (s); set by [`Integrator::start`] from the run's `dt`.
    fine: f64,
    /// State before an attempted flight step.
    backup: Vec<f64>,
    /// Accepted flight steps (work counter).
    pub flight_steps: u64,
    /// Flight steps rejected because a node crossed the plane inside them.
    pub landings: u64,
}

impl<S> fmt::Debug for Flight<S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Flight")
            .field("inner", &self.inner)
            .field("kind", &self.kind)
            .field("fine", &self.fine)
            .field("flight_steps", &self.flight_steps)
            .field("landings", &self.landings)
            .finish()
    }
}

impl<S: ContactSystem> Flight<S> {
    /// Flight steps around `inner`, reported as `kind`.
    pub fn new(system: &S, inner: Box<dyn Integrator<S>>, kind: IntegratorKind) -> Self {
        Self {
            inner,
            kind,
            fine: 0.0,
            backup: vec![0.0; system.state_len()],
            flight_steps: 0,
            landings: 0,
        }
    }

    /// The flight step H (s).
    fn coarse(&self) -> f64 {
        self.fine * f64::from(FLIGHT_RATIO)
    }

    /// The step to propose from the state `y` at `t`.
    fn proposal(&self, system: &S, t: f64, y: &[f64]) -> f64 {
        let h = to_grid(t, self.coarse());
        if h > 1.5 * self.fine && clear(system, y, h * APPROACH_SAFETY) {
            h
        } else {
            to_grid(t, self.fine)
        }
    }
}

/// Height above the touch height and normal speed of every contact node of `y`.
fn heights<'a, S: ContactSystem>(
    system: &'a S,
    y: &'a [f64],
) -> impl Iterator<Item = (f64, f64)> + 'a {
    let n3 = y.len() / 2;
    let touch = system.touch_height();
    let normal = system.ground_normal();
    (0..system.contact_points()).map(move |k| {
        let c = system.contact_node(k);
        let x = vec3(y, c);
        let v = vec3(&y[n3..], c);
        (system.ground_height(&x) - touch, v.dot(&normal))
    })
}

/// The step from `t` to the next point of the grid of spacing `grid` (a t off a grid
/// point by round-off counts as on it, so no sliver of a step is made).
fn to_grid(t: f64, grid: f64) -> f64 {
    let k = (t / grid + 1e-6).floor() + 1.0;
    k * grid - t
}

/// Whether every contact node is above the ground and stays so for `span` seconds at its
/// current approach speed.
fn clear<S: ContactSystem>(system: &S, y: &[f64], span: f64) -> bool {
    heights(system, y).all(|(z, zd)| z > 0.0 && z + zd.min(0.0) * span > 0.0)
}

/// Whether the cubic Hermite interpolant of a height with ends (z0, zd0) and (z1, zd1) over
/// a step h stays positive.
fn hermite_positive(z0: f64, zd0: f64, z1: f64, zd1: f64, h: f64) -> bool {
    if z0 <= 0.0 || z1 <= 0.0 {
        return false;
    }
    // z(s) = z0 h00 + h zd0 h10 + z1 h01 + h zd1 h11, s ∈ [0, 1]; z'(s) = a s² + b s + c
    let (m0, m1) = (h * zd0, h * zd1);
    let a = 6.0 * z0 + 3.0 * m0 - 6.0 * z1 + 3.0 * m1;
    let b = -6.0 * z0 - 4.0 * m0 + 6.0 * z1 - 2.0 * m1;
    let c = m0;
    let z = |s: f64| {
        let (s2, s3) = (s * s, s * s * s);
        z0 * (2.0 * s3 - 3.0 * s2 + 1.0)
            + m0 * (s3 - 2.0 * s2 + s)
            + z1 * (-2.0 * s3 + 3.0 * s2)
            + m1 * (s3 - s2)
    };
    let mut roots = [f64::NAN; 2];
    if a.abs() > 1e-300 {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let q = disc.sqrt();
            roots = [(-b - q) / (2.0 * a), (-b + q) / (2.0 * a)];
        }
    } else if b.abs() > 1e-300 {
        roots[0] = -c / b;
    }
    roots
        .iter()
        .filter(|s| s.is_finite() && **s > 0.0 && **s < 1.0)
        .all(|&s| z(s) > 0.0)
}

/// Whether no contact node crossed the plane between the states `y0` and `y1`, `h` apart.
fn stayed_clear<S: ContactSystem>(system: &S, y0: &[f64], y1: &[f64], h: f64) -> bool {
    heights(system, y0)
        .zip(heights(system, y1))
        .all(|((z0, zd0), (z1, zd1))| hermite_positive(z0, zd0, z1, zd1, h))
}

fn rejected(h_next: f64) -> StepOutcome {
    StepOutcome {
        accepted: false,
        h_next,
    }
}

impl<S: ContactSystem + 'static> Integrator<S> for Flight<S> {
    fn boxed_clone(&self) -> Option<Box<dyn Integrator<S>>> {
        Some(Box::new(Flight {
            inner: self.inner.boxed_clone()?,
            kind: self.kind,
            fine: self.fine,
            backup: self.backup.clone(),
            flight_steps: self.flight_steps,
            landings: self.landings,
        }))
    }

    fn kind(&self) -> IntegratorKind {
        self.kind
    }

    fn is_adaptive(&self) -> bool {
        true
    }

    fn preserves_constraints(&self) -> bool {
        self.inner.preserves_constraints()
    }

    /// H = [`FLIGHT_RATIO`]·dt.
    fn max_step(&self, dt: f64) -> f64 {
        dt * f64::from(FLIGHT_RATIO)
    }

    /// Takes the run's `dt` (the driver passes [`Integrator::max_step`], H) and proposes the
    /// first step.
    fn start(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &[f64],
        h_max: f64,
    ) -> Result<f64, CoreError> {
        self.fine = h_max / f64::from(FLIGHT_RATIO);
        self.inner.start(system, ws, t, y, self.fine)?;
        Ok(self.proposal(system, t, y))
    }

    fn step(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<StepOutcome, CoreError> {
        if h <= 1.5 * self.fine {
            let out = self.inner.step(system, ws, t, y, h)?;
            if !out.accepted {
                return Ok(out);
            }
            return Ok(StepOutcome {
                accepted: true,
                h_next: self.proposal(system, t + h, y),
            });
        }
        // a flight step: only from a clear state, kept only if nothing touched inside it
        if !clear(system, y, h * APPROACH_SAFETY) {
            return Ok(rejected(to_grid(t, self.fine)));
        }
        self.backup.copy_from_slice(y);
        let out = self.inner.step(system, ws, t, y, h)?;
        if !out.accepted || !stayed_clear(system, &self.backup, y, h) {
            y.copy_from_slice(&self.backup);
            self.inner.invalidate();
            self.landings += 1;
            return Ok(rejected(to_grid(t, self.fine)));
        }
        self.flight_steps += 1;
        Ok(StepOutcome {
            accepted: true,
            h_next: self.proposal(system, t + h, y),
        })
    }

    fn invalidate(&mut self) {
        self.inner.invalidate();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hermite_check_sees_a_dip_between_two_positive_ends() {
        // z(s) = (s − ½)² − 0.01 over h = 1: positive ends, negative in the middle
        let (z0, zd0, z1, zd1) = (0.24, -1.0, 0.24, 1.0);
        assert!(!hermite_positive(z0, zd0, z1, zd1, 1.0));
        // the same parabola lifted clear of the plane
        assert!(hermite_positive(0.26, -1.0, 0.26, 1.0, 1.0));
        // monotone descent ending above the plane
        assert!(hermite_positive(1.0, -0.5, 0.5, -0.5, 1.0));
        // ending below
        assert!(!hermite_positive(1.0, -2.0, -0.5, -2.0, 1.0));
    }

    #[test]
    fn steps_land_on_the_grid() {
        let h = to_grid(0.0, 1e-4);
        assert!((h - 1e-4).abs() < 1e-18);
        // from just past a grid point (round-off), the next full spacing
        let h = to_grid(3e-4 + 1e-17, 1e-4);
        assert!((3e-4 + 1e-17 + h - 4e-4).abs() < 1e-16);
        // from the fine grid to the coarse one
        let h = to_grid(1.3e-3, 1e-3);
        assert!((h - 0.7e-3).abs() < 1e-15);
        let h = to_grid(1.6e-3 - 1e-18, 1e-4);
        assert!((h - 1e-4).abs() < 1e-15);
    }
}
