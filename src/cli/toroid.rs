//! `tensegrity toroid`, `roll`, `fig-rolling` and `tipover`: each parses its arguments into a
//! request of the toroid crate, makes one library call ([`toroid::toroid_report`],
//! [`toroid::roll`], [`toroid::rolling_series`], [`toroid::tipover_report`]) and prints the
//! report. The defaults are the library's ([`toroid::defaults`]).

use super::values;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use tensegrity_io::figure::{Figure, Panel, Series};
use toroid::defaults;
use toroid::rolling::RollingSample;
use toroid::{
    ContactKind, FidelityChoice, RollReport, RollRequest, Stabilize, TipoverReport, TipoverRequest,
    ToroidParams, ToroidReport, ToroidRequest, WheelSpec,
};

const REF: ToroidParams = ToroidParams::REFERENCE;

/// The seven geometric parameters and the stabilising options, shared by the toroid commands.
#[derive(clap::Args, Debug, Clone)]
pub struct GeometryArgs {
    /// Number of sides (prisms) n.
    #[arg(long, default_value_t = REF.sides)]
    pub sides: usize,
    /// Outer tread width T (m).
    #[arg(long, default_value_t = REF.outer_tread, value_parser = values::positive)]
    pub outer_tread: f64,
    /// Inner tread width t (m).
    #[arg(long, default_value_t = REF.inner_tread, value_parser = values::positive)]
    pub inner_tread: f64,
    /// Tread offset D (m).
    #[arg(long, default_value_t = REF.offset, value_parser = values::non_negative)]
    pub offset: f64,
    /// Outer radius R_o (m).
    #[arg(long, default_value_t = REF.outer_radius, value_parser = values::positive)]
    pub outer_radius: f64,
    /// Inner radius R_i (m).
    #[arg(long, default_value_t = REF.inner_radius, value_parser = values::positive)]
    pub inner_radius: f64,
    /// Rim radius R_m (m).
    #[arg(long, default_value_t = REF.rim_radius, value_parser = values::positive)]
    pub rim_radius: f64,
    /// Stabilising strings: any of spokes, inner, outer (comma-separated), or none.
    #[arg(long, default_value_t = Stabilize::SPOKES_INNER)]
    pub stabilize: Stabilize,
    /// Bar mass per length (kg/m); strings are massless.
    #[arg(long, default_value_t = defaults::BAR_DENSITY, value_parser = values::positive, value_name = "KG_PER_M")]
    pub bar_density: f64,
}

impl GeometryArgs {
    /// The wheel the arguments describe.
    pub fn wheel(&self) -> WheelSpec {
        WheelSpec {
            params: ToroidParams {
                sides: self.sides,
                outer_tread: self.outer_tread,
                inner_tread: self.inner_tread,
                offset: self.offset,
                outer_radius: self.outer_radius,
                inner_radius: self.inner_radius,
                rim_radius: self.rim_radius,
            },
            stabilize: self.stabilize,
            bar_density: self.bar_density,
        }
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
    #[arg(long, default_value_t = defaults::DESIGN_MIN_TENSION, value_parser = values::positive)]
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

impl ToroidArgs {
    /// The library request the arguments describe.
    pub fn request(&self) -> ToroidRequest {
        ToroidRequest {
            wheel: self.geometry.wheel(),
            prism_only: self.prism_only,
            min_tension: self.min_tension,
            rim_window: self.rim_window,
            string_stiffness: self.string_stiffness,
        }
    }
}

/// Entry point of `tensegrity toroid`.
pub fn run_toroid(args: &ToroidArgs) -> Result<()> {
    let report = toroid::toroid_report(&args.request())?;
    if let Some(path) = &args.export_scene {
        write_scene(path, &report.structure)?;
        if !args.json {
            println!("wrote {}", path.display());
        }
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_toroid(args, &report);
    }
    Ok(())
}

/// Writes a structure as a TOML scene.
fn write_scene(path: &Path, structure: &tensegrity_core::Structure) -> Result<()> {
    tensegrity_io::write_text(path, "scene", &tensegrity_io::scene::to_toml(structure))
        .with_context(|| format!("writing the scene {}", path.display()))
}

fn print_toroid(args: &ToroidArgs, r: &ToroidReport) {
    println!(
        "toroid n = {} ({}): {} nodes, {} bars, {} strings",
        args.geometry.sides, r.stabilize, r.nodes, r.bars, r.strings
    );
    println!(
        "rank {}  self-stress states {}  internal mechanisms {}",
        r.rank, r.self_stress_dim, r.internal_mechanisms
    );
    if r.prestressable {
        println!("prestressable: yes, margin {:.6}", r.prestress_margin);
    } else {
        println!("prestressable: no");
    }
    println!("mass {:.6} kg   I1 {:.6} kg m^2", r.mass_kg, r.i1);
    println!("inertia about the centre (kg m^2):");
    for row in &r.inertia {
        println!("  [{:>12.6} {:>12.6} {:>12.6}]", row[0], row[1], row[2]);
    }
    if args.rim_window {
        match r.rim_radius_window {
            Some([lo, hi]) => {
                println!("single prism prestressable for R_m in [{lo:.6}, {hi:.6}] m")
            }
            None => println!("single prism prestressable for no R_m in (0, 1.5 R_o)"),
        }
    }
    if let Some(f) = &r.prestress_member_force {
        let range = |v: &[f64]| {
            let min = v.iter().copied().fold(f64::INFINITY, f64::min);
            let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (min, max)
        };
        let (bars, strings) = (range(&f[..r.bars]), range(&f[r.bars..]));
        println!(
            "prestress design (min string tension {} N): strings {:.3}..{:.3} N, bars {:.3}..{:.3} N",
            args.min_tension, strings.0, strings.1, bars.0, bars.1
        );
    }
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

impl From<FidelityArg> for FidelityChoice {
    fn from(f: FidelityArg) -> Self {
        match f {
            FidelityArg::Rigid => FidelityChoice::Rigid,
            FidelityArg::Full => FidelityChoice::Full,
            FidelityArg::Auto => FidelityChoice::Auto,
        }
    }
}

/// `--contact` values.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactArg {
    /// Thesis §3.2.2: weight-based normal reaction plus velocity damping.
    Thesis,
    /// Penalty spring–damper with regularised Coulomb friction.
    Penalty,
}

impl From<ContactArg> for ContactKind {
    fn from(c: ContactArg) -> Self {
        match c {
            ContactArg::Thesis => ContactKind::Thesis,
            ContactArg::Penalty => ContactKind::Penalty,
        }
    }
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
    #[arg(long, default_value_t = defaults::ROLL_T_END, value_parser = values::positive)]
    t_end: f64,
    /// Integration step (s).
    #[arg(long, default_value_t = defaults::ROLL_DT, value_parser = values::positive)]
    dt: f64,
    /// Model: the reduced rigid polygon, the full tensegrity dynamics, or auto (rigid when
    /// m g / (k R_o) < 1e-3, i.e. the strings barely stretch under the wheel's weight).
    #[arg(long, value_enum, default_value_t = FidelityArg::Auto)]
    fidelity: FidelityArg,
    /// Ground contact of the full model.
    #[arg(long, value_enum, default_value_t = ContactArg::Thesis)]
    contact: ContactArg,
    /// Ground damping (N·s/m): contact-velocity damping (thesis) or normal damping (penalty).
    #[arg(long, default_value_t = defaults::GROUND_DAMPING, value_parser = values::non_negative)]
    ground_damping: f64,
    /// Penalty ground stiffness (N/m).
    #[arg(long, default_value_t = defaults::GROUND_STIFFNESS, value_parser = values::positive)]
    ground_stiffness: f64,
    /// Static friction coefficient of the penalty ground (kinetic = 0.75 of it).
    #[arg(long, default_value_t = defaults::STATIC_FRICTION, value_parser = values::non_negative)]
    mu: f64,
    /// String stiffness of the full model (N/m).
    #[arg(long, default_value_t = defaults::STRING_STIFFNESS, value_parser = values::positive)]
    string_stiffness: f64,
    /// Smallest string tension of the full model's prestress (N).
    #[arg(long, default_value_t = defaults::ROLL_MIN_TENSION, value_parser = values::positive)]
    min_tension: f64,
    /// Integrator of the full model (default rk4 at --dt; rk45 and sdirk take --dt as their
    /// largest step, rtol 1e-6; sdirk for stiff strings or ground damping).
    #[arg(long, value_enum)]
    integrator: Option<super::simulate::IntegratorArg>,
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

impl RollArgs {
    /// The library request the arguments describe.
    pub fn request(&self) -> RollRequest {
        RollRequest {
            wheel: self.geometry.wheel(),
            incline: self.incline,
            t_end: self.t_end,
            dt: self.dt,
            fidelity: self.fidelity.into(),
            contact: self.contact.into(),
            ground_damping: self.ground_damping,
            ground_stiffness: self.ground_stiffness,
            mu: self.mu,
            string_stiffness: self.string_stiffness,
            min_tension: self.min_tension,
            integrator: self
                .integrator
                .map_or(RollRequest::default().integrator, Into::into),
            ..RollRequest::default()
        }
    }
}

/// Entry point of `tensegrity roll`.
pub fn run_roll(args: &RollArgs) -> Result<()> {
    let report = toroid::roll(&args.request())?;
    if let Some(path) = &args.svg {
        let runs = [(format!("n = {}", report.sides), report.samples.as_slice())];
        write_figure(path, &[axle_panel(&runs), reaction_panel(&runs)])?;
    }
    if let Some(path) = &args.out {
        write_history_csv(path, &report.samples)?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_roll(&report);
    }
    Ok(())
}

/// Writes the sampled rolling history as CSV.
fn write_history_csv(path: &Path, samples: &[RollingSample]) -> Result<()> {
    tensegrity_io::write_file(path, |w| {
        tensegrity_io::csv::write_rolling_history(w, samples)
    })
    .with_context(|| format!("writing the rolling history {}", path.display()))?;
    Ok(())
}

fn fidelity_name(r: &RollReport) -> &'static str {
    match r.fidelity {
        toroid::rolling_full::Fidelity::Rigid => "rigid",
        toroid::rolling_full::Fidelity::Full => "full",
    }
}

fn print_roll(r: &RollReport) {
    println!(
        "{} rolling, n = {}, incline {:.3} deg, {} s: {} impacts",
        fidelity_name(r),
        r.sides,
        r.incline_rad.to_degrees(),
        r.t_end,
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
    if r.min_normal_force < 0.0 {
        println!(
            "note: the net normal force goes negative for {:.3} s (min {:.3} N): the wheel would leave the slope there",
            r.lift_off_time, r.min_normal_force
        );
    }
    println!(
        "friction needed to roll without slip: {:.4}",
        r.required_friction
    );
}

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
}

/// Entry point of `tensegrity tipover`.
pub fn run_tipover(args: &TipoverArgs) -> Result<()> {
    if let Some(path) = &args.grid {
        let rows = toroid::friction_grid(args.grid_points, args.eps_max)?;
        write_friction_csv(path, &rows)?;
        println!("wrote {}", path.display());
        return Ok(());
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

/// Writes the (σ, ε, F_f/F_e) grid as CSV.
fn write_friction_csv(path: &Path, rows: &[(f64, f64, f64)]) -> Result<()> {
    tensegrity_io::write_file(path, |w| tensegrity_io::csv::write_friction_grid(w, rows))
        .with_context(|| format!("writing the friction map {}", path.display()))?;
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

/// Writes figure panels side by side (SVG or PNG by the extension).
fn write_figure(path: &Path, panels: &[Panel]) -> Result<()> {
    Figure::new(panels.to_vec())
        .save(path)
        .with_context(|| format!("writing the figure {}", path.display()))
}

fn axle_panel(runs: &[(String, &[RollingSample])]) -> Panel {
    let mut panel = Panel::new(
        "axle height above the incline (Fig. 3.10)",
        "time [s]",
        "axle height − mean [m]",
    );
    panel.series = runs
        .iter()
        .map(|(label, samples)| {
            let mean = samples.iter().map(|s| s.h).sum::<f64>() / samples.len() as f64;
            Series::new(
                label.clone(),
                samples.iter().map(|s| (s.t, s.h - mean)).collect(),
            )
        })
        .collect();
    panel
}

fn reaction_panel(runs: &[(String, &[RollingSample])]) -> Panel {
    let mut panel = Panel::new(
        "contact reaction (Fig. 3.11)",
        "time [s]",
        "normal force [N]",
    );
    panel.series = runs
        .iter()
        .map(|(label, samples)| {
            Series::new(
                label.clone(),
                samples.iter().map(|s| (s.t, s.normal)).collect(),
            )
        })
        .collect();
    panel
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
    #[arg(long, default_value_t = defaults::ROLL_T_END, value_parser = values::positive)]
    t_end: f64,
}

/// Entry point of `tensegrity fig-rolling`: thesis Figs. 3.10 (n = 8, 12, 16, 24) and 3.11
/// (n = 8, 16) for the reference wheel with spokes + inner rings.
pub fn run_fig_rolling(args: &FigRollingArgs) -> Result<()> {
    let request = RollRequest {
        fidelity: args.fidelity.into(),
        incline: args.incline,
        t_end: args.t_end,
        ..RollRequest::default()
    };
    let runs = toroid::rolling_series(&request, &defaults::FIG_3_10_SIDES)?;
    for r in &runs {
        println!(
            "n = {:>2}: axle oscillation {:.5} m, mean speed {:.3} m/s",
            r.sides, r.axle_height_oscillation, r.mean_speed
        );
    }
    let labelled: Vec<(String, &[RollingSample])> = runs
        .iter()
        .map(|r| (format!("n = {}", r.sides), r.samples.as_slice()))
        .collect();
    // Fig. 3.11 shows the reactions of n = 8 and 16 only
    let some = [labelled[0].clone(), labelled[2].clone()];
    write_figure(&args.out, &[axle_panel(&labelled), reaction_panel(&some)])?;
    println!("wrote {}", args.out.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser, Debug)]
    enum Cli {
        Roll(RollArgs),
        Toroid(ToroidArgs),
    }

    #[test]
    fn the_cli_defaults_are_the_library_defaults() {
        let Cli::Roll(roll) = Cli::try_parse_from(["t", "roll"]).unwrap() else {
            unreachable!()
        };
        assert_eq!(roll.request(), RollRequest::default());
        let Cli::Toroid(t) = Cli::try_parse_from(["t", "toroid"]).unwrap() else {
            unreachable!()
        };
        assert_eq!(t.request(), ToroidRequest::default());
    }

    #[test]
    fn an_unknown_stabilising_option_is_a_usage_error() {
        let err = Cli::try_parse_from(["t", "toroid", "--stabilize", "wheels"]).unwrap_err();
        assert!(err.to_string().contains("wheels"), "{err}");
    }
}
