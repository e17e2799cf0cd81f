//! Classic fixed-step fourth-order Runge–Kutta (the MOTES scheme), allocation-free.
//!
//! y_{n+1} = y_n + h/6 (k₁ + 2k₂ + 2k₃ + k₄). Linear invariants (N P = D) are kept to
//! round-off; bar lengths drift at O(h⁴) (the λ closed form makes d²‖b‖²/dt² = 0 exactly).

use super::integrator::{Integrator, IntegratorKind, StepOutcome};
use super::model::{Model, Workspace};
use crate::error::CoreError;

/// Stage buffers of the RK4 stepper.
#[derive(Debug, Clone)]
pub struct Rk4 {
    k1: Vec<f64>,
    k2: Vec<f64>,
    k3: Vec<f64>,
    k4: Vec<f64>,
    tmp: Vec<f64>,
}

impl Rk4 {
    /// Buffers for a state of length `n`.
    pub fn new(n: usize) -> Self {
        Self {
            k1: vec![0.0; n],
            k2: vec![0.0; n],
            k3: vec![0.0; n],
            k4: vec![0.0; n],
            tmp: vec![0.0; n],
        }
    }
}

impl Integrator for Rk4 {
    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Rk4
    }

    /// Advances `y` from `t` to `t + h` in place (4 right-hand-side evaluations).
    fn step(
        &mut self,
        model: &Model,
        ws: &mut Workspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<StepOutcome, CoreError> {
        let n = y.len();
        model.rhs(t, y, &mut self.k1, ws)?;
        for i in 0..n {
            self.tmp[i] = y[i] + 0.5 * h * self.k1[i];
        }
        model.rhs(t + 0.5 * h, &self.tmp, &mut self.k2, ws)?;
        for i in 0..n {
            self.tmp[i] = y[i] + 0.5 * h * self.k2[i];
        }
        model.rhs(t + 0.5 * h, &self.tmp, &mut self.k3, ws)?;
        for i in 0..n {
            self.tmp[i] = y[i] + h * self.k3[i];
        }
        model.rhs(t + h, &self.tmp, &mut self.k4, ws)?;
        let h6 = h / 6.0;
        for i in 0..n {
            y[i] += h6 * (self.k1[i] + 2.0 * (self.k2[i] + self.k3[i]) + self.k4[i]);
        }
        Ok(StepOutcome::fixed(h))
    }
}
