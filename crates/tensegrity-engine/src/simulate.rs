//! `simulate`: a scene run in time ([`SimulateCommand`], a request named `simulate`) — the
//! scene's `[simulation]`, `[ground]` and `[[actuation]]` tables
//! ([`tensegrity_io::scene::build_simulation`]) under the request's overrides, one
//! [`Simulation`] run, its [`SimulationReport`].
//!
//! The overrides ([`SimulateCommand::apply`]): `t_end`, `integrator`, `dt`, `rtol`, `atol`
//! replace the scene's values; with no `dt` anywhere an adaptive integrator (rk45, sdirk) is
//! unbounded below t_end (dt = t_end) and a fixed-step one takes its [`default_step`] (rk4,
//! rattle, rk4-flight 1 ms, imex 0.5 ms, imex-ark 0.25 ms), shortened to the output
//! interval; when samples are written (a front end's trajectory or VTK output) the node
//! positions are recorded every `output_interval` (default: the scene's output times, else
//! t_end / 200, no finer than a step given). A fixed step given (by the request or the
//! scene) longer than the output interval is refused naming `dt`: the driver cuts its steps
//! at the sample times, so it would not be the step that runs. The contact integrators
//! (imex, imex-ark, rk4-flight) project onto the constraints after every step
//! ([`contact_integrator`]). A `strict` run whose invariants drifted past their limits fails
//! ([`SceneError::Strict`]) after its outputs are written.
//!
//! The convergence check ([`SimulateCommand::run_beside`]) runs the scene again beside the
//! run, in a second thread, at another resolution ([`companion`]): a fixed step times 4, or
//! 2, where that step stays well inside the method's stability (a coarse companion, a quarter
//! or half of the run's work; one at 4 dt that finds a quantity past its tolerance followed by
//! one at 2 dt), else halved ([`SimulateCommand::refine`], twice the work; an adaptive
//! integrator's tolerances divided by 10), a coarse run that fails followed by the refined
//! one. It
//! compares the final states on the problem's absolute [`Scales`]: the final nodes against
//! the structure's size L, the final velocities against the largest of the final and initial
//! speeds and √(|g| L), at least 1 mm/s ([`SimulateCommand::convergence`]), so that a
//! structure come to rest under gravity (final speeds of millimetres per second) is not judged
//! on the noise of its own speeds; each change is extrapolated to the run's error with the
//! documented order ([`companion::documented_order`]) and the cost of the check is stated
//! (`convergence.cost`).
//!
//! Its resource estimate ([`estimate`], [`tensegrity_dynamics::estimate::simulation`]): the steps t_end / dt (a
//! fixed step lands on every output time, an adaptive run takes at least as many), the
//! right-hand sides per step of the integrator, the samples streamed and, when written, their
//! bytes (~25 a number in CSV, ~40 in VTK).
//!
//! ```
//! use tensegrity_core::request::Request;
//! use tensegrity_engine::simulate::{simulate, SimulateCommand};
//! let c = SimulateCommand::from_values([
//!     ("scene", serde_json::json!("../../examples/double_pendulum.toml")),
//!     ("t_end", serde_json::json!(0.1)),
//! ])?;
//! let r = simulate(&c)?;
//! assert_eq!(r.t_end, 0.1);
//! assert!(r.bar_length_drift < 1e-8);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::scene::{required, SceneError, SceneSource};
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicBool, Ordering};
use tensegrity_core::budget::Estimate;
use tensegrity_core::request::{InvalidParameter, Request, RunChecks};
use tensegrity_core::CoreError;
use tensegrity_derive::Params;
use tensegrity_dynamics::convergence::Companion;
use tensegrity_dynamics::recorder::{Sample, SampleSink};
use tensegrity_dynamics::Simulation;
use tensegrity_dynamics::{
    Convergence, IntegratorKind, SimulationReport, SimulationResult, SimulationSettings,
};
use tensegrity_io::scene::{Scene, SimulationSpec};

pub mod companion;
pub mod elastic;
pub mod stepped;
use companion::Refined;

/// Samples per run when the scene names no output times and no interval is given.
pub const DEFAULT_SAMPLES: f64 = 200.0;

/// Default step of `rk4`, `rattle` and `rk4-flight` (its contact step) when neither the
/// request nor the scene gives `dt` (s).
pub const DEFAULT_DT: f64 = 1e-3;
/// Default step of `imex` (s): the split IMEX's in the full rolling model
/// (`wheel_rolling::defaults::IMEX_ROLL_DT`); on `examples/prism_drop.toml` for 3 s its final
/// nodes hold at half the step (1 ms: they move 1.1 %), but the landed prism's feet creep and
/// chatter there (20 % of the contact steps: a `creep_chatter` warning, not valid; use
/// `imex-ark`).
pub const DEFAULT_DT_IMEX: f64 = 5e-4;
/// Default step of `imex-ark` (s): the full rolling model's
/// (`wheel_rolling::defaults::IMEX_ARK_ROLL_DT`: on the creeping pivot its stage equations
/// stall more often at longer steps); a valid run of `examples/prism_drop.toml` for 3 s (its
/// final nodes move 0.05 % of the prism's size at half the step; 1 ms is valid there too,
/// 0.16 %).
pub const DEFAULT_DT_IMEX_ARK: f64 = 2.5e-4;

/// The step of a fixed-step integrator when neither the request nor the scene gives `dt`
/// (s): [`DEFAULT_DT`] for `rk4`, `rattle` and `rk4-flight`, [`DEFAULT_DT_IMEX`],
/// [`DEFAULT_DT_IMEX_ARK`]; `None` for the adaptive ones (their largest step is then
/// t_end). A front end shortens it to the output interval ([`SimulateCommand::apply`]).
///
/// ```
/// use tensegrity_dynamics::IntegratorKind;
/// use tensegrity_engine::simulate::default_step;
/// assert_eq!(default_step(IntegratorKind::Rk4), Some(1e-3));
/// assert_eq!(default_step(IntegratorKind::ImexArk), Some(2.5e-4));
/// assert_eq!(default_step(IntegratorKind::Sdirk), None);
/// ```
pub fn default_step(kind: IntegratorKind) -> Option<f64> {
    match kind {
        IntegratorKind::Rk4
        | IntegratorKind::Rattle
        | IntegratorKind::Rk4Flight
        | IntegratorKind::Newmark => Some(DEFAULT_DT),
        IntegratorKind::Imex => Some(DEFAULT_DT_IMEX),
        IntegratorKind::ImexArk => Some(DEFAULT_DT_IMEX_ARK),
        IntegratorKind::Rk45 | IntegratorKind::Sdirk => None,
    }
}

/// The contact integrators (`imex`, `imex-ark`, `rk4-flight`): their explicit part drifts
/// the bar lengths as RK4 does, so `simulate` projects their states onto the constraints
/// after every step, as the full rolling model runs them.
pub fn contact_integrator(kind: IntegratorKind) -> bool {
    matches!(
        kind,
        IntegratorKind::Imex | IntegratorKind::ImexArk | IntegratorKind::Rk4Flight
    )
}

/// Who gave the step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum StepSource {
    Request,
    Scene,
}

/// Who gave the output interval.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum IntervalSource {
    Request,
    Scene,
}

/// A scene run in time, as data: every field unset keeps the scene's value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct SimulateCommand {
    /// The scene: a TOML file, or its text (required).
    #[param(
        text,
        help = "The scene file (TOML) with an optional `[simulation]`, `[ground]`, `[[actuation]]`, or the scene's TOML text",
        required
    )]
    pub scene: Option<SceneSource>,
    /// End time (s); overrides `[simulation] t_end`.
    #[param(
        number,
        unit = "s",
        help = "End time; overrides `[simulation] t_end`",
        positive,
        optional
    )]
    pub t_end: Option<f64>,
    /// Integrator; overrides `[simulation] integrator`.
    #[param(choice = IntegratorKind::NAMES, help = "Integrator; overrides `[simulation] integrator` (default rk4): fixed-step RK4, adaptive RK45, constraint-preserving RATTLE, adaptive L-stable SDIRK for stiff strings and contact, IMEX (penalty contact split off, linearly implicit), IMEX-ARK (penalty contact implicit in every stage), RK4-flight (RK4, 5x longer steps while no contact node is near the ground); imex, imex-ark and rk4-flight project onto the constraints after every step; an elastic scene takes rk4, rk45 or newmark (implicit trapezoidal rule, stable at any step)", optional)]
    pub integrator: Option<IntegratorKind>,
    /// Fixed step (rk4, rattle, imex, imex-ark; the contact step of rk4-flight) or largest
    /// step (rk45, sdirk), s; unset: the scene's, else [`default_step`].
    #[param(
        number,
        unit = "s",
        help = "Fixed step, at most the output interval (default: rk4, rattle and rk4-flight 1e-3, imex 5e-4, imex-ark 2.5e-4, shortened to the output interval; rk4-flight's contact step, 5x in flight) or maximum step (rk45, sdirk; default t_end)",
        positive,
        optional
    )]
    pub dt: Option<f64>,
    /// Relative tolerance (rk45, sdirk).
    #[param(number, help = "Relative tolerance (rk45, sdirk)", positive, optional)]
    pub rtol: Option<f64>,
    /// Absolute tolerance (rk45, sdirk).
    #[param(number, help = "Absolute tolerance (rk45, sdirk)", positive, optional)]
    pub atol: Option<f64>,
    /// Sampling interval of the written samples (s).
    #[param(
        number,
        unit = "s",
        help = "Sampling interval of the written trajectory; default: the scene's output times, else t_end/200",
        positive,
        optional
    )]
    pub output_interval: Option<f64>,
    /// Fail when the run has a drift warning (or an unconverged final state).
    #[param(
        flag,
        help = "Fail (after writing the outputs) when the run has a drift warning or its final state did not converge"
    )]
    pub strict: bool,
    /// Re-run at a companion resolution beside the run (4 dt or 2 dt where that stays stable,
    /// else refined: [`companion`]) and report the final state's change, its extrapolated error and
    /// the check's cost in `convergence`.
    #[param(flag, help = RunChecks::CONVERGENCE_CHECK_HELP)]
    pub convergence_check: bool,
}

impl Default for SimulateCommand {
    /// Every override unset, not strict, convergence checked.
    fn default() -> Self {
        Self {
            scene: None,
            t_end: None,
            integrator: None,
            dt: None,
            rtol: None,
            atol: None,
            output_interval: None,
            strict: false,
            convergence_check: true,
        }
    }
}

impl Request for SimulateCommand {
    const NAME: &'static str = "simulate";
}

impl SimulateCommand {
    /// The scene (required).
    pub fn source(&self) -> Result<&SceneSource, InvalidParameter> {
        required(&self.scene)
    }

    /// Lays the overrides over the scene's settings (module docs); `file` is the scene's
    /// `[simulation]` table, `written` whether samples are written. A scene without `t_end`
    /// needs the request's. The step: the request's `dt`, else the scene's, else the
    /// integrator's [`default_step`] (no finer than the output interval); a given step of a
    /// fixed-step integrator longer than the output interval is refused (module docs).
    pub fn apply(
        &self,
        s: &mut SimulationSettings,
        file: Option<&SimulationSpec>,
        written: bool,
    ) -> Result<(), InvalidParameter> {
        match (self.t_end, file) {
            (Some(t), _) => s.t_end = t,
            (None, Some(_)) => {}
            (None, None) => {
                return Err(InvalidParameter::raw(
                    "t_end",
                    "(unset)",
                    "the scene has no `[simulation] t_end`: give the end time",
                ))
            }
        }
        if let Some(i) = self.integrator {
            s.integrator = i;
        }
        let given = match (self.dt, file.and_then(|x| x.dt)) {
            (Some(dt), _) => Some((dt, StepSource::Request)),
            (None, Some(dt)) => Some((dt, StepSource::Scene)),
            (None, None) => None,
        };
        // no step given anywhere: the integrator's own (adaptive: unbounded below t_end)
        s.dt = given.map_or_else(|| default_step(s.integrator).unwrap_or(s.t_end), |g| g.0);
        if contact_integrator(s.integrator) {
            s.project = true;
        }
        s.rtol = self.rtol.unwrap_or(s.rtol);
        s.atol = self.atol.unwrap_or(s.atol);
        // the request's interval applies to the samples written; the scene's always
        let mut interval = s
            .output_interval
            .map(|dt_out| (dt_out, IntervalSource::Scene));
        if written {
            s.quantities.nodes = true;
            if let Some(dt_out) = self.output_interval {
                s.output_interval = Some(dt_out);
                interval = Some((dt_out, IntervalSource::Request));
            } else if s.output_times.is_empty() && s.output_interval.is_none() {
                // the default sampling, no finer than a step given
                let dt_out = s.t_end / DEFAULT_SAMPLES;
                s.output_interval = Some(given.map_or(dt_out, |g| dt_out.max(g.0)));
            }
        }
        Self::check_step(s, given, interval)
    }

    /// The step against the output interval: a fixed step (and the contact step of
    /// `rk4-flight`) is cut at every sample time, so a step given (by the request or the
    /// scene) longer than the interval would not be the step that runs, and the convergence
    /// check's half step would refine nothing: refused, naming `dt` and where the interval
    /// comes from. The default step is shortened to the interval instead. Adaptive
    /// integrators sample their dense output: their largest step may exceed it.
    fn check_step(
        s: &mut SimulationSettings,
        given: Option<(f64, StepSource)>,
        interval: Option<(f64, IntervalSource)>,
    ) -> Result<(), InvalidParameter> {
        let Some(dt_out) = s.output_interval else {
            return Ok(());
        };
        if s.integrator.is_adaptive() || !(dt_out > 0.0 && s.dt > dt_out * (1.0 + 1e-9)) {
            return Ok(());
        }
        let Some((dt, source)) = given else {
            // (an interval too fine for `max_steps` keeps the step: the run's estimate, which
            // counts its steps at the interval, refuses it by its size)
            if (s.t_end / dt_out).ceil() <= s.max_steps as f64 {
                s.dt = dt_out;
            }
            return Ok(());
        };
        let of = match interval.map(|i| i.1) {
            Some(IntervalSource::Scene) => "the scene's `[simulation] output_interval`",
            _ => "`output_interval`",
        };
        let which = match source {
            StepSource::Request => "must not exceed",
            StepSource::Scene => "(the scene's `[simulation] dt`) must not exceed",
        };
        Err(InvalidParameter::new(
            "dt",
            dt,
            format!(
                "{which} the output interval {dt_out} s ({of}): a fixed step is cut at every \
                 sample time, so a longer one is not the step that runs; give a `dt` of at \
                 most {dt_out} s, or a longer output interval"
            ),
        ))
    }

    /// The runnable simulation of a scene already read, under the overrides.
    pub fn simulation(&self, scene: &Scene, written: bool) -> Result<Simulation, SceneError> {
        let mut simulation = scene.simulation()?;
        self.apply(
            &mut simulation.settings,
            scene.file.simulation.as_ref(),
            written,
        )?;
        Ok(simulation)
    }

    /// Reads the scene and sets up its run under the overrides (`written`: samples are
    /// written), the scene kept (its structure labels the outputs).
    pub fn prepare(&self, written: bool) -> Result<(Scene, Simulation), SceneError> {
        self.prepare_scene(self.source()?.load()?, written)
    }

    /// [`SimulateCommand::prepare`] of a scene already read (a rigid one: an elastic scene
    /// runs through [`SimulateCommand::elastic`]; its keys are refused here).
    pub fn prepare_scene(
        &self,
        scene: Scene,
        written: bool,
    ) -> Result<(Scene, Simulation), SceneError> {
        crate::scene::refuse_path_keys(&scene, "simulate")?;
        elastic::refuse_elastic_keys_of_rigid_run(&scene, "simulate (rigid bars)")?;
        let simulation = self.simulation(&scene, written)?;
        Ok((scene, simulation))
    }

    /// The `strict` rule: a run with drift warnings is an error.
    pub fn strict_check(&self, report: &SimulationReport) -> Result<(), SceneError> {
        if self.strict && !report.warnings.is_empty() {
            return Err(SceneError::Strict {
                warnings: report.warnings.clone(),
            });
        }
        Ok(())
    }
}

/// A sink that keeps no sample and stops the run once `.0` is set (the companion run of a run
/// that failed or was interrupted) or the run's sink's [`SampleSink::stop_flag`] `.1` is (a
/// Ctrl-C during a companion run after the run).
struct StopWhen<'a>(&'a AtomicBool, Option<&'static AtomicBool>);

impl SampleSink for StopWhen<'_> {
    fn accept(&mut self, _: Sample) -> Result<(), CoreError> {
        Ok(())
    }

    fn keep_going(&mut self) -> bool {
        !self.0.load(Ordering::Relaxed) && !self.1.is_some_and(|f| f.load(Ordering::Relaxed))
    }
}

/// A sink that keeps no sample (a run whose samples nobody writes).
struct Discard;

impl SampleSink for Discard {
    fn accept(&mut self, _: Sample) -> Result<(), CoreError> {
        Ok(())
    }
}

/// Runs `simulate` without writing samples: reads the scene, runs it (beside its companion
/// run with `convergence_check`), its report (an error under `strict` with drift warnings or an
/// unconverged final state).
pub fn simulate(command: &SimulateCommand) -> Result<SimulationReport, SceneError> {
    let scene = command.source()?.load()?;
    if elastic::is_elastic(&scene) {
        let run = command.elastic(&scene, false)?;
        let report = run.run_checked(command, &scene, &mut Discard)?;
        command.strict_check(&report)?;
        return Ok(report);
    }
    let (scene, simulation) = command.prepare_scene(scene, false)?;
    let report = command.run_checked(&scene, &simulation, &mut Discard)?;
    command.strict_check(&report)?;
    Ok(report)
}

/// Tolerance of the final node positions (relative to the structure's size).
pub const CONVERGENCE_NODES: f64 = 1e-2;
/// Tolerance of the final velocities (relative to the speed scale of the run, [`Scales`]).
pub const CONVERGENCE_VELOCITIES: f64 = 2e-2;
/// The smallest length scale (m) and speed scale (m/s) of the convergence check.
pub const SCALE_FLOOR: (f64, f64) = (1e-3, 1e-3);

/// The absolute scales the final state of a run is judged against (module docs): a length,
/// the structure's size L (the largest distance of a node from the centroid, at the start or
/// at the end, at least 1 mm), and a speed V, the largest of the run's final and initial
/// speeds and √(|g| L) (the speed of a fall through its own size), at least 1 mm/s
/// ([`SCALE_FLOOR`]). A structure that comes to rest has final speeds near zero: their
/// change between two runs is noise against themselves and is judged against V instead.
/// (Without gravity nor initial speeds, V is the final speeds' own, at least 1 mm/s.)
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// The structure's size L (m).
    pub length: f64,
    /// The speed scale V (m/s), before the final speeds of the two runs are taken in.
    pub speed: f64,
}

/// The largest distance of a point from their centroid (0 for none).
fn radius(points: &[[f64; 3]]) -> f64 {
    let n = points.len().max(1) as f64;
    let c = points.iter().fold([0.0; 3], |s, p| {
        [s[0] + p[0] / n, s[1] + p[1] / n, s[2] + p[2] / n]
    });
    points.iter().map(|p| distance(p, &c)).fold(0.0, f64::max)
}

fn distance(p: &[f64; 3], q: &[f64; 3]) -> f64 {
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

/// The largest distance between corresponding points of two lists.
fn gap(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| distance(p, q))
        .fold(0.0, f64::max)
}

/// The largest length of a list of vectors.
fn largest(v: &[[f64; 3]]) -> f64 {
    v.iter().map(|p| distance(p, &[0.0; 3])).fold(0.0, f64::max)
}

impl Scales {
    /// The scales of a run of `scene` (the size and the speeds at the end are taken in by
    /// [`SimulateCommand::convergence`]).
    pub fn of(scene: &Scene) -> Self {
        let s = &scene.structure;
        let nodes: Vec<[f64; 3]> = s.nodes().iter().map(|p| [p.x, p.y, p.z]).collect();
        let length = radius(&nodes).max(SCALE_FLOOR.0);
        let v0: Vec<[f64; 3]> = s
            .velocities()
            .unwrap_or_default()
            .iter()
            .map(|v| [v.x, v.y, v.z])
            .collect();
        let g = s.gravity().map_or(0.0, |g| g.norm());
        let speed = largest(&v0).max((g * length).sqrt()).max(SCALE_FLOOR.1);
        Self { length, speed }
    }
}

impl SimulateCommand {
    /// The refined resolution of `settings`: a fixed step halved; an adaptive integrator's
    /// tolerances divided by 10 and its largest step halved. Returns what changed.
    pub fn refine(settings: &mut SimulationSettings) -> &'static str {
        settings.dt *= 0.5;
        if settings.integrator.is_adaptive() {
            settings.rtol *= 0.1;
            settings.atol *= 0.1;
            "rtol/10, atol/10, largest step/2"
        } else {
            "dt/2"
        }
    }

    /// The convergence of a run's final state against its companion run's, filled into
    /// `conv` (empty, with its companion and order: [`companion`]), on the absolute `scales`
    /// of the problem ([`Scales`]): the largest distance between their final nodes against
    /// the structure's size (the larger of `scales.length` and the final nodes' radius) within
    /// [`CONVERGENCE_NODES`], the largest difference of their final velocities against the
    /// larger of the two runs' largest final speed and `scales.speed` within
    /// [`CONVERGENCE_VELOCITIES`], each change extrapolated to an error with `conv`'s order.
    pub fn convergence(
        main: &SimulationReport,
        other: &SimulationReport,
        mut conv: Convergence,
        scales: Scales,
    ) -> Convergence {
        let size = radius(&main.final_nodes).max(scales.length);
        let speed = largest(&main.final_velocities).max(largest(&other.final_velocities));
        conv.compare_change(
            "final_nodes",
            gap(&main.final_nodes, &other.final_nodes),
            size,
            scales.length,
            CONVERGENCE_NODES,
        )
        .compare_change(
            "final_velocities",
            gap(&main.final_velocities, &other.final_velocities),
            speed,
            scales.speed,
            CONVERGENCE_VELOCITIES,
        );
        conv
    }

    /// Runs `simulation` (of `scene`, under this command) into `sink`, and with
    /// `convergence_check` its companion run ([`companion`]) beside it in a second thread:
    /// the report with its `convergence` and a warning per unconverged quantity.
    pub fn run_checked(
        &self,
        scene: &Scene,
        simulation: &Simulation,
        sink: &mut dyn SampleSink,
    ) -> Result<SimulationReport, SceneError> {
        Ok(self.run_beside(scene, simulation, sink)?.report()?)
    }

    /// The run into `sink` and, with `convergence_check`, its companion run beside it (the
    /// scene is read again for it: a second, independent model): at 4 dt or 2 dt where that
    /// serves ([`companion::choose`]), and where that coarse run fails the refined one after it
    /// on the same thread; else the refined one ([`SimulateCommand::refine`]). A 4 dt companion
    /// that finds a quantity past its tolerance is followed by one at 2 dt after the run, whose
    /// verdict stands ([`companion`], "A 4 dt estimate past its tolerance").
    pub fn run_beside(
        &self,
        scene: &Scene,
        simulation: &Simulation,
        sink: &mut dyn SampleSink,
    ) -> Result<Checked, SceneError> {
        let scales = Scales::of(scene);
        if !self.convergence_check {
            let main = simulation.run_streaming(sink);
            return Ok(Checked {
                main,
                companion: None,
                scales,
            });
        }
        let kind = simulation.settings.integrator;
        let order = companion::documented_order(kind, companion::smooth(scene, simulation));
        // coarse where 4 dt or 2 dt serves (else why 2 dt does not), the refined run in reserve
        let chosen = companion::choose(simulation);
        let refused = match chosen {
            Companion::Refined => companion::coarse_refused(simulation),
            _ => None,
        };
        // the companions start from the run's step: a default step shortened to the written
        // samples' interval is not the one a run that writes nothing would take
        let companion_of = |c: &mut Simulation| c.settings.dt = simulation.settings.dt;
        let coarse = match refused {
            None => {
                let mut c = self.simulation(scene, false)?;
                companion_of(&mut c);
                companion::coarsen(&mut c.settings, chosen);
                Some(c)
            }
            Some(_) => None,
        };
        let mut fine = self.simulation(scene, false)?;
        companion_of(&mut fine);
        let what = Self::refine(&mut fine.settings);
        let stop = AtomicBool::new(false);
        let external = sink.stop_flag();
        let checked = std::thread::scope(|s| {
            let stop = &stop;
            let handle = s.spawn(move || {
                let mut watch = StopWhen(stop, external);
                let mut failed = String::new();
                if let Some(coarse) = coarse {
                    let result = coarse.run_streaming(&mut watch);
                    match companion::coarse_failure(&result) {
                        // (the run failed: nothing is compared, nothing more to run)
                        Some(why) if !stop.load(Ordering::Relaxed) => failed = why,
                        _ => {
                            return CompanionRun {
                                convergence: companion::coarse(order, chosen),
                                result,
                            }
                        }
                    }
                }
                let why = match &refused {
                    Some(_) if kind.is_adaptive() => Refined::Adaptive,
                    Some(why) => Refined::Refused(why),
                    // 4 dt or 2 dt served, and its run failed
                    None => Refined::AfterCoarse(chosen, &failed),
                };
                let convergence = companion::refined(what, order, why);
                CompanionRun {
                    convergence,
                    result: fine.run_streaming(&mut watch),
                }
            });
            let main = simulation.run_streaming(sink);
            // a run that failed (or was interrupted) is not compared: stop the companion
            stop.store(main.is_err(), Ordering::Relaxed);
            let companion = handle
                .join()
                .unwrap_or_else(|p| std::panic::resume_unwind(p));
            Checked {
                main,
                companion: Some(companion),
                scales,
            }
        });
        self.escalated(scene, simulation, checked, external)
    }

    /// `checked` whose 4 dt companion finds a quantity past its tolerance, checked again
    /// against the companion at 2 dt, whose verdict stands ([`companion`], "A 4 dt estimate
    /// past its tolerance"); any other `checked` as it is. The run at 2 dt stops once
    /// `stop_flag` is set (the run's sink's [`SampleSink::stop_flag`]).
    fn escalated(
        &self,
        scene: &Scene,
        simulation: &Simulation,
        checked: Checked,
        stop_flag: Option<&'static AtomicBool>,
    ) -> Result<Checked, SceneError> {
        let (Ok(main), Some(run)) = (&checked.main, &checked.companion) else {
            return Ok(checked);
        };
        let (Companion::Coarser, Ok(other)) = (run.convergence.companion, &run.result) else {
            return Ok(checked);
        };
        let judged = Self::convergence(
            &SimulationReport::from(main),
            &SimulationReport::from(other),
            run.convergence.clone(),
            checked.scales,
        );
        if judged.converged {
            return Ok(checked);
        }
        let past: Vec<&str> = judged
            .quantities
            .iter()
            .filter(|q| !q.converged)
            .map(|q| q.name.as_str())
            .collect();
        let mut coarse = self.simulation(scene, false)?;
        coarse.settings.dt = simulation.settings.dt;
        companion::coarsen(&mut coarse.settings, Companion::Coarse);
        let result = coarse.run_streaming(&mut StopWhen(&AtomicBool::new(false), stop_flag));
        if let Some(why) = companion::coarse_failure(&result) {
            // the 4 dt verdict stands, its label saying that the run at 2 dt failed
            let mut checked = checked;
            if let Some(run) = checked.companion.as_mut() {
                run.convergence.refinement = format!(
                    "{}; the run at 2 dt after it failed: {why}",
                    run.convergence.refinement
                );
                run.convergence.cost += Companion::Coarse.cost();
            }
            return Ok(checked);
        }
        let mut convergence = companion::coarse(judged.order, Companion::Coarse);
        convergence.refinement = format!(
            "2 dt (coarse companion, run after the one at 4 dt found {} past its tolerance)",
            past.join(", ")
        );
        convergence.cost += Companion::Coarser.cost();
        Ok(Checked {
            companion: Some(CompanionRun {
                convergence,
                result,
            }),
            ..checked
        })
    }
}

/// The resource estimate of the run of `simulation` under `command` ([`estimate`]), and
/// with `convergence_check` its companion run's ([`companion::choose`]): ¼ or ½ the run's
/// work for a coarse companion at 4 dt or 2 dt, 2 for a refined one (an adaptive run's
/// tolerances / 10 cost 10^(1/5) ≈ 1.6 times the steps of a fifth-order pair, 10^(1/3) ≈ 2.2
/// of SDIRK's third order: about twice too). A coarse companion that fails and is followed by
/// the refined one, or one at 4 dt followed by one at 2 dt, is not foreseen.
pub fn estimate_checked(
    command: &SimulateCommand,
    simulation: &Simulation,
    csv: bool,
    vtk: bool,
) -> Result<Estimate, CoreError> {
    let e = estimate(simulation, csv, vtk)?;
    if !command.convergence_check {
        return Ok(e);
    }
    // the companion writes nothing and shares the run's description
    let cost = companion::choose(simulation).cost();
    Ok(Estimate {
        work_s: (1.0 + cost) * e.work_s,
        ..e
    })
}

/// The companion run of a convergence check: the comparison it is for (empty: its
/// refinement, companion, order and cost) and its result.
#[derive(Debug)]
pub struct CompanionRun {
    /// The empty comparison ([`companion`]), filled by [`Checked::report`].
    pub convergence: Convergence,
    /// The companion run's result.
    pub result: Result<SimulationResult, CoreError>,
}

/// A run and its companion run ([`SimulateCommand::run_beside`]).
#[derive(Debug)]
pub struct Checked {
    /// The run (its error, an interrupt included, as the core gave it).
    pub main: Result<SimulationResult, CoreError>,
    /// The companion run; `None` when not checked.
    pub companion: Option<CompanionRun>,
    /// The absolute scales the final state is judged against ([`Scales`]).
    pub scales: Scales,
}

impl Checked {
    /// The run's report, with the convergence of its final state and a warning per
    /// unconverged quantity (or for a companion run that failed).
    pub fn report(self) -> Result<SimulationReport, CoreError> {
        let mut report = SimulationReport::from(&self.main?);
        let convergence = match self.companion {
            None => return Ok(report),
            Some(CompanionRun {
                convergence,
                result: Ok(other),
            }) => SimulateCommand::convergence(
                &report,
                &SimulationReport::from(&other),
                convergence,
                self.scales,
            ),
            Some(CompanionRun {
                mut convergence,
                result: Err(e),
            }) => {
                // (a coarse companion that fails is followed by the refined one, and one at
                // 4 dt past a tolerance by one at 2 dt: this is it)
                let which = match convergence.companion {
                    Companion::Refined => "refined",
                    _ => "coarse",
                };
                convergence.refinement =
                    format!("{}: the {which} run failed: {e}", convergence.refinement);
                convergence.converged = false;
                convergence
            }
        };
        report.warnings.extend(convergence.warnings());
        report.valid = report.warnings.is_empty();
        report.convergence = Some(convergence);
        Ok(report)
    }
}

/// The resource estimate of a run (module docs), after the core's check of its settings (a
/// fixed step that cannot finish is refused here); `csv`, `vtk`: the samples written. Named
/// `t_end = …, dt = …` (and the output interval).
pub fn estimate(simulation: &Simulation, csv: bool, vtk: bool) -> Result<Estimate, CoreError> {
    simulation.validate()?;
    let s = &simulation.settings;
    let mut parameter = format!("t_end = {} s, dt = {} s", s.t_end, s.dt);
    if let Some(dt_out) = s.output_interval {
        parameter.push_str(&format!(", output interval {dt_out} s"));
    }
    let bytes_per_number = 25.0 * f64::from(u8::from(csv)) + 40.0 * f64::from(u8::from(vtk));
    Ok(tensegrity_dynamics::estimate::simulation(
        simulation,
        true,
        csv || vtk,
        bytes_per_number,
        parameter,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;
    use tensegrity_core::request::check_description;

    const SCENE: &str = "../../examples/double_pendulum.toml";

    #[test]
    fn the_request_describes_its_fields() {
        check_description::<SimulateCommand>().unwrap();
        let c = SimulateCommand::from_values([
            ("scene", json!(SCENE)),
            ("integrator", json!("sdirk")),
            ("dt", json!("1e-3")),
        ])
        .unwrap();
        assert_eq!(
            (c.integrator, c.dt),
            (Some(IntegratorKind::Sdirk), Some(1e-3))
        );
        let e = SimulateCommand::from_values([("scene", json!(SCENE)), ("dt", json!("nan"))])
            .unwrap_err();
        assert_eq!(e.name, "dt");
    }

    #[test]
    fn overrides_replace_the_scene_and_outputs_sample_the_nodes() {
        let scene = SceneSource::parse(SCENE).load().unwrap();
        let file = scene.file.simulation.as_ref();
        let c = SimulateCommand {
            t_end: Some(2.0),
            integrator: Some(IntegratorKind::Rk45),
            ..Default::default()
        };
        let mut s = SimulationSettings::default();
        c.apply(&mut s, file, true).unwrap();
        assert_eq!((s.t_end, s.integrator), (2.0, IntegratorKind::Rk45));
        assert!(s.quantities.nodes);
        // no scene table at all: the end time must be given
        let e = SimulateCommand::default()
            .apply(&mut SimulationSettings::default(), None, false)
            .unwrap_err();
        assert_eq!(e.name, "t_end");
        // an adaptive run without any dt is unbounded below t_end
        let mut s = SimulationSettings::default();
        let c = SimulateCommand {
            t_end: Some(3.0),
            integrator: Some(IntegratorKind::Rk45),
            ..Default::default()
        };
        c.apply(&mut s, None, true).unwrap();
        assert_eq!(s.dt, 3.0);
        assert_eq!(s.output_interval, Some(3.0 / DEFAULT_SAMPLES));
    }

    const DROP: &str = "../../examples/prism_drop.toml";

    /// The settings of `c` over the scene `path` (`written`: samples written).
    fn applied(
        c: &SimulateCommand,
        path: &str,
        written: bool,
    ) -> Result<SimulationSettings, InvalidParameter> {
        let scene = SceneSource::parse(path).load().unwrap();
        let file = scene.file.simulation.as_ref();
        let mut s = file.map_or_else(SimulationSettings::default, |f| f.to_settings());
        c.apply(&mut s, file, written)?;
        Ok(s)
    }

    #[test]
    fn a_fixed_step_longer_than_the_output_interval_is_refused() {
        // the scene samples every 10 ms; its rk45 has no step
        let rk4 = |dt| SimulateCommand {
            integrator: Some(IntegratorKind::Rk4),
            dt: Some(dt),
            ..Default::default()
        };
        let e = applied(&rk4(0.02), DROP, false).unwrap_err();
        assert_eq!((e.name.as_ref(), e.value.as_str()), ("dt", "0.02"));
        assert!(
            e.reason
                .starts_with("must not exceed the output interval 0.01 s (the scene's"),
            "{e}"
        );
        assert_eq!(applied(&rk4(0.01), DROP, false).unwrap().dt, 0.01);
        // an adaptive method samples its dense output: its largest step may be longer
        let rk45 = SimulateCommand {
            dt: Some(0.5),
            ..Default::default()
        };
        assert_eq!(applied(&rk45, DROP, false).unwrap().dt, 0.5);
        // the request's interval, when samples are written
        let out = SimulateCommand {
            output_interval: Some(1e-3),
            ..rk4(2e-3)
        };
        assert!(applied(&out, DROP, false).is_ok());
        let e = applied(&out, DROP, true).unwrap_err();
        assert!(e.reason.contains("0.001 s (`output_interval`)"), "{e}");
        // the scene's own step
        let text = std::fs::read_to_string(DROP)
            .unwrap()
            .replace("integrator = \"rk45\"", "integrator = \"rk4\"\ndt = 0.02");
        let e = applied(&SimulateCommand::default(), &text, false).unwrap_err();
        assert!(
            e.reason
                .starts_with("(the scene's `[simulation] dt`) must not exceed"),
            "{e}"
        );
    }

    #[test]
    fn an_unset_step_is_the_integrators_default_within_the_output_interval() {
        let with = |kind| SimulateCommand {
            integrator: Some(kind),
            ..Default::default()
        };
        // the scene's rk45 has no step: the one chosen follows the integrator asked for
        let ark = applied(&with(IntegratorKind::ImexArk), DROP, false).unwrap();
        assert_eq!((ark.dt, ark.project), (DEFAULT_DT_IMEX_ARK, true));
        let imex = applied(&with(IntegratorKind::Imex), DROP, false).unwrap();
        assert_eq!(imex.dt, DEFAULT_DT_IMEX);
        let rk4 = applied(&with(IntegratorKind::Rk4), DROP, false).unwrap();
        assert_eq!((rk4.dt, rk4.project), (DEFAULT_DT, false));
        let sdirk = applied(&with(IntegratorKind::Sdirk), DROP, false).unwrap();
        assert_eq!(sdirk.dt, 3.0);
        // a finer sampling shortens the default step, not a given one
        let fine = SimulateCommand {
            output_interval: Some(2e-4),
            ..with(IntegratorKind::Rk4)
        };
        assert_eq!(applied(&fine, DROP, true).unwrap().dt, 2e-4);
        // the default sampling is no finer than a step given
        let coarse = SimulateCommand {
            t_end: Some(1.0),
            dt: Some(0.05),
            ..with(IntegratorKind::Rk4)
        };
        let s = applied(&coarse, "../../examples/dbar.toml", true).unwrap();
        assert_eq!((s.dt, s.output_interval), (0.05, Some(0.05)));
        let s = applied(
            &SimulateCommand { dt: None, ..coarse },
            "../../examples/dbar.toml",
            true,
        );
        assert_eq!(s.unwrap().output_interval, Some(1.0 / DEFAULT_SAMPLES));
    }

    #[test]
    fn final_speeds_near_zero_are_judged_on_the_problems_speed() {
        let scene = SceneSource::parse(DROP).load().unwrap();
        let scales = Scales::of(&scene);
        // the prism's nodes lie 1.118 m from their centroid; g = 9.81 m/s²
        assert!((scales.length - 1.25f64.sqrt()).abs() < 1e-12, "{scales:?}");
        assert!((scales.speed - (9.81 * scales.length).sqrt()).abs() < 1e-12);
        let c = SimulateCommand {
            scene: Some(SceneSource::parse(DROP)),
            t_end: Some(0.05),
            ..Default::default()
        };
        let main = simulate(&c).unwrap();
        // a structure come to rest: final speeds of 2 mm/s that moved by 1 mm/s (50 %)
        let at_rest = |v: f64| SimulationReport {
            final_velocities: vec![[v, 0.0, 0.0]; main.final_velocities.len()],
            ..main.clone()
        };
        let conv = SimulateCommand::convergence(
            &at_rest(2e-3),
            &at_rest(1e-3),
            Convergence::new("dt/2"),
            scales,
        );
        assert!(conv.converged, "{conv:?}");
        let r = conv.quantities[1].relative_change.unwrap();
        assert!((r - 1e-3 / scales.speed).abs() < 1e-15, "{r}");
        // the same change of speeds as large as the scale does not converge
        let fast = SimulateCommand::convergence(
            &at_rest(4.0),
            &at_rest(3.8),
            Convergence::new("dt/2"),
            scales,
        );
        assert!(!fast.converged && fast.quantities[0].converged, "{fast:?}");
    }

    #[test]
    fn the_estimate_counts_the_steps_and_the_written_samples() {
        let scene = SceneSource::parse(SCENE).load().unwrap();
        let c = SimulateCommand {
            t_end: Some(1.0),
            dt: Some(1e-3),
            integrator: Some(IntegratorKind::Rk4),
            output_interval: Some(1e-2),
            ..Default::default()
        };
        let sim = c.simulation(&scene, true).unwrap();
        let quiet = estimate(&sim, false, false).unwrap();
        let csv = estimate(&sim, true, false).unwrap();
        assert_eq!(quiet.output_bytes, 0.0);
        // 101 samples of t and at least the node positions, 25 bytes a number in CSV, 40 in VTK
        let per_sample = csv.output_bytes / (101.0 * 25.0);
        let nodes = scene.structure.n_nodes() as f64;
        assert!(per_sample >= 1.0 + 3.0 * nodes && per_sample.fract() == 0.0);
        let vtk = estimate(&sim, false, true).unwrap();
        assert_eq!(vtk.output_bytes / csv.output_bytes, 40.0 / 25.0);
        assert!(csv
            .parameters
            .to_string()
            .starts_with("t_end = 1 s, dt = 0.001 s"));
        // 1000 RK4 steps: work grows with t_end
        let long = SimulateCommand {
            t_end: Some(1e5),
            ..c
        };
        let sim = long.simulation(&scene, false).unwrap();
        assert!(estimate(&sim, false, false).unwrap().work_s > 1e4 * quiet.work_s);
    }
}
