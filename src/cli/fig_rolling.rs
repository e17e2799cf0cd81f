//! `tensegrity fig-rolling`: thesis Figs. 3.10 (n = 8, 12, 16, 24) and 3.11 (n = 8, 16) for
//! the reference wheel with spokes + inner rings. Its flags are the fields of
//! [`FigRollingRequest`] ([`RequestArgs`]); `--out` is opened before the wheels roll
//! ([`tensegrity_figures::fig_rolling`]: one thread per wheel); the summary of each run and
//! the impact impulse per new contact against n (§3.3.1) are printed.

use super::request_args::RequestArgs;
use anyhow::Result;
use std::path::PathBuf;
use tensegrity_figures::rolling::{FigRolling, FigRollingRequest};

/// Arguments of `tensegrity fig-rolling`.
#[derive(clap::Args, Debug)]
pub struct FigRollingArgs {
    /// Output figure: SVG, PNG or PDF by the extension.
    #[arg(long, value_name = "FILE", default_value = "rolling.svg")]
    out: PathBuf,
    #[command(flatten)]
    request: RequestArgs<FigRollingRequest>,
    /// Print the runs' reports, the impulse table (`impacts`) and the figure's path as JSON.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    figure: super::figure_args::FigureArgs,
}

/// Entry point of `tensegrity fig-rolling`.
pub fn run(args: &FigRollingArgs) -> Result<()> {
    let request: FigRollingRequest = args.request.request()?;
    let sides = FigRollingRequest::SIDES;
    // a setting only the full model reads, under --fidelity rigid, is refused as by `roll`
    request
        .roll_request(sides[0])
        .check_rigid_given(|name| args.request.given(name))
        .map_err(super::request_args::usage)?;
    let _progress = super::guard::rolling_series(&request.roll_request(sides[0]), &sides)?;
    let sink = args.figure.open_required("--out", &args.out)?;
    // a wheel that only failed to converge is re-run at half its step if that fits the
    // work limit (measured wall time; said so below)
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let budget = super::guard::limits().work_s;
    let rolled = tensegrity_figures::fig_rolling_within(&request, budget, cores)?;
    sink.finish(&rolled.figure())?;
    if args.json {
        let (runs, impacts, figure) = (&rolled.runs, rolled.impacts(), args.out.display());
        let figure = figure.to_string();
        let notes = rolled.ensemble_notes();
        return super::output::print_json(
            &serde_json::json!({"runs": runs, "impacts": impacts, "figure": figure,
                "ensemble_notes": notes, "refined": rolled.refined}),
        );
    }
    print_series(&rolled);
    for note in rolled.ensemble_notes() {
        println!("ensemble: {note}");
    }
    println!("wrote {}", args.out.display());
    Ok(())
}

/// Prints one line per wheel (model, validity, axle height, speed) and the impulse table.
fn print_series(rolled: &FigRolling) {
    for r in &rolled.runs {
        println!(
            "n = {:>2} ({:?}, {}): mean axle height {:.4} m, oscillation {:.5} m, mean speed {:.3} m/s, airborne {:.1} %{}",
            r.sides,
            r.fidelity,
            r.contact,
            r.summary.mean_axle_height,
            r.summary.axle_height_oscillation,
            r.summary.mean_speed,
            100.0 * r.summary.airborne_fraction,
            if r.summary.valid { "" } else { "  NOT VALID" }
        );
        for w in &r.summary.warnings {
            eprintln!("warning (n = {}): {w}", r.sides);
        }
    }
    print_refinements(rolled);
    println!("\nimpact impulse per new contact (§3.3.1), means over each run's impacts:");
    println!(
        "{:>4} {:>8} {:>14} {:>18} {:>16} {:>14}",
        "n", "impacts", "normal [N s]", "tangential [N s]", "normal/m [m/s]", "omega+/omega-"
    );
    for m in rolled.impacts() {
        println!(
            "{:>4} {:>8} {:>14.5} {:>18.5} {:>16.5} {:>14.5}",
            m.sides,
            m.impacts,
            m.normal_impulse,
            m.tangential_impulse,
            m.normal_per_mass,
            m.omega_ratio
        );
    }
}

/// What was refined automatically, and the remedy of a run that only failed to converge
/// and was not: a finer step.
fn print_refinements(rolled: &FigRolling) {
    for r in &rolled.refined {
        println!(
            "n = {}: not converged at dt = {} s, refined automatically to dt = {} s (within --max-work)",
            r.sides, r.from_dt, r.to_dt
        );
    }
    let unconverged: Vec<&toroid::RollReport> = rolled
        .runs
        .iter()
        .filter(|r| r.summary.only_unconverged())
        .collect();
    if let Some(first) = unconverged.first() {
        let sides: Vec<String> = unconverged.iter().map(|r| r.sides.to_string()).collect();
        println!(
            "note: n = {} not converged at dt = {} s: rerun with --dt {} (twice the work: raise --max-work)",
            sides.join(", "),
            first.dt,
            0.5 * first.dt
        );
    }
}
