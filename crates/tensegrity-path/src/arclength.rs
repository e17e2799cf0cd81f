//! Pseudo-arclength continuation of R(x) = λ P (crate docs).
//!
//! In the scaled coordinates z = (q/u_ref, λ) — q the free coordinates' displacement from the
//! last point, u_ref = ‖K₀⁻¹ P‖ the linear response to the reference load, so that both parts
//! weigh alike — the path's unit tangent t solves K v = P, t ∝ (v/u_ref, 1), oriented so that
//! t · t_prev > 0 (the first one with dλ of the target's sign); this orientation carries the path through a limit
//! point, where t's λ part changes sign. The predictor is z + s t, the corrector Newton's
//! method on R(x) = λ P together with the hyperplane t · (z − z_pred) = 0 (bordered: K a = λP −
//! R, K b = P, δλ = −(c + t_q·a/u_ref)/(t_q·b/u_ref + t_λ), δq = a + δλ b). The step s grows
//! by half after an easy corrector (≤ 4 iterations) and halves after a failed one.
//!
//! **Events.** Between two points where the tangent's λ part changes sign lies a limit point:
//! the step from the earlier point is bisected on that sign until the bracket is 10⁻¹² of the
//! step, which puts λ within 10⁻¹⁰ relative of its extremum (λ is quadratic in s there); its
//! mode is the eigenvector of the tangent's softest eigenvalue. A change of the number of
//! negative eigenvalues without one is a bifurcation, bisected alike on that count. Strings
//! that go slack or take tension again are reported at the first point where they do, with
//! the load factor where the slack set changes (bisected alike on that set).
//!
//! **Branch switching** (`switch_branch`, dense tangents). At the first bifurcation the path
//! leaves along the critical mode φ (the eigenvector of the eigenvalue that crossed zero,
//! oriented by its largest component): the predictor is z + s (φ, 0), the corrector holds
//! the displacement along φ (its hyperplane) and finds λ. On the new branch the displacement
//! is scaled by [`BRANCH_SCALE`] of the structure's size (the linear response that scales
//! the path before it can be far smaller than the buckled motion).

use crate::dofs::Dofs;
use crate::error::{PathError, Result};
use crate::factor::Factored;
use crate::forces::{member_states, resisting_forces};
use crate::model::{ElasticModel, MemberKind};
use crate::newton::{self, residual, tolerance, Equilibrium};
use crate::point::{Event, PathPoint, PathReport, Reaction, Stop};
use crate::stability::{spectrum, Spectrum};
use nalgebra::{DVector, Vector3};

/// Settings of [`follow`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSettings {
    /// Stop when λ reaches this (the last point is then exactly at it).
    pub target: f64,
    /// Stop after this many points.
    pub max_steps: usize,
    /// The first arc-length step (scaled units: 1 is the linear response to P).
    pub initial_step: f64,
    /// The largest step.
    pub max_step: f64,
    /// The smallest step before the path stops.
    pub min_step: f64,
    /// At the first bifurcation (dense tangents only: its mode is needed), leave the path
    /// along the mode: the branch on the side of the mode's largest component.
    pub switch_branch: bool,
}

impl Default for PathSettings {
    /// λ up to 1, at most 500 points, steps from 0.05 (up to 0.25, down to 10⁻⁸).
    fn default() -> Self {
        Self {
            target: 1.0,
            max_steps: 500,
            initial_step: 0.05,
            max_step: 0.25,
            min_step: 1e-8,
            switch_branch: false,
        }
    }
}

impl PathSettings {
    fn check(&self) -> Result<()> {
        let bad = |name, value: f64, reason: &str| PathError::InvalidSetting {
            name,
            value,
            reason: reason.into(),
        };
        if !(self.target.is_finite() && self.target != 0.0) {
            return Err(bad("target", self.target, "must be finite and not zero"));
        }
        if !(self.initial_step > 0.0
            && self.max_step >= self.initial_step
            && self.min_step > 0.0
            && self.min_step < self.initial_step)
        {
            return Err(bad(
                "initial_step",
                self.initial_step,
                "need 0 < min_step < initial_step ≤ max_step",
            ));
        }
        if self.max_steps == 0 {
            return Err(bad("max_steps", 0.0, "must be at least 1"));
        }
        Ok(())
    }
}

/// An equilibrium with its tangent direction and spectrum.
#[derive(Debug, Clone)]
struct State {
    eq: Equilibrium,
    /// Unit tangent (q part scaled by 1/u_ref, then λ).
    t_q: DVector<f64>,
    t_lambda: f64,
    spectrum: Spectrum,
}

struct Tracer<'a> {
    model: &'a ElasticModel,
    dofs: Dofs,
    u_ref: f64,
    /// The sign of the target: the first step's direction in λ.
    direction: f64,
}

impl Tracer<'_> {
    /// The state at `eq` with its tangent oriented along `previous` (or with dλ of the sign
    /// of the target).
    fn state(&self, eq: Equilibrium, previous: Option<(&DVector<f64>, f64)>) -> Result<State> {
        let mut k = Factored::of(self.model, &self.dofs, &eq.states)
            .ok_or(PathError::Singular { lambda: eq.lambda })?;
        let spectrum = k.spectrum();
        let rate = newton::load_rate(self.model, &self.dofs, &eq.states);
        let (mut t_q, mut t_lambda) = match k.solve(&rate) {
            Some(v) => {
                let t_q = v / self.u_ref;
                let norm = (t_q.norm_squared() + 1.0).sqrt();
                (t_q / norm, 1.0 / norm)
            }
            // exactly at a limit point (a bisection can land there) the tangent is the
            // critical mode at a stationary λ
            None if spectrum.mode.len() == self.dofs.len() => (spectrum.mode.normalize(), 0.0),
            None => return Err(PathError::Singular { lambda: eq.lambda }),
        };
        let flip = match previous {
            Some((pq, pl)) => t_q.dot(pq) + t_lambda * pl < 0.0,
            None => t_lambda * self.direction < 0.0,
        };
        if flip {
            t_q = -t_q;
            t_lambda = -t_lambda;
        }
        Ok(State {
            eq,
            t_q,
            t_lambda,
            spectrum,
        })
    }

    /// The corrector from `from` along its tangent by the step `s`; its iteration count.
    fn step(&self, from: &State, s: f64) -> Result<(Equilibrium, usize)> {
        let n = self.model.nodes.len();
        let q_pred = &from.t_q * (s * self.u_ref);
        let lambda_pred = from.eq.lambda + s * from.t_lambda;
        let mut q = q_pred.clone();
        let mut lambda = lambda_pred;
        for iteration in 0..=newton::MAX_ITERATIONS {
            newton::check_rest_lengths(self.model, lambda)?;
            let driven = self.dofs.drive(&from.eq.x, lambda - from.eq.lambda);
            let x: Vec<Vector3<f64>> = self
                .dofs
                .expand(&q, n)
                .iter()
                .zip(&driven)
                .map(|(u, x0)| x0 + u)
                .collect();
            let states = member_states(self.model, &x, lambda);
            let g = residual(self.model, &self.dofs, &states, lambda);
            let c =
                from.t_q.dot(&(&q - &q_pred)) / self.u_ref + from.t_lambda * (lambda - lambda_pred);
            let tol = tolerance(self.model, &states, &x, lambda);
            if g.amax() <= tol && c.abs() <= 1e-12 * s.max(1e-300) {
                return Ok((
                    Equilibrium {
                        x,
                        lambda,
                        states,
                        residual: g.amax(),
                    },
                    iteration,
                ));
            }
            if iteration == newton::MAX_ITERATIONS || !g.amax().is_finite() {
                break;
            }
            let Some(mut lu) = Factored::of(self.model, &self.dofs, &states) else {
                return Err(PathError::Singular { lambda });
            };
            let rate = newton::load_rate(self.model, &self.dofs, &states);
            let (Some(a), Some(b)) = (lu.solve(&g), lu.solve(&rate)) else {
                return Err(PathError::Singular { lambda });
            };
            let denominator = from.t_q.dot(&b) / self.u_ref + from.t_lambda;
            let d_lambda = -(c + from.t_q.dot(&a) / self.u_ref) / denominator;
            if !d_lambda.is_finite() {
                return Err(PathError::Singular { lambda });
            }
            q += a + b * d_lambda;
            lambda += d_lambda;
        }
        Err(PathError::NotConverged {
            lambda,
            residual: f64::NAN,
            tolerance: 0.0,
            iterations: newton::MAX_ITERATIONS,
            hint: String::new(),
        })
    }

    /// Bisects the step from `from` on a change of `key` between `from` and the state at
    /// `s_hi`: the state nearest the change.
    fn bisect(&self, from: &State, s_hi: f64, key: impl Fn(&State) -> bool) -> Result<State> {
        let k0 = key(from);
        let (mut lo, mut hi) = (0.0, s_hi);
        let mut best = None;
        while hi - lo > 1e-12 * s_hi {
            let mid = 0.5 * (lo + hi);
            let (eq, _) = self.step(from, mid)?;
            let st = self.state(eq, Some((&from.t_q, from.t_lambda)))?;
            if key(&st) == k0 {
                lo = mid;
            } else {
                hi = mid;
            }
            best = Some(st);
        }
        match best {
            Some(b) => Ok(b),
            None => {
                let (eq, _) = self.step(from, s_hi)?;
                self.state(eq, Some((&from.t_q, from.t_lambda)))
            }
        }
    }

    fn point(&self, step: usize, st: &State) -> PathPoint {
        point_of(self.model, &self.dofs, step, &st.eq, Some(&st.spectrum))
    }

    fn mode(&self, st: &State) -> Vec<[f64; 3]> {
        if st.spectrum.mode.len() != self.dofs.len() {
            // not computed (a sparse tangent)
            return Vec::new();
        }
        let u = self.dofs.expand(&st.spectrum.mode, self.model.nodes.len());
        let largest = u
            .iter()
            .map(|v| v.amax())
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        u.iter().map(|v| (v / largest).into()).collect()
    }
}

/// The path point of `eq` (its spectrum computed unless given).
pub(crate) fn point_of(
    model: &ElasticModel,
    dofs: &Dofs,
    step: usize,
    eq: &Equilibrium,
    spectrum_given: Option<&Spectrum>,
) -> PathPoint {
    let computed;
    let spectrum = match spectrum_given {
        Some(s) => s,
        None => {
            computed = Factored::of(model, dofs, &eq.states).map_or_else(
                || spectrum(&nalgebra::DMatrix::zeros(0, 0)),
                |k| k.spectrum(),
            );
            &computed
        }
    };
    let displacements: Vec<[f64; 3]> =
        eq.x.iter()
            .zip(&model.nodes)
            .map(|(x, x0)| (x - x0).into())
            .collect();
    let max_displacement =
        eq.x.iter()
            .zip(&model.nodes)
            .map(|(x, x0)| (x - x0).norm())
            .fold(0.0, f64::max);
    let r = resisting_forces(model, &eq.states);
    let reactions = dofs
        .held
        .iter()
        .map(|(i, d)| Reaction {
            node: *i,
            direction: (*d).into(),
            force: d.dot(&(r[*i] - model.load[*i] * eq.lambda - model.dead_load(*i))),
        })
        .collect();
    PathPoint {
        step,
        lambda: eq.lambda,
        nodes: eq.x.iter().map(|x| (*x).into()).collect(),
        displacements,
        max_displacement,
        tensions: eq.states.iter().map(|s| s.tension).collect(),
        slack: slack(model, eq),
        reactions,
        smallest_eigenvalues: spectrum.smallest.clone(),
        stability: spectrum.stability,
        residual: eq.residual,
    }
}

/// The displacement per unit arc length on a switched branch, as a fraction of the
/// structure's size (module docs).
pub const BRANCH_SCALE: f64 = 0.01;

/// The slack strings of an equilibrium.
fn slack(model: &ElasticModel, eq: &Equilibrium) -> Vec<usize> {
    model
        .members
        .iter()
        .zip(&eq.states)
        .enumerate()
        .filter(|(_, (m, s))| m.kind == MemberKind::String && s.slack)
        .map(|(k, _)| k)
        .collect()
}

/// Follows the load path of `model` from its reference state (first brought to equilibrium
/// at λ = 0) until λ reaches `settings.target`, past limit points (module docs). A path that
/// cannot go on (the step fell below its smallest) keeps its points and says why in `stop`.
///
/// ```
/// use nalgebra::Vector3;
/// use tensegrity_path::{follow, ElasticMember, ElasticModel, MemberKind, PathSettings, Support};
/// // a bar along x pulled along x: linear to within its stretch, λ up to 1
/// let bar = ElasticMember { nodes: [0, 1], kind: MemberKind::Bar, ea: 1e4, rest_length: 1.0 };
/// let m = ElasticModel { nodes: vec![Vector3::zeros(), Vector3::x()], members: vec![bar],
///     supports: vec![Support::pinned(0), Support { node: 1, directions: vec![Vector3::y(), Vector3::z()] }],
///     load: vec![Vector3::zeros(), Vector3::new(100.0, 0.0, 0.0)], drivers: Default::default() };
/// let path = follow(&m, &PathSettings::default()).unwrap();
/// let last = path.points.last().unwrap();
/// assert_eq!(last.lambda, 1.0);
/// assert!((last.displacements[1][0] - 0.01).abs() < 1e-12);
/// ```
pub fn follow(model: &ElasticModel, settings: &PathSettings) -> Result<PathReport> {
    settings.check()?;
    let model = &model.clone().validated()?;
    // driven rest lengths are linear in λ: positive at both ends, positive between
    newton::check_rest_lengths(model, settings.target)?;
    let dofs = Dofs::of(model)?;
    let start = newton::solve(model, &dofs, &model.nodes, 0.0, 0.0)?;
    let p = newton::load_rate(model, &dofs, &start.states);
    if p.amax() == 0.0 {
        return Err(PathError::model("load", "the reference load is zero on every free direction and nothing else is driven: give [[loads]] on nodes that can move"));
    }
    let v0 = Factored::of(model, &dofs, &start.states)
        .and_then(|mut k| k.solve(&p))
        .ok_or(PathError::Singular { lambda: 0.0 })?;
    let mut tracer = Tracer {
        model,
        dofs,
        u_ref: v0.norm().max(f64::MIN_POSITIVE),
        direction: settings.target.signum(),
    };
    let mut current = tracer.state(start, None)?;
    let mut points = vec![tracer.point(0, &current)];
    let mut events = Vec::new();
    let mut s = settings.initial_step;
    let target = settings.target;
    let mut switched = false;
    while points.len() <= settings.max_steps {
        let (eq, iterations) = match tracer.step(&current, s) {
            Ok(r) => r,
            Err(e) => {
                s *= 0.5;
                if s < settings.min_step {
                    let message = PathError::StepTooSmall {
                        lambda: current.eq.lambda,
                        min_step: settings.min_step,
                        points: points.len(),
                    }
                    .to_string();
                    return Ok(PathReport {
                        points,
                        events,
                        stop: Stop::StepTooSmall {
                            message: format!("{message} (last: {e})"),
                        },
                    });
                }
                continue;
            }
        };
        let next = tracer.state(eq, Some((&current.t_q, current.t_lambda)))?;
        let step = points.len();
        if next.t_lambda.signum() != current.t_lambda.signum() {
            let fold = tracer.bisect(&current, s, |st| st.t_lambda > 0.0)?;
            events.push(Event::LimitPoint {
                lambda: fold.eq.lambda,
                after_step: step - 1,
                max_displacement: tracer.point(step, &fold).max_displacement,
                mode: tracer.mode(&fold),
            });
        } else if next.spectrum.negative != current.spectrum.negative {
            // located where the eigenvalue crosses zero itself (the trigger above has a
            // tolerance against round-off)
            let n0 = current.spectrum.below_zero;
            let branch = tracer.bisect(&current, s, move |st| st.spectrum.below_zero == n0)?;
            let switch = settings.switch_branch
                && !switched
                && branch.spectrum.mode.len() == tracer.dofs.len();
            events.push(Event::Bifurcation {
                lambda: branch.eq.lambda,
                after_step: step - 1,
                mode: tracer.mode(&branch),
                switched: switch,
            });
            if switch {
                // on to the other branch: the bifurcation point, then a tangent along the
                // mode (λ held in the predictor), the orientation of its largest component
                switched = true;
                let mut along = branch.clone();
                let phi = &branch.spectrum.mode;
                let largest = phi
                    .iter()
                    .fold(0.0f64, |m, &v| if v.abs() > m.abs() { v } else { m });
                along.t_q = phi.normalize() * largest.signum();
                along.t_lambda = 0.0;
                points.push(tracer.point(step, &branch));
                // the new branch moves along the mode at a nearly constant λ: its steps are
                // measured on the structure's size, not on the (possibly tiny) linear
                // response to the load that scales the path before it
                tracer.u_ref = tracer
                    .u_ref
                    .max(BRANCH_SCALE * crate::model::extent(&model.nodes));
                current = along;
                s = settings.initial_step;
                continue;
            }
        }
        let (before, after) = (slack(model, &current.eq), slack(model, &next.eq));
        let went: Vec<usize> = after
            .iter()
            .filter(|k| !before.contains(k))
            .copied()
            .collect();
        let back: Vec<usize> = before
            .iter()
            .filter(|k| !after.contains(k))
            .copied()
            .collect();
        if !went.is_empty() || !back.is_empty() {
            let set0 = before.clone();
            let change = tracer.bisect(&current, s, move |st| slack(model, &st.eq) == set0)?;
            let lambda = change.eq.lambda;
            if !went.is_empty() {
                events.push(Event::Slackened {
                    members: went,
                    lambda,
                    at_step: step,
                });
            }
            if !back.is_empty() {
                events.push(Event::Retensioned {
                    members: back,
                    lambda,
                    at_step: step,
                });
            }
        }
        let crossed = (next.eq.lambda - target) * (current.eq.lambda - target) <= 0.0
            && next.eq.lambda != current.eq.lambda;
        if crossed {
            // the last point exactly at the target: Newton at λ = target from the point
            // interpolated between the two
            let w = (target - current.eq.lambda) / (next.eq.lambda - current.eq.lambda);
            let guess: Vec<Vector3<f64>> = current
                .eq
                .x
                .iter()
                .zip(&next.eq.x)
                .map(|(a, b)| a + (b - a) * w)
                .collect();
            let at = newton::solve(model, &tracer.dofs, &guess, target, target)?;
            let last = tracer.state(at, Some((&next.t_q, next.t_lambda)))?;
            points.push(tracer.point(step, &last));
            return Ok(PathReport {
                points,
                events,
                stop: Stop::ReachedTarget,
            });
        }
        points.push(tracer.point(step, &next));
        current = next;
        s = if iterations <= 4 {
            (s * 1.5).min(settings.max_step)
        } else {
            s
        };
    }
    Ok(PathReport {
        points,
        events,
        stop: Stop::MaxSteps,
    })
}
