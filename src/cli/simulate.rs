//! `tensegrity simulate SCENE.toml [--t-end S] [--integrator rk4|rk45|rattle|sdirk] [--dt S]
//! [--rtol X] [--atol X] [--out traj.csv] [--output-interval S] [--json]`.
//!
//! The scene's `[simulation]`, `[ground]` and `[[actuation]]` tables configure the run;
//! command-line flags override the file. With `--json` the report is one JSON object with
//! exactly the keys `t_end`, `steps`, `rhs_evals`, `final_nodes` (n×3, file node numbering:
//! class-1 copies merged back), `final_velocities`, `energy_drift` (max relative),
//! `bar_length_drift` (max absolute, m), `constraint_drift` (max absolute ‖N P − D‖, m) and
//! `wall_time_s` (the integration alone, without parsing and output).

use super::output;
use anyhow::{bail, Context, Result};
use std::path::PathBuf;
use tensegrity_core::dynamics::{IntegratorKind, SimulationReport, SimulationSettings};
use tensegrity_core::CoreError;
use tensegrity_core::Structure;
use tensegrity_io::interrupt::{self, Interrupted};
use tensegrity_io::scene::{build_simulation, ActuationSpec, GroundSpec, Scene, SimulationSpec};
use tensegrity_io::sink::{SimulationOutputs, VtkSeriesSink};
use tensegrity_io::trajectory::TrajectoryWriter;

/// Integrator choice on the command line.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum IntegratorArg {
    /// Classic fixed-step RK4.
    Rk4,
    /// Adaptive Dormand–Prince 5(4).
    Rk45,
    /// Constraint-preserving RATTLE (fixed step, 2nd order).
    Rattle,
    /// Adaptive L-stable SDIRK 3(2) (stiff strings and contact).
    Sdirk,
}

impl From<IntegratorArg> for IntegratorKind {
    fn from(a: IntegratorArg) -> Self {
        match a {
            IntegratorArg::Rk4 => IntegratorKind::Rk4,
            IntegratorArg::Rk45 => IntegratorKind::Rk45,
            IntegratorArg::Rattle => IntegratorKind::Rattle,
            IntegratorArg::Sdirk => IntegratorKind::Sdirk,
        }
    }
}

/// Arguments of `tensegrity simulate`.
#[derive(clap::Args, Debug)]
pub struct SimulateArgs {
    /// The scene file (TOML) with an optional `[simulation]`, `[ground]`, `[[actuation]]`.
    pub scene: PathBuf,
    /// End time (s); overrides `[simulation] t_end`.
    #[arg(long, value_name = "S", value_parser = super::values::positive)]
    pub t_end: Option<f64>,
    /// Integrator; overrides `[simulation] integrator` (default rk4).
    #[arg(long, value_enum)]
    pub integrator: Option<IntegratorArg>,
    /// Fixed step (rk4, rattle; default 1e-3) or maximum step (rk45, sdirk; default t_end), s.
    #[arg(long, value_name = "S", value_parser = super::values::positive)]
    pub dt: Option<f64>,
    /// Relative tolerance (rk45, sdirk).
    #[arg(long, value_name = "X", value_parser = super::values::positive)]
    pub rtol: Option<f64>,
    /// Absolute tolerance (rk45, sdirk).
    #[arg(long, value_name = "X", value_parser = super::values::positive)]
    pub atol: Option<f64>,
    /// Write the node trajectories to this CSV file.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Sampling interval of the CSV (s); default: the scene's output times, else t_end/200.
    #[arg(long, value_name = "S", value_parser = super::values::positive)]
    pub output_interval: Option<f64>,
    /// Write the trajectory for ParaView: one `.vtu` per output time plus `series.pvd`.
    #[arg(long, value_name = "DIR")]
    pub vtk: Option<PathBuf>,
    /// Print the JSON report.
    #[arg(long)]
    pub json: bool,
    /// Fail (exit 1, after writing the outputs) when the run has a drift warning.
    #[arg(long)]
    pub strict: bool,
}

/// Entry point of `tensegrity simulate`: reads the scene, runs it, prints the report.
pub fn run(args: &SimulateArgs) -> Result<()> {
    let scene = Scene::from_path(&args.scene)?;
    run_scene(
        args,
        &scene.structure,
        scene.file.simulation.as_ref(),
        scene.file.ground.as_ref(),
        &scene.file.actuation,
    )
}

/// Runs `tensegrity simulate` on an already parsed scene.
///
/// The caller passes the structure and the scene's optional `[simulation]`, `[ground]` and
/// `[[actuation]]` tables; `args` overrides the simulation table. Prints the report (JSON
/// with `--json`) on stdout and writes `--out` and `--vtk` if given.
pub fn run_scene(
    args: &SimulateArgs,
    structure: &Structure,
    sim: Option<&SimulationSpec>,
    ground: Option<&GroundSpec>,
    actuation: &[ActuationSpec],
) -> Result<()> {
    let mut simulation = build_simulation(structure, sim, ground, actuation)
        .with_context(|| format!("setting up the simulation of {}", args.scene.display()))?;
    apply_overrides(args, &mut simulation.settings, sim)?;
    let _progress = super::guard::simulation(&simulation, args.out.is_some(), args.vtk.is_some())?;
    let csv = output::open("--out", args.out.as_deref(), |p| {
        TrajectoryWriter::create(p, structure)
    })?;
    let vtk = output::open("--vtk", args.vtk.as_deref(), |d| {
        VtkSeriesSink::open(d, structure)
    })?;
    let mut outputs = SimulationOutputs::new(csv, vtk);
    let _polled = interrupt::polled();
    let run = simulation.run_streaming(&mut outputs);
    let written = outputs.finish(run.as_ref().err())?;
    let (rows, frames) = (written.rows, written.frames);
    let result = match run {
        Err(CoreError::Interrupted { t }) => {
            let note = args
                .out
                .is_some()
                .then(|| format!("{rows} trajectory rows kept, marked incomplete"));
            return Err(Interrupted { t: Some(t), note }.into());
        }
        other => other.with_context(|| format!("simulating {}", args.scene.display()))?,
    };
    if !args.json {
        if let Some(p) = &args.out {
            println!("{rows} rows written to {}", p.display());
        }
        if let Some(dir) = &args.vtk {
            println!(
                "{frames} VTK frames and series.pvd written to {}",
                dir.display()
            );
        }
    }
    let report = SimulationReport::from(&result);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_report(simulation.settings.integrator, &report);
    }
    for w in &report.warnings {
        eprintln!("warning: {}", super::spell::flags(&w.to_string()));
    }
    if args.strict && !report.warnings.is_empty() {
        anyhow::bail!(
            "--strict: {} drift warning(s) (see above)",
            report.warnings.len()
        );
    }
    Ok(())
}

/// Applies the command-line overrides to the scene's simulation settings.
fn apply_overrides(
    args: &SimulateArgs,
    s: &mut SimulationSettings,
    sim: Option<&SimulationSpec>,
) -> Result<()> {
    match (args.t_end, sim) {
        (Some(t), _) => s.t_end = t,
        (None, Some(_)) => {}
        (None, None) => bail!(
            "{}: no end time: give `[simulation] t_end` in the scene or --t-end",
            args.scene.display()
        ),
    }
    if let Some(i) = args.integrator {
        s.integrator = i.into();
    }
    if let Some(dt) = args.dt {
        s.dt = dt;
    } else if s.integrator.is_adaptive() && sim.and_then(|x| x.dt).is_none() {
        // no step given anywhere: rk45/sdirk choose their own, unbounded below t_end
        s.dt = s.t_end;
    }
    if let Some(r) = args.rtol {
        s.rtol = r;
    }
    if let Some(a) = args.atol {
        s.atol = a;
    }
    if args.out.is_some() || args.vtk.is_some() {
        s.quantities.nodes = true;
        if let Some(dt_out) = args.output_interval {
            s.output_interval = Some(dt_out);
        } else if s.output_times.is_empty() && s.output_interval.is_none() {
            s.output_interval = Some(s.t_end / 200.0);
        }
    }
    Ok(())
}

fn print_report(integrator: IntegratorKind, report: &SimulationReport) {
    println!(
        "simulated {} s with {} ({} steps, {} force evaluations) in {:.3} ms",
        report.t_end,
        integrator,
        report.steps,
        report.rhs_evals,
        report.wall_time_s * 1e3
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
    println!("final nodes (m):");
    for (i, n) in report.final_nodes.iter().enumerate() {
        println!("  {i:4}  {:+.9e} {:+.9e} {:+.9e}", n[0], n[1], n[2]);
    }
}
