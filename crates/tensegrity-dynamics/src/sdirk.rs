//! L-stable singly diagonally implicit Runge–Kutta (SDIRK) for stiff strings and stiff or
//! dissipative ground contact.
//!
//! # Method
//!
//! Alexander's three-stage SDIRK of order 3 (SIAM J. Numer. Anal. 14, 1977; the coefficients
//! are [`SDIRK3`]), stiffly accurate (the last stage is the solution) and L-stable, so that
//! string modes of frequency ω ≫ 1/h and contact dampers with c/m ≫ 1/h are damped instead of
//! amplified:
//!
//! ```text
//!  γ  | γ
//!  c₂ | (1−γ)/2   γ                    γ = 0.435866521508459 (root of x³ − 3x² + 3x/2 − 1/6)
//!  1  | b₁        b₂      γ            c₂ = (1+γ)/2
//! ----+-------------------------      b₁ = −(6γ² − 16γ + 1)/4,  b₂ = (6γ² − 20γ + 5)/4
//!     | b₁        b₂      γ
//!     | γ/(1−γ)   (1−2γ)/(1−γ)  0      (embedded, order 2)
//! ```
//!
//! Stage i solves z_i = ψ_i + hγ f(t + c_i h, z_i), ψ_i = y_n + h Σ_{j<i} a_ij k_j, by
//! simplified Newton iterations with the matrix I − hγJ; then k_i = (z_i − ψ_i)/(hγ) and
//! y_{n+1} = z₃. The error estimate is Shampine's filtered difference
//! (I − hγJ)⁻¹ h Σ (b_i − b̂_i) k_i, which stays O(1)·tolerance on the stiff components; a
//! step is accepted when its weighted RMS norm (weights atol + rtol·max(|y_n|, |y_{n+1}|)) is
//! at most 1, and the next step is h·min(5, max(0.2, 0.9‖e‖^{-1/3})).
//!
//! # Jacobian
//!
//! y = (x, v) and f = (v, a(x, v)), so J = [[0, I], [A_x, A_v]]. A_x and A_v are forward
//! differences of the *full* right-hand side (strings, contact, the λ closed form and the Ω
//! projection of the joints and supports), one column per coordinate: 6 n₁ force
//! evaluations per Jacobian (plus one for the base value). An analytic Jacobian of the string and contact forces alone would
//! miss the constraint projection Ω that a stiff string at a joint acts through, and the
//! bar-length term λ; the finite-difference one is exact to O(√ε) for all of them. It is
//! reused over steps and refreshed only when a Newton iteration contracts slowly (θ > 0.05) or
//! fails. The Newton matrix is reduced to the velocity block by the Schur complement
//! E = I − hγA_v − (hγ)²A_x (3 n₁ unknowns instead of 6 n₁, an eighth of the LU flops),
//! factored with [`DenseLu`] and refactored only when h changes (steps within ×[1, 1.2] of
//! the factored one keep it).
//!
//! # Constraints and output
//!
//! After every accepted step the state is projected back onto the bar lengths and N P = D
//! ([`ConstrainedSystem::project`]; for the model the RATTLE constraint set), so the method
//! reports that it keeps the constraints. The method runs on any [`ConstrainedSystem`] (the
//! state y = (x, v) with x and v of equal length). Dense output is the cubic Hermite
//! interpolant through (y_n, f_n) and (y_{n+1}, k₃) (order 3, like the method).

use super::integrator::{Integrator, IntegratorKind, StepOutcome};
use super::system::{ConstrainedSystem, System};
use super::tableau::{Tableau, SDIRK3};
use tensegrity_core::error::{CoreError, NumericsError};
use tensegrity_linalg::DenseLu;

/// The coefficients ([`SDIRK3`]).
const TAB: Tableau<3> = SDIRK3;

/// Error weights b − b̂ of [`SDIRK3`].
const E: [f64; 3] = TAB.error_weights();

/// γ of Alexander's SDIRK3: the root in (1/6, 1/2) of x³ − 3x² + 3x/2 − 1/6.
pub const GAMMA: f64 = TAB.diagonal();

/// Largest Newton matrix (3 n₁ class-1 coordinates, i.e. 400 bars): the dense Jacobian and
/// LU need three n×n matrices, 138 MB at this size.
pub const MAX_COORDINATES: usize = 2400;

/// Newton iterations per stage before the step is retried.
const MAX_NEWTON: usize = 10;
/// A Newton contraction ‖Δ_{k+1}‖/‖Δ_k‖ at or above this counts as divergence.
const THETA_DIVERGE: f64 = 0.9;
/// Refresh the Jacobian after a step whose Newton contraction exceeded this.
const THETA_REFRESH: f64 = 0.05;

/// Work counters of the implicit solver (beyond the driver's steps and force evaluations,
/// which include the Jacobian columns).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SdirkStats {
    /// Finite-difference Jacobians (6 n₁ force evaluations each).
    pub jacobians: u64,
    /// LU factorisations of the Newton matrix.
    pub factorizations: u64,
    /// Newton iterations (one force evaluation each).
    pub newton_iterations: u64,
    /// Stage solves that did not converge (the step was retried).
    pub newton_failures: u64,
}

/// The SDIRK stepper: tolerances, Jacobian, Newton matrix, stages and dense output, with the
/// constraint set `C` of its system ([`ConstrainedSystem::Constraints`]) that it projects
/// onto.
#[derive(Debug)]
pub struct Sdirk<C> {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Adaptive steps from the embedded estimate (default). Without it every step whose
    /// Newton iterations converge is accepted (fixed step; used to measure the order).
    pub error_control: bool,
    /// Work counters.
    pub stats: SdirkStats,
    n3: usize,
    ax: Vec<f64>,
    av: Vec<f64>,
    jac_fresh: bool,
    jac_stale: bool,
    lu: DenseLu,
    lu_h: f64,
    k: [Vec<f64>; 3],
    z: Vec<f64>,
    psi: Vec<f64>,
    fz: Vec<f64>,
    r: Vec<f64>,
    bv: Vec<f64>,
    w: Vec<f64>,
    f0: Vec<f64>,
    f0_valid: bool,
    eta: f64,
    theta_max: f64,
    y_old: Vec<f64>,
    f_old: Vec<f64>,
    y_new: Vec<f64>,
    y_last: Vec<f64>,
    has_last: bool,
    t_old: f64,
    h_old: f64,
    cons: C,
    proj_tol: f64,
}

/// How one attempt at a step ended.
enum Attempt {
    /// A stage's Newton iteration diverged or did not converge in time.
    NewtonFailed,
    /// All stages converged; the weighted error norm of the step.
    Done(f64),
}

impl<C> Sdirk<C> {
    /// A stepper for `system` with the given tolerances. Fails when the system is too large
    /// for dense Jacobians ([`MAX_COORDINATES`]) or its constraints are singular.
    pub fn new<S: ConstrainedSystem<Constraints = C>>(
        system: &S,
        rtol: f64,
        atol: f64,
    ) -> Result<Self, CoreError> {
        let n = system.state_len();
        let n3 = n / 2;
        if n3 > MAX_COORDINATES {
            return Err(CoreError::invalid_parameter(
                "integrator",
                n3 as f64,
                format!(
                    "sdirk factors dense {n3}×{n3} Newton matrices (3 coordinates per class-1 \
                     node); at most {MAX_COORDINATES} are supported: use rk45 or rattle"
                ),
            ));
        }
        let v = || vec![0.0; n];
        Ok(Self {
            rtol,
            atol,
            error_control: true,
            stats: SdirkStats::default(),
            n3,
            ax: vec![0.0; n3 * n3],
            av: vec![0.0; n3 * n3],
            jac_fresh: false,
            jac_stale: true,
            lu: DenseLu::new(n3),
            lu_h: f64::NAN,
            k: [v(), v(), v()],
            z: v(),
            psi: v(),
            fz: v(),
            r: v(),
            bv: vec![0.0; n3],
            w: v(),
            f0: v(),
            f0_valid: false,
            eta: 1.0,
            theta_max: 0.0,
            y_old: v(),
            f_old: v(),
            y_new: v(),
            y_last: v(),
            has_last: false,
            t_old: 0.0,
            h_old: 0.0,
            cons: system.constraints()?,
            proj_tol: system.constraint_tolerance(),
        })
    }

    /// The Newton stopping threshold κ on the weighted norm (Hairer–Wanner's choice for
    /// RADAU5: min(0.03, √rtol), never below 10ε/rtol).
    fn kappa(&self) -> f64 {
        0.03_f64
            .min(self.rtol.sqrt())
            .max(10.0 * f64::EPSILON / self.rtol)
    }

    /// Weighted RMS norm of `v` with the weights in `self.w`.
    fn norm(&self, v: &[f64]) -> f64 {
        let s: f64 = v.iter().zip(&self.w).map(|(x, w)| (x / w).powi(2)).sum();
        (s / v.len().max(1) as f64).sqrt()
    }

    /// f0 = f(t, y) when it is not known from the last stage of the previous step.
    fn ensure_f0<S: System>(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &[f64],
    ) -> Result<(), CoreError> {
        if !self.f0_valid {
            system.rhs(t, y, &mut self.f0, ws)?;
            self.f0_valid = true;
        }
        Ok(())
    }

    /// Forward-difference A_x, A_v at (t, y): 6 n₁ + 1 force evaluations. The base value
    /// f(t, y) is evaluated afresh (the cached f0 from the last stage is only accurate to the
    /// Newton tolerance, which a difference quotient would amplify by 1/δ) and kept as f0.
    fn jacobian<S: System>(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &[f64],
    ) -> Result<(), CoreError> {
        self.jacobian_at(system, ws, t, y)?;
        self.f0.copy_from_slice(&self.psi);
        self.f0_valid = true;
        Ok(())
    }

    /// Forward-difference A_x, A_v at (t, p), with f(t, p) left in `self.psi`.
    fn jacobian_at<S: System>(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        p: &[f64],
    ) -> Result<(), CoreError> {
        let n3 = self.n3;
        system.rhs(t, p, &mut self.psi, ws)?;
        self.z.copy_from_slice(p);
        for j in 0..2 * n3 {
            let yj = self.z[j];
            let d = f64::EPSILON.sqrt() * yj.abs().max(1e-2);
            self.z[j] = yj + d;
            let d = self.z[j] - yj; // the step actually taken
            system.rhs(t, &self.z, &mut self.fz, ws)?;
            self.z[j] = yj;
            let (m, col) = if j < n3 {
                (&mut self.ax, j)
            } else {
                (&mut self.av, j - n3)
            };
            for i in 0..n3 {
                m[i * n3 + col] = (self.fz[n3 + i] - self.psi[n3 + i]) / d;
            }
        }
        self.stats.jacobians += 1;
        self.jac_fresh = true;
        self.jac_stale = false;
        self.lu_h = f64::NAN;
        Ok(())
    }

    /// Factors E = I − hγA_v − (hγ)²A_x unless it is factored for this h already.
    fn factor(&mut self, h: f64) -> Result<(), CoreError> {
        if self.lu_h == h {
            return Ok(());
        }
        let n3 = self.n3;
        let hg = h * GAMMA;
        let e = self.lu.matrix_mut();
        for i in 0..n3 {
            for j in 0..n3 {
                let ij = i * n3 + j;
                e[ij] = -hg * self.av[ij] - hg * hg * self.ax[ij];
            }
            e[i * n3 + i] += 1.0;
        }
        self.lu_h = f64::NAN;
        self.lu.factor()?;
        self.stats.factorizations += 1;
        self.lu_h = h;
        Ok(())
    }

    /// Solves (I − hγJ) Δ = r in place (r = (r_x, r_v), length 6 n₁) through the Schur
    /// complement: E Δv = r_v + hγ A_x r_x, Δx = r_x + hγ Δv.
    fn solve(&mut self, h: f64, r: &mut [f64]) {
        let n3 = self.n3;
        let hg = h * GAMMA;
        let (rx, rv) = r.split_at_mut(n3);
        for (i, b) in self.bv.iter_mut().enumerate() {
            let row = &self.ax[i * n3..(i + 1) * n3];
            *b = rv[i] + hg * row.iter().zip(rx.iter()).map(|(a, x)| a * x).sum::<f64>();
        }
        self.lu.solve_in_place(&mut self.bv);
        rv.copy_from_slice(&self.bv);
        for (x, v) in rx.iter_mut().zip(rv.iter()) {
            *x += hg * v;
        }
    }
}

impl<C> Sdirk<C> {
    /// Simplified Newton for stage `i` at time `ts` from the guess in `self.z` (ψ in
    /// `self.psi`); on success k_i = (z − ψ)/(hγ). Returns whether it converged.
    fn newton_stage<S: System>(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        ts: f64,
        h: f64,
        i: usize,
    ) -> bool {
        let hg = h * GAMMA;
        let kappa = self.kappa();
        let mut eta = self.eta.max(f64::EPSILON).powf(0.8);
        let mut prev = f64::INFINITY;
        for it in 0..MAX_NEWTON {
            self.stats.newton_iterations += 1;
            if system.rhs(ts, &self.z, &mut self.fz, ws).is_err() {
                return false;
            }
            let mut r = std::mem::take(&mut self.r);
            for (((r, p), f), z) in r.iter_mut().zip(&self.psi).zip(&self.fz).zip(&self.z) {
                *r = p + hg * f - z;
            }
            self.solve(h, &mut r);
            let nd = self.norm(&r);
            self.z.iter_mut().zip(&r).for_each(|(z, d)| *z += d);
            self.r = r;
            if !nd.is_finite() {
                return false;
            }
            if it > 0 {
                let theta = nd / prev;
                self.theta_max = self.theta_max.max(theta);
                if theta >= THETA_DIVERGE {
                    return false;
                }
                eta = theta / (1.0 - theta);
            }
            if eta * nd <= kappa || nd <= 1e-3 * kappa {
                self.eta = eta;
                let k = &mut self.k[i];
                for ((k, z), p) in k.iter_mut().zip(&self.z).zip(&self.psi) {
                    *k = (z - p) / hg;
                }
                return true;
            }
            prev = nd;
        }
        false
    }

    /// The three stages and the filtered error estimate of a step of size h from (t, y).
    fn attempt<S: System>(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &[f64],
        h: f64,
    ) -> Attempt {
        let tab = TAB;
        self.theta_max = 0.0;
        for i in 0..3 {
            self.psi.copy_from_slice(y);
            for j in 0..i {
                let a = h * tab.a[i][j];
                self.psi
                    .iter_mut()
                    .zip(&self.k[j])
                    .for_each(|(p, k)| *p += a * k);
            }
            // guess: the last step's Hermite cubic extrapolated to the stage time (O(h⁴)),
            // else the previous stage's slope (f0 for the first)
            if !self.extrapolate(t + tab.c[i] * h) {
                let guess = if i == 0 { &self.f0 } else { &self.k[i - 1] };
                let hg = h * GAMMA;
                for ((z, p), g) in self.z.iter_mut().zip(&self.psi).zip(guess) {
                    *z = p + hg * g;
                }
            }
            if !self.newton_stage(system, ws, t + tab.c[i] * h, h, i) {
                self.stats.newton_failures += 1;
                return Attempt::NewtonFailed;
            }
        }
        self.y_new.copy_from_slice(&self.z);
        let mut e = std::mem::take(&mut self.r);
        for (idx, e) in e.iter_mut().enumerate() {
            *e = h * (0..3).map(|j| E[j] * self.k[j][idx]).sum::<f64>();
        }
        self.solve(h, &mut e);
        for ((w, a), b) in self.w.iter_mut().zip(y).zip(&self.y_new) {
            *w = self.atol + self.rtol * a.abs().max(b.abs());
        }
        let n3 = self.n3;
        let err = e[..n3]
            .iter()
            .zip(&self.w[..n3])
            .map(|(x, w)| (x / w).powi(2))
            .sum::<f64>();
        let err = (err / n3.max(1) as f64).sqrt();
        self.r = e;
        Attempt::Done(if err.is_finite() { err } else { f64::INFINITY })
    }

    /// Accepts y_new: projects it onto the constraints, keeps the dense output, advances y.
    /// Returns `false` (nothing changed) when the projection fails.
    fn accept<S: ConstrainedSystem<Constraints = C>>(
        &mut self,
        system: &S,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> bool {
        if system
            .project(&mut self.cons, &mut self.y_new, self.proj_tol, t + h)
            .is_err()
        {
            return false;
        }
        self.y_old.copy_from_slice(y);
        self.f_old.copy_from_slice(&self.f0);
        self.t_old = t;
        self.h_old = h;
        self.has_last = true;
        y.copy_from_slice(&self.y_new);
        self.y_last.copy_from_slice(&self.y_new);
        // stiffly accurate: k₃ ≈ f(t + h, y_{n+1}) starts the next step
        self.f0.copy_from_slice(&self.k[2]);
        self.f0_valid = true;
        self.jac_fresh = false;
        if self.theta_max > THETA_REFRESH {
            self.jac_stale = true;
        }
        true
    }

    /// Weights atol + rtol·|y| of the Newton norm.
    fn set_weights(&mut self, y: &[f64]) {
        for (w, a) in self.w.iter_mut().zip(y) {
            *w = self.atol + self.rtol * a.abs();
        }
    }

    /// The step after an accepted one with error norm `err`: 0.9 err^{-1/3} within ×[0.2, 5],
    /// kept equal to h within ×[1, 1.2] so that the Newton matrix is reused.
    fn next_step(&self, h: f64, err: f64) -> f64 {
        if !self.error_control {
            return h;
        }
        let fac = (0.9 * err.max(1e-10).powf(-1.0 / 3.0)).clamp(0.2, 5.0);
        if (1.0..=1.2).contains(&fac) {
            h
        } else {
            h * fac
        }
    }
}

impl<S: ConstrainedSystem> Integrator<S> for Sdirk<S::Constraints> {
    fn kind(&self) -> IntegratorKind {
        IntegratorKind::Sdirk
    }

    fn is_adaptive(&self) -> bool {
        self.error_control
    }

    fn preserves_constraints(&self) -> bool {
        true
    }

    fn has_dense_output(&self) -> bool {
        true
    }

    fn invalidate(&mut self) {
        self.f0_valid = false;
        self.jac_fresh = false;
        self.has_last = false;
    }

    /// f(t, y), the first Jacobian, and a starting step from Hairer & Wanner's heuristic for
    /// order 3 (one more force evaluation).
    fn start(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &[f64],
        h_max: f64,
    ) -> Result<f64, CoreError> {
        self.has_last = false;
        self.jacobian(system, ws, t, y)?;
        if !self.error_control {
            return Ok(h_max);
        }
        self.set_weights(y);
        let d0 = self.norm(y);
        let d1 = self.norm(&self.f0);
        let h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        }
        .min(h_max);
        for ((z, a), f) in self.z.iter_mut().zip(y).zip(&self.f0) {
            *z = a + h0 * f;
        }
        system.rhs(t + h0, &self.z, &mut self.fz, ws)?;
        let mut diff = std::mem::take(&mut self.r);
        for ((d, a), b) in diff.iter_mut().zip(&self.fz).zip(&self.f0) {
            *d = (a - b) / h0;
        }
        let d2 = self.norm(&diff);
        self.r = diff;
        Ok(super::integrator::starting_step(h0, d1, d2, 0.25, h_max))
    }

    /// One step of size h from (t, y): Newton failures refresh an old Jacobian and retry, then
    /// reject with h/4; an error estimate above 1 rejects with a smaller step.
    fn step(
        &mut self,
        system: &S,
        ws: &mut S::Workspace,
        t: f64,
        y: &mut [f64],
        h: f64,
    ) -> Result<StepOutcome, CoreError> {
        self.ensure_f0(system, ws, t, y)?;
        if self.jac_stale {
            self.jacobian(system, ws, t, y)?;
        }
        let mut second_chance = true;
        loop {
            self.set_weights(y);
            let attempt = match self.factor(h) {
                Ok(()) => self.attempt(system, ws, t, y, h),
                Err(_) => Attempt::NewtonFailed,
            };
            if matches!(attempt, Attempt::NewtonFailed) && self.jac_fresh && second_chance {
                // Large rotations of stiff strings within the step: a Jacobian at y_n misses
                // their turned directions. Retry once with one at the failing stage's iterate.
                second_chance = false;
                let mut p = std::mem::take(&mut self.y_new);
                p.copy_from_slice(&self.z);
                let ok = p.iter().all(|v| v.is_finite())
                    && self.jacobian_at(system, ws, t + h, &p).is_ok();
                self.y_new = p;
                if ok {
                    self.jac_stale = true;
                    continue;
                }
            }
            match attempt {
                Attempt::NewtonFailed if !self.jac_fresh => self.jacobian(system, ws, t, y)?,
                Attempt::NewtonFailed => return self.reject(h, 0.25),
                Attempt::Done(err) if self.error_control && err > 1.0 => {
                    let fac = (0.9 * err.powf(-1.0 / 3.0)).clamp(0.2, 0.9);
                    return self.reject(h, fac);
                }
                Attempt::Done(err) => {
                    if !self.accept(system, t, y, h) {
                        return self.reject(h, 0.5);
                    }
                    return Ok(StepOutcome {
                        accepted: true,
                        h_next: self.next_step(h, err),
                    });
                }
            }
        }
    }

    /// Cubic Hermite interpolation of the last accepted step at `t`.
    fn interpolate(&self, t: f64, out: &mut [f64]) -> bool {
        self.hermite(t, out);
        true
    }
}

impl<C> Sdirk<C> {
    /// Writes the last step's Hermite cubic at `t` into `self.z`; `false` when there is no
    /// last step (first step, or the state was changed outside).
    fn extrapolate(&mut self, t: f64) -> bool {
        if !self.has_last {
            return false;
        }
        let mut z = std::mem::take(&mut self.z);
        self.hermite(t, &mut z);
        self.z = z;
        true
    }

    /// The cubic through (y_old, f_old) and (y_last, f0) over the last accepted step, at t.
    fn hermite(&self, t: f64, out: &mut [f64]) {
        let h = self.h_old;
        let s = (t - self.t_old) / h;
        let (s2, s3) = (s * s, s * s * s);
        let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
        let h10 = (s3 - 2.0 * s2 + s) * h;
        let h01 = -2.0 * s3 + 3.0 * s2;
        let h11 = (s3 - s2) * h;
        for (i, o) in out.iter_mut().enumerate() {
            // the end slope k₃ of the last step is in f0 now
            *o =
                h00 * self.y_old[i] + h10 * self.f_old[i] + h01 * self.y_last[i] + h11 * self.f0[i];
        }
    }
}

impl<C> Sdirk<C> {
    /// A rejected step: the state is untouched; a fixed-step run cannot shrink its step and
    /// fails instead.
    fn reject(&self, h: f64, factor: f64) -> Result<StepOutcome, CoreError> {
        if !self.error_control {
            return Err(NumericsError::NoConvergence {
                operation: "sdirk Newton iteration (fixed step too large)",
            }
            .into());
        }
        Ok(StepOutcome {
            accepted: false,
            h_next: h * factor,
        })
    }
}
