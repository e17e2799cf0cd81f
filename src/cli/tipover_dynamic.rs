//! `tensegrity tipover --dynamic [geometry flags] [--ramp-time S] [--ramp-to X] [--hold S]
//! [--mu MU] [--out lean.csv] [--json]`: the static tip-over threshold checked by the full 3-D
//! dynamics (one call to [`toroid::tipover_dynamic::DynamicTipover::run`]).

use super::values;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use toroid::rolling_lean::LeanRolling;
use toroid::tipover_dynamic::{DynamicTipover, DynamicTipoverReport, LeanSample};
use toroid::WheelSpec;

/// The flags of the dynamic run (flattened into `tipover`).
#[derive(clap::Args, Debug, Clone)]
#[command(group(clap::ArgGroup::new("time_run").args(["dynamic", "rolling"]).multiple(false)))]
pub struct DynamicArgs {
    /// Check the threshold with the full 3-D dynamics: the wheel at rest on a side on level
    /// ground, a lateral force ramped at the hub.
    #[arg(long)]
    pub dynamic: bool,
    /// Instead, roll the wheel down a plane with a side slope and report its lean (the
    /// conclusion's stability claim); with --incline, --side-slope, --t-end.
    #[arg(long, conflicts_with = "dynamic")]
    pub rolling: bool,
    /// Incline downhill of the --rolling plane, e.g. `30deg`.
    #[arg(long, default_value = "30deg", value_parser = crate::cli::angle::parse_angle, requires = "rolling")]
    pub incline: f64,
    /// Side slope of the --rolling plane, e.g. `5deg`.
    #[arg(long, default_value = "5deg", value_parser = crate::cli::angle::parse_angle, allow_hyphen_values = true, requires = "rolling")]
    pub side_slope: f64,
    /// Simulated time of the --rolling run (s).
    #[arg(long, default_value_t = 3.0, value_parser = values::positive, requires = "rolling")]
    pub t_end: f64,
    /// Ramp duration (s), from 0 to --ramp-to × the static threshold.
    #[arg(long, default_value_t = 4.0, value_parser = values::positive, requires = "dynamic")]
    pub ramp_time: f64,
    /// Largest force of the ramp, as a multiple of the static threshold.
    #[arg(long, default_value_t = 1.3, value_parser = values::positive, requires = "dynamic")]
    pub ramp_to: f64,
    /// Time the largest force is held after the ramp (s).
    #[arg(long, default_value_t = 0.0, value_parser = values::non_negative, requires = "dynamic")]
    pub hold: f64,
    /// Static friction coefficient of the ground (kinetic = 0.75 μ).
    #[arg(long, default_value_t = 1.0, value_parser = values::positive, requires = "time_run")]
    pub mu: f64,
    /// String stiffness of the wheel (N/m): the threshold is the rigid one only for a stiff
    /// wheel (a soft one deforms and tips early).
    #[arg(long, default_value_t = 2e6, value_parser = values::positive, requires = "time_run")]
    pub string_stiffness: f64,
    /// RK4 step (s); stiffer strings need a smaller one.
    #[arg(long, default_value_t = 1e-4, value_parser = values::positive, requires = "time_run")]
    pub dt: f64,
    /// Write the history (t, force, lean, near_normal, far_normal) to this CSV.
    #[arg(long, value_name = "FILE", requires = "time_run")]
    pub out: Option<PathBuf>,
}

/// Runs the lean-while-rolling study and prints its report.
pub fn run_rolling(args: &DynamicArgs, wheel: &WheelSpec, gravity: f64, json: bool) -> Result<()> {
    let toroid = wheel.build()?;
    let run = LeanRolling {
        incline: args.incline,
        side_slope: args.side_slope,
        t_end: args.t_end,
        wheel: DynamicTipover {
            gravity,
            mu: args.mu,
            string_stiffness: args.string_stiffness,
            dt: args.dt,
            ..DynamicTipover::default()
        },
    };
    let r = run.run(&toroid).context("rolling lean run failed")?;
    for w in &r.warnings {
        eprintln!("warning: {w}");
    }
    if let Some(path) = &args.out {
        use std::fmt::Write;
        let mut text = String::from("t,lean,downhill,across\n");
        for s in &r.samples {
            let _ = writeln!(text, "{},{},{},{}", s.t, s.lean, s.downhill, s.across);
        }
        tensegrity_io::write_text(path, "lean history", &text)
            .with_context(|| format!("writing the lean history {}", path.display()))?;
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&r)?);
    } else {
        println!(
            "n = {}, T = {} m rolling {:.2}° down with a {:.2}° side slope (static limit {:.2}°)",
            r.sides,
            r.outer_tread,
            r.incline.to_degrees(),
            r.side_slope.to_degrees(),
            r.static_critical_side_slope.to_degrees()
        );
        println!(
            "largest lean {:.4} rad, final {:.4} rad, {:.3} m downhill: {}",
            r.max_lean,
            r.final_lean,
            r.downhill,
            match r.fall_time {
                Some(t) => format!("fell at t = {t:.3} s"),
                None => "stayed up".to_string(),
            }
        );
        println!("{}", validity_line(r.valid, r.max_penetration));
    }
    Ok(())
}

/// Runs the dynamic check and prints its report.
pub fn run(args: &DynamicArgs, wheel: &WheelSpec, gravity: f64, json: bool) -> Result<()> {
    let toroid = wheel.build()?;
    let settings = DynamicTipover {
        gravity,
        ramp_time: args.ramp_time,
        ramp_to: args.ramp_to,
        hold: args.hold,
        mu: args.mu,
        string_stiffness: args.string_stiffness,
        dt: args.dt,
        ..DynamicTipover::default()
    };
    let report = settings
        .run(&toroid)
        .context("dynamic tip-over run failed")?;
    if let Some(path) = &args.out {
        write_history(path, &report.samples)?;
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print(&report);
    }
    Ok(())
}

fn write_history(path: &Path, samples: &[LeanSample]) -> Result<()> {
    use std::fmt::Write;
    let mut text = String::from("t,force,lean,near_normal,far_normal\n");
    for s in samples {
        let _ = writeln!(
            text,
            "{},{},{},{},{}",
            s.t, s.force, s.lean, s.near_normal, s.far_normal
        );
    }
    tensegrity_io::write_text(path, "lean history", &text)
        .with_context(|| format!("writing the lean history {}", path.display()))
}

fn print(r: &DynamicTipoverReport) {
    println!(
        "n = {}, T = {} m, mass {:.4} kg, resting on a side (hub height {:.4} m)",
        r.sides, r.outer_tread, r.mass_kg, r.hub_height
    );
    println!("static threshold (m g/2)(T/h): {:.4} N", r.static_threshold);
    match (r.dynamic_threshold, r.relative_difference) {
        (Some(d), Some(rel)) => println!(
            "dynamic threshold (near tread edge unloads): {d:.4} N ({:+.2} %)",
            100.0 * rel
        ),
        _ => println!("the near tread edge never unloaded: the wheel did not tip"),
    }
    println!(
        "largest lean {:.4} rad, final {:.4} rad: {}",
        r.max_lean,
        r.final_lean,
        if r.tipped { "tipped over" } else { "upright" }
    );
    println!("{}", validity_line(r.valid, r.max_penetration));
}

fn validity_line(valid: bool, max_penetration: f64) -> String {
    format!(
        "validity: {}; max penetration {max_penetration:.3e} m",
        if valid {
            "valid"
        } else {
            "NOT valid (see the warnings)"
        }
    )
}
