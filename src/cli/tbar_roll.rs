//! `tensegrity tbar roll`: parses the flags into a [`TbarRollRequest`], makes one library
//! call ([`tensegrity_engine::tbar_roll::tbar_roll`]: the T-bar wheel beside the toroid of
//! equal outer radius, rigid or full model, with tip-over) and prints the report. The
//! defaults are the library's (the fidelity-dependent ones resolved by the request).

use super::angle::parse_angle;
use super::tbar::{BarBaseArg, RimArg};
use super::values;
use anyhow::Result;
use tbar_wheel::roll::{TbarRollReport, TbarRollRequest, TbarRollRow};
use tbar_wheel::BarBase;
use tensegrity_engine::tbar_roll;
use wheel_rolling::{defaults, Fidelity, RollSettings, WheelRun};

/// Arguments of `tensegrity tbar roll`.
#[derive(clap::Args, Debug)]
pub struct TbarRollArgs {
    /// Complexity q.
    #[arg(long, default_value_t = 1)]
    complexity: usize,
    /// Departure angle β.
    #[arg(long, value_parser = parse_angle)]
    beta: f64,
    /// Cylindrical parameterisation with offset δ.
    #[arg(
        long,
        value_name = "D",
        allow_hyphen_values = true,
        conflicts_with = "spherical",
        required_unless_present = "spherical"
    )]
    cylindrical: Option<f64>,
    /// Spherical parameterisation with angle ε.
    #[arg(long, value_name = "E", value_parser = parse_angle)]
    spherical: Option<f64>,
    /// Tip radius r₀ (m): the rolling polygon's circumradius.
    #[arg(long, default_value_t = 1.0, value_parser = values::positive)]
    r0: f64,
    /// Roll the extended wheel with its copy at OFFSET (m) along ι̂₁ (else the single loop).
    #[arg(long, value_name = "OFFSET", allow_hyphen_values = true)]
    extended: Option<f64>,
    /// Base of the radial bar.
    #[arg(long, value_enum, default_value_t = BarBaseArg::Rim)]
    bar_base: BarBaseArg,
    /// Rim mass: none (`fixed`: a massless rigid rim, the treads' bars only; the default of
    /// the rigid model) or the rim body's bars (`body`; the full model's only choice).
    #[arg(long, value_enum)]
    rim: Option<RimArg>,
    /// Rolling model: `rigid` (the reduced polygon) or `full` (the tensegrity dynamics of the
    /// prestressed wheel with its rim body).
    #[arg(long, value_enum, default_value_t = FidelityArg::Rigid)]
    fidelity: FidelityArg,
    /// Numbers of treads n = π/φ to roll (comma separated); default 8, 12, 16, 24 for the
    /// rigid model, 8 for the full model (its cost grows steeply with n, see the guard).
    #[arg(long, value_delimiter = ',')]
    treads: Option<Vec<usize>>,
    /// Slope angle.
    #[arg(long, value_parser = parse_angle, default_value = "50deg")]
    incline: f64,
    /// Simulated time (s); default 10 s for the rigid model, 1 s for the full model.
    #[arg(long, value_parser = values::positive)]
    t_end: Option<f64>,
    /// Integration step (s).
    #[arg(long, default_value_t = defaults::ROLL_DT, value_parser = values::positive)]
    dt: f64,
    /// Gravity (m/s²).
    #[arg(long, default_value_t = defaults::GRAVITY, value_parser = values::positive)]
    gravity: f64,
    /// Bar density (kg/m) of both wheels; strings are massless.
    #[arg(long, default_value_t = tbar_wheel::rolling::DEFAULT_BAR_DENSITY, value_parser = values::positive)]
    bar_density: f64,
    /// Static friction coefficient of the slope.
    #[arg(long, default_value_t = defaults::STATIC_FRICTION, value_parser = values::non_negative)]
    mu_static: f64,
    /// Kinetic friction coefficient (default 0.75 μ_s).
    #[arg(long, value_parser = values::non_negative)]
    mu_kinetic: Option<f64>,
    /// Normal coefficient of restitution of an impact (the full model's penalty damping
    /// follows from it unless --ground-damping is given).
    #[arg(long, default_value_t = defaults::RESTITUTION, value_parser = values::non_negative)]
    restitution: f64,
    /// Full model: density of the rim body's bars (kg/m; default: --bar-density).
    #[arg(long, value_parser = values::positive)]
    rim_density: Option<f64>,
    /// Full model: stiffness of every string (N/m).
    #[arg(long, default_value_t = defaults::STRING_STIFFNESS, value_parser = values::positive)]
    string_stiffness: f64,
    /// Full model: smallest string tension of the prestress (N); default: the prestress
    /// that carries twice the wheel's weight on one tip of each copy from every direction.
    #[arg(long, value_parser = values::positive)]
    min_tension: Option<f64>,
    /// Full model: penalty ground stiffness per contact node (N/m).
    #[arg(long, default_value_t = defaults::GROUND_STIFFNESS, value_parser = values::positive)]
    ground_stiffness: f64,
    /// Full model: normal ground damping per contact node (N·s/m; default from
    /// --restitution).
    #[arg(long, value_parser = values::non_negative)]
    ground_damping: Option<f64>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// The rolling model of `tensegrity tbar roll`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum FidelityArg {
    /// The reduced rigid polygon (unilateral contact, impacts).
    Rigid,
    /// The full tensegrity dynamics of the prestressed wheel with its rim body.
    Full,
}

impl TbarRollArgs {
    /// The library request the flags describe.
    pub fn request(&self) -> TbarRollRequest {
        TbarRollRequest {
            complexity: self.complexity,
            beta: self.beta,
            cylindrical: self.cylindrical,
            spherical: self.spherical,
            r0: self.r0,
            extended: self.extended,
            bar_base: match self.bar_base {
                BarBaseArg::Rim => BarBase::Rim,
                BarBaseArg::Chord => BarBase::Chord,
            },
            rim: self.rim.map(Into::into),
            fidelity: match self.fidelity {
                FidelityArg::Rigid => Fidelity::Rigid,
                FidelityArg::Full => Fidelity::Full,
            },
            treads: self.treads.clone(),
            settings: RollSettings {
                incline: self.incline,
                dt: self.dt,
                gravity: self.gravity,
                restitution: self.restitution,
                string_stiffness: self.string_stiffness,
                ground_stiffness: self.ground_stiffness,
                ground_damping: self.ground_damping,
            },
            t_end: self.t_end,
            bar_density: self.bar_density,
            mu_static: self.mu_static,
            mu_kinetic: self.mu_kinetic,
            rim_density: self.rim_density,
            min_tension: self.min_tension,
        }
    }
}

/// Entry point of `tensegrity tbar roll`.
pub fn run(args: &TbarRollArgs) -> Result<()> {
    let request = args.request();
    let _progress = match tbar_roll::estimate(&request)? {
        Some(e) => Some(super::guard::check(e)?),
        None => None,
    };
    let report = tbar_roll::tbar_roll(&request)?;
    for row in &report.rows {
        for e in &row.errors {
            eprintln!("warning: n = {}: {}", row.treads, super::spell::flags(e));
        }
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_roll(&report);
    }
    Ok(())
}

fn print_roll(r: &TbarRollReport) {
    println!(
        "{} (rim {}) rolling down {:.2}° for {} s, {} model; toroid of equal outer radius",
        r.structure,
        r.rim.as_str(),
        r.incline_rad.to_degrees(),
        r.t_end,
        if r.full_tensegrity_rolling {
            "full tensegrity"
        } else {
            "reduced rigid"
        }
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
        println!("     warning: {}", super::spell::flags(w));
    }
}
