//! `tensegrity tipover`: parses the arguments into a [`toroid::TipoverRequest`], makes one
//! library call ([`toroid::tipover_report`]) and prints the report.

use super::values;
use anyhow::Result;
use std::path::{Path, PathBuf};
use tensegrity_io::sink::FileSink;
use toroid::defaults;
use toroid::{TipoverReport, TipoverRequest};

use super::toroid::GeometryArgs;

/// Arguments of `tensegrity tipover`.
#[derive(clap::Args, Debug)]
pub struct TipoverArgs {
    #[command(flatten)]
    geometry: GeometryArgs,
    /// Gravity (m/s²).
    #[arg(long, default_value_t = defaults::GRAVITY, value_parser = values::positive)]
    gravity: f64,
    /// Instead of one wheel, write F_f/F_e over a σ × ε grid (Fig. 3.13) to this CSV.
    #[arg(long)]
    grid: Option<PathBuf>,
    /// Grid points per axis.
    #[arg(long, default_value_t = 50, value_parser = values::at_least_two)]
    grid_points: usize,
    /// Largest ε of the grid.
    #[arg(long, default_value_t = 1.0, value_parser = values::positive)]
    eps_max: f64,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    dynamic: super::tipover_dynamic::DynamicArgs,
}

/// Entry point of `tensegrity tipover`.
pub fn run_tipover(args: &TipoverArgs) -> Result<()> {
    if args.dynamic.rolling {
        return super::tipover_dynamic::run_rolling(
            &args.dynamic,
            &args.geometry.wheel(),
            args.gravity,
            args.json,
        );
    }
    if args.dynamic.dynamic {
        return super::tipover_dynamic::run(
            &args.dynamic,
            &args.geometry.wheel(),
            args.gravity,
            args.json,
        );
    }
    if let Some(path) = &args.grid {
        return run_grid(args, path);
    }
    let request = TipoverRequest {
        wheel: args.geometry.wheel(),
        gravity: args.gravity,
    };
    let report = toroid::tipover_report(&request)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
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
