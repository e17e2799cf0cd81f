//! Newmark's step ([`crate::newmark`]) with rigid bars ([`crate::rigid_bars`]): the unknowns
//! are the acceleration a₁ and the multipliers μ₁ at the step's end, q₁ = q₀ + h q̇₀ +
//! (h²/4)(a₀ + a₁), q̇₁ = q̇₀ + (h/2)(a₀ + a₁), and the residuals
//!
//! > r = M a₁ − F(q₁, q̇₁) − G(q₁)ᵀ μ₁ = 0,   g(q₁) = 0
//!
//! (the lengths held at the positions themselves, index 3). Newton's matrix in the scaled
//! update Δa' = (h²/4) Δa is
//!
//! > [J − Σ μ_k H_k, −Gᵀ; G, 0],   J = (4/h²) M + K_T + (2/h) C_T,   H_k = ∇²g_k,
//!
//! solved by its Schur complement: z = J_μ⁻¹ r, W = J_μ⁻¹ Gᵀ, (G W) Δμ = G z − g,
//! Δa' = −z + W Δμ. The iteration stops when r is at the tolerance of the unconstrained step
//! and every |g_k| at round-off (16 ε L_k (L_k + ‖x_i‖ + ‖x_j‖)), or when the update is at
//! round-off; the velocities q̇₁ are then projected onto G(q₁) q̇ = 0 in the mass metric
//! (the trapezoidal rule keeps them there only to O(h²)).

use crate::factor::{Factored, DENSE_MAX};
use crate::rigid_bars::{dot, Row};
use crate::tangent::member_block_triplets;
use crate::transient::{ElasticDynamics, TransientWorkspace};
use nalgebra::{DMatrix, DVector, Matrix3};
use tensegrity_core::error::CoreError;

/// A converged step: (q₁, q̇₁, a₁).
pub type Stepped = (DVector<f64>, DVector<f64>, DVector<f64>);

/// A converged step, or the residual left when Newton did not converge.
pub type Outcome = Result<Stepped, f64>;

/// The step's settings.
#[derive(Debug, Clone, Copy)]
pub struct Step {
    /// The time at its start (s).
    pub t: f64,
    /// Its size (s).
    pub h: f64,
    /// The residual's absolute floor (N): what double precision resolves on the stiffest
    /// elastic member.
    pub floor: f64,
    /// The residual's relative tolerance.
    pub tolerance: f64,
    /// Newton iterations before the step is given up.
    pub max_iterations: usize,
}

/// One constrained Newmark step from the state `y` with acceleration `a0` (module docs);
/// `jacobian` gives J at (q₁, q̇₁) as triplets; `iterations` counts Newton's iterations.
pub fn solve(
    system: &ElasticDynamics,
    ws: &mut TransientWorkspace,
    y: &[f64],
    a0: &DVector<f64>,
    step: &Step,
    iterations: &mut u64,
    jacobian: impl Fn(&DVector<f64>, &DVector<f64>) -> Vec<(usize, usize, f64)>,
) -> Result<Outcome, CoreError> {
    let Some(bars) = system.rigid_bars() else {
        return Ok(Err(f64::INFINITY));
    };
    let (model, dofs) = (system.model(), system.dofs());
    let m = system.n_free();
    let h = step.h;
    let q0 = DVector::from_column_slice(&y[..m]);
    let u0 = DVector::from_column_slice(&y[m..]);
    let (c_q, c_u) = (0.25 * h * h, 0.5 * h);
    let base = &q0 + &u0 * h + a0 * c_q;
    let mut a1 = a0.clone();
    let mut mu = DVector::zeros(bars.len());
    let mut residual = f64::INFINITY;
    for _ in 0..step.max_iterations {
        *iterations += 1;
        let q1 = &base + &a1 * c_q;
        let u1 = &u0 + (a0 + &a1) * c_u;
        let f = system.reduced_forces(step.t + h, q1.as_slice(), u1.as_slice(), ws)?;
        let x = system.positions(q1.as_slice());
        let rows = bars.rows(model, dofs, &x);
        let gt_mu = transpose_times(&rows, &mu, m);
        let ma = system.mass_times(a1.as_slice());
        let r = &ma - &f - &gt_mu;
        let g = bars.residuals(model, &x);
        let held = g
            .iter()
            .zip(bars.tolerances(model, &x).iter())
            .all(|(g, t)| g.abs() <= *t);
        let scale = ma
            .amax()
            .max(f.amax())
            .max(gt_mu.amax())
            .max(f64::MIN_POSITIVE);
        residual = r.amax();
        if held && residual <= (step.tolerance * scale).max(step.floor) {
            return finish(system, q1, u1, a1).map(Ok);
        }
        // J − Σ μ_k H_k: H_k = [[I, −I], [−I, I]] on the bar's two nodes
        let mut triplets = jacobian(&q1, &u1);
        let mut on_member = vec![0.0; model.members.len()];
        for (&k, &mk) in bars.members.iter().zip(mu.iter()) {
            on_member[k] = mk;
        }
        let states = crate::forces::member_states(model, &x, 0.0);
        triplets.extend(member_block_triplets(
            model,
            dofs,
            |k, _| (on_member[k] != 0.0).then(|| Matrix3::identity() * (-on_member[k])),
            &states,
        ));
        let Some(mut factor) = Factored::from_triplets(m, &triplets, DENSE_MAX) else {
            return Ok(Err(residual));
        };
        let Some(z) = factor.solve(&r) else {
            return Ok(Err(residual));
        };
        let mut w = Vec::with_capacity(rows.len());
        for row in &rows {
            let mut col = DVector::zeros(m);
            for &(b, v) in row {
                col[b] += v;
            }
            let Some(col) = factor.solve(&col) else {
                return Ok(Err(residual));
            };
            w.push(col);
        }
        let n = rows.len();
        let s = DMatrix::from_fn(n, n, |k, l| dot(&rows[k], w[l].as_slice()));
        let rhs = DVector::from_fn(n, |k, _| dot(&rows[k], z.as_slice()) - g[k]);
        let Some(dmu) = s.lu().solve(&rhs) else {
            return Ok(Err(residual));
        };
        let mut da = -z;
        for (wk, &d) in w.iter().zip(dmu.iter()) {
            da += wk * d;
        }
        let da = da / c_q;
        a1 += &da;
        mu += &dmu;
        if held && da.amax() <= 1e-13 * a1.amax().max(f64::MIN_POSITIVE) {
            let q1 = &base + &a1 * c_q;
            let u1 = &u0 + (a0 + &a1) * c_u;
            return finish(system, q1, u1, a1).map(Ok);
        }
    }
    Ok(Err(residual))
}

/// Gᵀ μ on `m` free coordinates.
fn transpose_times(rows: &[Row], mu: &DVector<f64>, m: usize) -> DVector<f64> {
    let mut out = DVector::zeros(m);
    for (row, &mk) in rows.iter().zip(mu.iter()) {
        for &(b, v) in row {
            out[b] += v * mk;
        }
    }
    out
}

/// The converged step with its velocities projected onto G(q₁) q̇ = 0.
fn finish(
    system: &ElasticDynamics,
    q1: DVector<f64>,
    mut u1: DVector<f64>,
    a1: DVector<f64>,
) -> Result<Stepped, CoreError> {
    system.project_velocities(q1.as_slice(), u1.as_mut_slice())?;
    Ok((q1, u1, a1))
}
