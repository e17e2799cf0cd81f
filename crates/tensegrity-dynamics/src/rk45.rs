//! Adaptive Dormand–Prince 5(4) with error control, dense output and event location, for any
//! [`System`]; the coefficients are [`DORMAND_PRINCE`].
//!
//! Stages k_i = f(t + c_i h, y + h Σ_{j<i} a_ij k_j), i = 1…7, the last at
//! y_{n+1} = y + h Σ b_j k_j (first same as last: it is the next step's k₁); error
//! estimate h Σ e_j k_j with e = b − b̂ (b̂ of order 4).
//!
//! Written in-house rather than taken from diffsol: the right-hand side needs our own
//! preallocated workspace (Ω factorisation) and fallible evaluation, steps are followed by
//! optional constraint projection, and the problem is small and non-stiff, so an explicit
//! FSAL pair with Hairer's 4th-order continuous extension is all that is needed.
//!
//! Error norm: ‖e‖ = sqrt(mean((e_i / (atol + rtol·max(|y_i|, |y1_i|)))²)); a step is
//! accepted when ‖e‖ ≤ 1, and the next step is h·min(5, max(0.2, 0.9‖e‖^{-1/5})).

use super::integrator::{Integrator, IntegratorKind, StepOutcome};
use super::system::System;
use super::tableau::{Tableau, DORMAND_PRINCE};
use tensegrity_core::error::CoreError;

/// The coefficients ([`DORMAND_PRINCE`]).
const TAB: Tableau<7> = DORMAND_PRINCE;
/// Stage matrix (its last row is b: first same as last).
const A: [[f64; 7]; 7] = TAB.a;
/// Abscissae.
const C: [f64; 7] = TAB.c;
/// Error weights b − b̂.
const E: [f64; 7] = TAB.error_weights();
/// Dense-output coefficients.
const D: [f64; 7] = TAB.dense_output();

/// Dormand–Prince 5(4) stepper state.
#[derive(Debug, Clone)]
pub struct Dopri5 {
    k: [Vec<f64>; 7],
    tmp: Vec<f64>,
    y_new: Vec<f64>,
    cont: [Vec<f64>; 5],
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    fsal_valid: bool,
    /// Time and step of the last accepted step (for dense output).
    t_old: f64,
    h_old: f64,
}

impl Dopri5 {
    /// Buffers for a state of length `n` and the given tolerances.
    pub fn new(n: usize, rtol: f64, atol: f64) -> Self {
        let v = || vec![0.0; n];
        Self {
            k: [v(), v(), v(), v(), v(), v(), v()],
            tmp: v(),
            y_new: v(),
            cont: [v(), v(), v(), v(), v()],
            rtol,
            atol,
            fsal_valid: false,
            t_old: 0.0,
            h_old: 0.0,
        }
    }
}

impl<S: System> Integrator<S> for Dopri5 {
    fn boxed_clone(&self) -> Option<Box<dyn Integrator<S>>> {
        Some(Box::new(self.clone()))
    }

    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Rk45
    }

    fn is_adaptive(&self) -> bool {
        true
    }

    fn has_dense_output(&self) -> bool {
        true
    }

    /// Forgets the cached first stage (call after the state was modified externally, e.g. by a
    /// projection).
    fn invalidate(&mut self) {
        self.fsal_valid = false;
    }

    /// A starting step size (Hairer & Wanner's heuristic, 2 right-hand-side evaluations).
    fn start(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &[f64],
        h_max: f64,
    ) -> Result<f64, CoreError> {
        let n = y.len();
        system.rhs(t, y, &mut self.k[0], ws)?;
        self.fsal_valid = true;
        let sc = |i: usize| self.atol + self.rtol * y[i].abs();
        let norm = |v: &dyn Fn(usize) -> f64| {
            ((0..n).map(|i| (v(i) / sc(i)).powi(2)).sum::<f64>() / n as f64).sqrt()
        };
        let d0 = norm(&|i| y[i]);
        let d1 = norm(&|i| self.k[0][i]);
        let h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        }
        .min(h_max);
        for i in 0..n {
            self.tmp[i] = y[i] + h0 * self.k[0][i];
        }
        system.rhs(t + h0, &self.tmp, &mut self.k[1], ws)?;
        let d2 = norm(&|i| (self.k[1][i] - self.k[0][i]) / h0);
        Ok(super::integrator::starting_step(h0, d1, d2, 0.2, h_max))
    }

    /// Attempts one step of size `h` from (t, y). On success (error ≤ 1) `y` is advanced and
    /// the dense output is set up for [t, t+h]; otherwise `y` is untouched and the outcome
    /// carries the step to retry with.
    fn step(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<StepOutcome, CoreError> {
        let n = y.len();
        if !self.fsal_valid {
            system.rhs(t, y, &mut self.k[0], ws)?;
            self.fsal_valid = true;
        }
        for s in 1..7 {
            for i in 0..n {
                let mut acc = 0.0;
                for j in 0..s {
                    let a = A[s][j];
                    if a != 0.0 {
                        acc += a * self.k[j][i];
                    }
                }
                self.tmp[i] = y[i] + h * acc;
            }
            system.rhs(t + C[s] * h, &self.tmp, &mut self.k[s], ws)?;
            if s == 6 {
                self.y_new.copy_from_slice(&self.tmp);
            }
        }
        // error estimate
        let mut err = 0.0;
        for i in 0..n {
            let mut e = 0.0;
            for j in 0..7 {
                e += E[j] * self.k[j][i];
            }
            let sc = self.atol + self.rtol * y[i].abs().max(self.y_new[i].abs());
            err += (h * e / sc).powi(2);
        }
        let err = (err / n as f64).sqrt();
        if !err.is_finite() {
            return Ok(rejected(0.2 * h));
        }
        let fac = (0.9 * err.max(1e-10).powf(-0.2)).clamp(0.2, 5.0);
        if err > 1.0 {
            return Ok(rejected(h * fac.min(1.0)));
        }
        // dense output
        for i in 0..n {
            let ydiff = self.y_new[i] - y[i];
            let bspl = h * self.k[0][i] - ydiff;
            self.cont[0][i] = y[i];
            self.cont[1][i] = ydiff;
            self.cont[2][i] = bspl;
            self.cont[3][i] = ydiff - h * self.k[6][i] - bspl;
            let mut d = 0.0;
            for j in 0..7 {
                d += D[j] * self.k[j][i];
            }
            self.cont[4][i] = h * d;
        }
        self.t_old = t;
        self.h_old = h;
        y.copy_from_slice(&self.y_new);
        // FSAL
        let (first, rest) = self.k.split_at_mut(6);
        first[0].copy_from_slice(&rest[0]);
        Ok(StepOutcome {
            accepted: true,
            h_next: h * fac,
        })
    }

    /// Dense output of the last accepted step at time `t` (inside it), 4th order.
    fn interpolate(&self, t: f64, out: &mut [f64]) -> bool {
        let th = (t - self.t_old) / self.h_old;
        let th1 = 1.0 - th;
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.cont[0][i]
                + th * (self.cont[1][i]
                    + th1 * (self.cont[2][i] + th * (self.cont[3][i] + th1 * self.cont[4][i])));
        }
        true
    }
}

fn rejected(h_next: f64) -> StepOutcome {
    StepOutcome {
        accepted: false,
        h_next,
    }
}
