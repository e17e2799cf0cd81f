//! `tensegrity tbar roll`: its flags are the fields of [`TbarRollRequest`] ([`RequestArgs`]);
//! one library call ([`tensegrity_engine::tbar_roll::tbar_roll`]: the T-bar wheel beside the toroid of
//! equal outer radius, rigid or full model, with tip-over) and prints the report. The
//! defaults are the library's (the fidelity-dependent ones resolved by the request).
//! `--out FILE.csv` writes one row per tread count: the per-row result columns of the engine
//! (the `rows.0.` columns of [`TbarRollReport`]'s `Columns`, the prefix left out), opened
//! before the run.
//! `--animate FILE.gif|FILE.webm` draws the T-bar wheel of the first tread count rolling
//! ([`super::animate`]; the nodes of [`TbarRollRequest::drawing`] from its run's frames: the
//! full model's nodes, or the rigid model's pose placing them), also opened before the run.

use super::animate::Opened;
use super::output;
use super::request_args::RequestArgs;
use anyhow::Result;
use std::path::PathBuf;
use tbar_wheel::roll::{TbarRollReport, TbarRollRequest, TbarRollRow, Watch};
use tensegrity_core::columns::Columns;
use tensegrity_core::request::Request;
use tensegrity_engine::tbar_roll;
use tensegrity_figures::animation::{Animation, Camera, Scenery};
use tensegrity_io::sink::{CsvSink, RollingOutputs};
use wheel_rolling::WheelRun;

/// Arguments of `tensegrity tbar roll`: the request's flags ([`TbarRollRequest`]).
#[derive(clap::Args, Debug)]
pub struct TbarRollArgs {
    #[command(flatten)]
    request: RequestArgs<TbarRollRequest>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// Write one CSV row per tread count (T-bar and toroid runs, tip-over).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    #[command(flatten)]
    animate: super::animate::AnimateArgs,
    #[command(flatten)]
    figure: super::figure_args::FigureArgs,
}

/// Entry point of `tensegrity tbar roll`.
pub fn run(args: &TbarRollArgs) -> Result<()> {
    let request: TbarRollRequest = args.request.request()?;
    let _progress = match tbar_roll::estimate(&request)? {
        Some(e) => Some(super::guard::check(e)?),
        None => None,
    };
    let csv = output::open("--out", args.out.as_deref(), |p| {
        CsvSink::with_header(p, "tbar roll rows CSV", &row_columns().collect::<Vec<_>>())
    })?;
    let mut animation = match args.animate.open_with(args.figure.options()?)? {
        Some(o) => Some(tbar_animation(o, &request)?),
        None => None,
    };
    let report = watched_report(&request, animation.as_mut())?;
    let animation = animation.map(|a| a.marked(report.valid, &report.warnings));
    super::animate::finish(animation, args.animate.animate.as_deref())?;
    if let Some(csv) = csv {
        write_rows(csv, &report)?;
    }
    for row in &report.rows {
        for e in &row.errors {
            eprintln!("warning: n = {}: {}", row.treads, super::spell::flags(e));
        }
    }
    if args.json {
        super::output::print_json(&report)?;
    } else {
        print_roll(&report);
    }
    Ok(tbar_roll::strict_check(&request, &report)?)
}

/// The T-bar wheel of the first tread count rolling: its members in the side view turned by
/// −incline (the slope goes down to the right), on the slope, the camera following it.
fn tbar_animation(o: Opened, request: &TbarRollRequest) -> Result<Animation> {
    request.validate()?;
    let n = request.treads().first().copied().unwrap_or_default();
    let drawn = request.drawing(n, request.rim()?)?;
    let title = format!("T-bar wheel rolling (n = {n})");
    let mut s = Scenery::structure(title, &drawn, None);
    s.ground = Some((nalgebra::Vector3::zeros(), nalgebra::Vector3::z()));
    (s.tilt, s.camera) = (-request.settings.incline, Camera::Follow);
    Ok(o.start(s, request.t_end())
        .with_tolerance(request.spec(request.fidelity).full_dt()))
}

/// The report, the first row's T-bar run drawn into `animation` if any.
fn watched_report(
    request: &TbarRollRequest,
    animation: Option<&mut Animation>,
) -> Result<TbarRollReport> {
    let Some(a) = animation else {
        return Ok(tbar_roll::report(request)?);
    };
    let times = a.times().to_vec();
    let mut outputs = RollingOutputs::new(None, None).with_frames(a);
    let watch = Watch {
        times: &times,
        observer: &mut outputs,
    };
    Ok(tbar_roll::report_watched(request, Some(watch))?)
}

/// The per-row result columns: the engine's `rows.0.*` columns without the prefix.
fn row_columns() -> impl Iterator<Item = &'static str> {
    <TbarRollReport as Columns>::columns()
        .iter()
        .filter_map(|c| c.name.strip_prefix("rows.0."))
}

/// One CSV row per tread count, each value as the JSON report has it.
fn write_rows(mut csv: CsvSink, report: &TbarRollReport) -> Result<()> {
    let json = serde_json::to_value(report)?;
    let rows = json["rows"].as_array().map_or(&[][..], Vec::as_slice);
    for row in rows {
        csv.record(row_columns().map(|c| {
            sweeps::table::lookup(row, c)
                .and_then(sweeps::table::scalar)
                .unwrap_or_default()
        }))?;
    }
    let path = csv.path().display().to_string();
    let n = csv.finish()?;
    eprintln!("wrote {n} rows to {path}");
    Ok(())
}

fn print_roll(r: &TbarRollReport) {
    println!(
        "{} (rim {}) rolling down {:.2}° for {} s, {} model; toroid of equal outer radius{}",
        r.structure,
        r.rim.as_str(),
        r.incline_rad.to_degrees(),
        r.t_end,
        if r.full_tensegrity_rolling {
            "full tensegrity"
        } else {
            "reduced rigid"
        },
        super::output::invalid_mark(r.valid)
    );
    println!("  n   T-bar m [kg]  I1 [kg m²]  oscillation [m]  speed [m/s]  valid | toroid m  oscillation [m]  speed [m/s]  valid");
    let cell = |s: &Option<WheelRun>| match s {
        Some(s) => format!(
            "{:>10.4} {:>11.4} {:>16.6} {:>12.4} {:>6}",
            s.mass_kg,
            s.i1,
            s.summary.axle_height_oscillation,
            s.summary.mean_speed,
            s.summary.valid
        ),
        None => format!("{:>58}", "—"),
    };
    for row in &r.rows {
        println!(
            "{:>3} {} | {}",
            row.treads,
            cell(&row.tbar),
            cell(&row.toroid)
        );
        if let Some(t) = row.tbar.as_ref().filter(|t| !t.fidelity_reason.is_empty()) {
            println!("     model: {} ({})", t.model.name(), t.fidelity_reason);
        }
        print_full(row);
        if let Some(t) = &row.tipover {
            println!(
                "     tips over above a lateral axle force of {:.4} N (on an edge {:.4} N), μ_s > {:.4}",
                t.critical_lateral_force, t.critical_lateral_force_edge, t.min_friction_to_tip
            );
            for w in &t.warnings {
                println!("     note: {w}");
            }
        }
    }
}

/// The full run's contact figures and its rigid reference's first impact.
fn print_full(row: &TbarRollRow) {
    let (Some(f), Some(t)) = (&row.full, &row.tbar) else {
        return;
    };
    let s = &t.summary;
    println!(
        "     full: {} nodes, {} bars, {} strings; bar prestress {:.3} N, tip-load capacity {:.3} N; {} impacts, airborne {:.3}, slip {:.3}, penetration {:.2e} m, energy error {:.2e}",
        f.nodes, f.bars, f.strings, f.prestress.bar_compression, f.prestress.tip_load_capacity,
        s.impacts, s.airborne_fraction, s.slip_fraction, s.max_penetration, s.energy_balance_error
    );
    let first = |s: Option<&WheelRun>| match s.and_then(|s| s.summary.first_impact) {
        Some(i) => format!("t = {:.4} s, ω⁻ = {:.4} rad/s", i.t, i.omega_before),
        None => "none".to_string(),
    };
    println!(
        "     first impact: full {}; rigid polygon {}",
        first(Some(t)),
        first(row.tbar_rigid_reference.as_ref())
    );
    for w in &s.warnings {
        println!("     warning: {}", super::spell::flags(&w.to_string()));
    }
}
