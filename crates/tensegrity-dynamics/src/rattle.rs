//! RATTLE: a second-order, symplectic (for conservative forces), constraint-preserving step
//! for bar lengths and N P = D, over any [`ConstrainedSystem`] (the constraints and their
//! projection: [`ConstraintSet`](super::ConstraintSet) for the model).
//!
//! In class-1 coordinates q (two nodes per bar) the bars are point pairs with the block
//! mass matrix M = [[m/3, m/6], [m/6, m/3]] ⊗ I₃ (translational plus J = m/12 rotational
//! inertia) subject to g(q) = 0: ½(‖b_k‖² − l_k²) = 0 for every bar and N P − D = 0. With
//! G = ∂g/∂q and applied forces f(t, q, v) ([`ConstrainedSystem::forces`]):
//!
//! v½ = v_n + h/2 M⁻¹(f_n + G(q_n)ᵀμ),  q_{n+1} = q_n + h v½,  g(q_{n+1}) = 0,
//! v_{n+1} = v½ + h/2 M⁻¹(f_{n+1} + G(q_{n+1})ᵀν),  G(q_{n+1}) v_{n+1} = 0.
//!
//! The position multipliers come from a quasi-Newton iteration with the SPD matrix
//! G M⁻¹ Gᵀ at q_n (sparse, factored once per step and reused as the velocity matrix of
//! the previous step). With velocity-dependent forces (string damping, ground) the last
//! half-kick is iterated twice on v_{n+1}.

use super::integrator::{Integrator, IntegratorKind, StepOutcome};
use super::system::ConstrainedSystem;
use nalgebra::Vector3;
use tensegrity_core::error::{CoreError, DynamicsError};

/// The RATTLE stepper over the constraint set `C` of its system
/// ([`ConstrainedSystem::Constraints`]).
#[derive(Debug)]
pub struct Rattle<C> {
    cons: C,
    x_old: Vec<f64>,
    v_half: Vec<f64>,
    f_cache: Vec<Vector3<f64>>,
    cache_valid: bool,
    velocity_dependent: bool,
    /// Position tolerance of the constraint solve (absolute, on ½(‖b‖² − l²) and N P − D;
    /// raised to the round-off floor ε·max|x|·ℓ far from the origin).
    pub tol: f64,
}

impl<C> Rattle<C> {
    /// A stepper for `system`; fails when its constraints are redundant.
    pub fn new<S: ConstrainedSystem<Constraints = C>>(system: &S) -> Result<Self, CoreError> {
        let n = system.state_len();
        Ok(Self {
            cons: system.constraints()?,
            x_old: vec![0.0; n / 2],
            v_half: vec![0.0; n / 2],
            f_cache: vec![Vector3::zeros(); n / 6],
            cache_valid: false,
            velocity_dependent: system.velocity_dependent_forces(),
            tol: system.constraint_tolerance(),
        })
    }
}

impl<S: ConstrainedSystem> Integrator<S> for Rattle<S::Constraints> {
    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Rattle
    }

    fn preserves_constraints(&self) -> bool {
        true
    }

    /// Advances y = (q, v) from t to t + h.
    fn step(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<StepOutcome, CoreError> {
        let n3 = y.len() / 2;
        let (x, v) = y.split_at_mut(n3);
        if !self.cache_valid {
            let f = system.forces(t, x, v, ws);
            self.f_cache.copy_from_slice(f);
            // the state the previous step accepted (or the initial one, where a failure is a
            // redundant constraint set and stays one)
            system.factor_constraints(&mut self.cons, x)?;
        }
        // half kick and drift
        self.x_old.copy_from_slice(x);
        self.v_half.copy_from_slice(v);
        system.add_inverse_mass(&self.f_cache, 0.5 * h, &mut self.v_half);
        for i in 0..n3 {
            x[i] += h * self.v_half[i];
        }
        // constraint forces at q_n: solve g(q_{n+1}) = 0
        // a failure from here on is the step's, not the constraints': they factored at q_n
        let failed = |residual: Option<f64>| -> CoreError {
            // the grid step shortened by round-off (0.04999999999999993) printed as 0.05
            let dt = format!("{h:.12e}").parse().unwrap_or(h);
            DynamicsError::RattleStepFailed { t, dt, residual }.into()
        };
        if let Err(e) = system.solve_positions(&mut self.cons, x, self.tol, t, 100) {
            let residual = match e {
                CoreError::Dynamics(DynamicsError::ConstraintNotConverged { residual, .. }) => {
                    residual
                }
                _ => f64::NAN,
            };
            return Err(failed(Some(residual)));
        }
        for i in 0..n3 {
            self.v_half[i] = (x[i] - self.x_old[i]) / h;
        }
        // second half kick at q_{n+1}
        if system.factor_constraints(&mut self.cons, x).is_err() {
            return Err(failed(None));
        }
        v.copy_from_slice(&self.v_half);
        let iterations = if self.velocity_dependent { 3 } else { 1 };
        for _ in 0..iterations {
            let f = system.forces(t + h, x, v, ws);
            v.copy_from_slice(&self.v_half);
            system.add_inverse_mass(f, 0.5 * h, v);
            system.project_velocities(&mut self.cons, v);
            if !self.velocity_dependent {
                // the forces at q_{n+1} start the next step
                self.f_cache.copy_from_slice(f);
            }
        }
        self.cache_valid = !self.velocity_dependent;
        Ok(StepOutcome::fixed(h))
    }

    /// Forces a fresh force evaluation and factorisation at the next step.
    fn invalidate(&mut self) {
        self.cache_valid = false;
    }
}
