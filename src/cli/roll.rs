//! `tensegrity roll` and `fig-rolling`: parse the arguments into a [`toroid::RollRequest`],
//! make one library call ([`toroid::roll_with_frames`]) per wheel and print or plot the
//! report; warnings go to stderr as well.

use super::values;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use tensegrity_io::figure::{Figure, Panel, Series};
use toroid::defaults;
use toroid::rolling::RollingSample;
use toroid::rolling_full::WheelFrame;
use toroid::{ContactKind, FidelityChoice, RollReport, RollRequest};

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
            incline: self.incline,
            t_end: self.t_end,
            dt: self.dt,
            fidelity: self.fidelity.into(),
            contact: self.contact.into(),
            ground_damping: self.ground_damping,
            ground_stiffness: self.ground_stiffness,
            mu: self.mu,
            restitution: self.restitution,
            string_stiffness: self.string_stiffness,
            min_tension: self.min_tension,
            integrator: self
                .integrator
                .map_or(RollRequest::default().integrator, Into::into),
            ..RollRequest::default()
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
    for w in &report.warnings {
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
    match report.stopped_at {
        Some(t) => anyhow::bail!(
            "the integration stopped at t = {t} s of --t-end {} s: the results above cover [0, {t}] s only (see the warnings)",
            args.t_end
        ),
        None => Ok(()),
    }
}

fn write_svg(args: &RollArgs, path: &Path, request: &RollRequest, r: &RollReport) -> Result<()> {
    match &args.frames {
        Some(times) => {
            let toroid = request.wheel.build()?;
            let members = toroid.structure.member_nodes();
            let panels: Vec<Panel> = times
                .iter()
                .filter_map(|&t| r.frames.iter().find(|f| (f.t - t).abs() <= args.dt))
                .map(|f| frame_panel(f, &members))
                .collect();
            write_figure(path, &panels)
        }
        None => {
            let runs = [(format!("n = {}", r.sides), r.samples.as_slice())];
            write_figure(path, &[axle_panel(&runs), reaction_panel(&runs)])
        }
    }
}

/// The wheel's members in the rolling plane (s, h) at one time (thesis Fig. 3.8).
fn frame_panel(frame: &WheelFrame, members: &[[usize; 2]]) -> Panel {
    let mut panel = Panel::new(
        format!("t = {:.3} s", frame.t),
        "along the slope s [m]",
        "above the slope h [m]",
    );
    let (lo, hi) = frame
        .nodes
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
    panel
        .series
        .push(Series::new("slope", vec![(lo, 0.0), (hi, 0.0)]));
    panel.series.extend(members.iter().map(|&[a, b]| {
        let (p, q) = (frame.nodes[a], frame.nodes[b]);
        Series::new("", vec![(p.y, p.z), (q.y, q.z)])
    }));
    panel
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

fn fidelity_name(r: &RollReport) -> &'static str {
    match r.fidelity {
        toroid::rolling_full::Fidelity::Rigid => "rigid",
        toroid::rolling_full::Fidelity::Full => "full",
    }
}

fn print_roll(r: &RollReport) {
    println!(
        "{} rolling ({} contact), n = {}, incline {:.3} deg, {} s: {} impacts",
        fidelity_name(r),
        r.contact,
        r.sides,
        r.incline_rad.to_degrees(),
        r.t_end,
        r.impacts
    );
    println!("model: {} ({})", fidelity_name(r), r.fidelity_reason);
    println!(
        "axle height above the slope: mean {:.4} m, RMS oscillation {:.6} m ({})",
        r.mean_axle_height,
        r.axle_height_oscillation,
        if r.t_end > 1.0 {
            "after 1 s"
        } else {
            "whole run"
        }
    );
    println!(
        "mean speed {:.4} m/s   final speed {:.4} m/s   max reaction {:.3} N",
        r.mean_speed, r.final_speed, r.max_reaction
    );
    if let Some(i) = r.first_impact {
        println!(
            "first impact at t = {:.6} s: omega {:.6} -> {:.6} rad/s",
            i.t, i.omega_before, i.omega_after
        );
    }
    println!(
        "validity: {}; min normal force {:.4} N, airborne {:.2} %, slipping {:.2} %, max penetration {:.3e} m, energy budget residual {:.2e}",
        if r.valid { "valid" } else { "NOT VALID" },
        r.min_normal_force,
        100.0 * r.airborne_fraction,
        100.0 * r.slip_fraction,
        r.max_penetration,
        r.energy_balance_error
    );
    for w in &r.warnings {
        println!("warning: {w}");
    }
}

/// Writes figure panels side by side (SVG or PNG by the extension).
fn write_figure(path: &Path, panels: &[Panel]) -> Result<()> {
    Figure::new(panels.to_vec())
        .save(path)
        .with_context(|| format!("writing the figure {}", path.display()))
}

/// The empty band above the data that a legend of `entries` lines needs (fraction of the
/// data's span).
fn legend_band(entries: usize) -> f64 {
    0.1 + 0.1 * entries as f64
}

fn axle_panel(runs: &[(String, &[RollingSample])]) -> Panel {
    let mut panel = Panel::new(
        "axle height above the incline (Fig. 3.10)",
        "time [s]",
        "axle height above the slope [m]",
    )
    .legend_above(legend_band(runs.len()));
    panel.series = runs
        .iter()
        .map(|(label, samples)| {
            Series::new(label.clone(), samples.iter().map(|s| (s.t, s.h)).collect())
        })
        .collect();
    panel
}

fn reaction_panel(runs: &[(String, &[RollingSample])]) -> Panel {
    let mut panel = Panel::new(
        "contact reaction (Fig. 3.11)",
        "time [s]",
        "normal force [N]",
    )
    .legend_above(legend_band(runs.len()));
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
    /// Model (auto: the cheapest valid one per wheel; with the default strings, full).
    #[arg(long, value_enum, default_value_t = FidelityArg::Auto)]
    fidelity: FidelityArg,
    /// Ground contact of the full model.
    #[arg(long, value_enum, default_value_t = ContactArg::Penalty)]
    contact: ContactArg,
    /// Slope angle.
    #[arg(long, value_parser = super::angle::parse_angle, default_value = "50deg")]
    incline: f64,
    /// Simulated time (s).
    #[arg(long, default_value_t = defaults::ROLL_T_END, value_parser = values::positive)]
    t_end: f64,
    /// Static friction coefficient μ_s (μ_k = 0.75 μ_s).
    #[arg(long, default_value_t = defaults::STATIC_FRICTION, value_parser = values::non_negative)]
    mu: f64,
    /// Normal coefficient of restitution e.
    #[arg(long, default_value_t = defaults::RESTITUTION)]
    restitution: f64,
}

/// Entry point of `tensegrity fig-rolling`: thesis Figs. 3.10 (n = 8, 12, 16, 24) and 3.11
/// (n = 8, 16) for the reference wheel with spokes + inner rings, the wheels rolled in
/// parallel, and the impact impulse per new contact against n (§3.3.1).
pub fn run_fig_rolling(args: &FigRollingArgs) -> Result<()> {
    let request = RollRequest {
        fidelity: args.fidelity.into(),
        contact: args.contact.into(),
        incline: args.incline,
        t_end: args.t_end,
        mu: args.mu,
        restitution: args.restitution,
        ..RollRequest::default()
    };
    let _progress = super::guard::rolling_series(&request, &defaults::FIG_3_10_SIDES)?;
    let runs = super::roll_series::parallel_series(&request, &defaults::FIG_3_10_SIDES)?;
    super::roll_series::print_series(&runs);
    let labelled: Vec<(String, &[RollingSample])> = runs
        .iter()
        .map(|r| {
            let mark = if r.valid { "" } else { " (NOT VALID)" };
            let label = format!("n = {} {}{mark}", r.sides, fidelity_name(r));
            (label, r.samples.as_slice())
        })
        .collect();
    // Fig. 3.11 shows the reactions of n = 8 and 16 only
    let some = [labelled[0].clone(), labelled[2].clone()];
    write_figure(&args.out, &[axle_panel(&labelled), reaction_panel(&some)])?;
    println!("wrote {}", args.out.display());
    Ok(())
}
