//! Classic fixed-step fourth-order Runge–Kutta (the MOTES scheme), allocation-free, for any
//! [`System`].
//!
//! k₁ = f(t, y), k₂ = f(t + h/2, y + h/2 k₁), k₃ = f(t + h/2, y + h/2 k₂),
//! k₄ = f(t + h, y + h k₃), y_{n+1} = y_n + h/6 (k₁ + 2k₂ + 2k₃ + k₄): the coefficients of
//! [`RK4`], whose weights b = (1, 2, 2, 1)/6 are applied in that grouped
//! form. Linear invariants (N P = D) are kept to round-off; bar lengths drift at O(h⁴) (the
//! λ closed form makes d²‖b‖²/dt² = 0 exactly).

use super::integrator::{Integrator, IntegratorKind, StepOutcome};
use super::system::System;
use super::tableau::{Tableau, RK4};
use tensegrity_core::error::CoreError;

/// The coefficients (A, b, c).
const TAB: Tableau<4> = RK4;
/// 1/b₁: the update is y + (h/6)(k₁ + 2(k₂ + k₃) + k₄).
const WEIGHT_DIVISOR: f64 = 1.0 / TAB.b[0];
/// b₂/b₁.
const MIDDLE_WEIGHT: f64 = TAB.b[1] / TAB.b[0];
// The grouped update is the tableau's: b = (1, 2, 2, 1)/6 exactly, and each stage reads only
// the previous one.
const _: () = assert!(
    WEIGHT_DIVISOR == 6.0
        && MIDDLE_WEIGHT == 2.0
        && TAB.b[2] == TAB.b[1]
        && TAB.b[3] == TAB.b[0]
        && TAB.a[2][0] == 0.0
        && TAB.a[3][0] == 0.0
        && TAB.a[3][1] == 0.0
);

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

impl<S: System> Integrator<S> for Rk4 {
    fn boxed_clone(&self) -> Option<Box<dyn Integrator<S>>> {
        Some(Box::new(self.clone()))
    }

    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Rk4
    }

    /// Advances `y` from `t` to `t + h` in place (4 right-hand-side evaluations).
    fn step(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<StepOutcome, CoreError> {
        // the stages as zipped loops (vectorised, no index checks); each entry is computed
        // exactly as y_i + (a h) k_i
        fn stage(tmp: &mut [f64], y: &[f64], c: f64, k: &[f64]) {
            for ((t, y), k) in tmp.iter_mut().zip(y).zip(k) {
                *t = y + c * k;
            }
        }
        let (a, c) = (&TAB.a, &TAB.c);
        system.rhs(t, y, &mut self.k1, ws)?;
        stage(&mut self.tmp, y, a[1][0] * h, &self.k1);
        system.rhs(t + c[1] * h, &self.tmp, &mut self.k2, ws)?;
        stage(&mut self.tmp, y, a[2][1] * h, &self.k2);
        system.rhs(t + c[2] * h, &self.tmp, &mut self.k3, ws)?;
        stage(&mut self.tmp, y, a[3][2] * h, &self.k3);
        system.rhs(t + c[3] * h, &self.tmp, &mut self.k4, ws)?;
        let h6 = h / WEIGHT_DIVISOR;
        for ((((y, k1), k2), k3), k4) in y
            .iter_mut()
            .zip(&self.k1)
            .zip(&self.k2)
            .zip(&self.k3)
            .zip(&self.k4)
        {
            *y += h6 * (k1 + MIDDLE_WEIGHT * (k2 + k3) + k4);
        }
        Ok(StepOutcome::fixed(h))
    }
}
