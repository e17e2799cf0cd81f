//! [`ConstraintSet`]: the bar lengths and N P = D of a [`Model`] as holonomic constraints,
//! with the projection onto them, and the model's [`ConstrainedSystem`] (what RATTLE and the
//! projecting methods step).
//!
//! # Equations
//!
//! In class-1 coordinates x (two nodes per bar) the bars are point pairs with the block
//! mass matrix M = [[m/3, m/6], [m/6, m/3]] ⊗ I₃ (translational plus J = m/12 rotational
//! inertia), M⁻¹ = [[4, −2], [−2, 4]]/m per bar, subject to g(x) = 0: ½(‖b_k‖² − l_k²) = 0
//! for every bar and N P − D = 0, with gradient G = ∂g/∂x (rows −b_k, b_k for a bar, ±e_d for
//! N P = D).
//!
//! * **Positions**: x ← x + M⁻¹Gᵀδ with G M⁻¹ Gᵀ δ = −g(x), a quasi-Newton iteration whose
//!   factor of G M⁻¹ Gᵀ is the previous projection's (refactored at x when it does not
//!   converge within a few iterations), to max |g| ≤ max(tol, 16 ε max|x| ℓ).
//! * **Velocities**: v ← v + M⁻¹Gᵀδ with G M⁻¹ Gᵀ δ = −G v, G at the corrected positions.

use super::model::{Model, Workspace};
use super::omega::{ConstraintMatrix, Row, RowEntry};
use super::system::{set3, vec3, ConstrainedSystem};
use nalgebra::Vector3;
use tensegrity_core::error::{CoreError, DynamicsError};

/// The bar-length and N P = D constraints with their sparse multiplier system.
#[derive(Debug)]
pub struct ConstraintSet {
    sys: ConstraintMatrix,
    n_bars: usize,
    targets: Vec<f64>,
    r: Vec<f64>,
    cf: Vec<Vector3<f64>>,
    length2: Vec<f64>,
    /// max(longest bar, 1 m): the length scale of the residuals' round-off.
    length_scale: f64,
    /// Whether `sys` holds the factor of the last projection's corrected positions (the
    /// next projection's position step starts from it; a factor taken in between by RATTLE
    /// is as recent and serves as well).
    factored: bool,
    /// Positions before a position step that starts from the previous projection's factor.
    start: Vec<f64>,
}

/// Multiple of ε·max|x|·ℓ below which a constraint residual is round-off: b = x_b − x_a
/// carries an absolute error ~ε max|x| however short the bar, so ½(‖b‖² − l²) cannot be
/// driven below ~√3 ε max|x| l (and N P − D below ~ε max|x| per entry). Far from the origin
/// (a wheel 100 m down a slope) this floor exceeds a fixed tolerance of 10⁻¹⁴ l², which
/// made the iteration fail on a converged state.
const ROUNDOFF_FLOOR: f64 = 16.0 * f64::EPSILON;

/// Iterations the position step may take from the previous projection's factor before it
/// refactors at the current positions.
const STALE_ITERATIONS: usize = 6;

impl ConstraintSet {
    /// Builds the constraint rows of `model` (bars first, then N P = D).
    pub fn new(model: &Model) -> Result<Self, CoreError> {
        let nb = model.bars.len();
        let mut rows = Vec::with_capacity(nb + model.linear_rows.len());
        let mut targets = Vec::with_capacity(rows.capacity());
        for k in 0..nb {
            rows.push(Row {
                entries: [
                    Some(RowEntry {
                        node: 2 * k,
                        grad: Vector3::zeros(),
                    }),
                    Some(RowEntry {
                        node: 2 * k + 1,
                        grad: Vector3::zeros(),
                    }),
                ],
            });
            targets.push(0.0);
        }
        for r in &model.linear_rows {
            rows.push(r.row.clone());
            targets.push(r.target);
        }
        let n = rows.len();
        Ok(Self {
            sys: ConstraintMatrix::new(rows, false)?,
            n_bars: nb,
            targets,
            r: vec![0.0; n],
            cf: vec![Vector3::zeros(); model.n1],
            length2: model.bars.iter().map(|b| b.length0 * b.length0).collect(),
            length_scale: model.bars.iter().map(|b| b.length0).fold(1.0, f64::max),
            factored: false,
            start: Vec::new(),
        })
    }

    fn set_grads(&mut self, x: &[f64]) {
        for k in 0..self.n_bars {
            let b = vec3(x, 2 * k + 1) - vec3(x, 2 * k);
            let e = &mut self.sys.rows[k].entries;
            if let Some(a) = e[0].as_mut() {
                a.grad = -b;
            }
            if let Some(a) = e[1].as_mut() {
                a.grad = b;
            }
        }
    }

    /// Factors G M⁻¹ Gᵀ with G at the positions `x`.
    pub(crate) fn factor(&mut self, model: &Model, x: &[f64]) -> Result<(), CoreError> {
        self.set_grads(x);
        self.sys.assemble_and_factor(&[], &model.inv_mass)
    }

    /// Residuals g(x) into self.r; returns max |g|.
    fn residual(&mut self, x: &[f64]) -> f64 {
        let mut worst: f64 = 0.0;
        for k in 0..self.n_bars {
            let b = vec3(x, 2 * k + 1) - vec3(x, 2 * k);
            self.r[k] = 0.5 * (b.norm_squared() - self.length2[k]);
        }
        for (i, row) in self.sys.rows.iter().enumerate().skip(self.n_bars) {
            self.r[i] = row
                .entries
                .iter()
                .flatten()
                .map(|e| e.grad.dot(&vec3(x, e.node)))
                .sum::<f64>()
                - self.targets[i];
        }
        for v in &self.r {
            worst = worst.max(v.abs());
        }
        worst
    }

    /// Velocity residuals G v into self.r.
    fn velocity_residual(&mut self, v: &[f64]) {
        for (i, row) in self.sys.rows.iter().enumerate() {
            self.r[i] = row
                .entries
                .iter()
                .flatten()
                .map(|e| e.grad.dot(&vec3(v, e.node)))
                .sum::<f64>();
        }
    }

    /// out += scale · M⁻¹ Gᵀ m (with the gradients currently stored).
    fn add_minv_gt(&mut self, model: &Model, m: &[f64], scale: f64, out: &mut [f64]) {
        self.cf.iter_mut().for_each(|c| *c = Vector3::zeros());
        for (row, &mu) in self.sys.rows.iter().zip(m) {
            for e in row.entries.iter().flatten() {
                self.cf[e.node] += e.grad * mu;
            }
        }
        apply_minv(model, &self.cf, scale, out);
    }
    /// Drops the factor kept from the last projection: the next one factors at its own
    /// positions (a restart from a saved state then projects as the original run did after
    /// the same call).
    pub fn forget(&mut self) {
        self.factored = false;
    }

    /// Projects positions onto g = 0 along M⁻¹Gᵀ, then velocities onto G v = 0 with G at the
    /// corrected positions. The position step's G is the previous projection's (a quasi-Newton
    /// iteration one step stale: a few solves instead of a factorisation), or that of the
    /// current x when it does not converge within six iterations (and in the first
    /// projection). Returns the remaining position residual.
    pub fn project(
        &mut self,
        model: &Model,
        y: &mut [f64],
        tol: f64,
        t: f64,
    ) -> Result<f64, CoreError> {
        let n3 = 3 * model.n1;
        let (x, v) = y.split_at_mut(n3);
        // The position step is a quasi-Newton iteration: it starts from the factor of the
        // previous projection (one step away, a few cheap iterations), and refactors at x only
        // if that does not converge within STALE_ITERATIONS.
        let mut converged = false;
        if self.factored {
            self.start.clear();
            self.start.extend_from_slice(x);
            converged = self
                .solve_positions(model, x, tol, t, STALE_ITERATIONS)
                .is_ok();
            if !converged {
                x.copy_from_slice(&self.start);
            }
        }
        self.factored = false;
        if !converged {
            self.factor(model, x)?;
            self.solve_positions(model, x, tol, t, 100)?;
        }
        // the velocities are projected with G at the corrected positions
        self.factor(model, x)?;
        self.factored = true;
        self.project_velocities(model, v);
        Ok(self.residual(x))
    }

    /// Quasi-Newton position solve with the current factorisation.
    pub(crate) fn solve_positions(
        &mut self,
        model: &Model,
        x: &mut [f64],
        tol: f64,
        t: f64,
        iterations: usize,
    ) -> Result<(), CoreError> {
        let reach = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let tol = tol.max(ROUNDOFF_FLOOR * reach * self.length_scale);
        let mut res = f64::INFINITY;
        for _ in 0..iterations {
            res = self.residual(x);
            if res <= tol {
                return Ok(());
            }
            let mut d = std::mem::take(&mut self.r);
            d.iter_mut().for_each(|v| *v = -*v);
            self.sys.solve_in_place(&mut d);
            self.add_minv_gt(model, &d, 1.0, x);
            self.r = d;
        }
        Err(DynamicsError::ConstraintNotConverged { t, residual: res }.into())
    }

    /// Projects the velocities onto G v = 0 along M⁻¹Gᵀ (G of the current factor).
    pub(crate) fn project_velocities(&mut self, model: &Model, v: &mut [f64]) {
        self.velocity_residual(v);
        let mut d = std::mem::take(&mut self.r);
        d.iter_mut().for_each(|x| *x = -*x);
        self.sys.solve_in_place(&mut d);
        self.add_minv_gt(model, &d, 1.0, v);
        self.r = d;
    }
}

/// out += scale · M⁻¹ f per bar (M⁻¹ = [[4, −2], [−2, 4]]/m).
fn apply_minv(model: &Model, f: &[Vector3<f64>], scale: f64, out: &mut [f64]) {
    for (k, bar) in model.bars.iter().enumerate() {
        let (a, b) = (2 * k, 2 * k + 1);
        let s = scale * bar.inv_mass;
        let da = (f[a] * 4.0 - f[b] * 2.0) * s;
        let db = (f[b] * 4.0 - f[a] * 2.0) * s;
        set3(out, a, &(vec3(out, a) + da));
        set3(out, b, &(vec3(out, b) + db));
    }
}

impl ConstrainedSystem for Model {
    type Constraints = ConstraintSet;

    fn constraints(&self) -> Result<ConstraintSet, CoreError> {
        ConstraintSet::new(self)
    }

    /// 10⁻¹⁴ max(1 m², l_max²).
    fn constraint_tolerance(&self) -> f64 {
        1e-14
            * self
                .bars
                .iter()
                .map(|b| b.length0 * b.length0)
                .fold(1.0, f64::max)
    }

    fn project(
        &self,
        constraints: &mut ConstraintSet,
        y: &mut [f64],
        tol: f64,
        t: f64,
    ) -> Result<f64, CoreError> {
        constraints.project(self, y, tol, t)
    }

    fn factor_constraints(
        &self,
        constraints: &mut ConstraintSet,
        x: &[f64],
    ) -> Result<(), CoreError> {
        constraints.factor(self, x)
    }

    fn solve_positions(
        &self,
        constraints: &mut ConstraintSet,
        x: &mut [f64],
        tol: f64,
        t: f64,
        iterations: usize,
    ) -> Result<(), CoreError> {
        constraints.solve_positions(self, x, tol, t, iterations)
    }

    fn project_velocities(&self, constraints: &mut ConstraintSet, v: &mut [f64]) {
        constraints.project_velocities(self, v);
    }

    /// Loads, gravity, strings and ground ([`Model::rhs`] without the constraint forces).
    fn forces<'w>(
        &self,
        t: f64,
        x: &[f64],
        v: &[f64],
        ws: &'w mut Workspace,
    ) -> &'w [Vector3<f64>] {
        ws.rhs_evals += 1;
        self.applied_forces(t, x, v, ws);
        &ws.f
    }

    fn add_inverse_mass(&self, f: &[Vector3<f64>], scale: f64, out: &mut [f64]) {
        apply_minv(self, f, scale, out);
    }

    /// A ground, a damped string or a damped cluster.
    fn velocity_dependent_forces(&self) -> bool {
        self.ground.is_some()
            || self.strings.iter().any(|s| s.law.damping > 0.0)
            || self.clusters.iter().any(|c| c.damping > 0.0)
    }
}
