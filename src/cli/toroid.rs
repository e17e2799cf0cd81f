//! `tensegrity toroid`, `tensegrity roll` and `tensegrity tipover`.

use super::plot::{Panel, Series};
use anyhow::{Context, Result};
use serde::Serialize;
use std::io::Write;
use std::path::PathBuf;
use toroid::rolling::RigidRolling;
use toroid::rolling_full::{auto_fidelity, ContactModel, Fidelity, FullRolling};
use toroid::{
    analyse, build, build_prism, friction_grid, prestress_design, tipover, Stabilize, ToroidParams,
};

/// The seven geometric parameters and the stabilising options, shared by the toroid commands.
#[derive(clap::Args, Debug, Clone)]
pub struct GeometryArgs {
    /// Number of sides (prisms) n.
    #[arg(long, default_value_t = 8)]
    pub sides: usize,
    /// Outer tread width T (m).
    #[arg(long, default_value_t = 0.4)]
    pub outer_tread: f64,
    /// Inner tread width t (m).
    #[arg(long, default_value_t = 0.3)]
    pub inner_tread: f64,
    /// Tread offset D (m).
    #[arg(long, default_value_t = 0.1)]
    pub offset: f64,
    /// Outer radius R_o (m).
    #[arg(long, default_value_t = 1.0)]
    pub outer_radius: f64,
    /// Inner radius R_i (m).
    #[arg(long, default_value_t = 0.6)]
    pub inner_radius: f64,
    /// Rim radius R_m (m).
    #[arg(long, default_value_t = 0.8)]
    pub rim_radius: f64,
    /// Stabilising strings: any of spokes, inner, outer (comma-separated), or none.
    #[arg(long, default_value = "spokes,inner")]
    pub stabilize: String,
    /// Bar mass per length (kg/m); strings are massless.
    #[arg(long, default_value_t = 1.0, value_name = "KG_PER_M")]
    pub bar_density: f64,
}

impl GeometryArgs {
    fn params(&self) -> ToroidParams {
        ToroidParams {
            sides: self.sides,
            outer_tread: self.outer_tread,
            inner_tread: self.inner_tread,
            offset: self.offset,
            outer_radius: self.outer_radius,
            inner_radius: self.inner_radius,
            rim_radius: self.rim_radius,
        }
    }

    fn stabilize(&self) -> Result<Stabilize> {
        Ok(self.stabilize.parse()?)
    }
}

/// Arguments of `tensegrity toroid`.
#[derive(clap::Args, Debug)]
pub struct ToroidArgs {
    #[command(flatten)]
    geometry: GeometryArgs,
    /// Analyse a single prism (six nodes, K6) instead of the whole wheel.
    #[arg(long)]
    prism_only: bool,
    /// Minimum string tension of the prestress design (N).
    #[arg(long, default_value_t = 10.0)]
    min_tension: f64,
    /// Also search the rim radii R_m for which a single prism is prestressable.
    #[arg(long)]
    rim_window: bool,
    /// Write the structure as a scene file (for `tensegrity statics` or `simulate`).
    #[arg(long, value_name = "FILE")]
    export_scene: Option<PathBuf>,
    /// With --export-scene: give every string this stiffness (N/m) and the rest length that
    /// realises the prestress design.
    #[arg(long, value_name = "N_PER_M", requires = "export_scene")]
    string_stiffness: Option<f64>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct ToroidReport {
    nodes: usize,
    bars: usize,
    strings: usize,
    stabilize: String,
    rank: usize,
    self_stress_dim: usize,
    prestressable: bool,
    prestress_margin: f64,
    internal_mechanisms: usize,
    mass_kg: f64,
    inertia: [[f64; 3]; 3],
    #[serde(rename = "I1")]
    i1: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    prestress_member_force: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rim_radius_window: Option<[f64; 2]>,
}

/// Entry point of `tensegrity toroid`.
pub fn run_toroid(args: &ToroidArgs) -> Result<()> {
    let p = args.geometry.params();
    let t = if args.prism_only {
        build_prism(&p, args.geometry.bar_density)?
    } else {
        build(&p, args.geometry.stabilize()?, args.geometry.bar_density)?
    };
    let a = analyse(&t)?;
    let design = if a.prestressable {
        Some(prestress_design(&t, args.min_tension)?)
    } else {
        None
    };
    if let Some(path) = &args.export_scene {
        let structure = match (args.string_stiffness, &design) {
            (Some(k), Some(d)) => toroid::prestressed_structure(&t, d, k)?,
            (Some(_), None) => anyhow::bail!("--string-stiffness needs a prestressable toroid"),
            (None, _) => t.structure.clone(),
        };
        std::fs::write(path, tensegrity_io::scene::to_toml(&structure))
            .with_context(|| format!("cannot write {}", path.display()))?;
        if !args.json {
            println!("wrote {}", path.display());
        }
    }
    let window = if args.rim_window {
        toroid::rim_radius_window(&p, 0.02 * p.outer_radius, 1.5 * p.outer_radius, 75, 1e-6)?
    } else {
        None
    };
    let report = ToroidReport {
        nodes: a.nodes,
        bars: a.bars,
        strings: a.strings,
        stabilize: if args.prism_only {
            "prism".into()
        } else {
            t.stabilize.to_string()
        },
        rank: a.rank,
        self_stress_dim: a.self_stress_dim,
        prestressable: a.prestressable,
        prestress_margin: a.prestress_margin,
        internal_mechanisms: a.internal_mechanisms,
        mass_kg: a.mass_kg,
        inertia: std::array::from_fn(|i| std::array::from_fn(|j| a.inertia[(i, j)])),
        i1: a.i1,
        prestress_member_force: design
            .as_ref()
            .map(|d| d.member_force.iter().copied().collect()),
        rim_radius_window: window.map(|(a, b)| [a, b]),
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
        return Ok(());
    }
    println!(
        "toroid n = {} ({}): {} nodes, {} bars, {} strings",
        p.sides, report.stabilize, a.nodes, a.bars, a.strings
    );
    println!(
        "rank {}  self-stress states {}  internal mechanisms {}",
        a.rank, a.self_stress_dim, a.internal_mechanisms
    );
    if a.prestressable {
        println!("prestressable: yes, margin {:.6}", a.prestress_margin);
    } else {
        println!("prestressable: no");
    }
    println!("mass {:.6} kg   I1 {:.6} kg m^2", a.mass_kg, a.i1);
    println!("inertia about the centre (kg m^2):");
    for i in 0..3 {
        println!(
            "  [{:>12.6} {:>12.6} {:>12.6}]",
            a.inertia[(i, 0)],
            a.inertia[(i, 1)],
            a.inertia[(i, 2)]
        );
    }
    if args.rim_window {
        match window {
            Some((lo, hi)) => {
                println!("single prism prestressable for R_m in [{lo:.6}, {hi:.6}] m")
            }
            None => println!("single prism prestressable for no R_m in (0, 1.5 R_o)"),
        }
    }
    if let Some(d) = design {
        let s = &t.structure;
        let nb = s.n_bars();
        let bars = d.member_force.rows(0, nb);
        let strings = d.member_force.rows(nb, s.n_strings());
        println!(
            "prestress design (min string tension {} N): strings {:.3}..{:.3} N, bars {:.3}..{:.3} N",
            args.min_tension,
            strings.min(),
            strings.max(),
            bars.min(),
            bars.max()
        );
    }
    Ok(())
}

/// `--fidelity` values.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum FidelityArg {
    /// Reduced rigid polygon.
    Rigid,
    /// Full tensegrity dynamics.
    Full,
    /// Rigid when the strings are stiff enough.
    Auto,
}

/// `--contact` values.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactArg {
    /// Thesis §3.2.2: weight-based normal reaction plus velocity damping.
    Thesis,
    /// Penalty spring–damper with regularised Coulomb friction.
    Penalty,
}

/// Arguments of `tensegrity roll`.
#[derive(clap::Args, Debug)]
pub struct RollArgs {
    #[command(flatten)]
    geometry: GeometryArgs,
    /// Slope angle (e.g. `50deg`, `pi/4`, radians).
    #[arg(long, value_parser = super::angle::parse_angle, default_value = "50deg")]
    incline: f64,
    /// Simulated time (s).
    #[arg(long, default_value_t = 10.0)]
    t_end: f64,
    /// Integration step (s).
    #[arg(long, default_value_t = 1e-4)]
    dt: f64,
    /// Model: the reduced rigid polygon, the full tensegrity dynamics, or auto (rigid when
    /// m g / (k R_o) < 1e-3, i.e. the strings barely stretch under the wheel's weight).
    #[arg(long, value_enum, default_value_t = FidelityArg::Auto)]
    fidelity: FidelityArg,
    /// Ground contact of the full model.
    #[arg(long, value_enum, default_value_t = ContactArg::Thesis)]
    contact: ContactArg,
    /// Ground damping (N·s/m): contact-velocity damping (thesis) or normal damping (penalty).
    #[arg(long, default_value_t = 200.0)]
    ground_damping: f64,
    /// Penalty ground stiffness (N/m).
    #[arg(long, default_value_t = 1e5)]
    ground_stiffness: f64,
    /// Static friction coefficient of the penalty ground (kinetic = 0.75 of it).
    #[arg(long, default_value_t = 0.8)]
    mu: f64,
    /// String stiffness of the full model (N/m).
    #[arg(long, default_value_t = 2e4)]
    string_stiffness: f64,
    /// Smallest string tension of the full model's prestress (N).
    #[arg(long, default_value_t = 20.0)]
    min_tension: f64,
    /// Write the sampled history (1 ms) to this CSV file.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Plot the axle height and the contact reactions against time to this SVG file.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct RollReport {
    fidelity: &'static str,
    sides: usize,
    incline_rad: f64,
    t_end: f64,
    mass_kg: f64,
    #[serde(rename = "I1")]
    i1: f64,
    impacts: usize,
    axle_height_oscillation: f64,
    mean_speed: f64,
    max_reaction: f64,
    min_normal_force: f64,
    lift_off_time: f64,
    required_friction: f64,
    mean_slip_speed: f64,
}

/// Entry point of `tensegrity roll`.
pub fn run_roll(args: &RollArgs) -> Result<()> {
    let t = build(
        &args.geometry.params(),
        args.geometry.stabilize()?,
        args.geometry.bar_density,
    )?;
    let a = analyse(&t)?;
    let fidelity = match args.fidelity {
        FidelityArg::Rigid => Fidelity::Rigid,
        FidelityArg::Full => Fidelity::Full,
        FidelityArg::Auto => auto_fidelity(
            a.mass_kg,
            9.81,
            args.string_stiffness,
            t.params.outer_radius,
        ),
    };
    let r = match fidelity {
        Fidelity::Rigid => {
            let mut model = RigidRolling::of(&t, &a, args.incline);
            model.dt = args.dt;
            model.run(args.t_end)?
        }
        Fidelity::Full => {
            let contact = match args.contact {
                ContactArg::Thesis => ContactModel::Thesis {
                    damping: args.ground_damping,
                },
                ContactArg::Penalty => ContactModel::Penalty {
                    stiffness: args.ground_stiffness,
                    damping: args.ground_damping,
                    mu_static: args.mu,
                    mu_kinetic: 0.75 * args.mu,
                },
            };
            let full = FullRolling {
                incline: args.incline,
                contact,
                string_stiffness: args.string_stiffness,
                min_string_tension: args.min_tension,
                dt: args.dt,
                ..FullRolling::default()
            };
            full.run(&t, args.t_end)?
        }
    };
    let fidelity_name = match fidelity {
        Fidelity::Rigid => "rigid",
        Fidelity::Full => "full",
    };
    if let Some(path) = &args.svg {
        let label = format!("n = {}", args.geometry.sides);
        let panels = [
            axle_panel(&[(label.clone(), &r)]),
            reaction_panel(&[(label, &r)]),
        ];
        std::fs::write(path, super::plot::svg(&panels))
            .with_context(|| format!("cannot write {}", path.display()))?;
    }
    if let Some(path) = &args.out {
        let mut f = std::io::BufWriter::new(
            std::fs::File::create(path)
                .with_context(|| format!("cannot create {}", path.display()))?,
        );
        writeln!(
            f,
            "t_s,axle_s_m,axle_h_m,pivot_m,omega_rad_s,normal_N,tangential_N,energy_J,slip_m_s"
        )?;
        for s in &r.samples {
            writeln!(
                f,
                "{},{},{},{},{},{},{},{},{}",
                s.t, s.s, s.h, s.pivot, s.omega, s.normal, s.tangential, s.energy, s.slip
            )?;
        }
    }
    let report = RollReport {
        fidelity: fidelity_name,
        sides: args.geometry.sides,
        incline_rad: args.incline,
        t_end: args.t_end,
        mass_kg: a.mass_kg,
        i1: a.i1,
        impacts: r.impacts,
        axle_height_oscillation: r.axle_height_oscillation,
        mean_speed: r.mean_speed,
        max_reaction: r.max_reaction,
        min_normal_force: r.min_normal,
        lift_off_time: r.lift_off_time,
        required_friction: r.required_friction,
        mean_slip_speed: r.mean_slip_speed,
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        println!(
            "{fidelity_name} rolling, n = {}, incline {:.3} deg, {} s: {} impacts",
            report.sides,
            args.incline.to_degrees(),
            args.t_end,
            r.impacts
        );
        println!(
            "axle-height oscillation (RMS after 1 s) {:.6} m",
            r.axle_height_oscillation
        );
        println!(
            "mean speed {:.4} m/s   max reaction {:.3} N",
            r.mean_speed, r.max_reaction
        );
        if r.min_normal < 0.0 {
            println!(
                "note: the net normal force goes negative for {:.3} s (min {:.3} N): the wheel would leave the slope there",
                r.lift_off_time, r.min_normal
            );
        }
        println!(
            "friction needed to roll without slip: {:.4}",
            r.required_friction
        );
    }
    Ok(())
}

/// Arguments of `tensegrity tipover`.
#[derive(clap::Args, Debug)]
pub struct TipoverArgs {
    #[command(flatten)]
    geometry: GeometryArgs,
    /// Gravity (m/s²).
    #[arg(long, default_value_t = 9.81)]
    gravity: f64,
    /// Instead of one wheel, write F_f/F_e over a σ × ε grid (Fig. 3.13) to this CSV.
    #[arg(long)]
    grid: Option<PathBuf>,
    /// Grid points per axis.
    #[arg(long, default_value_t = 50)]
    grid_points: usize,
    /// Largest ε of the grid.
    #[arg(long, default_value_t = 1.0)]
    eps_max: f64,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// Entry point of `tensegrity tipover`.
pub fn run_tipover(args: &TipoverArgs) -> Result<()> {
    if let Some(path) = &args.grid {
        let rows = friction_grid(args.grid_points, args.eps_max)?;
        let mut f = std::io::BufWriter::new(
            std::fs::File::create(path)
                .with_context(|| format!("cannot create {}", path.display()))?,
        );
        writeln!(f, "sigma,epsilon,normalized_friction")?;
        for (s, e, v) in rows {
            writeln!(f, "{s},{e},{v}")?;
        }
        println!("wrote {}", path.display());
        return Ok(());
    }
    let t = build(
        &args.geometry.params(),
        args.geometry.stabilize()?,
        args.geometry.bar_density,
    )?;
    let mass = toroid::wheel_mass(&t.structure);
    let r = tipover(&t.params, mass, args.gravity)?;
    #[derive(Serialize)]
    struct Report {
        mass_kg: f64,
        rho: f64,
        epsilon: f64,
        sigma: f64,
        cot_theta: f64,
        critical_lateral_force: f64,
        normalized_friction: f64,
        min_friction_to_tip: f64,
    }
    let report = Report {
        mass_kg: mass,
        rho: r.rho,
        epsilon: r.epsilon,
        sigma: r.sigma,
        cot_theta: r.cot_theta,
        critical_lateral_force: r.critical_lateral_force,
        normalized_friction: r.normalized_friction,
        min_friction_to_tip: r.min_friction_to_tip,
    };
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        println!(
            "mass {:.4} kg  ρ = T/R_o = {:.4}  ε = t/T = {:.4}  σ = R_i/R_o = {:.4}",
            mass, r.rho, r.epsilon, r.sigma
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
    Ok(())
}

fn axle_panel(runs: &[(String, &toroid::rolling::RollingResult)]) -> Panel {
    Panel {
        title: "axle height above the incline (Fig. 3.10)".into(),
        x_label: "time [s]".into(),
        y_label: "axle height − mean [m]".into(),
        series: runs
            .iter()
            .map(|(label, r)| {
                let mean = r.samples.iter().map(|s| s.h).sum::<f64>() / r.samples.len() as f64;
                Series {
                    label: label.clone(),
                    points: r.samples.iter().map(|s| (s.t, s.h - mean)).collect(),
                }
            })
            .collect(),
    }
}

fn reaction_panel(runs: &[(String, &toroid::rolling::RollingResult)]) -> Panel {
    Panel {
        title: "contact reaction (Fig. 3.11)".into(),
        x_label: "time [s]".into(),
        y_label: "normal force [N]".into(),
        series: runs
            .iter()
            .map(|(label, r)| Series {
                label: label.clone(),
                points: r.samples.iter().map(|s| (s.t, s.normal)).collect(),
            })
            .collect(),
    }
}

/// Arguments of `tensegrity fig-rolling`.
#[derive(clap::Args, Debug)]
pub struct FigRollingArgs {
    /// Output SVG file.
    #[arg(long, value_name = "FILE", default_value = "rolling.svg")]
    out: PathBuf,
    /// Model.
    #[arg(long, value_enum, default_value_t = FidelityArg::Full)]
    fidelity: FidelityArg,
    /// Slope angle.
    #[arg(long, value_parser = super::angle::parse_angle, default_value = "50deg")]
    incline: f64,
    /// Simulated time (s).
    #[arg(long, default_value_t = 10.0)]
    t_end: f64,
}

/// Entry point of `tensegrity fig-rolling`: thesis Figs. 3.10 (n = 8, 12, 16, 24) and 3.11
/// (n = 8, 16) for the reference wheel with spokes + inner rings.
pub fn run_fig_rolling(args: &FigRollingArgs) -> Result<()> {
    let mut runs = Vec::new();
    for n in [8usize, 12, 16, 24] {
        let t = build(
            &ToroidParams::default().sides(n),
            "spokes,inner".parse()?,
            1.0,
        )?;
        let a = analyse(&t)?;
        let fidelity = match args.fidelity {
            FidelityArg::Rigid => Fidelity::Rigid,
            FidelityArg::Full => Fidelity::Full,
            FidelityArg::Auto => auto_fidelity(a.mass_kg, 9.81, 2e4, t.params.outer_radius),
        };
        let r = match fidelity {
            Fidelity::Rigid => RigidRolling::of(&t, &a, args.incline).run(args.t_end)?,
            Fidelity::Full => FullRolling {
                incline: args.incline,
                contact: ContactModel::Thesis { damping: 200.0 },
                ..FullRolling::default()
            }
            .run(&t, args.t_end)?,
        };
        println!(
            "n = {n:>2}: axle oscillation {:.5} m, mean speed {:.3} m/s",
            r.axle_height_oscillation, r.mean_speed
        );
        runs.push((format!("n = {n}"), r));
    }
    let all: Vec<(String, &toroid::rolling::RollingResult)> =
        runs.iter().map(|(l, r)| (l.clone(), r)).collect();
    let some: Vec<(String, &toroid::rolling::RollingResult)> = [0, 2]
        .iter()
        .map(|&i| (runs[i].0.clone(), &runs[i].1))
        .collect();
    std::fs::write(
        &args.out,
        super::plot::svg(&[axle_panel(&all), reaction_panel(&some)]),
    )
    .with_context(|| format!("cannot write {}", args.out.display()))?;
    println!("wrote {}", args.out.display());
    Ok(())
}
