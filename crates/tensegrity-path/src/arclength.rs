//! Pseudo-arclength continuation of R(x) = λ P (crate docs).
//!
//! In the scaled coordinates z = (q/u_ref, λ) — q the free coordinates' displacement from the
//! last point, u_ref = ‖K₀⁻¹ P‖ the linear response to the reference load, so that both parts
//! weigh alike — the path's unit tangent t solves K v = P, t ∝ (v/u_ref, 1), oriented so that
//! t · t_prev > 0 (the first one with dλ of the target's sign); this orientation carries the path through a limit
//! point, where t's λ part changes sign. The predictor is z + s t, the corrector Newton's
//! method on R(x) = λ P together with the hyperplane t · (z − z_pred) = 0 (bordered: K a = λP −
//! R, K b = P, δλ = −(c + t_q·a/u_ref)/(t_q·b/u_ref + t_λ), δq = a + δλ b). The step s grows
//! by half after an easy corrector (≤ 4 iterations) and halves after a failed one — no
//! equilibrium in [`newton::MAX_ITERATIONS`], a residual or an update that is not finite, a
//! singular tangent, anywhere in the step (its events and its landing included). Below
//! `min_step` the path stops with the points so far and says why, and at which load factor,
//! in [`Stop::StepTooSmall`]; it never returns NaN.
//!
//! **A step must not jump.** A corrector that lands farther than [`MAX_CORRECTION`] step
//! lengths off its predictor (the chord more than about 27° off the tangent) fails the step
//! too: it left the path for another branch. Where one part of a structure folds while the
//! rest, which dominates the scaled coordinates, hardly notices (a low two-bar truss in a
//! row of higher ones), a long step's corrector converged past both of its folds — its apex
//! snapped through, λ rising again, no negative eigenvalue at either end — so that neither
//! the sign of dλ/ds nor the count of negative eigenvalues, compared between the two points,
//! saw a fold; the step halves until the path follows the snap.
//!
//! **Slack strings.** A step holds the slack set of the point it starts from: the corrector
//! solves the smooth equations in which the strings taut there stay taut (a tension may turn
//! negative) and the slack ones stay slack (a length may pass the rest length). Where, at the
//! end of the step, a string's margin — a taut one's tension, a slack one's tension as if taut
//! with its sign turned — is negative, the step stops where the first of them reaches zero
//! (regula falsi on the smallest margin along the step, to 10⁻³ of the residual tolerance:
//! λ to about 10⁻¹² relative), every string within the residual tolerance of zero changes its
//! state there (a symmetric structure's strings together), and the rest of the step goes on
//! from there with the new set. So a set never changes where the path has no such
//! equilibrium: a corrector of the free problem, whose set changes with its iterates, can
//! converge across the change to another branch nearby (a long step past the slack of a
//! prism's verticals lands on non-symmetric equilibria with one vertical slack). The
//! tangent jumps where the set changes: λ turning back there is a limit point, a change of
//! the number of negative eigenvalues a bifurcation, both at that load factor.
//!
//! **Events.** Between two points where the tangent's λ part changes sign lies a limit point:
//! the step from the earlier point is bisected on that sign until the bracket is 10⁻¹² of the
//! step, which puts λ within 10⁻¹⁰ relative of its extremum (λ is quadratic in s there); its
//! mode is the eigenvector of the tangent's softest eigenvalue. A change of the number of
//! negative eigenvalues without one is a bifurcation, bisected alike on that count. Strings
//! that go slack or take tension again are reported with the load factor where their set
//! changes, at the first point where they are in it.
//!
//! **The target.** The step that crosses λ = target (before any limit point or bifurcation on
//! it) lands on it on the path: regula falsi on λ(s) − target along the step, then Newton at
//! λ = target from there, both with the step's slack set held — not Newton from a point
//! between two points, which past an instability can converge to another branch.
//!
//! **Branch switching** (`switch_branch`, dense and sparse tangents: a sparse one's mode comes
//! from shift-invert iteration, [`crate::factor`]; where that finds none the bifurcation is
//! reported with `switched: false` and the path goes on). At the first bifurcation the path
//! leaves along the critical mode φ (the eigenvector of the eigenvalue that crossed zero,
//! oriented by its largest component): the predictor is z + s (φ, 0), the corrector holds
//! the displacement along φ (its hyperplane) and finds λ. On the new branch the displacement
//! is scaled by [`BRANCH_SCALE`] of the structure's size (the linear response that scales
//! the path before it can be far smaller than the buckled motion).

use crate::dofs::Dofs;
use crate::error::{PathError, Result};
use crate::factor::Factored;
use crate::forces::{member_states, resisting_forces, MemberState};
use crate::model::{ElasticModel, MemberKind};
use crate::newton::{self, largest_residual, residual, tolerance, Equilibrium};
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
    /// At the first bifurcation, leave the path along its mode (dense or sparse tangent; not
    /// where the mode could not be computed): the branch on the side of the mode's largest
    /// component.
    pub switch_branch: bool,
    /// Stop, keeping the points so far, once this much wall time (s) has passed
    /// ([`Stop::WorkLimit`]): how a front end keeps a path whose number of points is not
    /// known in advance within its work limit. `None`: no limit.
    pub max_seconds: Option<f64>,
}

impl Default for PathSettings {
    /// λ up to 1, at most 500 points, steps from 0.05 (up to 0.25, down to 10⁻⁸), no time
    /// limit.
    fn default() -> Self {
        Self {
            target: 1.0,
            max_steps: 500,
            initial_step: 0.05,
            max_step: 0.25,
            min_step: 1e-8,
            switch_branch: false,
            max_seconds: None,
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
        if let Some(t) = self.max_seconds.filter(|t| !(t.is_finite() && *t > 0.0)) {
            return Err(bad("max_seconds", t, "must be finite and positive"));
        }
        Ok(())
    }
}

/// An equilibrium with its tangent direction and spectrum. Its member states also fix the
/// slack set that a corrector from it holds ([`held_states`]).
#[derive(Debug, Clone)]
struct State {
    eq: Equilibrium,
    /// Unit tangent (q part scaled by 1/u_ref, then λ).
    t_q: DVector<f64>,
    t_lambda: f64,
    spectrum: Spectrum,
}

/// A corrector's equilibrium, its displacement q from the state it started from (reduced
/// coordinates) and the iterations it took.
#[derive(Debug, Clone)]
struct Trial {
    eq: Equilibrium,
    q: DVector<f64>,
    iterations: usize,
}

/// Why a step failed (the path then shortens it): the text of the error.
#[derive(Debug)]
struct Failed(String);

impl From<PathError> for Failed {
    fn from(e: PathError) -> Self {
        Self(e.to_string())
    }
}

/// How a step ended.
enum End {
    /// At the next point.
    Next(State),
    /// Exactly at the target.
    Landed(State),
    /// At a bifurcation, leaving along its mode (`switch_branch`): the point there and the
    /// state with the tangent along the mode.
    Switched { branch: State, along: State },
}

/// A step: its events, how it ended, the most corrector iterations it took.
struct Advance {
    events: Vec<Event>,
    end: End,
    iterations: usize,
}

/// The farthest a step's corrector may land from its predictor, per unit of the step (the
/// tangent of the angle between the tangent and the chord: 0.5, about 27°, a cosine of 0.89):
/// farther, the step is tried again at half its length (module docs).
pub const MAX_CORRECTION: f64 = 0.5;

/// How many times the slack set may change within one step before the step counts as failed
/// (a string that flips between slack and taut and back without the path moving).
pub const MAX_SET_CHANGES: usize = 16;

/// The states of the members at `x` and `lambda` with the slack set of `like` held: a string
/// taut there stays taut (its tension may turn negative), a slack one stays slack (whatever
/// its length) — the smooth equilibrium equations of one slack set, which the corrector
/// solves (module docs).
fn held_states(
    model: &ElasticModel,
    x: &[Vector3<f64>],
    lambda: f64,
    like: &[MemberState],
) -> Vec<MemberState> {
    let mut states = member_states(model, x, lambda);
    for ((m, s), held) in model.members.iter().zip(&mut states).zip(like) {
        if m.kind != MemberKind::String || s.slack == held.slack {
            continue;
        }
        s.slack = held.slack;
        s.tension = if held.slack {
            0.0
        } else {
            m.ea * (s.length - s.rest_length) / s.rest_length
        };
    }
    // a cluster's segments follow its first segment's entry in `like`
    for (c, cluster) in model.clusters.iter().enumerate() {
        let range = model.cluster_states(c);
        let held = like[range.start].slack;
        if states[range.start].slack == held {
            continue;
        }
        let length = crate::clusters::cluster_length(model, c, &states);
        let tension = if held {
            0.0
        } else {
            let rest = model.cluster_rest_length(c, lambda);
            cluster.stiffness_at(rest) * (length - rest)
        };
        for s in &mut states[range] {
            s.slack = held;
            s.tension = tension;
        }
    }
    states
}

/// A string's margin to a change of its state (N): a taut string's tension, a slack one's
/// tension as if taut with the sign turned (positive while it is shorter than its rest
/// length); a bar never changes (infinite). A cluster's margin is its first segment's
/// entry (its tension, or −k (L − L₀) when slack); its other segments' are infinite.
fn margin(model: &ElasticModel, k: usize, states: &[MemberState]) -> f64 {
    let s = &states[k];
    if let Some(m) = model.members.get(k) {
        return if m.kind != MemberKind::String {
            f64::INFINITY
        } else if s.slack {
            -m.ea * (s.length - s.rest_length) / s.rest_length
        } else {
            s.tension
        };
    }
    let Some(c) = model.reported_index(k).map(|r| r - model.members.len()) else {
        return f64::INFINITY;
    };
    if s.slack {
        // the segment's state carries the cluster's rest length at the state's load factor
        let length = crate::clusters::cluster_length(model, c, states);
        -model.clusters[c].stiffness_at(s.rest_length) * (length - s.rest_length)
    } else {
        s.tension
    }
}

/// The strings whose margin at `states` is negative (a taut one compressed, a slack one
/// stretched).
fn negative_margins(model: &ElasticModel, states: &[MemberState]) -> Vec<usize> {
    (0..states.len())
        .filter(|&k| margin(model, k, states) < 0.0)
        .collect()
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
        if !(t_q.iter().all(|v| v.is_finite()) && t_lambda.is_finite()) {
            return Err(PathError::Singular { lambda: eq.lambda });
        }
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

    /// The corrector from `from` along its tangent by the step `s`.
    fn step(&self, from: &State, s: f64) -> Result<Trial> {
        let q_pred = &from.t_q * (s * self.u_ref);
        let lambda_pred = from.eq.lambda + s * from.t_lambda;
        self.correct(
            from,
            q_pred.clone(),
            lambda_pred,
            Some((&q_pred, lambda_pred, s)),
        )
    }

    /// The distance of a corrector's equilibrium `trial` from its predictor (the step `s`
    /// from `from`) in the scaled coordinates, per unit of the step: the tangent of the angle
    /// between `from`'s tangent and the chord to `trial` (the corrector moves normal to it).
    fn off_predictor(&self, from: &State, s: f64, trial: &Trial) -> f64 {
        let dq = (&trial.q - &from.t_q * (s * self.u_ref)) / self.u_ref;
        let dl = trial.eq.lambda - (from.eq.lambda + s * from.t_lambda);
        (dq.norm_squared() + dl * dl).sqrt() / s
    }

    /// Newton's method from the displacement `q` (from `from`'s position) at `lambda`, with
    /// the slack set of `from` held ([`held_states`]): with `arc` = (q_pred, λ_pred, s) on
    /// the hyperplane normal to `from`'s tangent through the predictor (λ free), else at the
    /// fixed `lambda`. A residual or an update that is not finite fails it.
    fn correct(
        &self,
        from: &State,
        mut q: DVector<f64>,
        mut lambda: f64,
        arc: Option<(&DVector<f64>, f64, f64)>,
    ) -> Result<Trial> {
        let n = self.model.nodes.len();
        let mut worst = f64::INFINITY;
        let mut tol = 0.0;
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
            let states = held_states(self.model, &x, lambda, &from.eq.states);
            let g = residual(self.model, &self.dofs, &x, &states, lambda);
            worst = largest_residual(&g);
            if !(worst.is_finite() && x.iter().all(|v| v.iter().all(|a| a.is_finite()))) {
                return Err(PathError::NotConverged {
                    lambda,
                    residual: f64::INFINITY,
                    tolerance: tol,
                    iterations: iteration,
                    hint: "; the corrector left double precision (the step was too long)".into(),
                });
            }
            tol = tolerance(self.model, &states, &x, lambda);
            let (c, on_plane) = match arc {
                Some((q_pred, lambda_pred, s)) => {
                    let c = from.t_q.dot(&(&q - q_pred)) / self.u_ref
                        + from.t_lambda * (lambda - lambda_pred);
                    (c, c.abs() <= 1e-12 * s.max(1e-300))
                }
                None => (0.0, true),
            };
            if worst <= tol && on_plane {
                return Ok(Trial {
                    eq: Equilibrium {
                        x,
                        lambda,
                        states,
                        residual: worst,
                    },
                    q,
                    iterations: iteration,
                });
            }
            if iteration == newton::MAX_ITERATIONS {
                break;
            }
            let Some(mut lu) = Factored::of(self.model, &self.dofs, &states) else {
                return Err(PathError::Singular { lambda });
            };
            let Some(a) = lu.solve(&g) else {
                return Err(PathError::Singular { lambda });
            };
            if arc.is_none() {
                q += a;
                continue;
            }
            let rate = newton::load_rate(self.model, &self.dofs, &states);
            let Some(b) = lu.solve(&rate) else {
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
            residual: worst,
            tolerance: tol,
            iterations: newton::MAX_ITERATIONS,
            hint: String::new(),
        })
    }

    /// Bisects the step from `from` on a change of `key` between `from` and the state at
    /// `s_hi`: the state nearest the change, with its step and its corrector's result.
    fn bisect(
        &self,
        from: &State,
        s_hi: f64,
        key: impl Fn(&State) -> bool,
    ) -> Result<(f64, Trial, State)> {
        let k0 = key(from);
        let (mut lo, mut hi) = (0.0, s_hi);
        let mut best = None;
        while hi - lo > 1e-12 * s_hi {
            let mid = 0.5 * (lo + hi);
            let trial = self.step(from, mid)?;
            let st = self.state(trial.eq.clone(), Some((&from.t_q, from.t_lambda)))?;
            if key(&st) == k0 {
                lo = mid;
            } else {
                hi = mid;
            }
            best = Some((mid, trial, st));
        }
        match best {
            Some(b) => Ok(b),
            None => {
                let trial = self.step(from, s_hi)?;
                let st = self.state(trial.eq.clone(), Some((&from.t_q, from.t_lambda)))?;
                Ok((s_hi, trial, st))
            }
        }
    }

    /// Where on the step from `from` (its slack set held) the first of the `strings`, whose
    /// margin is negative at `end` (the step `s_hi`), reaches zero: regula falsi (Illinois)
    /// on their smallest margin, to 10⁻³ of the residual tolerance or 10⁻¹³ of the step;
    /// the step there and its equilibrium, on the side where the margin is not positive.
    fn locate_change(
        &self,
        from: &State,
        s_hi: f64,
        end: Trial,
        strings: &[usize],
    ) -> Result<(f64, Trial)> {
        let model = self.model;
        let g = |eq: &Equilibrium| {
            strings
                .iter()
                .map(|&k| margin(model, k, &eq.states))
                .fold(f64::INFINITY, f64::min)
        };
        let f0 = g(&from.eq);
        if f0 <= 0.0 {
            let at = Trial {
                eq: from.eq.clone(),
                q: DVector::zeros(self.dofs.len()),
                iterations: 0,
            };
            return Ok((0.0, at));
        }
        let (mut lo, mut f_lo) = (0.0, f0);
        let (mut hi, mut f_hi) = (s_hi, g(&end.eq));
        let mut at_hi = end;
        // which end moved last (Illinois: the other one's value is halved when it stays twice)
        let mut moved_hi = None;
        for _ in 0..200 {
            let tol = tolerance(model, &at_hi.eq.states, &at_hi.eq.x, at_hi.eq.lambda);
            if hi - lo <= 1e-13 * s_hi || -f_hi <= 1e-3 * tol {
                break;
            }
            let mut s = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
            if !(s > lo && s < hi) {
                s = 0.5 * (lo + hi);
            }
            let trial = self.step(from, s)?;
            let f = g(&trial.eq);
            if f <= 0.0 {
                (hi, f_hi, at_hi) = (s, f, trial);
                if moved_hi == Some(true) {
                    f_lo *= 0.5;
                }
                moved_hi = Some(true);
            } else {
                (lo, f_lo) = (s, f);
                if moved_hi == Some(false) {
                    f_hi *= 0.5;
                }
                moved_hi = Some(false);
            }
        }
        Ok((hi, at_hi))
    }

    /// The state exactly at λ = `target` on the step from `from` (its slack set held) that
    /// ends at `end` (the step `s_end`) on the other side of it: regula falsi (Illinois) on
    /// λ(s) − target to 10⁻¹⁰ of |target|, then Newton at λ = target from there.
    fn land(&self, from: &State, s_end: f64, end: &Trial, target: f64) -> Result<State> {
        let near = 1e-10 * target.abs();
        let (mut lo, mut f_lo) = (0.0, from.eq.lambda - target);
        let (mut hi, mut f_hi) = (s_end, end.eq.lambda - target);
        let mut best = end.clone();
        let mut moved_hi = None;
        for _ in 0..200 {
            if (best.eq.lambda - target).abs() <= near || hi - lo <= 1e-13 * s_end {
                break;
            }
            let mut s = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
            if !(s > lo && s < hi) {
                s = 0.5 * (lo + hi);
            }
            let trial = self.step(from, s)?;
            let f = trial.eq.lambda - target;
            if f * f_hi > 0.0 {
                // on the side of `end`
                (hi, f_hi) = (s, f);
                if moved_hi == Some(true) {
                    f_lo *= 0.5;
                }
                moved_hi = Some(true);
            } else {
                (lo, f_lo) = (s, f);
                if moved_hi == Some(false) {
                    f_hi *= 0.5;
                }
                moved_hi = Some(false);
            }
            best = trial;
        }
        let at = self.correct(from, best.q.clone(), target, None)?;
        let mut eq = at.eq;
        // a string held taut that ended a round-off below zero force is slack there
        for (k, s) in eq.states.iter_mut().enumerate() {
            if self.model.is_tension_only(k) && !s.slack && s.tension < 0.0 {
                s.slack = true;
                s.tension = 0.0;
            }
        }
        self.state(eq, Some((&from.t_q, from.t_lambda)))
    }

    /// The first limit point or bifurcation on the step from `from` (its slack set held) to
    /// `end` (the step `s_end`), located by bisection: whether it is a limit point, its step,
    /// its corrector's result and its state.
    fn smooth_event(
        &self,
        from: &State,
        s_end: f64,
        end: &State,
    ) -> Result<Option<(bool, f64, Trial, State)>> {
        if end.t_lambda.signum() != from.t_lambda.signum() {
            let (s, trial, fold) = self.bisect(from, s_end, |st| st.t_lambda > 0.0)?;
            return Ok(Some((true, s, trial, fold)));
        }
        if end.spectrum.negative != from.spectrum.negative {
            // located where the eigenvalue crosses zero itself (the trigger above has a
            // tolerance against round-off)
            let n0 = from.spectrum.below_zero;
            let (s, trial, branch) =
                self.bisect(from, s_end, move |st| st.spectrum.below_zero == n0)?;
            return Ok(Some((false, s, trial, branch)));
        }
        Ok(None)
    }

    /// Reports the bifurcation at `branch` and, with `may_switch` and its mode known, the
    /// switch onto its branch.
    fn bifurcation(
        &self,
        branch: State,
        step: usize,
        may_switch: bool,
        events: &mut Vec<Event>,
    ) -> Option<End> {
        let switch = may_switch && branch.spectrum.mode.len() == self.dofs.len();
        events.push(Event::Bifurcation {
            lambda: branch.eq.lambda,
            after_step: step - 1,
            mode: self.mode(&branch),
            switched: switch,
        });
        if !switch {
            return None;
        }
        // on to the other branch: the bifurcation point, then a tangent along the mode (λ
        // held in the predictor), the orientation of its largest component
        let mut along = branch.clone();
        let phi = &branch.spectrum.mode;
        let largest = phi
            .iter()
            .fold(0.0f64, |m, &v| if v.abs() > m.abs() { v } else { m });
        along.t_q = phi.normalize() * largest.signum();
        along.t_lambda = 0.0;
        Some(End::Switched { branch, along })
    }

    /// One step of the path from `current` by the arc length `s` (module docs): the
    /// corrector with `current`'s slack set held; where a string's margin changes sign on the
    /// way, the step stops there (located by [`Self::locate_change`]), the set changes and
    /// the rest of the step goes on from there with the new set. Limit points and
    /// bifurcations on the way are located, and the step lands on `target` when it crosses
    /// it. `step` is the index its point gets.
    fn advance(
        &self,
        current: &State,
        s: f64,
        step: usize,
        target: f64,
        may_switch: bool,
    ) -> std::result::Result<Advance, Failed> {
        let model = self.model;
        let mut events = Vec::new();
        let mut from = current.clone();
        let mut left = s;
        let mut iterations = 0;
        for _ in 0..=MAX_SET_CHANGES {
            let trial = self.step(&from, left)?;
            iterations = iterations.max(trial.iterations);
            // a corrector that lands far off its predictor has left the path: it converged
            // on another branch (past a fold the step jumped over, whose tangents at both ends
            // look alike); the step is tried again shorter
            let off = self.off_predictor(&from, left, &trial);
            if off > MAX_CORRECTION {
                return Err(Failed(format!(
                    "the corrector landed {off:.2} step lengths off its predictor (load factor {:.6e} to {:.6e}): on another branch, past a fold or a bifurcation the step would skip",
                    from.eq.lambda, trial.eq.lambda
                )));
            }
            // the strings whose margin turned negative on the way
            let turned = negative_margins(model, &trial.eq.states);
            let changes = !turned.is_empty();
            let (s_end, end) = if changes {
                self.locate_change(&from, left, trial, &turned)?
            } else {
                (left, trial)
            };
            let end_state = self.state(end.eq.clone(), Some((&from.t_q, from.t_lambda)))?;
            // the target crossed before the first limit point or bifurcation: land there
            let crosses = |lambda: f64| {
                (lambda - target) * (from.eq.lambda - target) <= 0.0 && lambda != from.eq.lambda
            };
            let event = self.smooth_event(&from, s_end, &end_state)?;
            if let Some((_, s_at, at, _)) = &event {
                if crosses(at.eq.lambda) {
                    return Ok(Advance {
                        events,
                        end: End::Landed(self.land(&from, *s_at, at, target)?),
                        iterations,
                    });
                }
            }
            match event {
                Some((true, _, _, fold)) => events.push(Event::LimitPoint {
                    lambda: fold.eq.lambda,
                    after_step: step - 1,
                    max_displacement: self.point(step, &fold).max_displacement,
                    mode: self.mode(&fold),
                }),
                Some((false, _, _, branch)) => {
                    if let Some(switch) = self.bifurcation(branch, step, may_switch, &mut events) {
                        return Ok(Advance {
                            events,
                            end: switch,
                            iterations,
                        });
                    }
                }
                None => {}
            }
            if crosses(end.eq.lambda) {
                return Ok(Advance {
                    events,
                    end: End::Landed(self.land(&from, s_end, &end, target)?),
                    iterations,
                });
            }
            if !changes {
                return Ok(Advance {
                    events,
                    end: End::Next(end_state),
                    iterations,
                });
            }
            // the slack set changes here: every string that turned on the way and is within
            // the residual tolerance of zero force here changes with the first (the verticals
            // of a symmetric prism at once; a string that stays at zero force does not)
            let eq = &end_state.eq;
            let tol = tolerance(model, &eq.states, &eq.x, eq.lambda);
            let flips: Vec<usize> = turned
                .into_iter()
                .filter(|&k| margin(model, k, &eq.states) <= tol)
                .collect();
            let mut like = eq.states.clone();
            for &k in &flips {
                like[k].slack = !like[k].slack;
            }
            let states = held_states(model, &eq.x, eq.lambda, &like);
            let g = residual(model, &self.dofs, &eq.x, &states, eq.lambda);
            let changed = Equilibrium {
                x: eq.x.clone(),
                lambda: eq.lambda,
                residual: largest_residual(&g),
                states,
            };
            let next = self.state(changed, Some((&end_state.t_q, end_state.t_lambda)))?;
            let lambda = eq.lambda;
            let (went, back): (Vec<usize>, Vec<usize>) =
                flips.iter().partition(|&&k| next.eq.states[k].slack);
            let reported = |v: Vec<usize>| -> Vec<usize> {
                v.into_iter()
                    .filter_map(|k| model.reported_index(k))
                    .collect()
            };
            let (went, back) = (reported(went), reported(back));
            let mut changes = Vec::new();
            if !went.is_empty() {
                changes.push(Event::Slackened {
                    members: went,
                    lambda,
                    at_step: step,
                });
            }
            if !back.is_empty() {
                changes.push(Event::Retensioned {
                    members: back,
                    lambda,
                    at_step: step,
                });
            }
            // the tangent's jump there (reported before the set's change at the same λ): a
            // corner where λ turns back, or where the stiffness loses (or gains) a negative
            // eigenvalue
            let mut switch = None;
            if next.t_lambda.signum() != end_state.t_lambda.signum() {
                events.push(Event::LimitPoint {
                    lambda,
                    after_step: step - 1,
                    max_displacement: self.point(step, &next).max_displacement,
                    mode: self.mode(&next),
                });
            } else if next.spectrum.negative != end_state.spectrum.negative {
                switch = self.bifurcation(next.clone(), step, may_switch, &mut events);
            }
            events.extend(changes);
            if let Some(end) = switch {
                return Ok(Advance {
                    events,
                    end,
                    iterations,
                });
            }
            from = next;
            left -= s_end;
        }
        Err(Failed(format!(
            "the slack set changed more than {MAX_SET_CHANGES} times within one step from load factor {:.6e}: strings flip between slack and taut (where they slacken, the structure may be a mechanism)",
            current.eq.lambda
        )))
    }

    fn point(&self, step: usize, st: &State) -> PathPoint {
        point_of(self.model, &self.dofs, step, &st.eq, Some(&st.spectrum))
    }

    fn mode(&self, st: &State) -> Vec<[f64; 3]> {
        if st.spectrum.mode.len() != self.dofs.len() {
            // not found (a sparse tangent's shift-invert iteration failed)
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
    let rigid = dofs.held.iter().map(|(i, d)| Reaction {
        node: *i,
        direction: (*d).into(),
        force: d.dot(&(r[*i] - model.load[*i] * eq.lambda - model.dead_load(*i))),
    });
    // an elastic support's reaction is its springs' force
    let springs = dofs.springs.iter().map(|s| Reaction {
        node: s.node,
        direction: s.direction.into(),
        force: s.force(&(eq.x[s.node] - model.nodes[s.node]), eq.lambda),
    });
    let reactions = rigid.chain(springs).collect();
    PathPoint {
        step,
        lambda: eq.lambda,
        nodes: eq.x.iter().map(|x| (*x).into()).collect(),
        displacements,
        max_displacement,
        tensions: model.reported_tensions(&eq.states.iter().map(|s| s.tension).collect::<Vec<_>>()),
        slack: slack(model, eq),
        segment_tensions: (0..model.clusters.len())
            .map(|c| {
                eq.states[model.cluster_states(c)]
                    .iter()
                    .map(|s| s.tension)
                    .collect()
            })
            .collect(),
        pulleys: if model.has_friction() {
            model
                .clusters
                .iter()
                .map(|c| {
                    c.friction.as_ref().map_or_else(Vec::new, |f| {
                        f.pulleys.iter().map(|p| pulley_name(*p)).collect()
                    })
                })
                .collect()
        } else {
            Vec::new()
        },
        reactions,
        smallest_eigenvalues: spectrum.smallest.clone(),
        stability: spectrum.stability,
        residual: eq.residual,
    }
}

/// A pulley state's name in reports.
fn pulley_name(p: tensegrity_core::capstan::Pulley) -> &'static str {
    use tensegrity_core::capstan::Pulley;
    match p {
        Pulley::Stick => "stick",
        Pulley::SlipForward => "slip_forward",
        Pulley::SlipBackward => "slip_backward",
    }
}

/// The displacement per unit arc length on a switched branch, as a fraction of the
/// structure's size (module docs).
pub const BRANCH_SCALE: f64 = 0.01;

/// The slack strings and clusters of an equilibrium (clusters numbered after the members).
fn slack(model: &ElasticModel, eq: &Equilibrium) -> Vec<usize> {
    (0..eq.states.len())
        .filter(|&k| model.is_tension_only(k) && eq.states[k].slack)
        .filter_map(|k| model.reported_index(k))
        .collect()
}

/// Follows the load path of `model` from its reference state (first brought to equilibrium
/// at λ = 0) until λ reaches `settings.target`, past limit points (module docs). A path that
/// cannot go on (the step fell below its smallest: the corrector failed, its residual left
/// double precision, or a tangent was singular, at every step down to it) keeps its points
/// and says why, with the load factor where it stopped, in `stop`.
///
/// ```
/// use nalgebra::Vector3;
/// use tensegrity_path::{follow, ElasticMember, ElasticModel, MemberKind, PathSettings, Support};
/// // a bar along x pulled along x: linear to within its stretch, λ up to 1
/// let bar = ElasticMember { nodes: [0, 1], kind: MemberKind::Bar, ea: 1e4, rest_length: 1.0 };
/// let m = ElasticModel { nodes: vec![Vector3::zeros(), Vector3::x()], members: vec![bar],
///     clusters: Vec::new(),
///     supports: vec![Support::pinned(0), Support::along(1, vec![Vector3::y(), Vector3::z()])],
///     load: vec![Vector3::zeros(), Vector3::new(100.0, 0.0, 0.0)], drivers: Default::default() };
/// let path = follow(&m, &PathSettings::default()).unwrap();
/// let last = path.points.last().unwrap();
/// assert_eq!(last.lambda, 1.0);
/// assert!((last.displacements[1][0] - 0.01).abs() < 1e-12);
/// ```
pub fn follow(model: &ElasticModel, settings: &PathSettings) -> Result<PathReport> {
    settings.check()?;
    if let Some(c) = model.clusters.iter().position(|c| c.friction.is_some()) {
        return Err(PathError::model(
            format!("cluster {c}"),
            "pulley friction makes the path depend on its history: follow it by load control (`load_steps`), each step settled to the capstan law",
        ));
    }
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
    let started = std::time::Instant::now();
    while points.len() <= settings.max_steps {
        if let Some(seconds) = settings.max_seconds {
            if started.elapsed().as_secs_f64() > seconds {
                return Ok(PathReport {
                    points,
                    events,
                    stop: Stop::WorkLimit { seconds },
                });
            }
        }
        let step = points.len();
        let may_switch = settings.switch_branch && !switched;
        let advance = match tracer.advance(&current, s, step, target, may_switch) {
            Ok(a) => a,
            Err(Failed(why)) => {
                // a failed step (no equilibrium, a residual that left double precision, a
                // singular tangent) is tried again shorter; the points so far stay
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
                            message: format!("{message} (last: {why})"),
                        },
                    });
                }
                continue;
            }
        };
        events.extend(advance.events);
        match advance.end {
            End::Landed(last) => {
                points.push(tracer.point(step, &last));
                return Ok(PathReport {
                    points,
                    events,
                    stop: Stop::ReachedTarget,
                });
            }
            End::Switched { branch, along } => {
                switched = true;
                points.push(tracer.point(step, &branch));
                // the new branch moves along the mode at a nearly constant λ: its steps are
                // measured on the structure's size, not on the (possibly tiny) linear
                // response to the load that scales the path before it
                tracer.u_ref = tracer
                    .u_ref
                    .max(BRANCH_SCALE * crate::model::extent(&model.nodes));
                current = along;
                s = settings.initial_step;
            }
            End::Next(next) => {
                points.push(tracer.point(step, &next));
                current = next;
                if advance.iterations <= 4 {
                    s = (s * 1.5).min(settings.max_step);
                }
            }
        }
    }
    Ok(PathReport {
        points,
        events,
        stop: Stop::MaxSteps,
    })
}
