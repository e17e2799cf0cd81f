//! `tensegrity bench work-precision [--out DIR] [--quick]`: error against wall time for every
//! integrator on five scenes, two of them stiff (the engine's `bench_work_precision` request,
//! [`tensegrity_engine::bench`]), written as CSV and a figure (log–log, one curve per
//! integrator, one panel per scene: [`tensegrity_figures::work_precision`]).
//! `tensegrity bench anchors`: the anchor scenes and the scaling series
//! ([`super::bench_anchors`]).

use super::output;
use super::request_args::RequestArgs;
use anyhow::Result;
use std::path::PathBuf;
use tensegrity_dynamics::work_precision::Point;
use tensegrity_engine::bench::WorkPrecisionRequest;
use tensegrity_io::csv::WorkPrecisionRow;
use tensegrity_io::progress::{Measure, Progress};
use tensegrity_io::sink::{CsvSink, OutputDir};

/// Arguments of `tensegrity bench`.
#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    /// Which benchmark.
    #[command(subcommand)]
    pub what: BenchCommand,
}

/// Benchmarks.
#[derive(clap::Subcommand, Debug)]
pub enum BenchCommand {
    /// Error against wall time for rk4, rk45, rattle and sdirk on five scenes.
    WorkPrecision(WorkPrecisionArgs),
    /// The anchor scenes against the reference codes' times, and the cost against size of
    /// the toroid, towers, Michell trusses and rolling, with their fitted exponents.
    Anchors(super::bench_anchors::AnchorsArgs),
    /// One anchor run, nothing printed (what `bench anchors` counts under callgrind).
    #[command(hide = true)]
    AnchorRun(super::bench_anchors::AnchorRunArgs),
    /// One scaling series point's setup and calls, nothing printed (what `bench anchors`
    /// counts under callgrind).
    #[command(hide = true)]
    SeriesRun(super::bench_anchors::SeriesRunArgs),
}

/// Arguments of `tensegrity bench work-precision`: the request's flags
/// ([`WorkPrecisionRequest`]) and the output directory.
#[derive(clap::Args, Debug)]
pub struct WorkPrecisionArgs {
    #[command(flatten)]
    request: RequestArgs<WorkPrecisionRequest>,
    /// Output directory for work_precision.csv and work_precision.svg (created if missing;
    /// its parent must exist).
    #[arg(long, value_name = "DIR", default_value = "work-precision")]
    pub out: PathBuf,
    /// Print the points (the CSV's columns as keys) and the files as JSON.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    figure: super::figure_args::FigureArgs,
}

/// Runs `tensegrity bench work-precision`.
pub fn run(args: &BenchArgs) -> Result<()> {
    match &args.what {
        BenchCommand::WorkPrecision(a) => work_precision(a),
        BenchCommand::Anchors(a) => super::bench_anchors::anchors(a),
        BenchCommand::AnchorRun(a) => super::bench_anchors::anchor_run(a),
        BenchCommand::SeriesRun(a) => super::bench_anchors::series_run(a),
    }
}

fn work_precision(args: &WorkPrecisionArgs) -> Result<()> {
    let request: WorkPrecisionRequest = args.request.request()?;
    // the directory and both files are opened before the (long) measurement
    let dir = output::open_required("--out", &args.out, OutputDir::create)?;
    let csv_path = dir.join("work_precision.csv");
    let mut csv = output::open_required("--out", &csv_path, |p| {
        CsvSink::open(p, "work-precision CSV")
    })?;
    let svg_path = dir.join("work_precision.svg");
    let svg = args.figure.open_required("--out", &svg_path)?;
    let unit = "points";
    let progress = Progress::auto("bench", Measure::Count { total: 0, unit }, false);
    let mut tell = |done: usize, total: usize| {
        progress.set_total(total);
        progress.set(done as f64);
    };
    let report = tensegrity_engine::bench::work_precision_observed(&request, &mut tell)?;
    let (points, skipped) = (report.points, report.skipped);
    progress.finish();
    csv.extend(points.iter().map(row))?;
    csv.finish()?;
    svg.finish(&tensegrity_figures::work_precision::figure(&points))?;
    dir.keep();
    if args.json {
        let rows: Vec<_> = points.iter().map(row).collect();
        let (csv, figure) = (
            csv_path.display().to_string(),
            svg_path.display().to_string(),
        );
        return output::print_json(
            &serde_json::json!({"points": rows, "skipped": skipped, "csv": csv, "figure": figure}),
        );
    }
    println!(
        "{} points written to {} and {}",
        points.len(),
        csv_path.display(),
        svg_path.display()
    );
    for s in &skipped {
        println!(
            "no point: {} on {} at {}: {}",
            s.integrator, s.scene, s.parameter, s.reason
        );
    }
    Ok(())
}

fn row(p: &Point) -> WorkPrecisionRow {
    WorkPrecisionRow {
        scene: p.scene.to_string(),
        integrator: p.integrator.to_string(),
        parameter: p.parameter,
        steps: p.steps,
        rhs_evals: p.rhs_evals,
        error_m: p.error,
        wall_time_s: p.wall_time_s,
    }
}
