//! Classic fixed-step fourth-order Runge–Kutta (the MOTES scheme), allocation-free.
//!
//! y_{n+1} = y_n + h/6 (k₁ + 2k₂ + 2k₃ + k₄). Linear invariants (N P = D) are kept to
//! round-off; bar lengths drift at O(h⁴) (the λ closed form makes d²‖b‖²/dt² = 0 exactly).

use super::integrator::{Integrator, IntegratorKind, StepOutcome};
use super::model::{Model, Workspace};
use tensegrity_core::error::CoreError;

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
        // the stages as zipped loops (vectorised, no index checks); each entry is computed
        // exactly as y_i + (h/2) k_i etc.
        fn stage(tmp: &mut [f64], y: &[f64], c: f64, k: &[f64]) {
            for ((t, y), k) in tmp.iter_mut().zip(y).zip(k) {
                *t = y + c * k;
            }
        }
        model.rhs(t, y, &mut self.k1, ws)?;
        stage(&mut self.tmp, y, 0.5 * h, &self.k1);
        model.rhs(t + 0.5 * h, &self.tmp, &mut self.k2, ws)?;
        stage(&mut self.tmp, y, 0.5 * h, &self.k2);
        model.rhs(t + 0.5 * h, &self.tmp, &mut self.k3, ws)?;
        stage(&mut self.tmp, y, h, &self.k3);
        model.rhs(t + h, &self.tmp, &mut self.k4, ws)?;
        let h6 = h / 6.0;
        for ((((y, k1), k2), k3), k4) in y
            .iter_mut()
            .zip(&self.k1)
            .zip(&self.k2)
            .zip(&self.k3)
            .zip(&self.k4)
        {
            *y += h6 * (k1 + 2.0 * (k2 + k3) + k4);
        }
        Ok(StepOutcome::fixed(h))
    }
}
