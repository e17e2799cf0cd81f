//! `tensegrity solve SCENE.toml [--path | --load-steps K] [--target Λ] [--max-steps N]
//! [--out path.csv] [--svg FILE] [--vtk DIR] [--json]`: the engine's `solve` request
//! ([`SolveCommand`]): the scene's load path, elastic bars and tension-only strings, the loads
//! scaled by λ up to the target, followed by its arc length through limit points (or in K
//! load steps), printed as text or JSON; `--out` writes one row per point, `--svg` the
//! load–displacement figure ([`tensegrity_figures::load_path`]), `--vtk` one frame per point
//! with the member forces (all opened before the run).

use super::request_args::RequestArgs;
use anyhow::{Context, Result};
use nalgebra::Vector3;
use std::path::PathBuf;
use tensegrity_engine::solve::{SolveCommand, SolveReport};
use tensegrity_io::sink::{CsvSink, VtkSeriesSink};
use tensegrity_io::vtk::FrameData;
use tensegrity_path::point::Event;

/// The columns of `--out`.
const COLUMNS: [&str; 7] = [
    "step",
    "lambda",
    "max_displacement",
    "slack_strings",
    "min_eigenvalue",
    "stability",
    "residual",
];

/// Arguments of `tensegrity solve`.
#[derive(clap::Args, Debug)]
pub struct SolveArgs {
    #[command(flatten)]
    request: RequestArgs<SolveCommand>,
    /// Follow the path by its arc length, through limit points (the default; refused with
    /// --load-steps).
    #[arg(long, conflicts_with = "load_steps")]
    path: bool,
    /// Write one row per path point (step, lambda, max_displacement (m), slack_strings,
    /// min_eigenvalue (N/m), stability, residual (N)) to this CSV.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Draw the load–displacement curve (λ against the largest node displacement; limit
    /// points marked, stable and unstable stretches apart) to FILE (.svg, .png or .pdf).
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    #[command(flatten)]
    figure: super::figure_args::FigureArgs,
    /// Write a VTK series to DIR: one frame per path point (its step as the time), the member
    /// forces as cell data `force` (N), and series.pvd.
    #[arg(long, value_name = "DIR")]
    vtk: Option<PathBuf>,
    /// Print JSON (the summary and the whole path: every point's nodes, tensions, reactions).
    #[arg(long)]
    json: bool,
}

/// Entry point of `tensegrity solve`.
pub fn run(args: &SolveArgs) -> Result<()> {
    let command: SolveCommand = args.request.request()?;
    let sink = super::output::open("--out", args.out.as_deref(), |p| {
        CsvSink::with_header(p, "load path", &COLUMNS)
    })?;
    let figure = args.figure.open("--svg", args.svg.as_deref())?;
    let scene = command
        .source()
        .map_err(super::request_args::usage)?
        .load()?;
    let vtk = super::output::open("--vtk", args.vtk.as_deref(), |d| {
        VtkSeriesSink::open(d, &scene.structure)
    })?;
    let _progress = super::guard::check(tensegrity_engine::solve::estimate(
        &scene.structure,
        &command,
    ))?;
    let limits = super::guard::limits();
    let report = command
        .report_within(&scene, Some(&limits))
        .context("load path failed")?;
    warn_outside(&report, &command, scene.structure.nodes());
    if let Some(series) = vtk {
        write_frames(series, &report)?;
    }
    if let Some(sink) = figure {
        sink.finish(&curve(&report))?;
    }
    if let Some(sink) = sink {
        write_rows(sink, &report)?;
    }
    if args.json {
        super::output::print_json(&report)
    } else {
        print(&report);
        Ok(())
    }
}

/// One VTK frame per path point, its member forces as cell data.
fn write_frames(mut series: VtkSeriesSink<'_>, report: &SolveReport) -> Result<()> {
    for p in &report.path.points {
        let nodes: Vec<Vector3<f64>> = p.nodes.iter().map(|&x| x.into()).collect();
        let data = FrameData {
            velocities: None,
            member_forces: Some(&p.tensions),
            contact_forces: None,
        };
        series.frame_with(p.step as f64, &nodes, &data)?;
    }
    series.finish()?;
    Ok(())
}

/// One CSV row per path point ([`COLUMNS`]).
fn write_rows(mut sink: CsvSink, report: &SolveReport) -> Result<()> {
    for p in &report.path.points {
        let min = p
            .smallest_eigenvalues
            .first()
            .map_or(String::new(), |v| v.to_string());
        let stability = serde_json::to_value(p.stability)?
            .as_str()
            .unwrap_or("")
            .to_string();
        sink.record([
            p.step.to_string(),
            p.lambda.to_string(),
            p.max_displacement.to_string(),
            p.slack.len().to_string(),
            min,
            stability,
            p.residual.to_string(),
        ])?;
    }
    sink.finish()?;
    Ok(())
}

/// Warnings beside numbers a reader could take for more than they are: a path that stopped
/// before its target (its last point is not at the target), and a scene that was not in
/// equilibrium unloaded (its λ = 0 point moved from the scene's nodes, and every displacement
/// counts that move).
fn warn_outside(report: &SolveReport, command: &SolveCommand, scene_nodes: &[Vector3<f64>]) {
    if report.stop != "reached_target" {
        let why = match report.stop.as_str() {
            "max_work" => format!(
                "its work limit of {} s spent: raise it with --max-work",
                super::guard::limits().work_s
            ),
            stop => stop.replace('_', " "),
        };
        eprintln!(
            "warning: the path stopped at λ = {} before its target {} ({why}): the last point's numbers are not the target's",
            super::output::exact(report.final_load_factor),
            super::output::exact(command.target),
        );
    }
    let size = tensegrity_path::model::extent(scene_nodes);
    if let Some(start) = report.path.points.first() {
        if start.max_displacement > 1e-3 * size {
            eprintln!(
                "warning: the unloaded scene is not in equilibrium with its rest lengths: at λ = 0 its nodes moved up to {:.6e} m ({:.3} % of its size) before any load; every displacement is measured from the scene's nodes",
                start.max_displacement,
                100.0 * start.max_displacement / size
            );
        }
    }
}

/// The load–displacement figure of the path.
fn curve(r: &SolveReport) -> tensegrity_io::figure::Figure {
    use tensegrity_path::stability::Stability;
    let points: Vec<_> = r
        .path
        .points
        .iter()
        .map(|p| {
            (
                p.max_displacement,
                p.lambda,
                p.stability != Stability::Unstable,
            )
        })
        .collect();
    let folds: Vec<(f64, f64)> = r
        .path
        .events
        .iter()
        .filter_map(|e| match e {
            Event::LimitPoint {
                lambda,
                max_displacement,
                ..
            } => Some((*max_displacement, *lambda)),
            _ => None,
        })
        .collect();
    tensegrity_figures::load_path::figure(&points, &folds)
}

fn print(r: &SolveReport) {
    let how = if r.method == "path" {
        "arc-length path"
    } else {
        "load steps"
    };
    println!(
        "load path ({how}): {} points, λ to {} ({})",
        r.points,
        r.final_load_factor,
        r.stop.replace('_', " ")
    );
    for e in &r.path.events {
        match e {
            Event::LimitPoint { lambda, max_displacement, .. } => {
                println!("limit point at λ = {lambda:.9} (largest displacement {max_displacement:.6} m)")
            }
            Event::Bifurcation {
                lambda, switched, ..
            } => println!(
                "bifurcation at λ = {lambda:.9}{}",
                if *switched { " (the path leaves along its mode)" } else { "" }
            ),
            Event::Slackened { members, lambda, .. } => {
                println!("slack from λ = {lambda:.9}: member(s) {members:?}")
            }
            Event::Retensioned { members, lambda, .. } => {
                println!("taut again from λ = {lambda:.9}: member(s) {members:?}")
            }
            Event::Jump { from_lambda, to_lambda, ratio } => eprintln!(
                "warning: the load steps jumped between λ = {from_lambda} and {to_lambda} (the structure moved {ratio:.1} times the tangent's prediction): a limit point lies between and the last points are on another branch; --path follows the path through it"
            ),
        }
    }
    if let tensegrity_path::point::Stop::StepTooSmall { message } = &r.path.stop {
        println!("stopped: {message}");
    }
    if let Some(p) = r.path.points.last() {
        let stability = serde_json::to_value(p.stability).ok();
        println!(
            "last point: λ = {}, largest displacement {:.6} m, {} slack string(s), {} (smallest eigenvalue {})",
            p.lambda,
            p.max_displacement,
            p.slack.len(),
            stability.as_ref().and_then(|v| v.as_str()).unwrap_or("?"),
            p.smallest_eigenvalues.first().map_or("not computed".to_string(), |v| format!("{v:.6e} N/m")),
        );
    }
}
