//! The driver of the elastic dynamics ([`ElasticDynamics::run`], module docs of
//! [`crate::transient`]): the explicit methods' stability check (RK4: h ω_max ≤ 2.8, ω_max the
//! model's highest angular frequency), one loop over an [`Integrator`] — RK4 and RK45 of
//! `tensegrity-dynamics`, or Newmark ([`crate::newmark`]) — whose fixed steps are cut at the
//! output times and whose dense output (RK45) samples between them, and the energy balance
//! E(t) + W_d(t) = E(0) (W_d the dashpots' work by the trapezoidal rule at the step ends) as
//! the run's `energy_drift`. With rigid bars ([`crate::rigid_bars`]) every accepted state is
//! projected onto their lengths (RK45's first stage then recomputed), and the largest
//! length error met is the run's `bar_length_drift`.

use crate::newmark::Newmark;
use crate::transient::{ElasticDynamics, TransientWorkspace, RK4_STABILITY};
use std::time::Instant;
use tensegrity_core::error::{CoreError, DynamicsError, StepHint};
use tensegrity_core::structure::MemberId;
use tensegrity_dynamics::{
    Dopri5, DriftQuantity, DriftWarning, Integrator, IntegratorKind, Recorder, Rk4, Sample,
    SampleSink, SimulationResult, SimulationSettings, System,
};

impl ElasticDynamics {
    /// Checks a step against the explicit methods' stability limit (module docs).
    fn check_step(&self, settings: &SimulationSettings) -> std::result::Result<(), CoreError> {
        let bound = match settings.integrator {
            IntegratorKind::Rk4 => RK4_STABILITY,
            // the adaptive method's largest step (its own control shortens it)
            IntegratorKind::Rk45 | IntegratorKind::Newmark => return Ok(()),
            other => {
                return Err(DynamicsError::Unsupported {
                    item: format!("integrator = {other}"),
                    reason: "an elastic model is integrated by rk4, rk45 or newmark (the other methods step rigid bars)".into(),
                }
                .into())
            }
        };
        let omega = self.highest_frequency();
        // rounded down to the 4 digits the error shows: a step given as shown runs
        let exact = bound / omega;
        let unit = 10f64.powf(exact.log10().floor() - 3.0);
        let limit = (exact / unit).floor() * unit;
        if settings.dt > limit {
            return Err(DynamicsError::StepAboveStabilityLimit {
                dt: settings.dt,
                limit,
                omega,
                period: std::f64::consts::TAU / omega,
                integrator: "rk4",
            }
            .into());
        }
        Ok(())
    }

    /// A sample of the state `y` at `t` with the recorder's quantities.
    fn sample(&self, t: f64, y: &[f64], recorder: &Recorder) -> Sample {
        let q = recorder.quantities();
        Sample {
            t,
            nodes: q.nodes.then(|| self.nodes_of(y)),
            velocities: q.velocities.then(|| self.velocities_of(y)),
            member_forces: q.member_forces.then(|| self.member_forces_at(t, y)),
            energy: q.energy.then(|| {
                let e = self.energy_at(t, y);
                (e.kinetic, e.total())
            }),
            contact_forces: None,
            contact_work: None,
        }
    }

    /// Runs the model from its initial state under `settings` (t_end, integrator rk4, rk45
    /// or newmark, dt — the step, or the largest one of rk45 —, tolerances, output times,
    /// quantities, the energy limit of the drift limits) with every sample streamed to
    /// `sink`. A step above RK4's stability limit, another integrator or a bad setting is
    /// refused before the run.
    pub fn run(
        &self,
        settings: &SimulationSettings,
        sink: &mut dyn SampleSink,
    ) -> std::result::Result<SimulationResult, CoreError> {
        settings.validate()?;
        self.check_step(settings)?;
        let n = System::state_len(self);
        let mut method: Box<dyn Integrator<ElasticDynamics>> = match settings.integrator {
            IntegratorKind::Rk4 => Box::new(Rk4::new(n)),
            IntegratorKind::Rk45 => Box::new(Dopri5::new(n, settings.rtol, settings.atol)),
            _ => Box::new(Newmark::new(self)),
        };
        let mut ws = TransientWorkspace::default();
        let mut y = self.initial_state();
        // every run starts from the model's distribution of the clusters' material
        self.set_friction_rest_lengths(crate::clusters::friction_rest_lengths(self.model()));
        let mut recorder = Recorder::new(settings.output_times.clone(), settings.quantities);
        if let Some(dt_out) = settings.output_interval {
            recorder = recorder.with_interval(dt_out, settings.t_end);
        }
        let start = Instant::now();
        let e0 = self.energy(&y).total();
        let mut monitor = EnergyMonitor::new(e0, self.dissipation(&y));
        let mut t = 0.0;
        let mut h = method.start(self, &mut ws, t, &y, settings.dt)?;
        let (mut steps, mut rejected) = (0_u64, 0_u64);
        let mut previous = y.clone();
        let mut buffer = vec![0.0; n];
        let mut length_drift = 0.0_f64;
        self.emit_due(t, &y, &mut recorder, sink)?;
        // (a last step shorter than 10⁻⁹ dt is round-off of the summed steps, not a step)
        while settings.t_end - t > 1e-9 * settings.dt {
            if steps >= settings.max_steps {
                return Err(DynamicsError::MaxStepsExceeded {
                    max_steps: settings.max_steps,
                    t,
                }
                .into());
            }
            let mut step = h.min(settings.dt).min(settings.t_end - t);
            if !method.is_adaptive() {
                if let Some(due) = recorder.next_time() {
                    if due > t && due < t + step * (1.0 - 1e-12) {
                        step = due - t;
                    }
                }
            }
            previous.copy_from_slice(&y);
            let outcome = method
                .step(self, &mut ws, t, &mut y, step)
                .map_err(|e| elastic_remedy(e, step))?;
            h = outcome.h_next;
            if !outcome.accepted {
                rejected += 1;
                if h < settings.h_min {
                    return Err(DynamicsError::StepSizeTooSmall {
                        h_min: settings.h_min,
                        t,
                    }
                    .into());
                }
                continue;
            }
            let t_new = if settings.t_end - (t + step) <= 1e-9 * settings.dt {
                settings.t_end
            } else {
                t + step
            };
            steps += 1;
            if let Some(k) = y.iter().position(|v| !v.is_finite()) {
                let e = DynamicsError::NonFiniteState {
                    t: t_new,
                    member: self.member_at(k),
                    hint: StepHint::Unknown,
                };
                return Err(elastic_remedy(e.into(), step));
            }
            if self.project(t_new, &mut y)? && settings.integrator == IntegratorKind::Rk45 {
                method.invalidate();
            }
            if self.model().has_friction() {
                // the pulleys slide at the step's end; the strain energy that releases is
                // the friction's work (in the energy balance), and the forces jump
                monitor.dissipated += self.slide(&previous, &y).map_err(|_| {
                    DynamicsError::ElasticDiverged {
                    t,
                    dt: step,
                    what: "a cluster's material slid over its pulleys past a segment's rest length",
                }
                })?;
                method.invalidate();
            }
            length_drift = length_drift.max(self.bar_length_error(&y));
            monitor.step(self, t_new, &y, step);
            let dense = method.has_dense_output().then_some(&*method);
            self.emit_between(t, t_new, &y, &mut recorder, sink, dense, &mut buffer)?;
            t = t_new;
            sink.progress(t);
            if !sink.keep_going() {
                return Err(CoreError::Interrupted { t });
            }
            if !method.is_adaptive() {
                h = settings.dt;
            }
        }
        let wall_time_s = start.elapsed().as_secs_f64();
        let energy_drift = monitor.drift();
        let mut warnings = Vec::new();
        // an actuator does work: a driven run has no energy check (module docs of
        // crate::actuation)
        if energy_drift > settings.drift_limits.energy && !self.is_actuated() {
            warnings.push(DriftWarning {
                quantity: DriftQuantity::Energy,
                value: energy_drift,
                limit: settings.drift_limits.energy,
                integrator: settings.integrator,
                elastic: true,
            });
        }
        Ok(SimulationResult {
            t_end: t,
            steps,
            rejected_steps: rejected,
            rhs_evals: ws.rhs_evals,
            final_nodes: self.nodes_of(&y),
            final_velocities: self.velocities_of(&y),
            final_state: y,
            energy_drift,
            bar_length_drift: length_drift,
            constraint_drift: 0.0,
            wall_time_s,
            samples: Vec::new(),
            events: Vec::new(),
            warnings,
            contact_chatter: (0, 0),
        })
    }

    /// The member of a state entry's node (for an error).
    fn member_at(&self, k: usize) -> MemberId {
        let node = self.dofs().free[k % self.n_free()].0;
        self.model()
            .members
            .iter()
            .position(|m| m.nodes.contains(&node))
            .map_or(MemberId::Bar(0), |k| self.member_ids[k])
    }

    /// Emits the samples due at exactly `t` (the start).
    fn emit_due(
        &self,
        t: f64,
        y: &[f64],
        recorder: &mut Recorder,
        sink: &mut dyn SampleSink,
    ) -> std::result::Result<(), CoreError> {
        while let Some(due) = recorder.next_time() {
            if due > t + 1e-12 * t.abs().max(1e-300) {
                break;
            }
            let s = self.sample(t, y, recorder);
            recorder.record_sample(s.clone());
            sink.accept(s)?;
        }
        Ok(())
    }

    /// Emits the samples due in (t0, t1]: from the dense output inside the step, else (a
    /// fixed step landed on them) the state at t1.
    #[allow(clippy::too_many_arguments)]
    fn emit_between(
        &self,
        t0: f64,
        t1: f64,
        y: &[f64],
        recorder: &mut Recorder,
        sink: &mut dyn SampleSink,
        dense: Option<&dyn Integrator<ElasticDynamics>>,
        buffer: &mut [f64],
    ) -> std::result::Result<(), CoreError> {
        while let Some(due) = recorder.next_time() {
            if due > t1 * (1.0 + 1e-12) {
                break;
            }
            let s = match dense {
                Some(m) if due < t1 && due > t0 && m.interpolate(due, buffer) => {
                    self.sample(due, buffer, recorder)
                }
                _ => self.sample(t1, y, recorder),
            };
            recorder.record_sample(s.clone());
            sink.accept(s)?;
        }
        Ok(())
    }
}

/// The energy balance along a run: E(t) + the dashpots' work (trapezoidal rule at the step
/// ends) + the pulleys' friction work (the strain energy their sliding released) against E(0), relative to the largest of |E(0)|, T + U and the load's potential met.
#[derive(Debug, Clone, Copy)]
struct EnergyMonitor {
    e0: f64,
    dissipated: f64,
    power: f64,
    scale: f64,
    largest: f64,
}

impl EnergyMonitor {
    fn new(e0: f64, power: f64) -> Self {
        Self {
            e0,
            dissipated: 0.0,
            power,
            scale: e0.abs(),
            largest: 0.0,
        }
    }

    fn step(&mut self, system: &ElasticDynamics, t: f64, y: &[f64], h: f64) {
        let e = system.energy_at(t, y);
        let power = system.dissipation_at(t, y);
        self.dissipated += 0.5 * h * (self.power + power);
        self.power = power;
        self.scale = self.scale.max(e.kinetic + e.strain).max(e.load.abs());
        self.largest = self
            .largest
            .max((e.total() + self.dissipated - self.e0).abs());
    }

    fn drift(&self) -> f64 {
        if self.scale > 0.0 {
            self.largest / self.scale
        } else {
            0.0
        }
    }
}

/// A run-away state of the elastic dynamics with the remedy an elastic model can take (a
/// smaller step, `newmark`): the rigid-bar integrators the core's messages name are refused
/// here.
fn elastic_remedy(e: CoreError, dt: f64) -> CoreError {
    match e {
        CoreError::Dynamics(DynamicsError::Diverged { t, what }) => {
            DynamicsError::ElasticDiverged { t, dt, what }.into()
        }
        CoreError::Dynamics(DynamicsError::NonFiniteState { t, member, .. }) => {
            DynamicsError::NonFiniteState {
                t,
                member,
                hint: StepHint::Elastic { dt },
            }
            .into()
        }
        e => e,
    }
}
