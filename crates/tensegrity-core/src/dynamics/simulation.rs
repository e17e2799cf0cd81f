//! The simulation driver: integrator choice, output times, monitors, events, timing.

use super::model::{vec3, Model, NodeRef};
use super::monitors::Monitor;
use super::rattle::{ConstraintSet, Rattle};
use super::recorder::{Quantities, Recorder, Sample};
use super::rk4::Rk4;
use super::rk45::Dopri5;
use crate::error::CoreError;
use crate::structure::Structure;
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;
use std::time::Instant;

/// The time integrator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorKind {
    /// Classic fixed-step RK4 (MOTES parity).
    #[default]
    Rk4,
    /// Adaptive Dormand–Prince 5(4) with dense output and event location.
    Rk45,
    /// Fixed-step constraint-preserving RATTLE (2nd order, symplectic).
    Rattle,
}

impl fmt::Display for IntegratorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            IntegratorKind::Rk4 => "rk4",
            IntegratorKind::Rk45 => "rk45",
            IntegratorKind::Rattle => "rattle",
        })
    }
}

impl FromStr for IntegratorKind {
    type Err = String;
    /// Parses `rk4`, `rk45` or `rattle` (case-insensitive).
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "rk4" => Ok(Self::Rk4),
            "rk45" | "dopri5" => Ok(Self::Rk45),
            "rattle" => Ok(Self::Rattle),
            other => Err(format!(
                "unknown integrator \"{other}\" (expected rk4, rk45 or rattle)"
            )),
        }
    }
}

/// Settings of one run.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationSettings {
    /// End time (s); the run starts at t = 0.
    pub t_end: f64,
    /// Integrator.
    pub integrator: IntegratorKind,
    /// Step (s) of the fixed-step integrators; maximum step of RK45.
    pub dt: f64,
    /// Relative tolerance of RK45.
    pub rtol: f64,
    /// Absolute tolerance of RK45.
    pub atol: f64,
    /// Smallest RK45 step before giving up (s).
    pub h_min: f64,
    /// Maximum number of accepted steps.
    pub max_steps: u64,
    /// Output times (s) at which the recorder samples.
    pub output_times: Vec<f64>,
    /// Also sample every `output_interval` seconds from 0 to `t_end`.
    pub output_interval: Option<f64>,
    /// What the recorder samples.
    pub quantities: Quantities,
    /// Project RK4/RK45 states back onto bar lengths and N P = D after every step.
    pub project: bool,
    /// Blow-up distance (m); `None` = [`Model::default_blowup_limit`].
    pub blowup_distance: Option<f64>,
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
            project: false,
            blowup_distance: None,
        }
    }
}

/// Read-only view of a state in file numbering, passed to event functions.
#[derive(Debug, Clone, Copy)]
pub struct StateView<'a> {
    model: &'a Model,
    y: &'a [f64],
}

impl StateView<'_> {
    /// Position of file node `i`.
    pub fn node(&self, i: usize) -> Vector3<f64> {
        match self.model.node_map[i] {
            NodeRef::Free(c) => vec3(self.y, c),
            NodeRef::Anchor(p) => p,
        }
    }

    /// Velocity of file node `i`.
    pub fn velocity(&self, i: usize) -> Vector3<f64> {
        match self.model.node_map[i] {
            NodeRef::Free(c) => vec3(&self.y[3 * self.model.n1..], c),
            NodeRef::Anchor(_) => Vector3::zeros(),
        }
    }

    /// Number of file nodes.
    pub fn n_nodes(&self) -> usize {
        self.model.n_nodes
    }
}

/// An event function g(t, state); an event happens where g changes sign.
pub type EventFn = Box<dyn Fn(f64, &StateView<'_>) -> f64 + Send + Sync>;

/// An event to locate (RK45 only, using its dense output).
pub struct Event {
    /// Name reported in [`EventHit`].
    pub name: String,
    /// The event function.
    pub function: EventFn,
    /// Stop the run at the first occurrence.
    pub terminal: bool,
}

impl fmt::Debug for Event {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Event")
            .field("name", &self.name)
            .field("terminal", &self.terminal)
            .finish()
    }
}

/// A located event.
#[derive(Debug, Clone, PartialEq)]
pub struct EventHit {
    /// The event's name.
    pub name: String,
    /// When it happened (s), to ~1e-12 relative.
    pub t: f64,
}

/// The outcome of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationResult {
    /// Final time reached (s); earlier than requested after a terminal event.
    pub t_end: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps (RK45).
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
    /// use tensegrity_core::dynamics::{Simulation, SimulationSettings};
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

    /// Runs the simulation from t = 0 to `settings.t_end`.
    pub fn run(&self) -> Result<SimulationResult, CoreError> {
        let s = &self.settings;
        positive("t_end", s.t_end)?;
        match s.integrator {
            IntegratorKind::Rk4 | IntegratorKind::Rattle => positive("dt", s.dt)?,
            IntegratorKind::Rk45 => {
                positive("rtol", s.rtol)?;
                positive("atol", s.atol)?;
                positive("dt", s.dt)?;
            }
        }
        let model = &self.model;
        let mut ws = model.workspace()?;
        let mut y = self.y0.clone();
        let limit = s
            .blowup_distance
            .unwrap_or_else(|| model.default_blowup_limit());
        let mut times: Vec<f64> = s.output_times.clone();
        if let Some(dt_out) = s.output_interval {
            positive("output_interval", dt_out)?;
            let n = (s.t_end / dt_out * (1.0 + 1e-12)).floor() as usize;
            times.extend((0..=n).map(|i| (i as f64 * dt_out).min(s.t_end)));
        }
        times.retain(|&t| t >= 0.0 && t <= s.t_end * (1.0 + 1e-12));
        let mut rec = Recorder::new(times, s.quantities);
        let mut monitor = Monitor::new(model, &y);
        model.check_state(0.0, &y, limit)?;
        let eps = 1e-12 * s.t_end.max(1.0);
        while rec.next_time().is_some_and(|to| to <= eps) {
            rec.record(0.0, &y, model, &mut ws)?;
        }
        let mut projector = if s.project && s.integrator != IntegratorKind::Rattle {
            Some(ConstraintSet::new(model)?)
        } else {
            None
        };
        let proj_tol = 1e-14
            * model
                .bars
                .iter()
                .map(|b| b.length0 * b.length0)
                .fold(1.0, f64::max);
        let mut steps = 0u64;
        let mut rejected = 0u64;
        let mut events = Vec::new();
        let mut t = 0.0;
        let start = Instant::now();
        let mut diag_time = 0.0;
        match s.integrator {
            IntegratorKind::Rk4 | IntegratorKind::Rattle => {
                let mut rk4 = Rk4::new(y.len());
                let mut rattle = if s.integrator == IntegratorKind::Rattle {
                    Some(Rattle::new(model)?)
                } else {
                    None
                };
                let mut k = 0u64;
                while t < s.t_end - eps {
                    let grid = ((k + 1) as f64 * s.dt).min(s.t_end);
                    let target = match rec.next_time() {
                        Some(to) if to > t + eps && to < grid - eps => to,
                        _ => grid,
                    };
                    let h = target - t;
                    match rattle.as_mut() {
                        Some(r) => r.step(model, &mut ws, t, &mut y, h)?,
                        None => rk4.step(model, &mut ws, t, &mut y, h)?,
                    }
                    t = target;
                    if target == grid {
                        k += 1;
                    }
                    steps += 1;
                    if steps > s.max_steps {
                        return Err(CoreError::MaxStepsExceeded {
                            t: t,
                            max_steps: s.max_steps,
                        });
                    }
                    model.check_state(t, &y, limit)?;
                    if let Some(p) = projector.as_mut() {
                        p.project(model, &mut y, proj_tol, t)?;
                    }
                    monitor.observe(model, &y);
                    while rec.next_time().is_some_and(|to| to <= t + eps) {
                        let d0 = Instant::now();
                        rec.record(t, &y, model, &mut ws)?;
                        diag_time += d0.elapsed().as_secs_f64();
                    }
                }
            }
            IntegratorKind::Rk45 => {
                let mut dp = Dopri5::new(y.len(), s.rtol, s.atol);
                let mut h = dp.initial_step(model, &mut ws, 0.0, &y, s.dt)?;
                let mut buf = vec![0.0; y.len()];
                let mut g_prev: Vec<f64> = self
                    .events
                    .iter()
                    .map(|e| (e.function)(0.0, &StateView { model, y: &y }))
                    .collect();
                'outer: while t < s.t_end - eps {
                    h = h.min(s.t_end - t).min(s.dt);
                    if h < s.h_min {
                        return Err(CoreError::StepSizeTooSmall { t, h_min: s.h_min });
                    }
                    let (ok, h_next) = dp.try_step(model, &mut ws, t, &mut y, h)?;
                    if !ok {
                        rejected += 1;
                        h = h_next;
                        continue;
                    }
                    let mut t_new = t + h;
                    if s.t_end - t_new < eps {
                        t_new = s.t_end;
                    }
                    steps += 1;
                    if steps > s.max_steps {
                        return Err(CoreError::MaxStepsExceeded {
                            t: t_new,
                            max_steps: s.max_steps,
                        });
                    }
                    model.check_state(t_new, &y, limit)?;
                    // events
                    let mut stop_at: Option<f64> = None;
                    for (ei, ev) in self.events.iter().enumerate() {
                        let g1 = (ev.function)(t_new, &StateView { model, y: &y });
                        let g0 = g_prev[ei];
                        if g0 != 0.0 && (g0 < 0.0) != (g1 < 0.0) {
                            let (mut a, mut b) = (t, t_new);
                            let mut ga = g0;
                            for _ in 0..200 {
                                if b - a <= 1e-13 * b.abs().max(1.0) {
                                    break;
                                }
                                let m = 0.5 * (a + b);
                                dp.interpolate(m, &mut buf);
                                let gm = (ev.function)(m, &StateView { model, y: &buf });
                                if (gm < 0.0) == (ga < 0.0) && gm != 0.0 {
                                    a = m;
                                    ga = gm;
                                } else {
                                    b = m;
                                }
                            }
                            events.push(EventHit {
                                name: ev.name.clone(),
                                t: b,
                            });
                            if ev.terminal {
                                stop_at = Some(stop_at.map_or(b, |s: f64| s.min(b)));
                            }
                        }
                        g_prev[ei] = g1;
                    }
                    let t_stop = stop_at.unwrap_or(t_new);
                    while let Some(to) = rec.next_time() {
                        if to > t_stop + eps {
                            break;
                        }
                        let d0 = Instant::now();
                        if (to - t_new).abs() <= eps {
                            rec.record(to, &y, model, &mut ws)?;
                        } else {
                            dp.interpolate(to.max(t), &mut buf);
                            rec.record(to, &buf, model, &mut ws)?;
                        }
                        diag_time += d0.elapsed().as_secs_f64();
                    }
                    if let Some(ts) = stop_at {
                        dp.interpolate(ts, &mut buf);
                        y.copy_from_slice(&buf);
                        t = ts;
                        monitor.observe(model, &y);
                        break 'outer;
                    }
                    if let Some(p) = projector.as_mut() {
                        p.project(model, &mut y, proj_tol, t_new)?;
                        dp.invalidate();
                    }
                    monitor.observe(model, &y);
                    t = t_new;
                    h = h_next;
                }
            }
        }
        let wall_time_s = (start.elapsed().as_secs_f64() - diag_time).max(0.0);
        Ok(SimulationResult {
            t_end: t,
            steps,
            rejected_steps: rejected,
            rhs_evals: ws.rhs_evals,
            final_nodes: model.nodes_of(&y),
            final_velocities: model.velocities_of(&y),
            final_state: y,
            energy_drift: monitor.energy_drift(),
            bar_length_drift: monitor.bar_length_drift,
            constraint_drift: monitor.constraint_drift,
            wall_time_s,
            samples: rec.samples,
            events,
        })
    }
}
