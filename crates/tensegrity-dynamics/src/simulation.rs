//! The simulation driver: settings, validation, one loop over an [`Integrator`] with output
//! times, events, projection and monitors, and the result with its work counters.
//!
//! Each pass of the loop asks the step control for the next step (fixed-step methods: the
//! grid t_k = k·dt, shortened to land on output times; adaptive ones: their proposal capped
//! at `dt`, the end time and refused below `h_min`, and for one without dense output (flight
//! steps) shortened to land on output times too), lets the integrator attempt it, and on
//! acceptance checks the state (NaN, blow-up), locates events, records samples (through the
//! dense output where the integrator has one), projects non-conserving methods back onto the
//! constraints if asked, and updates the monitors.

use super::constraints::ConstraintSet;
use super::drift::{self, DriftLimits, DriftWarning, IntegratorCounts};
use super::events::EventTracker;
pub use super::events::{Event, EventFn, EventHit, StateView};
pub use super::integrator::IntegratorKind;
use super::integrator::{Integrator, IntegratorStats, StepOutcome};
use super::model::{Model, Workspace};
use super::monitors::Monitor;
use super::recorder::{Quantities, Recorder, Sample, SampleSink};
use super::system::ConstrainedSystem;
use nalgebra::Vector3;
use std::fmt;
use std::time::Instant;
use tensegrity_core::error::{CoreError, DynamicsError, StepHint};
use tensegrity_core::structure::Structure;

/// Settings of one run.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationSettings {
    /// End time (s); the run starts at t = 0.
    pub t_end: f64,
    /// Integrator.
    pub integrator: IntegratorKind,
    /// Step (s) of the fixed-step integrators; maximum step of RK45 and SDIRK.
    pub dt: f64,
    /// Relative tolerance of RK45 and SDIRK.
    pub rtol: f64,
    /// Absolute tolerance of RK45 and SDIRK.
    pub atol: f64,
    /// Smallest RK45/SDIRK step before giving up (s).
    pub h_min: f64,
    /// Maximum number of accepted steps.
    pub max_steps: u64,
    /// Output times (s) at which the recorder samples.
    pub output_times: Vec<f64>,
    /// Also sample every `output_interval` seconds from 0 to `t_end`.
    pub output_interval: Option<f64>,
    /// What the recorder samples.
    pub quantities: Quantities,
    /// Also sample the state at the end of every accepted step (for monitors that integrate
    /// along the run, under a method whose steps vary, e.g. [`IntegratorKind::Rk4Flight`]).
    pub sample_every_step: bool,
    /// Project RK4/RK45 states back onto bar lengths and N P = D after every step.
    pub project: bool,
    /// Blow-up distance (m); `None` = [`Model::default_blowup_limit`].
    pub blowup_distance: Option<f64>,
    /// Limits of the invariants' drift past which the result carries a warning.
    pub drift_limits: DriftLimits,
}

impl Default for SimulationSettings {
    fn default() -> Self {
        Self {
            t_end: 1.0,
            integrator: IntegratorKind::Rk4,
            dt: 1e-3,
            rtol: 1e-8,
            atol: 1e-10,
            h_min: 1e-14,
            max_steps: 100_000_000,
            output_times: Vec::new(),
            output_interval: None,
            quantities: Quantities::default(),
            sample_every_step: false,
            project: false,
            blowup_distance: None,
            drift_limits: DriftLimits::default(),
        }
    }
}

impl SimulationSettings {
    /// Checks the numerical settings of the chosen integrator: positive finite times, steps
    /// and tolerances, and a fixed-step run that fits in `max_steps`.
    pub fn validate(&self) -> Result<(), CoreError> {
        let s = self;
        positive("t_end", s.t_end)?;
        match s.integrator {
            IntegratorKind::Rk4
            | IntegratorKind::Rattle
            | IntegratorKind::Imex
            | IntegratorKind::ImexArk
            | IntegratorKind::Rk4Flight
            | IntegratorKind::Newmark => positive("dt", s.dt)?,
            IntegratorKind::Rk45 | IntegratorKind::Sdirk => {
                positive("rtol", s.rtol)?;
                positive("atol", s.atol)?;
                positive("dt", s.dt)?;
            }
        }
        if let Some(dt_out) = s.output_interval {
            positive("output_interval", dt_out)?;
        }
        // a fixed-step run that cannot finish is refused before it starts, not after
        // max_steps steps of work
        let steps = (s.t_end / s.dt).ceil();
        if !s.integrator.is_adaptive() && steps > s.max_steps as f64 {
            return Err(CoreError::invalid_parameter(
                "dt",
                s.dt,
                format!(
                    "t_end / dt = {steps:e} fixed steps, more than max_steps = {}: use a \
                     larger `dt` or a shorter `t_end`",
                    s.max_steps
                ),
            ));
        }
        Ok(())
    }
}

/// The outcome of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationResult {
    /// Final time reached (s); earlier than requested after a terminal event.
    pub t_end: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps (adaptive integrators).
    pub rejected_steps: u64,
    /// Right-hand-side (force) evaluations.
    pub rhs_evals: u64,
    /// The final class-1 state (positions then velocities).
    pub final_state: Vec<f64>,
    /// Final node positions in file numbering.
    pub final_nodes: Vec<Vector3<f64>>,
    /// Final node velocities in file numbering.
    pub final_velocities: Vec<Vector3<f64>>,
    /// Max relative energy drift (see [`Monitor::energy_drift`]).
    pub energy_drift: f64,
    /// Max absolute bar-length error (m).
    pub bar_length_drift: f64,
    /// Max absolute ‖N P − D‖ component (m).
    pub constraint_drift: f64,
    /// Wall time of the integration alone (s).
    pub wall_time_s: f64,
    /// The recorded samples.
    pub samples: Vec<Sample>,
    /// Located events.
    pub events: Vec<EventHit>,
    /// The invariants past their limits ([`SimulationSettings::drift_limits`]): a run with
    /// warnings integrated its equations too loosely to be trusted.
    pub warnings: Vec<DriftWarning>,
    /// Contact node-steps and those that chattered
    /// ([`Integrator::contact_chatter`]; (0, 0) for methods that do not count them).
    pub contact_chatter: (u64, u64),
}

impl SimulationResult {
    /// The work counters of the run (accepted and rejected steps, right-hand-side
    /// evaluations).
    pub fn stats(&self) -> IntegratorStats {
        IntegratorStats {
            steps: self.steps,
            rejected_steps: self.rejected_steps,
            rhs_evals: self.rhs_evals,
        }
    }
}

/// A runnable simulation: model, initial state, settings and events.
pub struct Simulation {
    /// The class-1 model.
    pub model: Model,
    /// Initial state (class-1 positions then velocities).
    pub y0: Vec<f64>,
    /// Settings.
    pub settings: SimulationSettings,
    /// Events to locate.
    pub events: Vec<Event>,
}

impl fmt::Debug for Simulation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Simulation")
            .field("model", &self.model)
            .field("settings", &self.settings)
            .field("events", &self.events)
            .finish()
    }
}

fn positive(name: &'static str, value: f64) -> Result<(), CoreError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(CoreError::invalid_parameter(
            name,
            value,
            "must be positive and finite",
        ))
    }
}

impl Simulation {
    /// A simulation of `structure` (no ground, no actuation) from its nodes and velocities.
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure};
    /// use tensegrity_dynamics::{Simulation, SimulationSettings};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    ///     .velocities([[0.0, -1.0, 0.0], [0.0, 1.0, 0.0]])
    ///     .bar(Bar::new(0, 1).mass(1.0))
    ///     .build()
    ///     .unwrap();
    /// let settings = SimulationSettings { t_end: 0.5, ..Default::default() };
    /// let r = Simulation::new(&s, settings).unwrap().run().unwrap();
    /// assert!(r.bar_length_drift < 1e-10);
    /// ```
    pub fn new(structure: &Structure, settings: SimulationSettings) -> Result<Self, CoreError> {
        let model = Model::new(structure, None)?;
        let y0 = model.initial_state(structure)?;
        Ok(Self {
            model,
            y0,
            settings,
            events: Vec::new(),
        })
    }

    /// Runs the simulation from t = 0 to `settings.t_end` (or to a terminal event).
    pub fn run(&self) -> Result<SimulationResult, CoreError> {
        self.run_inner(None)
    }

    /// Runs the simulation handing every recorded sample to `sink` as soon as it is taken
    /// (bounded memory: [`SimulationResult::samples`] stays empty). A sink that returns an
    /// error (e.g. [`CoreError::Interrupted`]) stops the run there with that error; the
    /// samples it accepted so far are complete.
    pub fn run_streaming(&self, sink: &mut dyn SampleSink) -> Result<SimulationResult, CoreError> {
        self.run_inner(Some(sink))
    }

    fn run_inner<'a>(
        &'a self,
        sink: Option<&'a mut dyn SampleSink>,
    ) -> Result<SimulationResult, CoreError> {
        self.validate()?;
        let s = &self.settings;
        let mut integrator = s.integrator.build(&self.model, s.rtol, s.atol)?;
        let mut driver = Driver::new(self, integrator.as_ref(), sink)?;
        let start = Instant::now();
        let h_max = integrator.max_step(s.dt);
        let h0 = integrator.start(&self.model, &mut driver.ws, 0.0, &driver.y, h_max)?;
        let mut control = if integrator.is_adaptive() {
            StepControl::Adaptive {
                h: h0,
                h_max,
                h_min: s.h_min,
                lands: !integrator.has_dense_output(),
            }
        } else {
            StepControl::Grid { dt: s.dt, k: 0 }
        };
        if let Err(e) = driver.integrate(integrator.as_mut(), &mut control) {
            return Err(diverged(e, driver.t, s));
        }
        let wall_time_s = (start.elapsed().as_secs_f64() - driver.diag_time).max(0.0);
        let counts = IntegratorCounts {
            implicit_solves: integrator.implicit_solves(),
            contact_chatter: integrator.contact_chatter(),
        };
        Ok(driver.finish(wall_time_s, counts))
    }

    /// Checks the numerical settings of the chosen integrator (also done by
    /// [`run`](Self::run)): positive finite times, steps and tolerances, and a fixed-step run
    /// that fits in `max_steps`.
    pub fn validate(&self) -> Result<(), CoreError> {
        self.settings.validate()
    }

    /// The recorder of the output times: the explicit ones within [0, t_end] merged with the
    /// `output_interval` grid, which is generated lazily.
    fn recorder(&self) -> Recorder {
        let s = &self.settings;
        let mut times: Vec<f64> = s.output_times.clone();
        times.retain(|&t| t >= 0.0 && t <= s.t_end * (1.0 + 1e-12));
        let rec = Recorder::new(times, s.quantities);
        match s.output_interval {
            Some(dt_out) => rec.with_interval(dt_out, s.t_end),
            None => rec,
        }
    }
}

/// A constraint system that factored at t = 0 and fails later fails because the state ran
/// away (a step too large for the stiffness), not because the constraints are redundant:
/// say so. A blow-up or a NaN names the remedy of the run's integrator.
pub(crate) fn diverged(e: CoreError, t: f64, settings: &SimulationSettings) -> CoreError {
    let hint = if settings.integrator.is_adaptive() {
        StepHint::Adaptive
    } else {
        StepHint::FixedStep { dt: settings.dt }
    };
    let what = match e {
        CoreError::Dynamics(DynamicsError::SingularConstraint { .. }) => {
            "the bar-direction constraint system lost rank as the state ran away"
        }
        CoreError::Dynamics(DynamicsError::ConstraintNotConverged { .. }) => {
            "the constraint projection did not converge"
        }
        CoreError::Dynamics(DynamicsError::BlowUp {
            t,
            member,
            distance,
            limit,
            ..
        }) => {
            return DynamicsError::BlowUp {
                t,
                member,
                distance,
                limit,
                hint,
            }
            .into()
        }
        CoreError::Dynamics(DynamicsError::NonFiniteState { t, member, .. }) => {
            return DynamicsError::NonFiniteState { t, member, hint }.into()
        }
        other => return other,
    };
    if t > 0.0 {
        CoreError::Dynamics(DynamicsError::Diverged { t, what })
    } else {
        e
    }
}

/// How the driver chooses the next step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum StepControl {
    /// Fixed steps on the grid t_k = k·dt (k counts grid points reached), shortened to land on
    /// output times.
    Grid { dt: f64, k: u64 },
    /// The integrator's proposal `h`, capped at `h_max` and the end time; with `lands` (a
    /// method without dense output, e.g. flight steps) also shortened to land on the next
    /// output time, so that its samples are taken at their times.
    Adaptive {
        h: f64,
        h_max: f64,
        h_min: f64,
        lands: bool,
    },
}

impl StepControl {
    /// The step to attempt from `t` and the time it ends at.
    pub(crate) fn next(
        &self,
        t: f64,
        t_end: f64,
        next_output: Option<f64>,
        eps: f64,
    ) -> Result<(f64, f64), CoreError> {
        match *self {
            StepControl::Grid { dt, k } => {
                let grid = ((k + 1) as f64 * dt).min(t_end);
                let target = match next_output {
                    Some(to) if to > t + eps && to < grid - eps => to,
                    _ => grid,
                };
                Ok((target - t, target))
            }
            StepControl::Adaptive {
                h,
                h_max,
                h_min,
                lands,
            } => {
                let mut h = h.min(t_end - t).min(h_max);
                match next_output {
                    Some(to) if lands && to > t + eps && to < t + h - eps => h = to - t,
                    _ => {}
                }
                if h < h_min {
                    return Err(DynamicsError::StepSizeTooSmall { t, h_min }.into());
                }
                let t_new = t + h;
                Ok((h, if t_end - t_new < eps { t_end } else { t_new }))
            }
        }
    }

    /// Takes note of an attempted step that was to end at `t_new`.
    pub(crate) fn update(&mut self, t_new: f64, t_end: f64, outcome: &StepOutcome) {
        match self {
            StepControl::Grid { dt, k } => {
                if outcome.accepted && t_new == ((*k + 1) as f64 * *dt).min(t_end) {
                    *k += 1;
                }
            }
            StepControl::Adaptive { h, .. } => *h = outcome.h_next,
        }
    }
}

/// The mutable state of one run.
struct Driver<'a> {
    sim: &'a Simulation,
    ws: Workspace,
    y: Vec<f64>,
    t: f64,
    /// Time tolerance 10⁻¹² max(t_end, 1).
    eps: f64,
    blowup_limit: f64,
    rec: Recorder,
    monitor: Monitor,
    projector: Option<ConstraintSet>,
    proj_tol: f64,
    events: EventTracker<'a>,
    buf: Vec<f64>,
    stats: IntegratorStats,
    /// Time spent recording (excluded from the reported wall time).
    diag_time: f64,
    /// Where samples go as they are taken (else they are kept in the recorder).
    sink: Option<&'a mut dyn SampleSink>,
}

impl<'a> Driver<'a> {
    /// Workspace, recorder, monitors and projector at t = 0 (samples due at 0 are taken).
    fn new(
        sim: &'a Simulation,
        integ: &dyn Integrator<Model>,
        sink: Option<&'a mut dyn SampleSink>,
    ) -> Result<Self, CoreError> {
        let (model, s) = (&sim.model, &sim.settings);
        let mut ws = model.workspace()?;
        let y = sim.y0.clone();
        // nodes that start on the ground hold from the start (stick ground)
        model.update_contact_anchors(&y, &mut ws);
        let blowup_limit = s
            .blowup_distance
            .unwrap_or_else(|| model.default_blowup_limit());
        let mut rec = sim.recorder();
        let monitor = Monitor::new(model, &y);
        model.check_state(0.0, &y, blowup_limit)?;
        let eps = 1e-12 * s.t_end.max(1.0);
        while rec.next_time().is_some_and(|to| to <= eps) {
            rec.record(0.0, &y, model, &mut ws)?;
        }
        let projector = if s.project && !integ.preserves_constraints() {
            Some(ConstraintSet::new(model)?)
        } else {
            None
        };
        let proj_tol = model.constraint_tolerance();
        let dense = integ.has_dense_output();
        let mut driver = Self {
            sim,
            events: EventTracker::new(&sim.events, model, 0.0, &y, dense),
            buf: vec![0.0; y.len()],
            ws,
            y,
            t: 0.0,
            eps,
            blowup_limit,
            rec,
            monitor,
            projector,
            proj_tol,
            stats: IntegratorStats::default(),
            diag_time: 0.0,
            sink,
        };
        driver.drain()?;
        Ok(driver)
    }

    /// Hands the samples taken so far to the sink, if there is one.
    fn drain(&mut self) -> Result<(), CoreError> {
        if let Some(sink) = self.sink.as_mut() {
            for sample in self.rec.samples.drain(..) {
                sink.accept(sample)?;
            }
        }
        Ok(())
    }

    /// The driver loop: attempt, accept or reject, and post-process accepted steps.
    fn integrate(
        &mut self,
        integ: &mut dyn Integrator<Model>,
        control: &mut StepControl,
    ) -> Result<(), CoreError> {
        let (model, s) = (&self.sim.model, &self.sim.settings);
        while self.t < s.t_end - self.eps {
            let (h, t_new) = control.next(self.t, s.t_end, self.rec.next_time(), self.eps)?;
            self.events.before_step(&self.y);
            let outcome = integ.step(model, &mut self.ws, self.t, &mut self.y, h)?;
            control.update(t_new, s.t_end, &outcome);
            if !outcome.accepted {
                self.stats.rejected_steps += 1;
                continue;
            }
            self.stats.steps += 1;
            if self.stats.steps > s.max_steps {
                return Err(DynamicsError::MaxStepsExceeded {
                    t: t_new,
                    max_steps: s.max_steps,
                }
                .into());
            }
            model.check_state(t_new, &self.y, self.blowup_limit)?;
            if let Some(sink) = self.sink.as_mut() {
                sink.progress(t_new);
            }
            if self.sink.as_mut().is_some_and(|sink| !sink.keep_going()) {
                return Err(CoreError::Interrupted { t: self.t });
            }
            if self.after_step(integ, t_new)? {
                break;
            }
        }
        Ok(())
    }

    /// Events, samples, projection and monitors after an accepted step [self.t, t_new];
    /// returns `true` when a terminal event stopped the run.
    fn after_step(
        &mut self,
        integ: &mut dyn Integrator<Model>,
        t_new: f64,
    ) -> Result<bool, CoreError> {
        let model = &self.sim.model;
        let span = (self.t, t_new);
        let stop = self.events.after_step(model, integ, span, &self.y);
        let dense = integ.has_dense_output();
        if dense {
            self.record_dense(integ, span, stop.unwrap_or(t_new))?;
        }
        if let Some(ts) = stop {
            self.events
                .state_at(integ, span, &self.y, ts, &mut self.buf);
            self.y.copy_from_slice(&self.buf);
            self.t = ts;
            self.monitor.observe(model, &self.y);
            if !dense {
                self.record_at_step_end()?;
            }
            return Ok(true);
        }
        if let Some(p) = self.projector.as_mut() {
            p.project(model, &mut self.y, self.proj_tol, t_new)?;
            integ.invalidate();
        }
        if model.update_contact_anchors(&self.y, &mut self.ws) {
            integ.invalidate();
        }
        self.monitor.observe(model, &self.y);
        self.t = t_new;
        if !dense {
            self.record_at_step_end()?;
        }
        if self.sim.settings.sample_every_step {
            let d0 = Instant::now();
            self.rec
                .record_step(self.t, &self.y, &self.sim.model, &mut self.ws)?;
            self.diag_time += d0.elapsed().as_secs_f64();
            self.drain()?;
        }
        Ok(false)
    }

    /// Samples due up to `t_stop` inside the step `span`, from the dense output (the step's
    /// end state itself at its end).
    fn record_dense(
        &mut self,
        integ: &dyn Integrator<Model>,
        (t0, t_new): (f64, f64),
        t_stop: f64,
    ) -> Result<(), CoreError> {
        let model = &self.sim.model;
        while let Some(to) = self.rec.next_time() {
            if to > t_stop + self.eps {
                break;
            }
            let d0 = Instant::now();
            if (to - t_new).abs() <= self.eps {
                self.rec.record(to, &self.y, model, &mut self.ws)?;
            } else {
                integ.interpolate(to.max(t0), &mut self.buf);
                self.rec.record(to, &self.buf, model, &mut self.ws)?;
            }
            self.diag_time += d0.elapsed().as_secs_f64();
        }
        self.drain()
    }

    /// Samples due at the current time (fixed steps land on the output times).
    fn record_at_step_end(&mut self) -> Result<(), CoreError> {
        while self
            .rec
            .next_time()
            .is_some_and(|to| to <= self.t + self.eps)
        {
            let d0 = Instant::now();
            self.rec
                .record(self.t, &self.y, &self.sim.model, &mut self.ws)?;
            self.diag_time += d0.elapsed().as_secs_f64();
        }
        self.drain()
    }

    /// The result of the run.
    fn finish(mut self, wall_time_s: f64, counts: IntegratorCounts) -> SimulationResult {
        let model = &self.sim.model;
        self.stats.rhs_evals = self.ws.rhs_evals;
        let warnings = drift::check(
            model,
            self.sim.settings.integrator,
            &self.sim.settings.drift_limits,
            [self.monitor.energy_drift(), self.monitor.energy_gain()],
            self.monitor.bar_length_drift,
            self.monitor.constraint_drift,
            counts,
        );
        SimulationResult {
            warnings,
            contact_chatter: counts.contact_chatter,
            t_end: self.t,
            steps: self.stats.steps,
            rejected_steps: self.stats.rejected_steps,
            rhs_evals: self.stats.rhs_evals,
            final_nodes: model.nodes_of(&self.y),
            final_velocities: model.velocities_of(&self.y),
            energy_drift: self.monitor.energy_drift(),
            bar_length_drift: self.monitor.bar_length_drift,
            constraint_drift: self.monitor.constraint_drift,
            final_state: self.y,
            wall_time_s,
            samples: self.rec.samples,
            events: self.events.hits,
        }
    }
}
