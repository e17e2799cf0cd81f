//! `tensegrity tipover`: the request's flags ([`RequestArgs`]) into a [`TipoverRequest`] (or,
//! with `--dynamic` / `--rolling`, the timed runs of [`super::tipover_dynamic`]), one library
//! call ([`toroid::tipover_report`]) and the report printed; `--grid` the Fig. 3.13 map.

use super::request_args::{Modes, RequestArgs};
use super::values;
use anyhow::Result;
use std::path::{Path, PathBuf};
use tensegrity_io::sink::FileSink;
use toroid::{TipoverDynamicRequest, TipoverReport, TipoverRequest, TipoverRollingRequest};

/// The flags of the three runs of `tipover`: static, `--dynamic`, `--rolling`.
type TipoverModes = Modes<TipoverRequest, TipoverDynamicRequest, TipoverRollingRequest>;

/// Arguments of `tensegrity tipover`: the flags of its three requests ([`TipoverRequest`],
/// with `--dynamic` [`TipoverDynamicRequest`], with `--rolling` [`TipoverRollingRequest`]:
/// each mode refuses the flags of the others), the mode and the outputs.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("time_run").args(["dynamic", "rolling"]).multiple(false)))]
pub struct TipoverArgs {
    #[command(flatten)]
    request: RequestArgs<TipoverModes>,
    /// Check the threshold with the full 3-D dynamics: the wheel at rest on a side on level
    /// ground, a lateral force ramped at the hub.
    #[arg(long)]
    dynamic: bool,
    /// Instead, roll the wheel down a plane with a side slope and report its lean (the
    /// conclusion's stability claim); with --incline, --side-slope, --t-end.
    #[arg(long, conflicts_with = "dynamic")]
    rolling: bool,
    /// Instead of one wheel, write F_f/F_e over a σ × ε grid (Fig. 3.13) to this CSV.
    #[arg(long)]
    grid: Option<PathBuf>,
    /// Grid points per axis.
    #[arg(long, default_value_t = sweeps::grids::FRICTION_GRID_POINTS, value_parser = values::at_least_two)]
    grid_points: usize,
    /// Largest ε of the grid.
    #[arg(long, default_value_t = sweeps::grids::FRICTION_GRID_EPS_MAX, value_parser = values::positive)]
    eps_max: f64,
    /// Write the history of --dynamic (t, force, lean, near_normal, far_normal) or --rolling
    /// (t, lean, downhill, across) to this CSV.
    #[arg(long, value_name = "FILE", requires = "time_run")]
    out: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    /// With --dynamic: the animation of the wheel under the ramp.
    #[command(flatten)]
    animate: super::animate::AnimateArgs,
}

/// Entry point of `tensegrity tipover`.
pub fn run_tipover(args: &TipoverArgs) -> Result<()> {
    let out = args.out.as_deref();
    if let (Some(p), false) = (&args.animate.animate, args.dynamic) {
        let why = "an animation draws the `dynamic` run only";
        let e = tensegrity_core::request::InvalidParameter::raw("animate", p.display(), why);
        return Err(super::request_args::usage(e));
    }
    if args.rolling {
        let req = args.request.request()?;
        return super::tipover_dynamic::run_rolling(&req, out, args.json);
    }
    if args.dynamic {
        let req = args.request.request()?;
        return super::tipover_dynamic::run(&req, out, args.json, &args.animate);
    }
    if let Some(path) = &args.grid {
        return run_grid(args, path);
    }
    let report = toroid::tipover_report(&args.request.request()?)?;
    if args.json {
        super::output::print_json(&report)?;
    } else {
        print_tipover(&report);
    }
    Ok(())
}

/// `--grid`: the (σ, ε, F_f/F_e) grid as CSV, its file opened before the grid is computed.
fn run_grid(args: &TipoverArgs, path: &Path) -> Result<()> {
    let _progress = super::guard::friction_grid(args.grid_points)?;
    let mut sink = super::output::open_required("--grid", path, FileSink::open)?;
    let rows = sweeps::grids::friction_grid(args.grid_points, args.eps_max)?;
    sink.write_with(|w| tensegrity_io::csv::write_friction_grid(w, &rows))?;
    sink.finish()?;
    println!("wrote {}", path.display());
    Ok(())
}

fn print_tipover(r: &TipoverReport) {
    println!(
        "mass {:.4} kg  ρ = T/R_o = {:.4}  ε = t/T = {:.4}  σ = R_i/R_o = {:.4}",
        r.mass_kg, r.rho, r.epsilon, r.sigma
    );
    println!(
        "tips over under a lateral axle force above {:.4} N",
        r.critical_lateral_force
    );
    println!(
        "friction needed at the threshold, F_f/F_e = {:.4}",
        r.normalized_friction
    );
    println!(
        "tips before sliding when μ_s > {:.4}",
        r.min_friction_to_tip
    );
}
