//! Bound-constrained limited-memory quasi-Newton minimisation: a projected L-BFGS in the
//! active-set form of L-BFGS-B (Byrd, Lu, Nocedal and Zhu 1995), on an exact gradient.
//!
//! Minimise f(x) subject to l ≤ x ≤ u (an infinite bound is none). Each iteration:
//!
//! 1. the projected gradient g̃ = x − P(x − ∇f), P the projection on the box; the iterate is
//!    stationary when ‖g̃‖∞ ≤ `gtol`;
//! 2. the active set A = {i : x_i = l_i and ∂_i f > 0, or x_i = u_i and ∂_i f < 0}: the
//!    variables a descent step would push out of the box are held;
//! 3. the direction d = −H ∇f on the free variables (zero on A), H the limited-memory inverse
//!    Hessian of the last m pairs s = x⁺ − x, y = ∇f⁺ − ∇f by the two-loop recursion, scaled by
//!    γ = sᵀy / yᵀy of the newest pair; a pair with sᵀy ≤ ε yᵀy is not stored (it would make H
//!    indefinite), and a direction that does not descend falls back to −∇f;
//! 4. a projected backtracking line search x(α) = P(x + α d) from α = 1 (the first iteration:
//!    α = 1 / ‖∇f‖∞, at most 1) to the Armijo condition f(x(α)) ≤ f(x) + c₁ ∇fᵀ(x(α) − x),
//!    c₁ = 10⁻⁴, each trial α shrunk to the minimiser of the quadratic through f(x), its slope
//!    and f(x(α)), kept within [0.1 α, 0.5 α]; a trial point where f cannot be evaluated (an
//!    error) counts as f = ∞;
//! 5. the stop on the objective (scipy's `ftol`): (f − f⁺) ≤ `ftol` · max(|f|, |f⁺|, 1).
//!
//! This is the projected-gradient variant, not the generalised Cauchy point and subspace
//! minimisation of the original code: on the force density problems here (a few hundred
//! bounded force densities, an exact adjoint gradient) it reaches the same optima, checked
//! against scipy's L-BFGS-B through jax-fdm (`docs/guide/design.md`). Why written here: the
//! L-BFGS-B crates are bindings to the Fortran or C code (a Fortran toolchain, last released
//! in 2016 and 2023) or an R-compatibility layer; `argmin`'s L-BFGS takes no bounds.
//!
//! ```
//! use formfind::design::lbfgsb::{minimize, LbfgsbSettings, Stop};
//! // Rosenbrock with x₀ ≤ 0.5: the minimum (0.5, 0.25) sits on the bound
//! let rosen = |x: &[f64], g: &mut [f64]| -> Result<f64, ()> {
//!     let (a, b) = (1.0 - x[0], x[1] - x[0] * x[0]);
//!     g[0] = -2.0 * a - 400.0 * x[0] * b;
//!     g[1] = 200.0 * b;
//!     Ok(a * a + 100.0 * b * b)
//! };
//! let lower = [f64::NEG_INFINITY; 2];
//! let upper = [0.5, f64::INFINITY];
//! let m = minimize(rosen, &[-1.2, 1.0], &lower, &upper, &LbfgsbSettings::default()).unwrap();
//! assert!((m.x[0] - 0.5).abs() < 1e-12 && (m.x[1] - 0.25).abs() < 1e-6, "{:?}", m.x);
//! assert!(matches!(m.stop, Stop::Gradient | Stop::Objective));
//! ```

use std::collections::VecDeque;

/// The Armijo constant c₁ of the line search.
const ARMIJO: f64 = 1e-4;
/// The curvature constant c₂ of the strong Wolfe conditions (0.9: the usual for
/// quasi-Newton directions).
const CURVATURE: f64 = 0.9;
/// Trial steps of one line search phase (bracketing or zoom) before it gives up.
const MAX_BACKTRACKS: usize = 40;

/// The stopping rules of [`minimize`] (defaults: scipy's L-BFGS-B).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LbfgsbSettings {
    /// Iterations at most (default 1000).
    pub max_iterations: usize,
    /// Objective evaluations at most (default 15 000).
    pub max_evaluations: usize,
    /// Pairs kept in the limited-memory Hessian (default 10).
    pub memory: usize,
    /// The relative decrease of f below which it stops (default 2.2·10⁻⁹, scipy's
    /// `factr` 10⁷ times the machine epsilon).
    pub ftol: f64,
    /// The projected gradient's largest component below which it stops (default 10⁻⁵).
    pub gtol: f64,
}

impl Default for LbfgsbSettings {
    fn default() -> Self {
        Self {
            max_iterations: 1000,
            max_evaluations: 15_000,
            memory: 10,
            ftol: 1e7 * f64::EPSILON,
            gtol: 1e-5,
        }
    }
}

/// Why [`minimize`] stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// The projected gradient is below `gtol`: a stationary point.
    Gradient,
    /// The objective decreased by less than `ftol` (relative) in the last iteration.
    Objective,
    /// `max_iterations` reached: not converged.
    Iterations,
    /// `max_evaluations` reached: not converged.
    Evaluations,
    /// No step along the steepest descent decreased the objective: at the precision the
    /// objective is evaluated to, the iterate cannot be improved (not converged by the rules).
    LineSearch,
}

impl Stop {
    /// Whether this is convergence (the gradient or the objective rule).
    pub fn converged(self) -> bool {
        matches!(self, Stop::Gradient | Stop::Objective)
    }

    /// A short name (`gradient`, `objective`, `iterations`, `evaluations`, `line_search`).
    pub fn name(self) -> &'static str {
        match self {
            Stop::Gradient => "gradient",
            Stop::Objective => "objective",
            Stop::Iterations => "iterations",
            Stop::Evaluations => "evaluations",
            Stop::LineSearch => "line_search",
        }
    }
}

/// One iterate of the history.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Iterate {
    /// The iteration (0: the start).
    pub iteration: usize,
    /// f(x).
    pub objective: f64,
    /// ‖x − P(x − ∇f)‖∞.
    pub projected_gradient: f64,
    /// ‖x − x_previous‖∞ (0 at the start).
    pub step: f64,
    /// Objective evaluations so far.
    pub evaluations: usize,
    /// The evaluation (counted from 1) that gave this iterate: the line search may accept an
    /// earlier trial than its last.
    pub evaluation: usize,
}

/// The result of [`minimize`].
#[derive(Debug, Clone, PartialEq)]
pub struct Minimum {
    /// The last accepted iterate.
    pub x: Vec<f64>,
    /// f there.
    pub objective: f64,
    /// ∇f there.
    pub gradient: Vec<f64>,
    /// Iterations taken.
    pub iterations: usize,
    /// Objective evaluations (each with its gradient).
    pub evaluations: usize,
    /// Why it stopped.
    pub stop: Stop,
    /// Every accepted iterate, the start first.
    pub history: Vec<Iterate>,
}

/// x − P(x − g), the projected gradient, in the max norm.
pub(super) fn projected_gradient_norm(x: &[f64], g: &[f64], lower: &[f64], upper: &[f64]) -> f64 {
    (0..x.len())
        .map(|i| (x[i] - (x[i] - g[i]).clamp(lower[i], upper[i])).abs())
        .fold(0.0, f64::max)
}

/// `x` projected on the box.
pub(super) fn project(x: &mut [f64], lower: &[f64], upper: &[f64]) {
    for i in 0..x.len() {
        x[i] = x[i].clamp(lower[i], upper[i]);
    }
}

/// The first entry of the history: the start x with f and ∇f there.
pub(super) fn start(f: f64, x: &[f64], g: &[f64], lower: &[f64], upper: &[f64]) -> Iterate {
    Iterate {
        iteration: 0,
        objective: f,
        projected_gradient: projected_gradient_norm(x, g, lower, upper),
        step: 0.0,
        evaluations: 1,
        evaluation: 1,
    }
}

/// The rules checked before each iteration: the gradient rule, then the caps.
pub(super) fn stop_before_iteration(
    (x, g): (&[f64], &[f64]),
    (lower, upper): (&[f64], &[f64]),
    (iterations, evaluations): (usize, usize),
    settings: &LbfgsbSettings,
) -> Option<Stop> {
    if projected_gradient_norm(x, g, lower, upper) <= settings.gtol {
        Some(Stop::Gradient)
    } else if iterations >= settings.max_iterations {
        Some(Stop::Iterations)
    } else if evaluations >= settings.max_evaluations {
        Some(Stop::Evaluations)
    } else {
        None
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Minimises f subject to `lower` ≤ x ≤ `upper` from `x0` (projected into the box; module
/// docs). `fg(x, g)` returns f(x) and writes ∇f into g; its error at the start is returned, at
/// a trial point it shrinks the step.
pub fn minimize<E>(
    mut fg: impl FnMut(&[f64], &mut [f64]) -> Result<f64, E>,
    x0: &[f64],
    lower: &[f64],
    upper: &[f64],
    settings: &LbfgsbSettings,
) -> Result<Minimum, E> {
    let n = x0.len();
    let project = |x: &mut [f64]| project(x, lower, upper);
    let mut x = x0.to_vec();
    project(&mut x);
    let mut g = vec![0.0; n];
    let mut f = fg(&x, &mut g)?;
    let mut evaluations = 1;
    let mut history = vec![start(f, &x, &g, lower, upper)];
    let mut pairs: VecDeque<(Vec<f64>, Vec<f64>)> = VecDeque::new();
    let (mut xt, mut gt) = (vec![0.0; n], vec![0.0; n]);
    let mut iterations = 0;
    let stop = loop {
        let counts = (iterations, evaluations);
        if let Some(stop) = stop_before_iteration((&x, &g), (lower, upper), counts, settings) {
            break stop;
        }
        let free: Vec<bool> = (0..n)
            .map(|i| !((x[i] <= lower[i] && g[i] > 0.0) || (x[i] >= upper[i] && g[i] < 0.0)))
            .collect();
        let mut accepted = None;
        // with memory, the quasi-Newton direction; if its line search fails, steepest descent
        for quasi_newton in [true, false] {
            if quasi_newton && pairs.is_empty() {
                continue;
            }
            let mut d = if quasi_newton {
                two_loop(&g, &free, &pairs)
            } else {
                (0..n).map(|i| if free[i] { -g[i] } else { 0.0 }).collect()
            };
            if dot(&g, &d) >= 0.0 {
                if !quasi_newton {
                    break;
                }
                d = (0..n).map(|i| if free[i] { -g[i] } else { 0.0 }).collect();
            }
            let first = if pairs.is_empty() {
                // scipy's first step: a unit step in x
                (1.0 / dot(&d, &d).sqrt()).min(1.0)
            } else {
                1.0
            };
            let mut search = Search {
                fg: &mut fg,
                x: &x,
                d: &d,
                lower,
                upper,
                evaluations: &mut evaluations,
                max_evaluations: settings.max_evaluations,
            };
            if let Some(found) = search.wolfe(f, &g, first, &mut xt, &mut gt) {
                accepted = Some(found);
                break;
            }
            pairs.clear();
        }
        let Some((ft, evaluation)) = accepted else {
            break if evaluations >= settings.max_evaluations {
                Stop::Evaluations
            } else {
                Stop::LineSearch
            };
        };
        iterations += 1;
        let s: Vec<f64> = (0..n).map(|i| xt[i] - x[i]).collect();
        let y: Vec<f64> = (0..n).map(|i| gt[i] - g[i]).collect();
        let (sy, yy) = (dot(&s, &y), dot(&y, &y));
        if sy > f64::EPSILON * yy && settings.memory > 0 {
            if pairs.len() == settings.memory {
                pairs.pop_front();
            }
            pairs.push_back((s.clone(), y));
        }
        let decreased = f - ft;
        let scale = f.abs().max(ft.abs()).max(1.0);
        std::mem::swap(&mut x, &mut xt);
        std::mem::swap(&mut g, &mut gt);
        f = ft;
        history.push(Iterate {
            iteration: iterations,
            objective: f,
            projected_gradient: projected_gradient_norm(&x, &g, lower, upper),
            step: s.iter().fold(0.0, |m, v| m.max(v.abs())),
            evaluations,
            evaluation,
        });
        if decreased <= settings.ftol * scale {
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

/// One line search along the projected path x(α) = P(x + α d) (module docs, step 4).
struct Search<'a, F> {
    fg: &'a mut F,
    x: &'a [f64],
    d: &'a [f64],
    lower: &'a [f64],
    upper: &'a [f64],
    evaluations: &'a mut usize,
    max_evaluations: usize,
}

/// A point of the line search: α, φ(α) = f(x(α)), φ′(α) and the iterate and gradient there.
struct Trial {
    /// The evaluation it was (counted from 1).
    evaluation: usize,
    alpha: f64,
    phi: f64,
    slope: f64,
    x: Vec<f64>,
    g: Vec<f64>,
}

impl<F, E> Search<'_, F>
where
    F: FnMut(&[f64], &mut [f64]) -> Result<f64, E>,
{
    /// φ at α: the projected point, f there (∞ where f fails) and φ′(α) = ∇f · d over the
    /// variables not stopped by a bound at α. `None` past the evaluation budget.
    fn trial(&mut self, alpha: f64) -> Option<Trial> {
        if *self.evaluations >= self.max_evaluations {
            return None;
        }
        *self.evaluations += 1;
        let n = self.x.len();
        let mut x = vec![0.0; n];
        let mut moving = vec![true; n];
        for i in 0..n {
            let free = self.x[i] + alpha * self.d[i];
            x[i] = free.clamp(self.lower[i], self.upper[i]);
            moving[i] = x[i] == free;
        }
        let mut g = vec![0.0; n];
        let phi = (self.fg)(&x, &mut g).unwrap_or(f64::INFINITY);
        let phi = if phi.is_nan() { f64::INFINITY } else { phi };
        let slope = (0..n)
            .filter(|&i| moving[i])
            .map(|i| g[i] * self.d[i])
            .sum();
        Some(Trial {
            evaluation: *self.evaluations,
            alpha,
            phi,
            slope,
            x,
            g,
        })
    }

    /// A step meeting the strong Wolfe conditions φ(α) ≤ φ(0) + c₁ α φ′(0) and
    /// |φ′(α)| ≤ c₂ |φ′(0)| (Nocedal and Wright, algorithms 3.5 and 3.6: bracketing, then
    /// zooming by safeguarded cubic interpolation), from α = `first`; else the best step
    /// that meets the first condition; `None` if none does. The accepted point and its
    /// gradient are written into `xt`, `gt`; f there and the evaluation it was are returned.
    fn wolfe(
        &mut self,
        f0: f64,
        g0: &[f64],
        first: f64,
        xt: &mut Vec<f64>,
        gt: &mut Vec<f64>,
    ) -> Option<(f64, usize)> {
        let slope0 = dot(g0, self.d);
        let armijo = |t: &Trial| t.phi <= f0 + ARMIJO * t.alpha * slope0;
        let curvature = |t: &Trial| t.slope.abs() <= -CURVATURE * slope0;
        let mut previous = Trial {
            evaluation: 0,
            alpha: 0.0,
            phi: f0,
            slope: slope0,
            x: self.x.to_vec(),
            g: g0.to_vec(),
        };
        let mut best: Option<Trial> = None;
        let mut alpha = first;
        let mut found = None;
        for i in 0..MAX_BACKTRACKS {
            let Some(t) = self.trial(alpha) else { break };
            if t.x == previous.x && i > 0 {
                // the bounds stop every variable: the last point is as far as the path goes
                found = armijo(&previous).then_some(previous);
                break;
            }
            if !armijo(&t) || (i > 0 && t.phi >= previous.phi) {
                found = self.zoom(previous, t, f0, slope0, &mut best);
                break;
            }
            if curvature(&t) {
                found = Some(t);
                break;
            }
            if t.slope >= 0.0 {
                found = self.zoom(t, previous, f0, slope0, &mut best);
                break;
            }
            alpha *= 2.0;
            best = Some(t.clone_point());
            previous = t;
        }
        let t = found.or(best).filter(|t| t.alpha > 0.0 && armijo(t))?;
        *xt = t.x;
        *gt = t.g;
        Some((t.phi, t.evaluation))
    }

    /// The zoom phase between `lo` (meets the first condition, the lower φ) and `hi`.
    fn zoom(
        &mut self,
        mut lo: Trial,
        mut hi: Trial,
        f0: f64,
        slope0: f64,
        best: &mut Option<Trial>,
    ) -> Option<Trial> {
        for _ in 0..MAX_BACKTRACKS {
            let (a, b) = (lo.alpha.min(hi.alpha), lo.alpha.max(hi.alpha));
            let width = b - a;
            if width <= f64::EPSILON * b {
                break;
            }
            let alpha = interpolate(&lo, &hi).clamp(a + 0.1 * width, b - 0.1 * width);
            let t = self.trial(alpha)?;
            if t.phi > f0 + ARMIJO * t.alpha * slope0 || t.phi >= lo.phi {
                hi = t;
            } else {
                if t.slope.abs() <= -CURVATURE * slope0 {
                    return Some(t);
                }
                if t.slope * (hi.alpha - lo.alpha) >= 0.0 {
                    hi = lo;
                }
                lo = t;
            }
        }
        // no point of both conditions in the budget: the best of the first condition
        if lo.alpha > 0.0 {
            Some(lo)
        } else {
            best.take()
        }
    }
}

impl Trial {
    fn clone_point(&self) -> Trial {
        Trial {
            evaluation: self.evaluation,
            alpha: self.alpha,
            phi: self.phi,
            slope: self.slope,
            x: self.x.clone(),
            g: self.g.clone(),
        }
    }
}

/// The minimiser of the cubic through two points of φ with their slopes (the quadratic
/// through the first point's value and slope and the second's value where the cubic has
/// none, or the midpoint where φ is infinite there).
fn interpolate(a: &Trial, b: &Trial) -> f64 {
    if !b.phi.is_finite() || !a.phi.is_finite() {
        return 0.5 * (a.alpha + b.alpha);
    }
    let d1 = a.slope + b.slope - 3.0 * (a.phi - b.phi) / (a.alpha - b.alpha);
    let disc = d1 * d1 - a.slope * b.slope;
    if disc >= 0.0 {
        let d2 = (b.alpha - a.alpha).signum() * disc.sqrt();
        let alpha =
            b.alpha - (b.alpha - a.alpha) * (b.slope + d2 - d1) / (b.slope - a.slope + 2.0 * d2);
        if alpha.is_finite() {
            return alpha;
        }
    }
    let h = b.alpha - a.alpha;
    let curvature = b.phi - a.phi - a.slope * h;
    if curvature > 0.0 {
        a.alpha - a.slope * h * h / (2.0 * curvature)
    } else {
        0.5 * (a.alpha + b.alpha)
    }
}

/// −H g on the free variables by the two-loop recursion (module docs, step 3).
fn two_loop(g: &[f64], free: &[bool], pairs: &VecDeque<(Vec<f64>, Vec<f64>)>) -> Vec<f64> {
    let n = g.len();
    let mask = |v: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|i| if free[i] { v[i] } else { 0.0 })
            .collect::<Vec<f64>>()
    };
    let mut q = mask(g);
    let mut alphas = Vec::with_capacity(pairs.len());
    for (s, y) in pairs.iter().rev() {
        let (s, y) = (mask(s), mask(y));
        let sy = dot(&s, &y);
        if sy <= 0.0 {
            alphas.push(None);
            continue;
        }
        let a = dot(&s, &q) / sy;
        for i in 0..n {
            q[i] -= a * y[i];
        }
        alphas.push(Some((a, sy)));
    }
    let gamma = pairs.back().map_or(1.0, |(s, y)| {
        let (s, y) = (mask(s), mask(y));
        let (sy, yy) = (dot(&s, &y), dot(&y, &y));
        if sy > 0.0 && yy > 0.0 {
            sy / yy
        } else {
            1.0
        }
    });
    for v in q.iter_mut() {
        *v *= gamma;
    }
    for ((s, y), a) in pairs.iter().zip(alphas.iter().rev()) {
        let Some((a, sy)) = *a else { continue };
        let (s, y) = (mask(s), mask(y));
        let b = dot(&y, &q) / sy;
        for i in 0..n {
            q[i] += (a - b) * s[i];
        }
    }
    q.iter().map(|v| -v).collect()
}
