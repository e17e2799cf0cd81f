//! The runs that stream: `simulate` (the node trajectory kept in memory, as the CLI's `--out`
//! writes it) and `roll` (the CLI's observed run) — the same library calls as the command
//! line, stopping at their next step once the interrupt flag is set, with the results so far.

use crate::errors::Failure;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use tensegrity_core::request::{Categorized, Category, Request};
use tensegrity_core::CoreError;
use tensegrity_dynamics::{Sample, SampleSink};
use tensegrity_engine::simulate::{elastic, SimulateCommand};
use tensegrity_engine::value::{Map, Value};
use tensegrity_engine::SceneError;
use tensegrity_io::interrupt;
use tensegrity_io::sink::RollingOutputs;
use toroid::RollRequest;

/// The samples of a run, as the CLI's `--out` CSV holds them: times, node positions
/// (row-major: sample, node, xyz) and, where the scene records them (`[simulation] record`),
/// velocities, member forces, energies and contact forces per sample.
#[derive(Debug, Default)]
pub struct Trajectory {
    /// Sample times (s).
    pub t: Vec<f64>,
    /// Positions, 3 per node per sample (m).
    pub nodes: Vec<f64>,
    /// Nodes per sample.
    pub n_nodes: usize,
    /// Velocities, 3 per node per sample (m/s), if recorded.
    pub velocities: Vec<f64>,
    /// Axial forces per sample (N, tension positive: bars, strings, clusters), if recorded.
    pub member_forces: Vec<f64>,
    /// Members per sample.
    pub n_members: usize,
    /// Kinetic and total energy per sample (J), if recorded.
    pub energy: Vec<[f64; 2]>,
    /// The contact nodes (file numbering), if contact forces are recorded.
    pub contact_nodes: Vec<usize>,
    /// Contact forces, 3 per contact node per sample (N).
    pub contact_forces: Vec<f64>,
    /// Where the simulated time goes for a progress report (f64 bits).
    pub progress: Option<Arc<AtomicU64>>,
    last_t: f64,
}

impl SampleSink for Trajectory {
    fn accept(&mut self, sample: Sample) -> Result<(), CoreError> {
        if interrupt::requested() {
            return Err(CoreError::Interrupted { t: self.last_t });
        }
        if let Some(nodes) = &sample.nodes {
            self.n_nodes = nodes.len();
            self.t.push(sample.t);
            self.nodes
                .extend(nodes.iter().flat_map(|n| [n.x, n.y, n.z]));
            if let Some(v) = &sample.velocities {
                self.velocities
                    .extend(v.iter().flat_map(|n| [n.x, n.y, n.z]));
            }
            if let Some(f) = &sample.member_forces {
                self.n_members = f.len();
                self.member_forces.extend(f);
            }
            if let Some((kinetic, total)) = sample.energy {
                self.energy.push([kinetic, total]);
            }
            if let Some(c) = &sample.contact_forces {
                self.contact_nodes = c.iter().map(|(node, _)| *node).collect();
                self.contact_forces
                    .extend(c.iter().flat_map(|(_, f)| [f.x, f.y, f.z]));
            }
        }
        self.last_t = sample.t;
        Ok(())
    }

    fn keep_going(&mut self) -> bool {
        !interrupt::requested()
    }

    fn stop_flag(&self) -> Option<&'static std::sync::atomic::AtomicBool> {
        Some(interrupt::flag())
    }

    fn progress(&mut self, t: f64) {
        if let Some(p) = &self.progress {
            p.store(t.to_bits(), Ordering::Relaxed);
        }
    }
}

/// What a simulation gave: the report (JSON text) or the failure, and the samples so far.
pub struct SimulateOutcome {
    /// The report, or why there is none.
    pub report: Result<Value, Failure>,
    /// The samples kept (those before an interruption).
    pub trajectory: Trajectory,
    /// The run was interrupted (at this time).
    pub interrupted_at: Option<f64>,
}

/// The simulation of `values` set up as the CLI does (`trajectory`: samples kept, as with
/// `--out`), its estimate checked against `limits`; `Err` before any work.
pub fn prepare_simulation(
    values: Map<String, Value>,
    trajectory: bool,
    limits: &tensegrity_core::budget::Limits,
) -> Result<PreparedSimulation, Failure> {
    let command = SimulateCommand::from_values(values).map_err(|e| Failure::invalid(&e))?;
    let refused = |e: SceneError| match e {
        SceneError::InvalidParameter(p) => Failure::invalid(&p),
        e => Failure::new(e.category(), e.to_string()),
    };
    let scene = command
        .source()
        .map_err(|e| Failure::invalid(&e))?
        .load()
        .map_err(|e| refused(e.into()))?;
    // the run and, with `convergence_check`, its refined run: the CLI's estimate
    let (estimate, simulation) = if elastic::is_elastic(&scene) {
        let run = command.elastic(&scene, trajectory).map_err(refused)?;
        let e = run
            .estimate(command.convergence_check, false, false)
            .map_err(refused)?;
        (e, Run::Elastic(run))
    } else {
        let (_, simulation) = command
            .prepare_scene(scene.clone(), trajectory)
            .map_err(refused)?;
        let e = tensegrity_engine::simulate::estimate_checked(&command, &simulation, false, false)
            .map_err(|e| Failure::new(e.category(), e.to_string()))?;
        (e, Run::Rigid(simulation))
    };
    limits
        .check(&estimate)
        .map_err(|over| Failure::over_budget(&over))?;
    Ok(PreparedSimulation {
        command,
        scene,
        simulation,
    })
}

/// A simulation read, validated and admitted: what [`simulate`] runs.
pub struct PreparedSimulation {
    command: SimulateCommand,
    scene: tensegrity_io::scene::Scene,
    simulation: Run,
}

impl PreparedSimulation {
    /// The end time of the run (s): the total of its progress.
    pub fn t_end(&self) -> f64 {
        match &self.simulation {
            Run::Rigid(s) => s.settings.t_end,
            Run::Elastic(run) => run.settings.t_end,
        }
    }
}

/// A rigid-bar or an elastic run.
enum Run {
    Rigid(tensegrity_dynamics::Simulation),
    Elastic(elastic::ElasticRun),
}

/// Runs a prepared simulation (on the worker thread) as the CLI does: with
/// `convergence_check` its refined run beside it, the report with its `convergence`.
pub fn simulate(prepared: PreparedSimulation, progress: Option<Arc<AtomicU64>>) -> SimulateOutcome {
    let PreparedSimulation {
        command,
        scene,
        simulation,
    } = prepared;
    let mut trajectory = Trajectory {
        progress,
        ..Trajectory::default()
    };
    let source = command
        .source()
        .map(ToString::to_string)
        .unwrap_or_default();
    let failed = |e: &dyn std::fmt::Display, category: Category| {
        Failure::new(category, e.to_string()).context(&format!("simulating {source}"))
    };
    let checked = match &simulation {
        Run::Rigid(simulation) => command.run_beside(&scene, simulation, &mut trajectory),
        Run::Elastic(run) => Ok(run.run_beside(&command, &scene, &mut trajectory)),
    };
    let (report, interrupted_at) = match checked {
        Err(e) => (Err(failed(&e, e.category())), None),
        Ok(checked) => match &checked.main {
            Err(CoreError::Interrupted { t }) => (
                Err(Failure::new(Category::Interrupted, "interrupted")),
                Some(*t),
            ),
            Err(e) => (Err(failed(e, e.category())), None),
            Ok(_) => match checked.report() {
                Err(e) => (Err(failed(&e, e.category())), None),
                Ok(report) => {
                    let strict = command
                        .strict_check(&report)
                        .map_err(|e| Failure::new(e.category(), e.to_string()));
                    (strict.and(conventional_json(&report)), None)
                }
            },
        },
    };
    SimulateOutcome {
        report,
        trajectory,
        interrupted_at,
    }
}

/// The columns of a rolling history, as the CLI's `roll --out` CSV names them.
pub const HISTORY_COLUMNS: [&str; 9] = [
    "t",
    "axle_s",
    "axle_h",
    "omega",
    "pivot_m",
    "normal_N",
    "tangential_N",
    "energy_J",
    "slip_m_s",
];

/// The observer of a rolling run from Python: every sample kept as a history row
/// ([`HISTORY_COLUMNS`]), everything else handed to the run's outputs.
pub struct History<'a> {
    outputs: RollingOutputs<'a>,
    rows: Vec<[f64; 9]>,
    /// Where the simulated time goes for a progress report (f64 bits).
    progress: Option<Arc<AtomicU64>>,
}

impl<'a> History<'a> {
    /// An observer keeping every sample, handing everything to `outputs`; `progress`: where
    /// the simulated time goes.
    pub fn new(outputs: RollingOutputs<'a>, progress: Option<Arc<AtomicU64>>) -> Self {
        Self {
            outputs,
            rows: Vec::new(),
            progress,
        }
    }

    /// The rows kept so far (taken out).
    pub fn take_rows(&mut self) -> Vec<[f64; 9]> {
        std::mem::take(&mut self.rows)
    }
}

impl wheel_rolling::Observer for History<'_> {
    fn sample(&mut self, s: &wheel_rolling::RollingSample) -> wheel_rolling::Flow {
        self.rows.push([
            s.t,
            s.s,
            s.h,
            s.omega,
            s.pivot,
            s.normal,
            s.tangential,
            s.energy,
            s.slip,
        ]);
        if let Some(p) = &self.progress {
            p.store(s.t.to_bits(), Ordering::Relaxed);
        }
        self.outputs.sample(s)
    }

    fn frame(&mut self, frame: &wheel_rolling::WheelFrame) -> wheel_rolling::Flow {
        self.outputs.frame(frame)
    }

    fn keep_going(&mut self) -> bool {
        self.outputs.keep_going()
    }

    fn stop_flag(&self) -> Option<&'static std::sync::atomic::AtomicBool> {
        self.outputs.stop_flag()
    }

    fn keeps_frames(&self) -> bool {
        self.outputs.keeps_frames()
    }
}

/// What a rolling run gave: the report (JSON text, also when interrupted or stopped by its
/// integration: the partial run's, as the CLI prints it), its history and how it ended.
pub struct RollOutcome {
    /// The report.
    pub report: Result<Value, Failure>,
    /// Every sample, a row of [`HISTORY_COLUMNS`] (those before a stop).
    pub history: Vec<[f64; 9]>,
    /// Why the run is incomplete: interrupted, or stopped by its integration (the CLI's exit
    /// 1 message).
    pub incomplete: Option<Failure>,
}

/// The request of `roll` (a bad value refused before any work; under `fidelity = "rigid"` a
/// setting only the full model reads is refused when given, as on the command line).
pub fn roll_request(values: Map<String, Value>) -> Result<RollRequest, Failure> {
    let given: Vec<String> = values.keys().cloned().collect();
    let request = RollRequest::from_values(values).map_err(|e| Failure::invalid(&e))?;
    request
        .check_rigid_given(|name| given.iter().any(|g| g == name))
        .map_err(|e| Failure::invalid(&e))?;
    Ok(request)
}

/// Runs `roll` as the CLI does: observed, stopping on the interrupt flag (on the worker
/// thread).
pub fn roll(request: RollRequest, progress: Option<Arc<AtomicU64>>) -> RollOutcome {
    let mut observer = History {
        outputs: RollingOutputs::new(None, None),
        rows: Vec::new(),
        progress,
    };
    let run = toroid::roll_observed(&request, &[], Some(&mut observer));
    let interrupted = interrupt::requested();
    let history = std::mem::take(&mut observer.rows);
    let mut report = match run {
        Ok(r) => r,
        Err(e) => {
            return RollOutcome {
                report: Err(Failure::new(e.category(), e.to_string())),
                history,
                incomplete: None,
            }
        }
    };
    report.frames = observer.outputs.take_frames();
    let incomplete = match (report.summary.stopped_at, interrupted) {
        (Some(_), true) => Some(Failure::new(Category::Interrupted, "interrupted")),
        (Some(t), false) => Some(Failure::new(
            Category::Numerical,
            format!(
                "the integration stopped at t = {t} s of `t_end` {} s: the results above cover [0, {t}] s only (see the warnings)",
                report.t_end
            ),
        )),
        (None, _) => None,
    };
    let json = conventional_json(&report);
    RollOutcome {
        report: json,
        history,
        incomplete,
    }
}

/// A report as the engine's value tree with the conventional keys beside its own (as the
/// CLI's `--json`: [`tensegrity_engine::keys`]).
fn conventional_json(report: &impl serde::Serialize) -> Result<Value, Failure> {
    let failure =
        |e: tensegrity_engine::value::Error| Failure::new(Category::Numerical, e.to_string());
    let value = tensegrity_engine::value::to_value(report).map_err(failure)?;
    Ok(tensegrity_engine::keys::conventional(value))
}
