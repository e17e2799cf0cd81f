//! Newmark's average-acceleration method (β = ¼, γ = ½: the implicit trapezoidal rule) for
//! the elastic dynamics M_r q̈ = F(q, q̇) ([`crate::transient`]):
//!
//! > q₁ = q₀ + h q̇₀ + (h²/4)(a₀ + a₁),   q̇₁ = q̇₀ + (h/2)(a₀ + a₁),   M_r a₁ = F(q₁, q̇₁),
//!
//! second order, unconditionally stable on linear systems and free of numerical damping (it
//! keeps a linear system's energy exactly), so it steps over the stiff axial modes of
//! elastic bars at the step the motion needs. The unknown q₁ solves
//! r(q₁) = M_r a₁(q₁) − F(q₁, q̇₁(q₁)) = 0 by Newton's method on
//!
//! > J = (4/h²) M_r + K_T(q₁) + (2/h) C_T(q₁),
//!
//! K_T the tangent stiffness ([`crate::tangent`]) and C_T the dashpots' c n nᵀ; a step whose
//! iteration does not converge is retried at half the step (counted as rejected), up to
//! [`MAX_HALVINGS`] times. With rigid bars the multipliers join the unknowns
//! ([`crate::newmark_rigid`]).

use crate::factor::{Factored, DENSE_MAX};
use crate::tangent::{member_block_triplets, tangent_triplets};
use crate::transient::{ElasticDynamics, TransientWorkspace};
use nalgebra::DVector;
use tensegrity_core::error::{CoreError, DynamicsError};
use tensegrity_dynamics::{Integrator, IntegratorKind, StepOutcome, System};

/// Newton iterations per step before it is retried at half the step.
pub const MAX_ITERATIONS: usize = 25;
/// Halvings of a step before the run stops.
pub const MAX_HALVINGS: u32 = 12;
/// The residual's relative tolerance (to the largest of M a and F), floored at what double
/// precision resolves on the stiffest member.
pub const TOLERANCE: f64 = 1e-10;

/// A converged step: (q₁, q̇₁, a₁).
type Stepped = (DVector<f64>, DVector<f64>, DVector<f64>);

/// The method's state between steps: the acceleration at the last accepted state.
#[derive(Debug, Clone, Default)]
pub struct Newmark {
    stiffest: f64,
    acceleration: Option<DVector<f64>>,
    dt: Option<f64>,
    solves: u64,
    iterations: u64,
}

impl Newmark {
    /// A fresh method for `system` (the acceleration is computed at the first step).
    pub fn new(system: &ElasticDynamics) -> Self {
        let stiffest = system
            .model()
            .members
            .iter()
            .enumerate()
            .filter(|(k, _)| !system.is_rigid(*k))
            .map(|(_, m)| m.ea / m.rest_length)
            .fold(0.0, f64::max);
        Self {
            stiffest,
            ..Self::default()
        }
    }

    /// Newton iterations made so far.
    pub fn iterations(&self) -> u64 {
        self.iterations
    }

    /// One step of size `h` from (q₀, q̇₀, a₀): the new (q₁, q̇₁, a₁), or the residual left
    /// when Newton did not converge.
    fn solve(
        &mut self,
        system: &ElasticDynamics,
        ws: &mut TransientWorkspace,
        t: f64,
        y: &[f64],
        a0: &DVector<f64>,
        h: f64,
    ) -> Result<Result<Stepped, f64>, CoreError> {
        let m = system.n_free();
        let q0 = DVector::from_column_slice(&y[..m]);
        let u0 = DVector::from_column_slice(&y[m..]);
        let base = &q0 + &u0 * h + a0 * (0.25 * h * h);
        let (c_q, c_u) = (0.25 * h * h, 0.5 * h);
        // the unknown is a₁ itself (q₁ = base + (h²/4) a₁): a residual M a₁ − F without
        // the cancellation of (q₁ − base) 4/h² at small steps; predictor a₁ = a₀
        let mut a1 = a0.clone();
        let mut residual = f64::INFINITY;
        // what double precision resolves on the stiffest member (as the static Newton's
        // tolerance, `crate::newton::tolerance`): 64 ε · max EA/L₀ · max ‖x‖
        let size = system
            .nodes_of(y)
            .iter()
            .map(|v| v.norm())
            .fold(1e-3, f64::max);
        let floor = 64.0 * f64::EPSILON * self.stiffest * size;
        if system.rigid_bars().is_some_and(|b| !b.is_empty()) {
            let step = crate::newmark_rigid::Step {
                t,
                h,
                floor,
                tolerance: TOLERANCE,
                max_iterations: MAX_ITERATIONS,
            };
            let jacobian =
                |q1: &DVector<f64>, u1: &DVector<f64>| Self::jacobian(system, t + h, q1, u1, h);
            return crate::newmark_rigid::solve(
                system,
                ws,
                y,
                a0,
                &step,
                &mut self.iterations,
                jacobian,
            );
        }
        for _ in 0..MAX_ITERATIONS {
            self.iterations += 1;
            let q1 = &base + &a1 * c_q;
            let u1 = &u0 + (a0 + &a1) * c_u;
            let f = system.reduced_forces(t + h, q1.as_slice(), u1.as_slice(), ws)?;
            let ma = system.mass_times(a1.as_slice());
            let r = &ma - &f;
            let scale = ma.amax().max(f.amax()).max(f64::MIN_POSITIVE);
            residual = r.amax();
            if residual <= (TOLERANCE * scale).max(floor) {
                return Ok(Ok((q1, u1, a1)));
            }
            // dr/da₁ = M_r + (h²/4) K_T + (h/2) C_T = (h²/4) J
            let triplets = Self::jacobian(system, t + h, &q1, &u1, h);
            let Some(mut factor) = Factored::from_triplets(m, &triplets, DENSE_MAX) else {
                return Ok(Err(residual));
            };
            let Some(da) = factor.solve(&r) else {
                return Ok(Err(residual));
            };
            let da = da / c_q;
            a1 -= &da;
            // an update at round-off: converged, whatever the residual's floor
            if da.amax() <= 1e-13 * a1.amax().max(f64::MIN_POSITIVE) {
                let q1 = &base + &a1 * c_q;
                let u1 = &u0 + (a0 + &a1) * c_u;
                return Ok(Ok((q1, u1, a1)));
            }
        }
        Ok(Err(residual))
    }

    /// (4/h²) M_r + K_T + (2/h) C_T at time `t` and (q₁, q̇₁), as triplets.
    fn jacobian(
        system: &ElasticDynamics,
        t: f64,
        q1: &DVector<f64>,
        u1: &DVector<f64>,
        h: f64,
    ) -> Vec<(usize, usize, f64)> {
        let mut y = q1.as_slice().to_vec();
        y.extend_from_slice(u1.as_slice());
        let (x, v) = (system.nodes_of(&y), system.velocities_of(&y));
        let states = system.member_states(t, &x, &v);
        let (model, dofs) = (system.model(), system.dofs());
        let mut t = tangent_triplets(model, dofs, &states);
        t.extend(
            system
                .mass_triplets()
                .iter()
                .map(|&(r, c, v)| (r, c, 4.0 / (h * h) * v)),
        );
        t.extend(member_block_triplets(
            model,
            dofs,
            |k, s| {
                let c = system.damping(k);
                (c > 0.0 && !s.slack).then(|| s.direction * s.direction.transpose() * (2.0 / h * c))
            },
            &states,
        ));
        // the clusters' dashpots: (2/h) c g gᵀ while taut
        t.extend(crate::clusters::rank_one_triplets(
            model,
            dofs,
            &states,
            |c| {
                let damping = model.clusters[c].damping;
                let taut = !states[model.cluster_states(c).start].slack;
                (damping > 0.0 && taut).then_some(2.0 / h * damping)
            },
        ));
        t
    }
}

impl Integrator<ElasticDynamics> for Newmark {
    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Newmark
    }

    fn step(
        &mut self,
        system: &ElasticDynamics,
        ws: &mut TransientWorkspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<StepOutcome, CoreError> {
        let m = system.n_free();
        let dt = *self.dt.get_or_insert(h);
        let a0 = match self.acceleration.take() {
            Some(a) => a,
            None => {
                let mut dy = vec![0.0; 2 * m];
                system.rhs(t, y, &mut dy, ws)?;
                DVector::from_column_slice(&dy[m..])
            }
        };
        self.solves += 1;
        match self.solve(system, ws, t, y, &a0, h)? {
            Ok((q1, u1, a1)) => {
                y[..m].copy_from_slice(q1.as_slice());
                y[m..].copy_from_slice(u1.as_slice());
                self.acceleration = Some(a1);
                Ok(StepOutcome::fixed(h))
            }
            Err(residual) => {
                self.acceleration = Some(a0);
                if h < dt / f64::from(1u32 << MAX_HALVINGS) {
                    return Err(DynamicsError::ImplicitStepFailed {
                        t,
                        dt: h,
                        residual,
                        iterations: MAX_ITERATIONS,
                    }
                    .into());
                }
                Ok(StepOutcome {
                    accepted: false,
                    h_next: 0.5 * h,
                })
            }
        }
    }

    fn invalidate(&mut self) {
        self.acceleration = None;
    }

    fn implicit_solves(&self) -> (u64, u64) {
        (self.solves, 0)
    }
}
