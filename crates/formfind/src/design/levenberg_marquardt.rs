//! Bound-constrained nonlinear least squares: a projected Levenberg–Marquardt method on an
//! exact Jacobian (Kanzow, Yamashita and Fukushima 2004, with Nielsen's damping update).
//!
//! Minimise f(x) = ‖r(x)‖² subject to l ≤ x ≤ u (an infinite bound is none), r the residuals
//! and J = ∂r/∂x their Jacobian. Each iteration:
//!
//! 1. the projected gradient g̃ = x − P(x − ∇f), ∇f = 2 Jᵀ r, P the projection on the box;
//!    the iterate is stationary when ‖g̃‖∞ ≤ `gtol`;
//! 2. the active set A = {i : x_i = l_i and ∂_i f > 0, or x_i = u_i and ∂_i f < 0} is held;
//! 3. on the free variables F the damped Gauss–Newton step solves
//!    (J_Fᵀ J_F + μ D) δ_F = −J_Fᵀ r, D = diag(J_Fᵀ J_F) floored at 10⁻¹² of its largest
//!    entry (Marquardt's scaling: the step does not depend on the variables' units);
//! 4. the trial x⁺ = P(x + δ) is accepted when the gain ratio ρ = (f − f(x⁺)) / (f − ‖r +
//!    J (x⁺ − x)‖²) exceeds 10⁻⁴ (both reductions computed without the cancellation of a
//!    difference: Σ (r − r⁺)(r + r⁺) and −(2 r + J s)ᵀ J s, s = x⁺ − x); then μ ← μ · max(1/3, 1 − (2ρ − 1)³) and ν ← 2, else
//!    μ ← μ ν and ν ← 2 ν (a trial where r cannot be evaluated is rejected the same way);
//! 5. the stop on the objective, as L-BFGS-B's (scipy's `ftol`): an accepted step with
//!    (f − f⁺) ≤ `ftol` · max(|f|, |f⁺|, 1), taken with μ ≤ [`GAUSS_NEWTON_DAMPING`]. A heavily
//!    damped step decreases f little because the Gauss–Newton model is poor there (a large
//!    residual, strong curvature of r), not because the minimum is near: such a crawl runs
//!    on to the gradient rule or the iteration cap, which says it did not converge.
//!
//! Near a minimum with small residuals the step is Gauss–Newton's and the convergence is
//! fast where a quasi-Newton method crawls: on a long, flat valley (jax-fdm's cable net,
//! `docs/guide/design.md`) L-BFGS stops on its `ftol` far from the optimum that this method
//! reaches (checked against scipy's trust-region reflective least squares). Each iteration
//! costs one Jacobian (one adjoint solve per residual in [`super::design`]) and one residual
//! evaluation per trial.
//!
//! ```
//! use formfind::design::levenberg_marquardt::minimize;
//! use formfind::design::lbfgsb::{LbfgsbSettings, Stop};
//! use nalgebra::DMatrix;
//! // Rosenbrock as least squares, r = (1 − x₀, 10 (x₁ − x₀²)), with x₀ ≤ 0.5: the minimum
//! // (0.5, 0.25) sits on the bound
//! let rj = |x: &[f64], jacobian: bool| -> Result<(Vec<f64>, Option<DMatrix<f64>>), ()> {
//!     let r = vec![1.0 - x[0], 10.0 * (x[1] - x[0] * x[0])];
//!     let j = jacobian.then(|| DMatrix::from_row_slice(2, 2, &[-1.0, 0.0, -20.0 * x[0], 10.0]));
//!     Ok((r, j))
//! };
//! let lower = [f64::NEG_INFINITY; 2];
//! let upper = [0.5, f64::INFINITY];
//! let settings = LbfgsbSettings { ftol: 0.0, gtol: 1e-12, ..LbfgsbSettings::default() };
//! let m = minimize(rj, &[-1.2, 1.0], &lower, &upper, &settings).unwrap();
//! assert!((m.x[0] - 0.5).abs() < 1e-12 && (m.x[1] - 0.25).abs() < 1e-12, "{:?}", m.x);
//! assert!((m.objective - 0.25).abs() < 1e-12 && m.stop == Stop::Gradient);
//! ```

use super::lbfgsb::{
    project, projected_gradient_norm, start, stop_before_iteration, Iterate, LbfgsbSettings,
    Minimum, Stop,
};
use nalgebra::{DMatrix, DVector};

/// The gain ratio above which a trial is accepted.
const ACCEPT: f64 = 1e-4;
/// Rejected trials in a row after which no step can decrease the objective.
const MAX_REJECTIONS: usize = 60;
/// The damping μ (relative to the diagonal of Jᵀ J) at or below which a step counts as
/// Gauss–Newton's for the objective rule (module docs).
pub const GAUSS_NEWTON_DAMPING: f64 = 1e-2;

/// Residuals and, when asked, their Jacobian.
type ResidualsAndJacobian = (Vec<f64>, Option<DMatrix<f64>>);

/// Minimises ‖r(x)‖² subject to `lower` ≤ x ≤ `upper` from `x0` (projected into the box;
/// module docs), with the stopping rules of [`LbfgsbSettings`] (`memory` unused).
/// `rj(x, jacobian)` returns r(x) and, when `jacobian`, J(x) (residuals × variables); its
/// error at the start is returned, at a trial point it rejects the trial.
pub fn minimize<E>(
    mut rj: impl FnMut(&[f64], bool) -> Result<ResidualsAndJacobian, E>,
    x0: &[f64],
    lower: &[f64],
    upper: &[f64],
    settings: &LbfgsbSettings,
) -> Result<Minimum, E> {
    let n = x0.len();
    let mut x = x0.to_vec();
    project(&mut x, lower, upper);
    let (r0, j0) = rj(&x, true)?;
    let mut r = DVector::from_vec(r0);
    let mut j = j0.expect("a Jacobian when asked");
    let mut evaluations = 1;
    let mut f = r.norm_squared();
    let mut g: Vec<f64> = (j.transpose() * &r * 2.0).iter().copied().collect();
    let mut history = vec![start(f, &x, &g, lower, upper)];
    let top = |jtj: &DMatrix<f64>| jtj.diagonal().iter().copied().fold(0.0f64, f64::max);
    let mut mu = 1e-3 * top(&(j.transpose() * &j)).max(f64::MIN_POSITIVE);
    let mut nu = 2.0;
    let mut rejections = 0;
    let mut iterations = 0;
    let stop = loop {
        let counts = (iterations, evaluations);
        if let Some(stop) = stop_before_iteration((&x, &g), (lower, upper), counts, settings) {
            break stop;
        }
        if rejections >= MAX_REJECTIONS {
            break Stop::LineSearch;
        }
        let free: Vec<usize> = (0..n)
            .filter(|&i| !((x[i] <= lower[i] && g[i] > 0.0) || (x[i] >= upper[i] && g[i] < 0.0)))
            .collect();
        let jf = j.select_columns(free.iter());
        let mut a = jf.transpose() * &jf;
        let b = -(jf.transpose() * &r);
        let floor = 1e-12 * top(&a).max(f64::MIN_POSITIVE);
        for i in 0..free.len() {
            a[(i, i)] += mu * a[(i, i)].max(floor);
        }
        let Some(chol) = a.cholesky() else {
            mu *= nu;
            nu *= 2.0;
            rejections += 1;
            continue;
        };
        let delta = chol.solve(&b);
        let mut xt = x.clone();
        for (c, &i) in free.iter().enumerate() {
            xt[i] += delta[c];
        }
        project(&mut xt, lower, upper);
        let s = DVector::from_iterator(n, (0..n).map(|i| xt[i] - x[i]));
        // f − ‖r + J s‖² = −(2 r + J s)ᵀ J s, free of the cancellation of the difference
        let js = &j * &s;
        let predicted = -(&r * 2.0 + &js).dot(&js);
        evaluations += 1;
        let trial = rj(&xt, false).ok().map(|(rt, _)| DVector::from_vec(rt));
        let ft = trial.as_ref().map_or(f64::INFINITY, |rt| rt.norm_squared());
        // f − f⁺ as Σ (r − r⁺)(r + r⁺): a residual the step leaves alone adds nothing
        let actual = trial
            .as_ref()
            .map_or(f64::NEG_INFINITY, |rt| (&r - rt).dot(&(&r + rt)));
        let rho = if predicted > 0.0 {
            actual / predicted
        } else {
            -1.0
        };
        if !(rho > ACCEPT && ft.is_finite()) {
            mu *= nu;
            nu *= 2.0;
            rejections += 1;
            continue;
        }
        rejections = 0;
        iterations += 1;
        let step = s.amax();
        // the Jacobian at the accepted point (its residuals recomputed with it)
        let (r1, j1) = rj(&xt, true)?;
        evaluations += 1;
        let decrease = actual;
        let previous = f;
        x = xt;
        r = DVector::from_vec(r1);
        j = j1.expect("a Jacobian when asked");
        f = r.norm_squared();
        g = (j.transpose() * &r * 2.0).iter().copied().collect();
        let damping = mu;
        mu *= (1.0 - (2.0 * rho - 1.0).powi(3)).max(1.0 / 3.0);
        nu = 2.0;
        history.push(Iterate {
            iteration: iterations,
            objective: f,
            projected_gradient: projected_gradient_norm(&x, &g, lower, upper),
            step,
            evaluations,
            evaluation: evaluations,
        });
        // a damped step's small decrease says the model is poor there, not that the
        // minimum is near: the objective rule counts for a (nearly) Gauss–Newton step only
        let gauss_newton = damping <= GAUSS_NEWTON_DAMPING;
        if gauss_newton && decrease <= settings.ftol * previous.abs().max(f.abs()).max(1.0) {
            break Stop::Objective;
        }
    };
    Ok(Minimum {
        x,
        objective: f,
        gradient: g,
        iterations,
        evaluations,
        stop,
        history,
    })
}
