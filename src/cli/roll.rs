//! `tensegrity roll` and `fig-rolling`: parse the arguments into a [`toroid::RollRequest`],
//! make one library call ([`toroid::roll`], [`toroid::rolling_series`]) and print or plot
//! the report.

use super::values;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use tensegrity_io::figure::{Figure, Panel, Series};
use toroid::defaults;
use toroid::rolling::RollingSample;
use toroid::{ContactKind, FidelityChoice, RollReport, RollRequest};

use super::toroid::GeometryArgs;

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
    let _progress = super::guard::roll(&args.request())?;
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
    let _progress = super::guard::rolling_series(&request, &defaults::FIG_3_10_SIDES)?;
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
