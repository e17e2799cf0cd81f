//! Samples a run at requested output times only, and only the requested quantities.

use super::model::{Model, Workspace};
use nalgebra::Vector3;
use tensegrity_core::error::CoreError;

/// Which quantities to record at each output time.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Quantities {
    /// Node positions (file numbering).
    pub nodes: bool,
    /// Node velocities (file numbering).
    pub velocities: bool,
    /// Axial member forces, tension positive, bars then strings (N).
    pub member_forces: bool,
    /// Kinetic and total energy (J).
    pub energy: bool,
    /// Ground contact forces on the contact nodes (N).
    pub contact_forces: bool,
}

impl Quantities {
    /// Positions only.
    pub fn nodes() -> Self {
        Self {
            nodes: true,
            ..Self::default()
        }
    }

    /// Everything.
    pub fn all() -> Self {
        Self {
            nodes: true,
            velocities: true,
            member_forces: true,
            energy: true,
            contact_forces: true,
        }
    }
}

/// One recorded sample.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Sample {
    /// Time (s).
    pub t: f64,
    /// Node positions, if requested.
    pub nodes: Option<Vec<Vector3<f64>>>,
    /// Node velocities, if requested.
    pub velocities: Option<Vec<Vector3<f64>>>,
    /// Member forces, if requested.
    pub member_forces: Option<Vec<f64>>,
    /// (kinetic, total) energy, if requested.
    pub energy: Option<(f64, f64)>,
    /// `(file node, force)` for every contact node, if requested.
    pub contact_forces: Option<Vec<(usize, Vector3<f64>)>>,
    /// The contact's non-conservative work from the start, (normal damping, friction) in J,
    /// as integrated by the step itself, when the integrator applies the contact in its own
    /// substeps (IMEX: the work of its implicit contact substeps is their exact change of
    /// kinetic energy); `None` when the contact is part of the right-hand side, whose work a
    /// sink integrates from `contact_forces`.
    pub contact_work: Option<(f64, f64)>,
}

/// Where the samples of a streamed run go ([`Simulation::run_streaming`]), one at a time, in
/// time order.
///
/// [`Simulation::run_streaming`]: super::Simulation::run_streaming
pub trait SampleSink {
    /// Takes one sample; an error stops the run with that error.
    fn accept(&mut self, sample: Sample) -> Result<(), CoreError>;

    /// Asked after every accepted step: `false` stops the run with
    /// [`CoreError::Interrupted`] (e.g. on Ctrl-C), even between samples.
    fn keep_going(&mut self) -> bool {
        true
    }

    /// Told the simulated time after every accepted step (a progress report: an adaptive
    /// run's steps are not known in advance, its time is).
    fn progress(&mut self, t: f64) {
        let _ = t;
    }

    /// A flag whose setting stops a convergence check's companion runs as well, those beside
    /// the run and those after it, which write to no sink (e.g. the process's interrupt flag,
    /// which [`SampleSink::keep_going`] reads for the run itself). `None` (the default): they
    /// stop only when the run itself failed.
    fn stop_flag(&self) -> Option<&'static std::sync::atomic::AtomicBool> {
        None
    }
}

impl SampleSink for Vec<Sample> {
    fn accept(&mut self, sample: Sample) -> Result<(), CoreError> {
        self.push(sample);
        Ok(())
    }
}

/// Regular output times k·dt, k = 0..=n, generated one at a time (a run of 10⁹ steps with
/// an output every step must not hold 10⁹ times in memory).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Grid {
    dt: f64,
    t_end: f64,
    n: u64,
    k: u64,
}

impl Grid {
    fn next_time(&self) -> Option<f64> {
        (self.k <= self.n).then(|| (self.k as f64 * self.dt).min(self.t_end))
    }
}

/// Collects samples at the requested times: explicit times merged with a regular grid.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Recorder {
    times: Vec<f64>,
    next: usize,
    grid: Option<Grid>,
    quantities: Quantities,
    /// Time of the last sample taken.
    last: Option<f64>,
    /// The samples taken so far (handed out and cleared by a streamed run).
    pub samples: Vec<Sample>,
}

impl Recorder {
    /// A recorder for sorted output `times` (unsorted input is sorted, duplicates removed).
    pub fn new(mut times: Vec<f64>, quantities: Quantities) -> Self {
        times.retain(|t| t.is_finite());
        times.sort_by(f64::total_cmp);
        times.dedup();
        Self {
            samples: Vec::new(),
            times,
            next: 0,
            grid: None,
            quantities,
            last: None,
        }
    }

    /// Adds the regular output times k·`dt` for k·dt ≤ `t_end` (the last one clamped to
    /// `t_end`), generated lazily.
    pub fn with_interval(mut self, dt: f64, t_end: f64) -> Self {
        let n = (t_end / dt * (1.0 + 1e-12)).floor();
        if dt > 0.0 && n.is_finite() && n >= 0.0 {
            self.grid = Some(Grid {
                dt,
                t_end,
                n: n as u64,
                k: 0,
            });
        }
        self
    }

    /// The next output time not yet sampled.
    pub fn next_time(&self) -> Option<f64> {
        let explicit = self.times.get(self.next).copied();
        match (explicit, self.grid.and_then(|g| g.next_time())) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }

    /// The explicit output times (the regular grid of [`Recorder::with_interval`] aside).
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// Moves past the output time `due` (both lists, when they share it).
    fn advance(&mut self, due: Option<f64>) {
        if self.times.get(self.next).copied() == due {
            self.next += 1;
        }
        if let Some(g) = self.grid.as_mut() {
            if g.next_time() == due {
                g.k += 1;
            }
        }
    }

    /// Records the state `y` at the next output time `t` and advances.
    pub fn record(
        &mut self,
        t: f64,
        y: &[f64],
        model: &Model,
        ws: &mut Workspace,
    ) -> Result<(), CoreError> {
        self.take(t, y, model, ws)?;
        let due = self.next_time();
        self.advance(due);
        Ok(())
    }

    /// Records a sample built by the caller (a model other than [`Model`], e.g. an elastic
    /// one) at the next output time, and advances.
    pub fn record_sample(&mut self, sample: Sample) {
        self.last = Some(sample.t);
        self.samples.push(sample);
        let due = self.next_time();
        self.advance(due);
    }

    /// What this recorder samples.
    pub fn quantities(&self) -> Quantities {
        self.quantities
    }

    /// Records the state `y` at time `t` unless the last sample was taken at `t`, without
    /// moving past any output time (the samples of
    /// [`SimulationSettings::sample_every_step`](super::SimulationSettings::sample_every_step)).
    pub fn record_step(
        &mut self,
        t: f64,
        y: &[f64],
        model: &Model,
        ws: &mut Workspace,
    ) -> Result<(), CoreError> {
        if self.last == Some(t) {
            return Ok(());
        }
        self.take(t, y, model, ws)
    }

    /// Takes one sample of `y` at `t`.
    fn take(
        &mut self,
        t: f64,
        y: &[f64],
        model: &Model,
        ws: &mut Workspace,
    ) -> Result<(), CoreError> {
        let q = self.quantities;
        let evals = ws.rhs_evals;
        let sample = Sample {
            t,
            nodes: q.nodes.then(|| model.nodes_of(y)),
            velocities: q.velocities.then(|| model.velocities_of(y)),
            member_forces: if q.member_forces {
                Some(model.member_forces(t, y, ws)?)
            } else {
                None
            },
            energy: q.energy.then(|| (model.kinetic_energy(y), model.energy(y))),
            contact_forces: q.contact_forces.then(|| model.contact_forces(t, y, ws)),
            contact_work: ws.contact_work,
        };
        ws.rhs_evals = evals; // diagnostics do not count as integration work
        self.samples.push(sample);
        self.last = Some(t);
        Ok(())
    }
}
