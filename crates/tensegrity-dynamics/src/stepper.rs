//! A simulation stepped and steered from outside: a controller (a robot policy, a
//! reinforcement-learning environment, a script) sets rest lengths, advances the physics by a
//! number of steps, reads the state, and saves or restores it.
//!
//! # Actions
//!
//! Each call of [`Stepper::step`] is one control period [t₀, t₁] with t₁ = t₀ + n·dt (n
//! steps of the settings' `dt`; adaptive integrators land on t₁ exactly). An [`Action`] gives
//! every actuator ([`Actuator`]: a string's or a clustered string's rest length) its rest
//! length at t₁ (a target) or its rate over the period; the rest length moves linearly in
//! between,
//!
//!   r(t) = r₀ (1 − w) + r₁ w,  w = (t − t₀)/(t₁ − t₀),
//!
//! the interpolation of a scene's `[[actuation]]` tables, so that a stepped run and a
//! simulation of the same table give the same trajectory (bit for bit under fixed-step
//! methods). The actuator limits act on r₁: a target is first clamped to
//! [`min_length`, `max_length`], then the change r₁ − r₀ to ±`max_rate`·(t₁ − t₀); a rate is
//! clamped to ±`max_rate` and the length it reaches to [`min_length`, `max_length`]. Since
//! r is linear between two admissible lengths, it stays admissible throughout.
//!
//! # Checks
//!
//! Every accepted step is checked as in [`Simulation::run`](crate::Simulation::run) (NaN,
//! blow-up distance, maximum steps), projected onto the constraints when the settings ask,
//! and watched by the run monitors; [`Stepper::warnings`] judges the drifts with the same
//! limits ([`drift::check`]). Energy is judged only while no actuator has moved (actuation
//! does work), as for a scene with actuation tables.

use super::constraints::ConstraintSet;
use super::drift::{self, DriftWarning, IntegratorCounts};
use super::integrator::{Integrator, IntegratorStats};
use super::model::{Drive, Model, Workspace};
use super::monitors::Monitor;
use super::simulation::{diverged, Simulation, SimulationSettings, StepControl};
use super::system::ConstrainedSystem;
use super::Anchor;
use nalgebra::{Rotation3, Unit, Vector3};
use tensegrity_core::error::{CoreError, DynamicsError, ModelError};

/// What an actuator drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ActuatorTarget {
    /// The rest length of string k (numbered as the structure's strings).
    String(usize),
    /// The whole rest length of clustered string k.
    Cluster(usize),
}

/// One actuator: a rest length a controller sets, with its limits.
///
/// ```
/// use tensegrity_dynamics::{Actuator, ActuatorTarget};
/// let a = Actuator::string(3).min_length(0.2).max_rate(0.5);
/// assert_eq!(a.target, ActuatorTarget::String(3));
/// assert_eq!(a.max_length, f64::INFINITY);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Actuator {
    /// The string or cluster driven.
    pub target: ActuatorTarget,
    /// Shortest rest length (m, ≥ 0; default 0).
    pub min_length: f64,
    /// Longest rest length (m; default ∞).
    pub max_length: f64,
    /// Fastest change of the rest length (m/s, > 0; default ∞).
    pub max_rate: f64,
}

impl Actuator {
    /// An actuator of string `k` without limits.
    ///
    /// ```
    /// use tensegrity_dynamics::Actuator;
    /// assert_eq!(Actuator::string(0).min_length, 0.0);
    /// ```
    pub fn string(k: usize) -> Self {
        Self {
            target: ActuatorTarget::String(k),
            min_length: 0.0,
            max_length: f64::INFINITY,
            max_rate: f64::INFINITY,
        }
    }

    /// An actuator of clustered string `k` (its whole rest length) without limits.
    ///
    /// ```
    /// use tensegrity_dynamics::{Actuator, ActuatorTarget};
    /// assert_eq!(Actuator::cluster(1).target, ActuatorTarget::Cluster(1));
    /// ```
    pub fn cluster(k: usize) -> Self {
        Self {
            target: ActuatorTarget::Cluster(k),
            ..Self::string(0)
        }
    }

    /// With the shortest rest length `m` (m).
    ///
    /// ```
    /// use tensegrity_dynamics::Actuator;
    /// assert_eq!(Actuator::string(0).min_length(0.3).min_length, 0.3);
    /// ```
    pub fn min_length(mut self, m: f64) -> Self {
        self.min_length = m;
        self
    }

    /// With the longest rest length `m` (m).
    ///
    /// ```
    /// use tensegrity_dynamics::Actuator;
    /// assert_eq!(Actuator::string(0).max_length(2.0).max_length, 2.0);
    /// ```
    pub fn max_length(mut self, m: f64) -> Self {
        self.max_length = m;
        self
    }

    /// With the fastest rate `r` (m/s).
    ///
    /// ```
    /// use tensegrity_dynamics::Actuator;
    /// assert_eq!(Actuator::string(0).max_rate(0.1).max_rate, 0.1);
    /// ```
    pub fn max_rate(mut self, r: f64) -> Self {
        self.max_rate = r;
        self
    }

    /// The rest length this actuator reaches at the end of a period of `period` seconds from
    /// `r0` under `action` (module docs: the limits act on the end value).
    fn end_length(&self, r0: f64, period: f64, action: f64, as_rate: bool) -> f64 {
        let (lo, hi) = (self.min_length, self.max_length);
        let step = self.max_rate * period;
        if as_rate {
            let rate = action.clamp(-self.max_rate, self.max_rate);
            (r0 + rate * period).clamp(lo, hi)
        } else {
            let target = action.clamp(lo, hi);
            if (target - r0).abs() <= step {
                target
            } else {
                r0 + step.copysign(target - r0)
            }
        }
    }
}

/// What a controller does over one control period.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Action<'a> {
    /// Every rest length stays where it is.
    Hold,
    /// The rest lengths (m) to reach at the end of the period, one per actuator.
    RestLengths(&'a [f64]),
    /// The rates of the rest lengths (m/s) over the period, one per actuator.
    Rates(&'a [f64]),
}

/// A saved state of a [`Stepper`]: restore it with [`Stepper::set_state`] (restarts,
/// rollouts from one state).
#[derive(Debug)]
pub struct StepperState {
    /// Time (s).
    pub t: f64,
    /// Control ticks of `dt` taken since t = 0.
    pub ticks: u64,
    /// The class-1 state (positions then velocities).
    pub y: Vec<f64>,
    /// The actuators' rest lengths (m).
    pub rest_lengths: Vec<f64>,
    /// Whether any actuator has moved since the start.
    pub actuated: bool,
    /// The stick ground's friction anchors.
    anchors: Vec<Option<Anchor>>,
    /// The contact work integrated by a contact-splitting method.
    contact_work: Option<(f64, f64)>,
    /// The step control (grid count or adaptive proposal).
    control: StepControl,
    /// A copy of the integrator with its memory, where it can be copied.
    integrator: Option<Box<dyn Integrator<Model>>>,
}

impl Clone for StepperState {
    fn clone(&self) -> Self {
        Self {
            y: self.y.clone(),
            rest_lengths: self.rest_lengths.clone(),
            anchors: self.anchors.clone(),
            integrator: self.integrator.as_ref().and_then(|i| i.boxed_clone()),
            ..*self
        }
    }
}

/// A simulation advanced one control period at a time (module docs).
///
/// ```
/// use tensegrity_core::{Bar, StringMember, Structure, Support};
/// use tensegrity_dynamics::{Action, Actuator, Simulation, SimulationSettings, Stepper};
/// // a 1 kg bar hanging from a pinned node by a string, pulled up by shortening the string
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 0.0, -2.0]])
///     .bar(Bar::new(1, 2).mass(1.0))
///     .string(StringMember::new(0, 1).stiffness(1e3).rest_length(0.99).damping(20.0))
///     .support(Support::pinned(0))
///     .build()
///     .unwrap();
/// let sim = Simulation::new(&s, SimulationSettings::default()).unwrap();
/// let mut stepper = Stepper::new(sim, vec![Actuator::string(0).max_rate(0.1)]).unwrap();
/// stepper.step(Action::RestLengths(&[0.5]), 100).unwrap(); // 0.1 s: 0.01 m at most
/// assert!((stepper.rest_lengths()[0] - 0.98).abs() < 1e-12);
/// assert!((stepper.time() - 0.1).abs() < 1e-15);
/// ```
pub struct Stepper {
    model: Model,
    settings: SimulationSettings,
    y0: Vec<f64>,
    integrator: Box<dyn Integrator<Model>>,
    ws: Workspace,
    y: Vec<f64>,
    t: f64,
    ticks: u64,
    control: StepControl,
    monitor: Monitor,
    projector: Option<ConstraintSet>,
    proj_tol: f64,
    blowup_limit: f64,
    actuators: Vec<Actuator>,
    /// Each actuator's rest-length slot (strings, then clusters).
    slots: Vec<usize>,
    /// The actuators' rest lengths now, and at t = 0.
    rest: Vec<f64>,
    rest0: Vec<f64>,
    stats: IntegratorStats,
}

impl std::fmt::Debug for Stepper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Stepper")
            .field("model", &self.model)
            .field("t", &self.t)
            .field("actuators", &self.actuators)
            .finish()
    }
}

impl Stepper {
    /// A stepper of `simulation` (its model with ground and any actuation tables, initial
    /// state and settings; `t_end`, output times and events are not used) driving
    /// `actuators`. Every actuator is checked: its string or cluster exists, is driven once,
    /// its limits are ordered (0 ≤ min ≤ max, rate > 0) and its initial rest length lies
    /// within them.
    pub fn new(simulation: Simulation, actuators: Vec<Actuator>) -> Result<Self, CoreError> {
        let Simulation {
            model,
            y0,
            settings,
            ..
        } = simulation;
        if !(settings.dt.is_finite() && settings.dt > 0.0) {
            return Err(CoreError::invalid_parameter(
                "dt",
                settings.dt,
                "must be positive and finite (the control tick of a stepped simulation)",
            ));
        }
        let slots = slots_of(&model, &actuators)?;
        let ws = model.workspace()?;
        // the rest lengths at t = 0: the static ones under the scene's actuation tables
        let at0 = model.rest_lengths_at(0.0);
        let rest0: Vec<f64> = slots.iter().map(|&s| at0[s]).collect();
        for (k, (a, &r)) in actuators.iter().zip(&rest0).enumerate() {
            if r < a.min_length || r > a.max_length {
                return Err(DynamicsError::InvalidActuator {
                    actuator: k,
                    reason: format!(
                        "its initial rest length {r} m lies outside its limits [{}, {}] m",
                        a.min_length, a.max_length
                    ),
                }
                .into());
            }
        }
        let integrator = settings
            .integrator
            .build(&model, settings.rtol, settings.atol)?;
        let projector = if settings.project && !integrator.preserves_constraints() {
            Some(ConstraintSet::new(&model)?)
        } else {
            None
        };
        let blowup_limit = settings
            .blowup_distance
            .unwrap_or_else(|| model.default_blowup_limit());
        let monitor = Monitor::new(&model, &y0);
        let mut stepper = Self {
            proj_tol: model.constraint_tolerance(),
            control: StepControl::Grid {
                dt: settings.dt,
                k: 0,
            },
            y: y0.clone(),
            y0,
            integrator,
            ws,
            t: 0.0,
            ticks: 0,
            monitor,
            projector,
            blowup_limit,
            rest: rest0.clone(),
            rest0,
            actuators,
            slots,
            stats: IntegratorStats::default(),
            settings,
            model,
        };
        stepper.reset()?;
        Ok(stepper)
    }

    /// Back to t = 0: the initial state, the initial rest lengths, a fresh integrator and
    /// fresh monitors.
    pub fn reset(&mut self) -> Result<(), CoreError> {
        let y0 = self.y0.clone();
        self.restart(y0)
    }

    /// Back to t = 0 with the initial state turned by `angle` (rad) about the axis through
    /// the nodes' centroid along the ground's normal (without a ground, against gravity;
    /// without either, z): a rigid motion, so a structure at rest on a level ground stays at
    /// rest (a random heading for a rolling robot). A structure held at supports is refused.
    pub fn reset_turned(&mut self, angle: f64) -> Result<(), CoreError> {
        if !angle.is_finite() {
            return Err(CoreError::invalid_parameter(
                "angle",
                angle,
                "must be finite",
            ));
        }
        let held = |r: &super::NodeRef| matches!(r, super::NodeRef::Anchor(_));
        if self.model.node_map.iter().any(held) {
            return Err(DynamicsError::Unsupported {
                item: "a turned reset".into(),
                reason: "the structure is held at supports, which a rigid turn would move; \
                         reset it without turning"
                    .into(),
            }
            .into());
        }
        let up = self
            .model
            .ground
            .as_ref()
            .map(|g| g.normal)
            .or_else(|| {
                let g = -self.model.total_weight;
                (g.norm() > 0.0).then_some(g)
            })
            .unwrap_or_else(Vector3::z);
        let turn = Rotation3::from_axis_angle(&Unit::new_normalize(up), angle);
        let n1 = self.model.n1;
        let (x, v) = self.y0.split_at(3 * n1);
        let c = x
            .chunks_exact(3)
            .map(|p| Vector3::new(p[0], p[1], p[2]))
            .sum::<Vector3<f64>>()
            / n1.max(1) as f64;
        let mut y = self.y0.clone();
        for i in 0..n1 {
            let p = Vector3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
            let q = c + turn * (p - c);
            let w = turn * Vector3::new(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
            y[3 * i..3 * i + 3].copy_from_slice(q.as_slice());
            y[3 * n1 + 3 * i..3 * n1 + 3 * i + 3].copy_from_slice(w.as_slice());
        }
        self.restart(y)
    }

    /// Drops what the integrator and the projection keep from earlier steps.
    fn forget(&mut self) {
        self.integrator.invalidate();
        if let Some(p) = self.projector.as_mut() {
            p.forget();
        }
    }

    /// t = 0 from state `y` (class-1 positions then velocities).
    fn restart(&mut self, y: Vec<f64>) -> Result<(), CoreError> {
        self.forget();
        self.model.drives.clear();
        self.ws = self.model.workspace()?;
        let s = &self.settings;
        self.integrator = s.integrator.build(&self.model, s.rtol, s.atol)?;
        self.y = y;
        self.t = 0.0;
        self.ticks = 0;
        self.rest.clone_from(&self.rest0);
        self.stats = IntegratorStats::default();
        self.model.update_contact_anchors(&self.y, &mut self.ws);
        self.model.check_state(0.0, &self.y, self.blowup_limit)?;
        self.monitor = Monitor::new(&self.model, &self.y);
        let h_max = self.integrator.max_step(s.dt);
        let h0 = self
            .integrator
            .start(&self.model, &mut self.ws, 0.0, &self.y, h_max)?;
        self.control = if self.integrator.is_adaptive() {
            StepControl::Adaptive {
                h: h0,
                h_max,
                h_min: s.h_min,
                lands: true,
            }
        } else {
            StepControl::Grid { dt: s.dt, k: 0 }
        };
        Ok(())
    }

    /// Advances one control period of `n_steps` ticks of `dt` under `action`. On an error
    /// (a non-finite action, a run that diverges) the state stays at the last accepted step.
    pub fn step(&mut self, action: Action<'_>, n_steps: u64) -> Result<(), CoreError> {
        if n_steps == 0 {
            return Err(CoreError::invalid_parameter(
                "n_steps",
                0.0,
                "must be at least 1",
            ));
        }
        let ticks = self.ticks + n_steps;
        let t1 = ticks as f64 * self.settings.dt;
        self.set_drives(action, t1)?;
        let eps = 1e-12 * t1.max(1.0);
        if let Err(e) = self.advance(t1, eps) {
            // the rest lengths where the run stopped, for a next period from there
            self.sync_rest();
            return Err(diverged(e, self.t, &self.settings));
        }
        self.ticks = ticks;
        Ok(())
    }

    /// Sets the drives of the period [t, t1] from `action` (module docs).
    fn set_drives(&mut self, action: Action<'_>, t1: f64) -> Result<(), CoreError> {
        let (values, as_rate) = match action {
            Action::Hold if self.model.drives.is_empty() => return Ok(()),
            Action::Hold => (None, false),
            Action::RestLengths(v) => (Some(v), false),
            Action::Rates(v) => (Some(v), true),
        };
        if let Some(v) = values {
            if v.len() != self.actuators.len() {
                return Err(ModelError::LengthMismatch {
                    what: "actions (one per actuator)".into(),
                    expected: self.actuators.len(),
                    found: v.len(),
                }
                .into());
            }
            if let Some((k, &x)) = v.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(DynamicsError::InvalidAction {
                    actuator: k,
                    value: x,
                    reason: "is not finite",
                }
                .into());
            }
        }
        let (t0, period) = (self.t, t1 - self.t);
        self.model.drives.clear();
        for (k, a) in self.actuators.iter().enumerate() {
            let r0 = self.rest[k];
            let r1 = match values {
                Some(v) => a.end_length(r0, period, v[k], as_rate),
                None => r0,
            };
            self.model.drives.push(Drive {
                slot: self.slots[k],
                t0,
                t1,
                r0,
                r1,
            });
        }
        // a step method that keeps stages or a Jacobian from the last period sees new forces
        self.integrator.invalidate();
        Ok(())
    }

    /// The driver loop of [`Simulation::run`](crate::Simulation::run) up to `t1`: attempt,
    /// accept or reject, check, project, update the contact anchors and the monitors.
    fn advance(&mut self, t1: f64, eps: f64) -> Result<(), CoreError> {
        while self.t < t1 - eps {
            let (h, t_new) = self.control.next(self.t, t1, None, eps)?;
            let outcome =
                self.integrator
                    .step(&self.model, &mut self.ws, self.t, &mut self.y, h)?;
            self.control.update(t_new, t1, &outcome);
            if !outcome.accepted {
                self.stats.rejected_steps += 1;
                continue;
            }
            self.stats.steps += 1;
            if self.stats.steps > self.settings.max_steps {
                return Err(DynamicsError::MaxStepsExceeded {
                    t: t_new,
                    max_steps: self.settings.max_steps,
                }
                .into());
            }
            self.model.check_state(t_new, &self.y, self.blowup_limit)?;
            if let Some(p) = self.projector.as_mut() {
                p.project(&self.model, &mut self.y, self.proj_tol, t_new)?;
                self.integrator.invalidate();
            }
            if self.model.update_contact_anchors(&self.y, &mut self.ws) {
                self.integrator.invalidate();
            }
            self.monitor.observe(&self.model, &self.y);
            self.t = t_new;
        }
        self.t = t1;
        // the period's rest lengths are reached (or the tables', for an actuator not yet
        // driven)
        self.sync_rest();
        Ok(())
    }

    /// The actuators' rest lengths at the current time, as the model applies them (drives,
    /// else the actuation tables, else the static values).
    fn sync_rest(&mut self) {
        let all = self.model.rest_lengths_at(self.t);
        for (r, &slot) in self.rest.iter_mut().zip(&self.slots) {
            *r = all[slot];
        }
    }

    /// The current state, to restore with [`set_state`](Self::set_state), with a copy of
    /// the integrator's memory (where [`Integrator::boxed_clone`] gives one). Taking it drops
    /// the factor the constraint projection keeps between steps (the projection refactors at
    /// its next step, as after a restore), so that the run from here and a run restored to
    /// here take the same steps.
    pub fn state(&mut self) -> StepperState {
        if let Some(p) = self.projector.as_mut() {
            p.forget();
        }
        let integrator = self.integrator.boxed_clone();
        if integrator.is_none() {
            self.integrator.invalidate();
        }
        StepperState {
            t: self.t,
            ticks: self.ticks,
            y: self.y.clone(),
            rest_lengths: self.rest.clone(),
            actuated: !self.model.drives.is_empty(),
            anchors: self.ws.anchors.clone(),
            contact_work: self.ws.contact_work,
            control: self.control,
            integrator,
        }
    }

    /// Restores a state saved by [`state`](Self::state) of this stepper (or one of the same
    /// model), with the integrator's memory where the state holds a copy: the run then goes
    /// on bit for bit as from the original; an integrator that cannot be copied (RATTLE,
    /// SDIRK: their constraint factorisations) restarts from it and agrees to its
    /// tolerance.
    pub fn set_state(&mut self, state: &StepperState) -> Result<(), CoreError> {
        if state.y.len() != self.y.len() || state.rest_lengths.len() != self.rest.len() {
            return Err(ModelError::LengthMismatch {
                what: "the saved state (state entries, rest lengths)".into(),
                expected: self.y.len() + self.rest.len(),
                found: state.y.len() + state.rest_lengths.len(),
            }
            .into());
        }
        self.model
            .check_state(state.t, &state.y, self.blowup_limit)?;
        self.y.clone_from(&state.y);
        self.t = state.t;
        self.ticks = state.ticks;
        self.rest.clone_from(&state.rest_lengths);
        self.ws.anchors.clone_from(&state.anchors);
        self.ws.contact_work = state.contact_work;
        self.control = state.control;
        if let Some(p) = self.projector.as_mut() {
            p.forget();
        }
        match state.integrator.as_ref().and_then(|i| i.boxed_clone()) {
            Some(i) => self.integrator = i,
            None => self.integrator.invalidate(),
        }
        self.model.drives.clear();
        if state.actuated {
            let t = self.t;
            let holds = self.slots.iter().zip(&self.rest).map(|(&slot, &r)| Drive {
                slot,
                t0: t,
                t1: t,
                r0: r,
                r1: r,
            });
            self.model.drives.extend(holds);
        }
        Ok(())
    }

    /// Time (s).
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The control tick (s): the settings' `dt`.
    pub fn dt(&self) -> f64 {
        self.settings.dt
    }

    /// The class-1 state (positions then velocities).
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// The model stepped.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The actuators.
    pub fn actuators(&self) -> &[Actuator] {
        &self.actuators
    }

    /// The actuators' rest lengths now (m).
    pub fn rest_lengths(&self) -> &[f64] {
        &self.rest
    }

    /// Node positions in file numbering.
    pub fn nodes(&self) -> Vec<Vector3<f64>> {
        self.model.nodes_of(&self.y)
    }

    /// Node velocities in file numbering.
    pub fn velocities(&self) -> Vec<Vector3<f64>> {
        self.model.velocities_of(&self.y)
    }

    /// Axial member forces now (N, tension positive: bars, strings, then clusters; see
    /// [`Model::member_forces`]).
    pub fn member_forces(&mut self) -> Result<Vec<f64>, CoreError> {
        let evals = self.ws.rhs_evals;
        let out = self.model.member_forces(self.t, &self.y, &mut self.ws);
        self.ws.rhs_evals = evals; // observations are not integration work
        out
    }

    /// The ground's force on every file node now (zero off the ground's contact nodes).
    pub fn contact_forces(&mut self) -> Vec<Vector3<f64>> {
        let mut out = vec![Vector3::zeros(); self.model.n_nodes];
        if self.model.ground.is_none() {
            return out;
        }
        let evals = self.ws.rhs_evals;
        for (i, f) in self.model.contact_forces(self.t, &self.y, &mut self.ws) {
            out[i] += f;
        }
        self.ws.rhs_evals = evals;
        out
    }

    /// Kinetic and total energy now (J), the strings' potential at their current rest
    /// lengths.
    pub fn energy(&self) -> (f64, f64) {
        let ke = self.model.kinetic_energy(&self.y);
        let rest = self.model.rest_lengths_at(self.t);
        (
            ke,
            ke + self.model.potential_energy_with(&self.y, Some(&rest)),
        )
    }

    /// Accepted and rejected steps and right-hand-side evaluations since the last reset.
    pub fn stats(&self) -> IntegratorStats {
        IntegratorStats {
            rhs_evals: self.ws.rhs_evals,
            ..self.stats
        }
    }

    /// The drifts past their limits since the last reset, as a run's
    /// [`SimulationResult::warnings`](crate::SimulationResult::warnings).
    pub fn warnings(&self) -> Vec<DriftWarning> {
        let counts = IntegratorCounts {
            implicit_solves: self.integrator.implicit_solves(),
            contact_chatter: self.integrator.contact_chatter(),
        };
        drift::check(
            &self.model,
            self.settings.integrator,
            &self.settings.drift_limits,
            [self.monitor.energy_drift(), self.monitor.energy_gain()],
            self.monitor.bar_length_drift,
            self.monitor.constraint_drift,
            counts,
        )
    }
}

/// Each actuator's rest-length slot, checked (module docs of [`Stepper::new`]).
fn slots_of(model: &Model, actuators: &[Actuator]) -> Result<Vec<usize>, CoreError> {
    let (n_s, n_c) = (model.strings.len(), model.clusters.len());
    let mut slots: Vec<usize> = Vec::with_capacity(actuators.len());
    for (k, a) in actuators.iter().enumerate() {
        let bad = |reason: String| -> CoreError {
            DynamicsError::InvalidActuator {
                actuator: k,
                reason,
            }
            .into()
        };
        let slot = match a.target {
            ActuatorTarget::String(s) if s < n_s => s,
            ActuatorTarget::Cluster(c) if c < n_c => n_s + c,
            ActuatorTarget::String(s) => {
                return Err(bad(format!("string {s} does not exist ({n_s} strings)")))
            }
            ActuatorTarget::Cluster(c) => {
                return Err(bad(format!("cluster {c} does not exist ({n_c} clusters)")))
            }
        };
        if let Some(first) = slots.iter().position(|&s| s == slot) {
            return Err(bad(format!(
                "drives the same rest length as actuator {first}"
            )));
        }
        let ordered = a.min_length >= 0.0 && a.min_length <= a.max_length;
        if !ordered || a.min_length.is_nan() || a.max_length.is_nan() {
            return Err(bad(format!(
                "its limits min_length = {} m, max_length = {} m must satisfy 0 ≤ min ≤ max",
                a.min_length, a.max_length
            )));
        }
        if a.max_rate.is_nan() || a.max_rate <= 0.0 {
            return Err(bad(format!(
                "its max_rate = {} m/s must be positive",
                a.max_rate
            )));
        }
        slots.push(slot);
    }
    Ok(slots)
}
