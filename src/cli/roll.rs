//! `tensegrity roll`: parses the arguments into a [`toroid::RollRequest`], makes one library
//! call ([`toroid::roll_with_frames`]) and prints or plots the report; warnings go to stderr
//! as well. `fig-rolling` is [`super::fig_rolling`]; the figure of `--svg` is
//! [`tensegrity_figures::roll_figure`].

use super::values;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use toroid::defaults;
use toroid::{RollReport, RollRequest};
use wheel_rolling::{ContactKind, FidelityChoice, RollSettings, RollingSample, WheelFrame};

use super::toroid::GeometryArgs;

/// `--fidelity` values.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum FidelityArg {
    /// Reduced rigid polygon (unilateral contact, impacts).
    Rigid,
    /// Full tensegrity dynamics.
    Full,
    /// The cheapest valid model: rigid when the strings are stiff enough and the rigid run
    /// is valid, else full.
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
    /// Penalty spring–damper that never pulls, with regularised Coulomb friction.
    Penalty,
    /// Thesis §3.2.2: weight-based normal reaction plus velocity damping (flagged when it
    /// pulls or sinks).
    Thesis,
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
    /// Model: the reduced rigid polygon, the full tensegrity dynamics, or auto (the cheapest
    /// valid one: rigid when m g / (k R_o) < 1e-3 and the rigid run is valid, else full).
    #[arg(long, value_enum, default_value_t = FidelityArg::Auto)]
    fidelity: FidelityArg,
    /// Ground contact of the full model.
    #[arg(long, value_enum, default_value_t = ContactArg::Penalty)]
    contact: ContactArg,
    /// Ground damping (N·s/m): normal damping per contact node (penalty) or contact-velocity
    /// damping (thesis, default 200). Given, it overrides the penalty damping that
    /// --restitution would choose.
    #[arg(long, value_parser = values::non_negative)]
    ground_damping: Option<f64>,
    /// Penalty ground stiffness per contact node (N/m).
    #[arg(long, default_value_t = defaults::GROUND_STIFFNESS, value_parser = values::positive)]
    ground_stiffness: f64,
    /// Static friction coefficient μ_s of the slope; the kinetic one is μ_k = 0.75 μ_s.
    #[arg(long, default_value_t = defaults::STATIC_FRICTION, value_parser = values::non_negative)]
    mu: f64,
    /// Normal coefficient of restitution e of an impact, in [0, 1]: the rigid model's impact
    /// law, and for the penalty contact the normal damping c = ζ √(2 k m_eff) with
    /// e = exp(−ζπ/√(1−ζ²)) (ignored when --ground-damping is given).
    #[arg(long, default_value_t = defaults::RESTITUTION)]
    restitution: f64,
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
    /// Write the sampled history (1 ms) to this CSV file: t, axle_s, axle_h, omega, then
    /// pivot_m, normal_N, tangential_N, energy_J, slip_m_s.
    #[arg(long)]
    out: Option<PathBuf>,
    /// With --frames: draw the wheel's members at those times (Fig. 3.8); without: plot the
    /// axle height above the slope and the normal reaction against time. SVG or PNG.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Times (s) of the wheel drawings of --svg, e.g. `0,1.5,3`.
    #[arg(long, value_delimiter = ',', value_name = "T,T,..")]
    frames: Option<Vec<f64>>,
    /// Write the node trajectories as a ParaView series (DIR/series.pvd, every 10 ms; slope
    /// coordinates: x along the axle, y down the slope, z above it).
    #[arg(long, value_name = "DIR")]
    vtk: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

impl RollArgs {
    /// The library request the arguments describe.
    pub fn request(&self) -> RollRequest {
        RollRequest {
            wheel: self.geometry.wheel(),
            settings: RollSettings {
                incline: self.incline,
                dt: self.dt,
                ground_damping: self.ground_damping,
                ground_stiffness: self.ground_stiffness,
                restitution: self.restitution,
                string_stiffness: self.string_stiffness,
                ..RollSettings::default()
            },
            t_end: self.t_end,
            fidelity: self.fidelity.into(),
            contact: self.contact.into(),
            mu: self.mu,
            min_tension: self.min_tension,
            integrator: self
                .integrator
                .map_or(RollRequest::default().integrator, Into::into),
        }
    }

    /// The frame times the outputs need: --frames, and the --vtk grid.
    fn frame_times(&self) -> Vec<f64> {
        let mut times = self.frames.clone().unwrap_or_default();
        if self.vtk.is_some() {
            let n = (self.t_end / defaults::ROLL_FRAME_DT).floor() as usize;
            times.extend((0..=n).map(|k| k as f64 * defaults::ROLL_FRAME_DT));
        }
        times
    }
}

/// Entry point of `tensegrity roll`.
pub fn run_roll(args: &RollArgs) -> Result<()> {
    let request = args.request();
    let _progress = super::guard::roll(&request)?;
    if let Some(t) = args
        .frames
        .iter()
        .flatten()
        .find(|t| !(0.0..=args.t_end).contains(*t))
    {
        anyhow::bail!(
            "--frames: time {t} s lies outside the run [0, {}] s",
            args.t_end
        );
    }
    let report = toroid::roll_with_frames(&request, &args.frame_times())?;
    for w in &report.summary.warnings {
        eprintln!("warning: {w}");
    }
    if let Some(path) = &args.svg {
        write_svg(args, path, &request, &report)?;
    }
    if let Some(dir) = &args.vtk {
        write_vtk(dir, &request, &report.frames)?;
    }
    if let Some(path) = &args.out {
        write_history_csv(path, &report.samples)?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_roll(&report);
    }
    match report.summary.stopped_at {
        Some(t) => anyhow::bail!(
            "the integration stopped at t = {t} s of --t-end {} s: the results above cover [0, {t}] s only (see the warnings)",
            args.t_end
        ),
        None => Ok(()),
    }
}

fn write_svg(args: &RollArgs, path: &Path, request: &RollRequest, r: &RollReport) -> Result<()> {
    let figure = tensegrity_figures::roll_figure(request, r, args.frames.as_deref())?;
    figure
        .save(path)
        .with_context(|| format!("writing the figure {}", path.display()))
}

fn write_vtk(dir: &Path, request: &RollRequest, frames: &[WheelFrame]) -> Result<()> {
    let toroid = request.wheel.build()?;
    let mut series = tensegrity_io::vtk::SeriesWriter::create(dir, &toroid.structure)
        .with_context(|| format!("creating the VTK series {}", dir.display()))?;
    for f in frames {
        series.frame(f.t, &f.nodes)?;
    }
    let n = series.finish()?;
    eprintln!("wrote {n} VTK frames to {}/series.pvd", dir.display());
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

fn print_roll(r: &RollReport) {
    let s = &r.summary;
    let model = r.fidelity.name();
    println!(
        "{model} rolling ({} contact), n = {}, incline {:.3} deg, {} s: {} impacts",
        r.contact,
        r.sides,
        r.incline_rad.to_degrees(),
        r.t_end,
        s.impacts
    );
    println!("model: {model} ({})", r.fidelity_reason);
    let span = if r.t_end > 1.0 {
        "after 1 s"
    } else {
        "whole run"
    };
    println!(
        "axle height above the slope: mean {:.4} m, RMS oscillation {:.6} m ({span})",
        s.mean_axle_height, s.axle_height_oscillation
    );
    println!(
        "mean speed {:.4} m/s   final speed {:.4} m/s   max reaction {:.3} N",
        s.mean_speed, s.final_speed, s.max_reaction
    );
    if let Some(i) = s.first_impact {
        println!(
            "first impact at t = {:.6} s: omega {:.6} -> {:.6} rad/s",
            i.t, i.omega_before, i.omega_after
        );
    }
    println!(
        "validity: {}; min normal force {:.4} N, airborne {:.2} %, slipping {:.2} %, max penetration {:.3e} m, energy budget residual {:.2e}",
        if s.valid { "valid" } else { "NOT VALID" },
        s.min_normal_force,
        100.0 * s.airborne_fraction,
        100.0 * s.slip_fraction,
        s.max_penetration,
        s.energy_balance_error
    );
    for w in &s.warnings {
        println!("warning: {w}");
    }
}
