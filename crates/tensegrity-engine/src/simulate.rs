//! `simulate`: a scene run in time ([`SimulateCommand`], a request named `simulate`) — the
//! scene's `[simulation]`, `[ground]` and `[[actuation]]` tables
//! ([`tensegrity_io::scene::build_simulation`]) under the request's overrides, one
//! [`Simulation`] run, its [`SimulationReport`].
//!
//! The overrides ([`SimulateCommand::apply`]): `t_end`, `integrator`, `dt`, `rtol`, `atol`
//! replace the scene's values; with no `dt` anywhere an adaptive integrator (rk45, sdirk) is
//! unbounded below t_end (dt = t_end); when samples are written (a front end's trajectory or
//! VTK output) the node positions are recorded every `output_interval` (default: the scene's
//! output times, else t_end / 200). A `strict` run whose invariants drifted past their limits
//! fails ([`SceneError::Strict`]) after its outputs are written.
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
use tensegrity_dynamics::recorder::{Sample, SampleSink};
use tensegrity_dynamics::Simulation;
use tensegrity_dynamics::{
    Convergence, IntegratorKind, SimulationReport, SimulationResult, SimulationSettings,
};
use tensegrity_io::scene::{Scene, SimulationSpec};

/// Samples per run when the scene names no output times and no interval is given.
pub const DEFAULT_SAMPLES: f64 = 200.0;

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
    #[param(choice = ["rk4", "rk45", "rattle", "sdirk", "imex", "imex-ark"], help = "Integrator; overrides `[simulation] integrator` (default rk4): fixed-step RK4, adaptive RK45, constraint-preserving RATTLE, adaptive L-stable SDIRK for stiff strings and contact, IMEX (penalty contact split off, linearly implicit), IMEX-ARK (penalty contact implicit in every stage)", optional)]
    pub integrator: Option<IntegratorKind>,
    /// Fixed step (rk4, rattle) or largest step (rk45, sdirk), s.
    #[param(
        number,
        unit = "s",
        help = "Fixed step (rk4, rattle; default 1e-3) or maximum step (rk45, sdirk; default t_end)",
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
    /// Re-run at a refined resolution beside the run ([`SimulateCommand::refine`]) and
    /// report the final state's change in `convergence`.
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
    /// needs the request's.
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
        if let Some(dt) = self.dt {
            s.dt = dt;
        } else if s.integrator.is_adaptive() && file.and_then(|x| x.dt).is_none() {
            // no step given anywhere: rk45/sdirk choose their own, unbounded below t_end
            s.dt = s.t_end;
        }
        s.rtol = self.rtol.unwrap_or(s.rtol);
        s.atol = self.atol.unwrap_or(s.atol);
        if written {
            s.quantities.nodes = true;
            if let Some(dt_out) = self.output_interval {
                s.output_interval = Some(dt_out);
            } else if s.output_times.is_empty() && s.output_interval.is_none() {
                s.output_interval = Some(s.t_end / DEFAULT_SAMPLES);
            }
        }
        Ok(())
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
        let scene = self.source()?.load()?;
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

/// A sink that keeps no sample and stops the run once `.0` is set (the refined run of a run
/// that failed or was interrupted).
struct StopWhen<'a>(&'a AtomicBool);

impl SampleSink for StopWhen<'_> {
    fn accept(&mut self, _: Sample) -> Result<(), CoreError> {
        Ok(())
    }

    fn keep_going(&mut self) -> bool {
        !self.0.load(Ordering::Relaxed)
    }
}

/// A sink that keeps no sample (a run whose samples nobody writes).
struct Discard;

impl SampleSink for Discard {
    fn accept(&mut self, _: Sample) -> Result<(), CoreError> {
        Ok(())
    }
}

/// Runs `simulate` without writing samples: reads the scene, runs it (beside its refined run
/// with `convergence_check`), its report (an error under `strict` with drift warnings or an
/// unconverged final state).
pub fn simulate(command: &SimulateCommand) -> Result<SimulationReport, SceneError> {
    let (scene, simulation) = command.prepare(false)?;
    let report = command.run_checked(&scene, &simulation, &mut Discard)?;
    command.strict_check(&report)?;
    Ok(report)
}

/// Tolerance of the final node positions (relative to the structure's size).
pub const CONVERGENCE_NODES: f64 = 1e-2;
/// Tolerance of the final velocities (relative to the largest final speed).
pub const CONVERGENCE_VELOCITIES: f64 = 2e-2;

impl SimulateCommand {
    /// The refined resolution of `settings`: a fixed step (rk4, rattle) halved; an adaptive
    /// integrator's tolerances divided by 10 and its largest step halved. Returns what changed.
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

    /// The convergence of a run's final state against the refined run's: the largest distance
    /// between their final nodes over the structure's size (the largest distance of a final
    /// node from their centroid, at least 1 mm) within [`CONVERGENCE_NODES`], the largest
    /// difference of their final velocities over the largest final speed (at least 1 mm/s)
    /// within [`CONVERGENCE_VELOCITIES`].
    pub fn convergence(
        main: &SimulationReport,
        refined: &SimulationReport,
        label: &str,
    ) -> Convergence {
        let gap = |a: &[[f64; 3]], b: &[[f64; 3]]| {
            a.iter()
                .zip(b)
                .map(|(p, q)| {
                    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
                })
                .fold(0.0, f64::max)
        };
        let n = main.final_nodes.len().max(1) as f64;
        let c = main.final_nodes.iter().fold([0.0; 3], |s, p| {
            [s[0] + p[0] / n, s[1] + p[1] / n, s[2] + p[2] / n]
        });
        let size = gap(&main.final_nodes, &vec![c; main.final_nodes.len()]).max(1e-3);
        let zero = vec![[0.0; 3]; main.final_velocities.len()];
        let speed = gap(&main.final_velocities, &zero).max(1e-3);
        let mut conv = Convergence::new(label);
        conv.compare_change(
            "final_nodes",
            gap(&main.final_nodes, &refined.final_nodes) / size,
            CONVERGENCE_NODES,
        )
        .compare_change(
            "final_velocities",
            gap(&main.final_velocities, &refined.final_velocities) / speed,
            CONVERGENCE_VELOCITIES,
        );
        conv
    }

    /// Runs `simulation` (of `scene`, under this command) into `sink`, and with
    /// `convergence_check` its refined run ([`SimulateCommand::refine`]) beside it in a second
    /// thread: the report with its `convergence` and a warning per unconverged quantity.
    pub fn run_checked(
        &self,
        scene: &Scene,
        simulation: &Simulation,
        sink: &mut dyn SampleSink,
    ) -> Result<SimulationReport, SceneError> {
        Ok(self.run_beside(scene, simulation, sink)?.report()?)
    }

    /// The run into `sink` and, with `convergence_check`, the refined run beside it (the
    /// scene is read again for it: a second, independent model).
    pub fn run_beside(
        &self,
        scene: &Scene,
        simulation: &Simulation,
        sink: &mut dyn SampleSink,
    ) -> Result<Checked, SceneError> {
        if !self.convergence_check {
            let main = simulation.run_streaming(sink);
            return Ok(Checked {
                main,
                refined: None,
            });
        }
        let mut fine = self.simulation(scene, false)?;
        let label = Self::refine(&mut fine.settings);
        let stop = AtomicBool::new(false);
        Ok(std::thread::scope(|s| {
            let watch = StopWhen(&stop);
            let handle = s.spawn(move || fine.run_streaming(&mut { watch }));
            let main = simulation.run_streaming(sink);
            // a run that failed (or was interrupted) is not compared: stop the refined one
            stop.store(main.is_err(), Ordering::Relaxed);
            let refined = handle
                .join()
                .unwrap_or_else(|p| std::panic::resume_unwind(p));
            Checked {
                main,
                refined: Some((label, refined)),
            }
        }))
    }
}

/// The resource estimate of the run of `simulation` under `command` ([`estimate`]), and
/// with `convergence_check` its refined run's after it ([`SimulateCommand::refine`]: twice
/// the work).
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
    // twice the steps, nothing written (adaptive: rtol/10 costs 10^(1/5) ≈ 1.6 times the
    // steps of a fifth-order pair, 10^(1/3) ≈ 2.2 of SDIRK's third order: about twice too)
    // the refined run writes nothing and shares the run's description
    Ok(Estimate {
        work_s: 3.0 * e.work_s,
        ..e
    })
}

/// A run and its refined run ([`SimulateCommand::run_beside`]).
#[derive(Debug)]
pub struct Checked {
    /// The run (its error, an interrupt included, as the core gave it).
    pub main: Result<SimulationResult, CoreError>,
    /// What the refined run changed, and its result; `None` when not checked.
    pub refined: Option<(&'static str, Result<SimulationResult, CoreError>)>,
}

impl Checked {
    /// The run's report, with the convergence of its final state and a warning per
    /// unconverged quantity (or for a refined run that failed).
    pub fn report(self) -> Result<SimulationReport, CoreError> {
        let mut report = SimulationReport::from(&self.main?);
        let convergence = match self.refined {
            None => return Ok(report),
            Some((label, Ok(fine))) => {
                SimulateCommand::convergence(&report, &SimulationReport::from(&fine), label)
            }
            Some((label, Err(e))) => {
                let mut c = Convergence::new(format!("{label}: the refined run failed: {e}"));
                c.converged = false;
                c
            }
        };
        report.warnings.extend(convergence.warnings());
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
