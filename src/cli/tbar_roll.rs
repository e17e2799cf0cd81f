//! `tensegrity tbar roll`: the T-bar wheel (or extended wheel) rolling down an incline with the
//! toroid crate's reduced rigid model ([`toroid::rolling::RigidRolling`], called through its
//! public fields), side by side with the toroid of equal outer radius and the same number of
//! sides, over the number of treads n = π/φ; plus the out-of-plane tip-over of the structure
//! ([`tbar_wheel::rolling::tipover`]).
//!
//! The composition lives here so that the tbar-wheel crate does not depend on the toroid
//! crate: tbar-wheel gives the polygon (n sides, circumradius r₀ = the tips), the mass and I₁
//! ([`tbar_wheel::rolling::mass_properties`], bars of `--bar-density`, strings massless), the
//! toroid crate the model. The toroid is the reference wheel (ERRATA: T = 0.4, t = 0.3,
//! D = 0.1, R_o = 1, R_i = 0.6, R_m = 0.8, spokes + inner rings) scaled by r₀ with n sides and
//! the same bar density. Only the reduced rigid model runs: a full tensegrity rolling of the
//! T-bar wheel is not implemented (`full_tensegrity_rolling: false` in the JSON).

use super::angle::parse_angle;
use super::values;
use anyhow::Result;
use michell3d::MichellParams;
use serde::Serialize;
use std::f64::consts::PI;
use tbar_wheel::rolling::{mass_properties, tipover, MassProperties, TipOver};
use tbar_wheel::{BarBase, Layout, TbarGeometry, TbarParams};
use toroid::defaults;
use toroid::rolling::{RigidRolling, RollingResult};

use super::tbar::{BarBaseArg, RimArg};

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
    /// Rim mass: none (`fixed`: a massless rigid rim, the treads' bars only) or the rim
    /// body's bars (`body`).
    #[arg(long, value_enum, default_value_t = RimArg::Fixed)]
    rim: RimArg,
    /// Numbers of treads n = π/φ to roll (comma separated).
    #[arg(long, value_delimiter = ',', default_values_t = defaults::FIG_3_10_SIDES)]
    treads: Vec<usize>,
    /// Slope angle.
    #[arg(long, value_parser = parse_angle, default_value = "50deg")]
    incline: f64,
    /// Simulated time (s).
    #[arg(long, default_value_t = defaults::ROLL_T_END, value_parser = values::positive)]
    t_end: f64,
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
    /// Normal coefficient of restitution of an impact.
    #[arg(long, default_value_t = defaults::RESTITUTION, value_parser = values::non_negative)]
    restitution: f64,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// One rigid rolling run, as reported.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunSummary {
    /// Mass m (kg).
    pub mass_kg: f64,
    /// I₁ about the axle (kg m²).
    #[serde(rename = "I1")]
    pub i1: f64,
    /// ω⁺/ω⁻ of a plastic pivot-to-pivot impact.
    pub impact_ratio: f64,
    /// Contact-pair impacts.
    pub impacts: usize,
    /// RMS axle-height deviation after the first second (m).
    pub axle_height_oscillation: f64,
    /// Mean downhill speed after the first second (m/s).
    pub mean_speed: f64,
    /// Downhill speed at the end (m/s).
    pub final_speed: f64,
    /// Whether the run stayed inside the model's assumptions.
    pub valid: bool,
    /// The violated assumptions.
    pub warnings: Vec<String>,
    /// Smallest normal contact force (N).
    pub min_normal_force: f64,
    /// Fraction of the time in flight.
    pub airborne_fraction: f64,
}

/// One number of treads.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RollRow {
    /// Treads per wheel n = π/φ (the polygon's sides).
    pub treads: usize,
    /// φ = π/n (rad).
    pub phi: f64,
    /// The T-bar wheel's mass properties.
    pub mass_properties: Option<MassProperties>,
    /// The T-bar wheel's run.
    pub tbar: Option<RunSummary>,
    /// The toroid of equal outer radius and n sides.
    pub toroid: Option<RunSummary>,
    /// Out-of-plane tip-over of the T-bar structure (its own weight).
    pub tipover: Option<TipOver>,
    /// Why a part is missing.
    pub errors: Vec<String>,
}

/// The report of `tensegrity tbar roll`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TbarRollReport {
    /// The rolling model: `rigid` (reduced polygon).
    pub model: &'static str,
    /// Whether a full tensegrity rolling of the T-bar wheel ran (not implemented).
    pub full_tensegrity_rolling: bool,
    /// `wheel` or `extended wheel`.
    pub structure: &'static str,
    /// `body` (rim body's bars in the mass) or `fixed` (massless rigid rim).
    pub rim: &'static str,
    /// Slope angle (rad).
    pub incline_rad: f64,
    /// Simulated time (s).
    pub t_end: f64,
    /// One row per number of treads.
    pub rows: Vec<RollRow>,
}

/// Entry point of `tensegrity tbar roll`.
pub fn run(args: &TbarRollArgs) -> Result<()> {
    let report = roll_report(args);
    for row in &report.rows {
        for e in &row.errors {
            eprintln!("warning: n = {}: {e}", row.treads);
        }
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_roll(&report);
    }
    Ok(())
}

/// Every row of the report.
pub fn roll_report(args: &TbarRollArgs) -> TbarRollReport {
    let layout = match args.extended {
        Some(offset) => Layout::Extended { offset },
        None => Layout::Wheel,
    };
    TbarRollReport {
        model: "rigid",
        full_tensegrity_rolling: false,
        structure: layout.name(),
        rim: tbar_wheel::RimMode::from(args.rim).as_str(),
        incline_rad: args.incline,
        t_end: args.t_end,
        rows: args.treads.iter().map(|&n| row(args, layout, n)).collect(),
    }
}

/// The T-bar parameters with n treads.
fn params(args: &TbarRollArgs, layout: Layout, n: usize) -> TbarParams {
    let phi = PI / n as f64;
    let (q, r0, beta) = (args.complexity, args.r0, args.beta);
    let m = match (args.cylindrical, args.spherical) {
        (_, Some(e)) => MichellParams::spherical(q, r0, beta, phi, e),
        (d, None) => MichellParams::cylindrical(q, r0, beta, phi, d.unwrap_or(0.0)),
    };
    let base = match args.bar_base {
        BarBaseArg::Rim => BarBase::Rim,
        BarBaseArg::Chord => BarBase::Chord,
    };
    TbarParams::tread(m)
        .with_layout(layout)
        .with_bar_base(base)
        .with_rim(args.rim.into())
}

fn row(args: &TbarRollArgs, layout: Layout, n: usize) -> RollRow {
    let mut row = RollRow {
        treads: n,
        phi: PI / n as f64,
        mass_properties: None,
        tbar: None,
        toroid: None,
        tipover: None,
        errors: Vec::new(),
    };
    let tbar = TbarGeometry::new(params(args, layout, n))
        .map_err(anyhow::Error::from)
        .and_then(|g| Ok((mass_properties(&g, args.bar_density)?, g)));
    match tbar {
        Ok((mp, g)) => {
            row.mass_properties = Some(mp);
            match tipover(&g, mp.mass, args.gravity) {
                Ok(t) => row.tipover = Some(t),
                Err(e) => row.errors.push(format!("tip-over: {e}")),
            }
            match run_rigid(args, &tbar_model(args, &mp)) {
                Ok(s) => row.tbar = Some(s),
                Err(e) => row.errors.push(format!("T-bar rolling: {e}")),
            }
        }
        Err(e) => row.errors.push(format!("T-bar wheel: {e}")),
    }
    match toroid_model(args, n).and_then(|m| run_rigid(args, &m)) {
        Ok(s) => row.toroid = Some(s),
        Err(e) => row.errors.push(format!("toroid: {e}")),
    }
    row
}

/// The reduced rigid model of the T-bar polygon.
pub fn tbar_model(args: &TbarRollArgs, mp: &MassProperties) -> RigidRolling {
    rigid_model(args, mp.sides, mp.outer_radius, mp.mass, mp.i1)
}

/// The reduced rigid model of a polygon of `sides` sides, circumradius `outer_radius`, mass
/// and I₁, in the settings of `args`.
fn rigid_model(
    args: &TbarRollArgs,
    sides: usize,
    outer_radius: f64,
    mass: f64,
    i1: f64,
) -> RigidRolling {
    RigidRolling {
        sides,
        outer_radius,
        mass,
        i1,
        incline: args.incline,
        gravity: args.gravity,
        dt: args.dt,
        output_dt: defaults::ROLL_OUTPUT_DT,
        mu_static: args.mu_static,
        mu_kinetic: args
            .mu_kinetic
            .unwrap_or(defaults::KINETIC_FRICTION_RATIO * args.mu_static),
        restitution: args.restitution,
    }
}

/// The reference toroid scaled to outer radius r₀, with n sides, in the same settings.
fn toroid_model(args: &TbarRollArgs, n: usize) -> Result<RigidRolling> {
    let r = toroid::ToroidParams::REFERENCE;
    let k = args.r0 / r.outer_radius;
    let p = toroid::ToroidParams {
        sides: n,
        outer_tread: k * r.outer_tread,
        inner_tread: k * r.inner_tread,
        offset: k * r.offset,
        outer_radius: k * r.outer_radius,
        inner_radius: k * r.inner_radius,
        rim_radius: k * r.rim_radius,
    };
    let t = toroid::build(&p, toroid::Stabilize::SPOKES_INNER, args.bar_density)?;
    let a = toroid::analyse(&t)?;
    let base = RigidRolling::of(&t, &a, args.incline);
    Ok(rigid_model(
        args,
        base.sides,
        base.outer_radius,
        base.mass,
        base.i1,
    ))
}

fn run_rigid(args: &TbarRollArgs, model: &RigidRolling) -> Result<RunSummary> {
    let r: RollingResult = model.run(args.t_end)?;
    Ok(RunSummary {
        mass_kg: model.mass,
        i1: model.i1,
        impact_ratio: model.impact_ratio(),
        impacts: r.impacts,
        axle_height_oscillation: r.axle_height_oscillation,
        mean_speed: r.mean_speed,
        final_speed: r.final_speed,
        valid: r.validity.valid(),
        warnings: r.validity.warnings.clone(),
        min_normal_force: r.validity.min_normal_force,
        airborne_fraction: r.validity.airborne_fraction,
    })
}

fn print_roll(r: &TbarRollReport) {
    println!(
        "{} (rim {}) rolling down {:.2}° for {} s, reduced rigid model; toroid of equal outer radius",
        r.structure,
        r.rim,
        r.incline_rad.to_degrees(),
        r.t_end
    );
    println!("  n   T-bar m [kg]  I1 [kg m²]  oscillation [m]  speed [m/s]  valid | toroid m  oscillation [m]  speed [m/s]  valid");
    let cell = |s: &Option<RunSummary>| match s {
        Some(s) => format!(
            "{:>10.4} {:>11.4} {:>16.6} {:>12.4} {:>6}",
            s.mass_kg, s.i1, s.axle_height_oscillation, s.mean_speed, s.valid
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

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;
    use tbar_wheel::rolling::impact_ratio;

    #[derive(Parser)]
    struct Wrap {
        #[command(flatten)]
        args: TbarRollArgs,
    }

    fn args(extra: &[&str]) -> TbarRollArgs {
        let mut v = vec![
            "x",
            "--beta",
            "pi/6",
            "--cylindrical",
            "0.25",
            "--t-end",
            "2",
        ];
        v.extend_from_slice(extra);
        Wrap::parse_from(v).args
    }

    #[test]
    fn the_tbar_model_is_the_polygon_of_the_wheel_and_its_impact_ratio_the_formula() {
        let a = args(&["--extended", "0.5", "--treads", "12"]);
        let g = TbarGeometry::new(params(&a, Layout::Extended { offset: 0.5 }, 12)).unwrap();
        let mp = mass_properties(&g, 1.0).unwrap();
        let m = tbar_model(&a, &mp);
        assert_eq!((m.sides, m.outer_radius), (12, 1.0));
        assert_eq!((m.mass, m.i1), (mp.mass, mp.i1));
        let mr2 = mp.mass;
        let want = (mp.i1 + mr2 * (PI / 6.0).cos()) / (mp.i1 + mr2);
        assert!((m.impact_ratio() - want).abs() < 1e-14);
        assert!((impact_ratio(&mp) - want).abs() < 1e-14);
        assert!((m.mu_kinetic - 0.6).abs() < 1e-15);
    }

    #[test]
    fn rows_compare_the_two_wheels_and_report_the_tipover() {
        let r = roll_report(&args(&["--extended", "0.4", "--treads", "8,12"]));
        assert_eq!((r.model, r.full_tensegrity_rolling), ("rigid", false));
        assert_eq!(r.rows.len(), 2);
        for row in &r.rows {
            assert!(row.errors.is_empty(), "{:?}", row.errors);
            let (t, o) = (row.tbar.as_ref().unwrap(), row.toroid.as_ref().unwrap());
            // both roll down 50° > π/n and bump: more treads, smaller oscillation
            assert!(t.impacts > 0 && o.impacts > 0);
            let tip = row.tipover.as_ref().unwrap();
            let mg = row.mass_properties.unwrap().mass * 9.81;
            assert!((tip.critical_lateral_force - 0.5 * mg * 0.4).abs() < 1e-12);
        }
        let osc = |i: usize| r.rows[i].tbar.as_ref().unwrap().axle_height_oscillation;
        assert!(osc(1) < osc(0));
        // the toroid column is `toroid::roll` with the rigid fidelity (the reference wheel, R_o = 1)
        let direct = toroid::roll(&toroid::RollRequest {
            wheel: toroid::WheelSpec::with_sides(8),
            fidelity: toroid::FidelityChoice::Rigid,
            t_end: 2.0,
            ..Default::default()
        })
        .unwrap();
        let ours = r.rows[0].toroid.as_ref().unwrap();
        assert_eq!((ours.mass_kg, ours.i1), (direct.mass_kg, direct.i1));
        assert_eq!(ours.axle_height_oscillation, direct.axle_height_oscillation);
        assert_eq!(ours.impacts, direct.impacts);
        let j = serde_json::to_value(&r).unwrap();
        for key in ["valid", "warnings", "min_normal_force", "airborne_fraction"] {
            assert!(j["rows"][0]["tbar"].get(key).is_some(), "{key}");
            assert!(j["rows"][0]["toroid"].get(key).is_some(), "{key}");
        }
    }
}
