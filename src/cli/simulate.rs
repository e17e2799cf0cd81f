//! `tensegrity simulate SCENE.toml [--t-end S]
//! [--integrator rk4|rk45|rattle|sdirk|imex|imex-ark|rk4-flight|newmark] [--dt S] [--rtol X]
//! [--atol X] [--out traj.csv] [--output-interval S] [--json]`.
//!
//! The flags are the engine's `simulate` request ([`SimulateCommand`]): the scene's
//! `[simulation]`, `[ground]` and `[[actuation]]` tables configure the run and the flags
//! override the file ([`SimulateCommand::apply`]: each integrator's default step, a fixed
//! step longer than the output interval refused as a bad `--dt`, exit 2); the run's estimate
//! is checked, the run
//! streamed to the outputs opened before it. With `--json` the report is one JSON object with
//! exactly the keys `t_end`, `steps`, `rhs_evals`, `final_nodes` (n×3, file node numbering:
//! class-1 copies merged back), `final_velocities`, `energy_drift` (max relative),
//! `bar_length_drift` (max absolute, m), `constraint_drift` (max absolute ‖N P − D‖, m) and
//! `wall_time_s` (the integration alone, without parsing and output). `--animate FILE.gif`
//! draws the structure over the run ([`super::animate`]); the progress (simulated time) goes
//! to stderr. An elastic scene (`[simulation] bars = "elastic"` or a bar's `elastic = true`,
//! its other bars rigid length constraints; or strings with point masses and no bar) runs the elastic dynamics ([`elastic`]) with the same flags, outputs
//! and report (`--animate` aside).

use super::output;
use super::request_args::{usage, RequestArgs};
use anyhow::{Context, Result};
use std::path::PathBuf;
use tensegrity_core::request::InvalidParameter;
use tensegrity_core::CoreError;
use tensegrity_dynamics::{IntegratorKind, SampleSink, SimulationReport};
use tensegrity_engine::simulate::{elastic, Checked, SimulateCommand};
use tensegrity_engine::{SceneError, SceneSource};
use tensegrity_figures::animation::Scenery;
use tensegrity_io::interrupt::{self, Interrupted};
use tensegrity_io::progress::Progress;
use tensegrity_io::scene::Scene;
use tensegrity_io::sink::{NodeFrames, SimulationOutputs, VtkSeriesSink};
use tensegrity_io::trajectory::TrajectoryWriter;

/// Arguments of `tensegrity simulate`: the request's flags ([`SimulateCommand`], the scene
/// positional) and the outputs.
#[derive(clap::Args, Debug)]
pub struct SimulateArgs {
    #[command(flatten)]
    request: RequestArgs<SimulateCommand>,
    /// Write the node trajectories to this CSV file.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Write the trajectory for ParaView: one `.vtu` per output time plus `series.pvd`.
    #[arg(long, value_name = "DIR")]
    pub vtk: Option<PathBuf>,
    /// Print the JSON report.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    animate: super::animate::AnimateArgs,
    #[command(flatten)]
    figure: super::figure_args::FigureArgs,
}

/// Entry point of `tensegrity simulate`: reads the scene, runs it, prints the report.
pub fn run(args: &SimulateArgs) -> Result<()> {
    let command: SimulateCommand = args.request.request()?;
    let scene = command
        .source()
        .map_err(usage)?
        .load()
        .map_err(|e| usage_of(e.into()))?;
    if elastic::is_elastic(&scene) {
        return run_elastic(args, &command, &scene);
    }
    let (csv, vtk) = (args.out.is_some(), args.vtk.is_some());
    let opened = args.animate.open_with(args.figure.options()?)?;
    let sampled = csv || vtk || opened.is_some();
    let (scene, mut simulation) = command.prepare_scene(scene, sampled).map_err(usage_of)?;
    let progress = super::guard::simulation(&command, &simulation, csv, vtk)?;
    let mut animation = opened.map(|o| {
        let scenery =
            Scenery::structure(title(&command), &scene.structure, simulation.model.ground());
        o.start(scenery, simulation.settings.t_end)
    });
    if let Some(a) = &animation {
        // the frames are samples at their own times (the trajectory holds them too)
        simulation
            .settings
            .output_times
            .extend_from_slice(a.times());
    }
    let frames = animation.as_mut().map(|a| a as &mut dyn NodeFrames);
    let run = Run(&command, &scene, progress.handle(), frames);
    let report = run_with_outputs(args, run, |sink| {
        command.run_beside(&scene, &simulation, sink)
    })?;
    let animation = animation.map(|a| a.marked(report.valid, &report.warnings));
    super::animate::finish(animation, args.animate.animate.as_deref())?;
    finish(args, &command, simulation.settings.integrator, &report)
}

/// A request's bad parameter is a usage error (exit 2).
fn usage_of(e: SceneError) -> anyhow::Error {
    match e {
        SceneError::InvalidParameter(p) => usage(p),
        e => e.into(),
    }
}

/// Prints the report (or its JSON) and its warnings; the `strict` rule.
fn finish(
    args: &SimulateArgs,
    command: &SimulateCommand,
    integrator: IntegratorKind,
    report: &SimulationReport,
) -> Result<()> {
    if args.json {
        super::output::print_json(report)?;
    } else {
        print_report(integrator, report);
    }
    for w in &report.warnings {
        eprintln!("warning: {}", super::spell::flags(&w.to_string()));
    }
    Ok(command.strict_check(report)?)
}

/// An elastic scene ([`elastic`]): the same outputs but `--animate`, which draws rigid-bar
/// runs only.
fn run_elastic(args: &SimulateArgs, command: &SimulateCommand, scene: &Scene) -> Result<()> {
    if let Some(gif) = &args.animate.animate {
        return Err(usage(InvalidParameter::text(
            "animate",
            gif.display(),
            "draws rigid-bar runs only: write the elastic run's trajectory with --out or --vtk",
        )));
    }
    let (csv, vtk) = (args.out.is_some(), args.vtk.is_some());
    let run = command.elastic(scene, csv || vtk).map_err(usage_of)?;
    let estimate = run.estimate(command.convergence_check, csv, vtk)?;
    let progress = super::guard::elastic_simulation(estimate, &run.settings)?;
    let report = run_with_outputs(args, Run(command, scene, progress.handle(), None), |sink| {
        Ok(run.run_beside(command, scene, sink))
    })?;
    finish(args, command, run.settings.integrator, &report)
}

/// The animation's title: the scene's file name, drawn as written (never as math).
fn title(command: &SimulateCommand) -> String {
    let name = match command.source() {
        Ok(SceneSource::Path(p)) => p.file_name().map(|n| n.to_string_lossy().into_owned()),
        _ => None,
    };
    tensegrity_io::figure::literal(&name.unwrap_or_else(|| "scene".into()))
}

/// What a run needs: the command, its scene, its progress and its animation.
struct Run<'a>(
    &'a SimulateCommand,
    &'a Scene,
    Progress,
    Option<&'a mut dyn NodeFrames>,
);

/// The run (`beside`: the run and its companion into a sink) streamed to `--out` and `--vtk`
/// (opened before it), what was written said.
fn run_with_outputs(
    args: &SimulateArgs,
    run: Run<'_>,
    beside: impl FnOnce(&mut dyn SampleSink) -> Result<Checked, SceneError>,
) -> Result<SimulationReport> {
    let Run(command, scene, progress, frames) = run;
    let (structure, source) = (&scene.structure, command.source()?);
    let csv = output::open("--out", args.out.as_deref(), |p| {
        TrajectoryWriter::create(p, structure)
    })?;
    let vtk = output::open("--vtk", args.vtk.as_deref(), |d| {
        VtkSeriesSink::open(d, structure)
    })?;
    let mut outputs = SimulationOutputs::new(csv, vtk).with_progress(progress);
    if let Some(f) = frames {
        outputs = outputs.with_frames(f);
    }
    let _polled = interrupt::polled();
    let checked = beside(&mut outputs)?;
    let written = outputs.finish(checked.main.as_ref().err())?;
    let report = match checked.report() {
        Err(CoreError::Interrupted { t }) => {
            let note = (args.out.is_some())
                .then(|| format!("{} trajectory rows kept, marked incomplete", written.rows));
            return Err(Interrupted { t: Some(t), note }.into());
        }
        other => other.with_context(|| format!("simulating {source}"))?,
    };
    if !args.json {
        if let Some(p) = &args.out {
            println!("{} rows written to {}", written.rows, p.display());
        }
        if let Some(dir) = &args.vtk {
            let frames = written.frames;
            println!(
                "{frames} VTK frames and series.pvd written to {}",
                dir.display()
            );
        }
    }
    Ok(report)
}

fn print_report(integrator: IntegratorKind, report: &SimulationReport) {
    println!(
        "simulated {} s with {} ({} steps, {} force evaluations) in {:.3} ms{}",
        report.t_end,
        integrator,
        report.steps,
        report.rhs_evals,
        report.wall_time_s * 1e3,
        super::output::invalid_mark(report.warnings.is_empty())
    );
    println!("max relative energy drift   {:.3e}", report.energy_drift);
    println!(
        "max bar-length drift        {:.3e} m",
        report.bar_length_drift
    );
    println!(
        "max |N P - D|               {:.3e} m",
        report.constraint_drift
    );
    super::output::print_convergence(report.convergence.as_ref());
    println!("final nodes (m):");
    for (i, n) in report.final_nodes.iter().enumerate() {
        println!("  {i:4}  {:+.9e} {:+.9e} {:+.9e}", n[0], n[1], n[2]);
    }
}
