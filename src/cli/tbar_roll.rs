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
//! the same bar density.
//!
//! `--fidelity rigid` (default) runs the reduced rigid model only (`full_tensegrity_rolling:
//! false`). `--fidelity full` runs the full tensegrity dynamics
//! ([`toroid::rolling_full::FullRolling::run_scene`] on the structure of
//! [`tbar_wheel::rolling_full::full_wheel`]: prestressed treads, a free rim body with mass,
//! penalty contact at the tips) and, for the toroid column, the toroid's own full model; each
//! T-bar row then also carries the rigid model of the same polygon with the full structure's
//! mass and I₁ (`tbar_rigid_reference`) for the first contact phase
//! (`full_tensegrity_rolling: true`). The full model needs the rim body (a free body): with
//! `--fidelity full` the rim is `body` (an explicit `--rim fixed` is refused).

use super::angle::parse_angle;
use super::values;
use anyhow::Result;
use michell3d::MichellParams;
use serde::Serialize;
use std::f64::consts::PI;
use tbar_wheel::rolling::{mass_properties_with, tipover, MassProperties, TipOver};
use tbar_wheel::rolling_full::{FullPrestress, PrestressLevel};
use tbar_wheel::{BarBase, Layout, RimMode, TbarGeometry, TbarParams};
use toroid::defaults;
use toroid::rolling::{RigidRolling, RollingResult};
use toroid::FirstImpact;

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
    /// The simulated time: `--t-end`, else 10 s (rigid) or 1 s (full).
    pub fn t_end(&self) -> f64 {
        self.t_end.unwrap_or(match self.fidelity {
            FidelityArg::Rigid => defaults::ROLL_T_END,
            FidelityArg::Full => FULL_T_END,
        })
    }

    /// The rim: `--rim`, else fixed (rigid) or body (full); the full model refuses `fixed`.
    pub fn rim(&self) -> Result<RimMode> {
        match (self.fidelity, self.rim) {
            (FidelityArg::Full, Some(RimArg::Fixed)) => anyhow::bail!(
                "--fidelity full needs a free body: the rim body (--rim body), not the fixed rim"
            ),
            (FidelityArg::Full, _) => Ok(RimMode::Body),
            (FidelityArg::Rigid, r) => Ok(r.map_or(RimMode::Fixed, RimMode::from)),
        }
    }

    /// The numbers of treads: `--treads`, else 8, 12, 16, 24 (rigid) or 8 (full).
    pub fn treads(&self) -> Vec<usize> {
        self.treads.clone().unwrap_or_else(|| match self.fidelity {
            FidelityArg::Rigid => defaults::FIG_3_10_SIDES.to_vec(),
            FidelityArg::Full => vec![8],
        })
    }

    fn rim_density(&self) -> f64 {
        self.rim_density.unwrap_or(self.bar_density)
    }

    fn mu_kinetic(&self) -> f64 {
        self.mu_kinetic
            .unwrap_or(defaults::KINETIC_FRICTION_RATIO * self.mu_static)
    }
}

/// Default simulated time of the full model (s): the full model costs far more a second.
pub const FULL_T_END: f64 = 1.0;

/// One rolling run, as reported.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunSummary {
    /// The model that ran: `rigid` or `full`.
    pub model: &'static str,
    /// Mass m (kg).
    pub mass_kg: f64,
    /// I₁ about the axle (kg m²).
    #[serde(rename = "I1")]
    pub i1: f64,
    /// ω⁺/ω⁻ of a plastic pivot-to-pivot impact.
    pub impact_ratio: f64,
    /// Contact-pair impacts.
    pub impacts: usize,
    /// The first impact (null if none).
    pub first_impact: Option<FirstImpact>,
    /// RMS axle-height deviation after the first second (m; over the whole run if shorter).
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
    /// Fraction of the time in contact and sliding.
    pub slip_fraction: f64,
    /// Deepest penetration of a contact node below the slope (m).
    pub max_penetration: f64,
    /// Energy-budget residual over its largest term.
    pub energy_balance_error: f64,
}

/// What only the full T-bar run has.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FullDetails {
    /// Nodes of the structure (rim body included).
    pub nodes: usize,
    /// Bars (treads' and rim body's).
    pub bars: usize,
    /// Strings.
    pub strings: usize,
    /// Rim-body bars kept (the isostatic rim).
    pub rim_bars: usize,
    /// Of these, spokes (to the two hubs).
    pub rim_spokes: usize,
    /// Rim-body bars left out as redundant (a rigid bar-only self-stress).
    pub redundant_rim_bars: usize,
    /// The prestress it was built with.
    pub prestress: FullPrestress,
    /// Normal ground damping per contact node (N·s/m).
    pub ground_damping: f64,
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
    /// The T-bar wheel's run (of the model asked for).
    pub tbar: Option<RunSummary>,
    /// Full model only: the rigid model of the same polygon, mass and I₁, for the first
    /// contact phase.
    pub tbar_rigid_reference: Option<RunSummary>,
    /// Full model only: the structure and its prestress.
    pub full: Option<FullDetails>,
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
    /// The rolling model: `rigid` (reduced polygon) or `full` (tensegrity dynamics).
    pub model: &'static str,
    /// Whether the full tensegrity rolling of the T-bar wheel ran (`--fidelity full`).
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
    let rim = args.rim()?;
    let _progress = guard(args, rim)?;
    let report = roll_report(args, rim);
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

/// The resource guard: the full runs (T-bar and toroid) of every row, one after the other.
fn guard(args: &TbarRollArgs, rim: RimMode) -> Result<Option<super::guard::Progress>> {
    if args.fidelity == FidelityArg::Rigid {
        return Ok(None);
    }
    let mut total: Option<tensegrity_core::budget::Estimate> = None;
    for n in args.treads() {
        let p = params(args, layout(args), n, rim);
        let mut e = tbar_wheel::rolling_full::full_roll_estimate(&p, args.t_end(), args.dt)?;
        if let Ok(req) = toroid_request(args, n) {
            e = e.then(toroid::budget::roll(&req));
        }
        total = Some(match total {
            Some(t) => t.then(e),
            None => e,
        });
    }
    total
        .map(|e| {
            super::guard::check(tensegrity_core::budget::Estimate {
                what: format!("the full rolling runs of n = {:?}", args.treads()),
                ..e
            })
        })
        .transpose()
}

fn layout(args: &TbarRollArgs) -> Layout {
    match args.extended {
        Some(offset) => Layout::Extended { offset },
        None => Layout::Wheel,
    }
}

/// Every row of the report.
pub fn roll_report(args: &TbarRollArgs, rim: RimMode) -> TbarRollReport {
    let layout = layout(args);
    let full = args.fidelity == FidelityArg::Full;
    TbarRollReport {
        model: if full { "full" } else { "rigid" },
        full_tensegrity_rolling: full,
        structure: layout.name(),
        rim: rim.as_str(),
        incline_rad: args.incline,
        t_end: args.t_end(),
        rows: args
            .treads()
            .into_iter()
            .map(|n| row(args, layout, rim, n))
            .collect(),
    }
}

/// The T-bar parameters with n treads.
fn params(args: &TbarRollArgs, layout: Layout, n: usize, rim: RimMode) -> TbarParams {
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
        .with_rim(rim)
}

fn row(args: &TbarRollArgs, layout: Layout, rim: RimMode, n: usize) -> RollRow {
    let mut row = RollRow {
        treads: n,
        phi: PI / n as f64,
        mass_properties: None,
        tbar: None,
        tbar_rigid_reference: None,
        full: None,
        toroid: None,
        tipover: None,
        errors: Vec::new(),
    };
    let p = params(args, layout, n, rim);
    match args.fidelity {
        FidelityArg::Rigid => rigid_tbar(args, &p, &mut row),
        FidelityArg::Full => full_tbar(args, &p, &mut row),
    }
    let toroid = match args.fidelity {
        FidelityArg::Rigid => toroid_model(args, n).and_then(|m| run_rigid(args, &m)),
        FidelityArg::Full => run_full_toroid(args, n),
    };
    match toroid {
        Ok(s) => row.toroid = Some(s),
        Err(e) => row.errors.push(format!("toroid: {e}")),
    }
    row
}

/// The T-bar columns of the rigid model: mass properties of the geometry, its run, tip-over.
fn rigid_tbar(args: &TbarRollArgs, p: &TbarParams, row: &mut RollRow) {
    let tbar = TbarGeometry::new(*p)
        .map_err(anyhow::Error::from)
        .and_then(|g| {
            Ok((
                mass_properties_with(&g, args.bar_density, args.rim_density())?,
                g,
            ))
        });
    match tbar {
        Ok((mp, g)) => {
            row.mass_properties = Some(mp);
            tbar_tipover(args, &g, &mp, row);
            match run_rigid(args, &tbar_model(args, &mp)) {
                Ok(s) => row.tbar = Some(s),
                Err(e) => row.errors.push(format!("T-bar rolling: {e}")),
            }
        }
        Err(e) => row.errors.push(format!("T-bar wheel: {e}")),
    }
}

/// The T-bar columns of the full model: the structure that ran (its mass properties, with
/// the isostatic rim body), its run, the rigid polygon of the same mass and I₁, tip-over.
fn full_tbar(args: &TbarRollArgs, p: &TbarParams, row: &mut RollRow) {
    let (s, d, w) = match run_full_tbar(args, p) {
        Ok(r) => r,
        Err(e) => return row.errors.push(format!("T-bar full rolling: {e}")),
    };
    row.mass_properties = Some(w.mass);
    tbar_tipover(args, &w.geometry, &w.mass, row);
    match run_rigid(args, &tbar_model(args, &w.mass)) {
        Ok(r) => row.tbar_rigid_reference = Some(r),
        Err(e) => row.errors.push(format!("T-bar rigid reference: {e}")),
    }
    (row.tbar, row.full) = (Some(s), Some(d));
}

fn tbar_tipover(args: &TbarRollArgs, g: &TbarGeometry, mp: &MassProperties, row: &mut RollRow) {
    match tipover(g, mp.mass, args.gravity) {
        Ok(t) => row.tipover = Some(t),
        Err(e) => row.errors.push(format!("tip-over: {e}")),
    }
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
        mu_kinetic: args.mu_kinetic(),
        restitution: args.restitution,
    }
}

/// The reference toroid's parameters scaled to outer radius r₀, with n sides.
fn toroid_params(args: &TbarRollArgs, n: usize) -> toroid::ToroidParams {
    let r = toroid::ToroidParams::REFERENCE;
    let k = args.r0 / r.outer_radius;
    toroid::ToroidParams {
        sides: n,
        outer_tread: k * r.outer_tread,
        inner_tread: k * r.inner_tread,
        offset: k * r.offset,
        outer_radius: k * r.outer_radius,
        inner_radius: k * r.inner_radius,
        rim_radius: k * r.rim_radius,
    }
}

/// The reference toroid scaled to outer radius r₀, with n sides, in the same settings.
fn toroid_model(args: &TbarRollArgs, n: usize) -> Result<RigidRolling> {
    let p = toroid_params(args, n);
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

/// The toroid's full-model request in the settings of `args`.
fn toroid_request(args: &TbarRollArgs, n: usize) -> Result<toroid::RollRequest> {
    let wheel = toroid::WheelSpec {
        params: toroid_params(args, n),
        stabilize: toroid::Stabilize::SPOKES_INNER,
        bar_density: args.bar_density,
    };
    let kinetic = args.mu_kinetic() / args.mu_static.max(f64::MIN_POSITIVE);
    if args.mu_kinetic.is_some() && (kinetic - defaults::KINETIC_FRICTION_RATIO).abs() > 1e-12 {
        anyhow::bail!(
            "the toroid's full model takes μ_k = {} μ_s; --mu-kinetic applies to the T-bar only",
            defaults::KINETIC_FRICTION_RATIO
        );
    }
    Ok(toroid::RollRequest {
        wheel,
        incline: args.incline,
        t_end: args.t_end(),
        dt: args.dt,
        gravity: args.gravity,
        fidelity: toroid::FidelityChoice::Full,
        contact: toroid::ContactKind::Penalty,
        ground_damping: args.ground_damping,
        ground_stiffness: args.ground_stiffness,
        mu: args.mu_static,
        restitution: args.restitution,
        string_stiffness: args.string_stiffness,
        min_tension: args.min_tension.unwrap_or(defaults::ROLL_MIN_TENSION),
        integrator: tensegrity_core::dynamics::IntegratorKind::Rk4,
    })
}

fn run_full_toroid(args: &TbarRollArgs, n: usize) -> Result<RunSummary> {
    let r = toroid::roll(&toroid_request(args, n)?)?;
    Ok(RunSummary {
        model: "full",
        mass_kg: r.mass_kg,
        i1: r.i1,
        impact_ratio: rigid_model(args, n, args.r0, r.mass_kg, r.i1).impact_ratio(),
        impacts: r.impacts,
        first_impact: r.first_impact,
        axle_height_oscillation: r.axle_height_oscillation,
        mean_speed: r.mean_speed,
        final_speed: r.final_speed,
        valid: r.valid,
        warnings: r.warnings,
        min_normal_force: r.min_normal_force,
        airborne_fraction: r.airborne_fraction,
        slip_fraction: r.slip_fraction,
        max_penetration: r.max_penetration,
        energy_balance_error: r.energy_balance_error,
    })
}

/// The T-bar wheel in the toroid crate's full model: its structure as a [`WheelScene`].
pub fn tbar_scene(w: &tbar_wheel::rolling_full::FullWheel) -> toroid::rolling_full::WheelScene {
    toroid::rolling_full::WheelScene {
        structure: w.structure.clone(),
        contact_groups: w.contact_groups.clone(),
        rim: w.rim_points.clone(),
        axle: Some(w.hubs),
        outer_radius: w.outer_radius,
        mass: w.mass.mass,
        i1: w.mass.i1,
    }
}

/// The full model of `args` for a wheel of mass m and I₁ with n sides.
fn full_model(args: &TbarRollArgs, m: f64, i1: f64, n: usize) -> toroid::rolling_full::FullRolling {
    use toroid::rolling_full::{contact_effective_mass, penalty_damping, ContactModel};
    let m_eff = contact_effective_mass(m, i1, args.r0, n);
    toroid::rolling_full::FullRolling {
        incline: args.incline,
        gravity: args.gravity,
        contact: ContactModel::Penalty {
            stiffness: args.ground_stiffness,
            damping: args
                .ground_damping
                .unwrap_or_else(|| penalty_damping(args.restitution, args.ground_stiffness, m_eff)),
            mu_static: args.mu_static,
            mu_kinetic: args.mu_kinetic(),
        },
        string_stiffness: args.string_stiffness,
        min_string_tension: args.min_tension.unwrap_or(defaults::ROLL_MIN_TENSION),
        dt: args.dt,
        ..Default::default()
    }
}

/// The full tensegrity rolling of the T-bar wheel of `p`.
pub fn run_full_tbar(
    args: &TbarRollArgs,
    p: &TbarParams,
) -> Result<(RunSummary, FullDetails, tbar_wheel::rolling_full::FullWheel)> {
    let req = tbar_wheel::rolling_full::FullWheelRequest {
        bar_density: args.bar_density,
        rim_density: args.rim_density(),
        string_stiffness: args.string_stiffness,
        prestress: match args.min_tension {
            Some(t) => PrestressLevel::MinTension(t),
            None => PrestressLevel::Weight {
                factor: tbar_wheel::rolling_full::DEFAULT_CAPACITY_FACTOR,
                gravity: args.gravity,
            },
        },
    };
    let w = tbar_wheel::rolling_full::full_wheel(p, &req)?;
    let scene = tbar_scene(&w);
    let model = full_model(args, w.mass.mass, w.mass.i1, scene.sides());
    let run = model.run_scene(&scene, args.t_end())?;
    let mut r = run.result;
    r.validity.warnings.extend(w.warnings(args.gravity));
    let ground_damping = match model.contact {
        toroid::rolling_full::ContactModel::Penalty { damping, .. } => damping,
        toroid::rolling_full::ContactModel::Thesis { damping } => damping,
    };
    let details = FullDetails {
        nodes: w.structure.n_nodes(),
        bars: w.structure.n_bars(),
        strings: w.structure.n_strings(),
        rim_bars: w.geometry.rim.as_ref().map_or(0, |r| r.bars.len()),
        rim_spokes: w.geometry.rim.as_ref().map_or(0, |r| r.spokes),
        redundant_rim_bars: w.redundant_rim_bars,
        prestress: w.prestress,
        ground_damping,
    };
    let ratio = tbar_wheel::rolling::impact_ratio(&w.mass);
    let s = summary("full", (w.mass.mass, w.mass.i1, ratio), &r);
    Ok((s, details, w))
}

/// The report of a run of a wheel of (mass, I₁, plastic impact ratio).
fn summary(model: &'static str, wheel: (f64, f64, f64), r: &RollingResult) -> RunSummary {
    let v = &r.validity;
    RunSummary {
        model,
        mass_kg: wheel.0,
        i1: wheel.1,
        impact_ratio: wheel.2,
        impacts: r.impacts,
        first_impact: r.impact_log.first().map(|i| FirstImpact {
            t: i.t,
            omega_before: i.omega_before,
            omega_after: i.omega_after,
        }),
        axle_height_oscillation: r.axle_height_oscillation,
        mean_speed: r.mean_speed,
        final_speed: r.final_speed,
        valid: v.valid(),
        warnings: v.warnings.clone(),
        min_normal_force: v.min_normal_force,
        airborne_fraction: v.airborne_fraction,
        slip_fraction: v.slip_fraction,
        max_penetration: v.max_penetration,
        energy_balance_error: v.energy_balance_error,
    }
}

fn run_rigid(args: &TbarRollArgs, model: &RigidRolling) -> Result<RunSummary> {
    let r: RollingResult = model.run(args.t_end())?;
    let wheel = (model.mass, model.i1, model.impact_ratio());
    Ok(summary("rigid", wheel, &r))
}

fn print_roll(r: &TbarRollReport) {
    println!(
        "{} (rim {}) rolling down {:.2}° for {} s, {} model; toroid of equal outer radius",
        r.structure,
        r.rim,
        r.incline_rad.to_degrees(),
        r.t_end,
        if r.full_tensegrity_rolling {
            "full tensegrity"
        } else {
            "reduced rigid"
        }
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
fn print_full(row: &RollRow) {
    let (Some(f), Some(t)) = (&row.full, &row.tbar) else {
        return;
    };
    println!(
        "     full: {} nodes, {} bars, {} strings; bar prestress {:.3} N, tip-load capacity {:.3} N; {} impacts, airborne {:.3}, slip {:.3}, penetration {:.2e} m, energy error {:.2e}",
        f.nodes, f.bars, f.strings, f.prestress.bar_compression, f.prestress.tip_load_capacity,
        t.impacts, t.airborne_fraction, t.slip_fraction, t.max_penetration, t.energy_balance_error
    );
    let first = |s: Option<&RunSummary>| match s.and_then(|s| s.first_impact) {
        Some(i) => format!("t = {:.4} s, ω⁻ = {:.4} rad/s", i.t, i.omega_before),
        None => "none".to_string(),
    };
    println!(
        "     first impact: full {}; rigid polygon {}",
        first(Some(t)),
        first(row.tbar_rigid_reference.as_ref())
    );
    for w in &t.warnings {
        println!("     warning: {w}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;
    use tbar_wheel::rolling::{impact_ratio, mass_properties};

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
        let p = params(&a, Layout::Extended { offset: 0.5 }, 12, RimMode::Fixed);
        let g = TbarGeometry::new(p).unwrap();
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
        let r = roll_report(
            &args(&["--extended", "0.4", "--treads", "8,12"]),
            RimMode::Fixed,
        );
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

    #[test]
    fn full_and_rigid_agree_through_the_first_pivot() {
        // n = 6 treads (φ = π/6), 40° > π/6, μ = 1.2 (no slip), e = 0; stiff strings
        // (2·10⁶ N/m) and ground (10⁶ N/m), a light rim body (0.05 kg/m): the full wheel
        // pivots about its downhill tip like the rigid polygon of the same mass and I₁. Both
        // slide a little at the end of the pivot (the pivot unloads), so ω⁻ stays below the
        // no-slip energy bound ½(I₁ + m r₀²) ω⁻² = 2 m g r₀ sin φ sin(π/n) (≈ 12 % below).
        // Measured (RK4 at 0.1 ms): t 1.0301 / 1.0302 s, ω⁻ 2.6015 / 2.5967 rad/s (0.2 %); at
        // 0.05 ms 1.02955 s and 2.6011 rad/s. About 10 s.
        let a = Wrap::parse_from([
            "x",
            "--beta",
            "pi/6",
            "--cylindrical",
            "0.25",
            "--treads",
            "6",
            "--fidelity",
            "full",
            "--t-end",
            "1.1",
            "--incline",
            "40deg",
            "--mu-static",
            "1.2",
            "--string-stiffness",
            "2e6",
            "--ground-stiffness",
            "1e6",
            "--dt",
            "1e-4",
            "--rim-density",
            "0.05",
        ])
        .args;
        let p = params(&a, Layout::Wheel, 6, RimMode::Body);
        let (full, details, w) = run_full_tbar(&a, &p).unwrap();
        let rigid = run_rigid(&a, &tbar_model(&a, &w.mass)).unwrap();
        let (m, i1, g, phi) = (w.mass.mass, w.mass.i1, 9.81, 40f64.to_radians());
        let omega = (4.0 * m * g * phi.sin() * (PI / 6.0).sin() / (i1 + m)).sqrt();
        let (r, f) = (rigid.first_impact.unwrap(), full.first_impact.unwrap());
        assert!(r.omega_before < omega && r.omega_before > 0.8 * omega);
        assert!((f.t - r.t).abs() < 0.03 * r.t, "{} vs {}", f.t, r.t);
        assert!((f.omega_before - r.omega_before).abs() < 0.01 * r.omega_before);
        assert!(full.max_penetration < 0.01 && full.min_normal_force >= 0.0);
        assert_eq!((details.rim_bars, details.redundant_rim_bars), (54, 7));
        assert_eq!(details.rim_spokes, 30);
        assert_eq!((details.nodes, details.bars, details.strings), (26, 60, 24));
    }
}
