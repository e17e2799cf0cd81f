//! `tensegrity tbar`: the T-bar tread, wheel or extended wheel of thesis chapter 5. Parses the
//! arguments into a [`tbar_wheel::TbarRequest`], makes one library call
//! ([`tbar_wheel::tbar_report`]) and prints the report (text or JSON); `--export-scene`,
//! `--vtk` and `--svg` hand the structure or the drawing to tensegrity-io. `--loop-study`
//! prints the single loop against the extended wheel ([`tbar_wheel::standing`]);
//! `tensegrity tbar roll` rolls the wheel ([`super::tbar_roll`]).

use crate::cli::angle::parse_angle;
mod outputs;

use anyhow::Result;
use michell3d::MichellParams;
use std::path::PathBuf;
use tbar_wheel::envelope::{DEFAULT_DIRECTIONS, DEFAULT_EA, DEFAULT_LOAD};
use tbar_wheel::mass::DEFAULT_MATERIAL;
use tbar_wheel::{BarBase, Layout, RimMode, TbarParams, TbarReport, TbarRequest};

/// `--bar-base` values.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum BarBaseArg {
    /// The rim point [0, r_q, 0].
    Rim,
    /// The chord point [0, r_q cos φ, 0].
    Chord,
}

/// `--rim` values.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum RimArg {
    /// Rigid rim: every rim node and bar base pinned.
    Fixed,
    /// A free rim body of bars (ring, spokes, hub and axle).
    Body,
}

impl From<RimArg> for RimMode {
    fn from(r: RimArg) -> Self {
        match r {
            RimArg::Fixed => RimMode::Fixed,
            RimArg::Body => RimMode::Body,
        }
    }
}

/// Subcommands of `tensegrity tbar`.
#[derive(clap::Subcommand, Debug)]
pub enum TbarCommand {
    /// Roll the T-bar wheel down an incline (reduced rigid model) against the toroid of
    /// equal outer radius, over the number of treads π/φ; tip-over of the extended wheel.
    Roll(Box<super::tbar_roll::TbarRollArgs>),
}

/// Arguments of `tensegrity tbar`.
#[derive(clap::Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct TbarArgs {
    /// `roll`: rolling and tip-over.
    #[command(subcommand)]
    command: Option<TbarCommand>,
    /// Complexity q (lattice levels; level q lies on the rim).
    #[arg(long, default_value_t = 1)]
    complexity: usize,
    /// Departure angle β (e.g. `pi/6`, `30deg`).
    #[arg(long, value_parser = parse_angle, required = true)]
    beta: Option<f64>,
    /// Segmentation angle φ; a wheel needs π/φ integer.
    #[arg(long, value_parser = parse_angle, required = true)]
    phi: Option<f64>,
    /// Cylindrical parameterisation with offset δ (dimensionless, eq. 4.11).
    #[arg(
        long,
        value_name = "D",
        allow_hyphen_values = true,
        conflicts_with = "spherical",
        required_unless_present = "spherical"
    )]
    cylindrical: Option<f64>,
    /// Spherical parameterisation with angle ε (eq. 4.12).
    #[arg(long, value_name = "E", value_parser = parse_angle)]
    spherical: Option<f64>,
    /// Tip radius r₀ (m).
    #[arg(long, default_value_t = 1.0)]
    r0: f64,
    /// Build the wheel: π/φ treads every 2φ about ι̂₁.
    #[arg(long)]
    wheel: bool,
    /// Build the extended wheel: the wheel and a copy translated by OFFSET (m) along ι̂₁.
    #[arg(long, value_name = "OFFSET", allow_hyphen_values = true)]
    extended: Option<f64>,
    /// Base of the radial bar.
    #[arg(long, value_enum, default_value_t = BarBaseArg::Rim)]
    bar_base: BarBaseArg,
    /// Rim: rigid supports (`fixed`) or a free rim body of bars with a hub (`body`).
    #[arg(long, value_enum, default_value_t = RimArg::Fixed)]
    rim: RimArg,
    /// Instead of one analysis: the single loop against the extended wheel (copy at
    /// `--extended`, default 0.5 r₀) with a free rim body, free and standing on the ground.
    #[arg(long)]
    loop_study: bool,
    /// Instead of one analysis: the mass price against the Michell truss of single treads
    /// over `--sweep-complexities` × `--sweep-deltas` (δ, or ε with `--spherical`).
    #[arg(long)]
    mass_sweep: bool,
    /// Complexities q of `--mass-sweep`.
    #[arg(long, value_delimiter = ',', default_values_t = [1usize, 2, 3])]
    sweep_complexities: Vec<usize>,
    /// Offsets δ (or angles ε, radians) of `--mass-sweep`.
    #[arg(long, value_delimiter = ',', default_values_t = [0.05, 0.1, 0.25, 0.5, 1.0])]
    sweep_deltas: Vec<f64>,
    /// Tip load magnitude w₀ (N) of the load envelope.
    #[arg(long, default_value_t = DEFAULT_LOAD)]
    load: f64,
    /// Axial stiffness EA of every member (N).
    #[arg(long, default_value_t = DEFAULT_EA)]
    ea: f64,
    /// Bar compression P (N) of the slack map.
    #[arg(long)]
    prestress: Option<f64>,
    /// Directions of the slack map (quasi-uniform sphere).
    #[arg(long, default_value_t = DEFAULT_DIRECTIONS)]
    directions: usize,
    /// Material of the sizing (built-in table).
    #[arg(long, default_value = DEFAULT_MATERIAL)]
    material: String,
    /// Write the structure as a scene file.
    #[arg(long, value_name = "FILE")]
    export_scene: Option<PathBuf>,
    /// Write the structure as a VTK `.vtu` file.
    #[arg(long, value_name = "FILE")]
    vtk: Option<PathBuf>,
    /// Draw the side and top views (SVG or PNG by the extension).
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

impl TbarArgs {
    /// The library request the arguments describe.
    pub fn request(&self) -> TbarRequest {
        let (beta, phi) = (self.beta.unwrap_or(f64::NAN), self.phi.unwrap_or(f64::NAN));
        let m = match (self.cylindrical, self.spherical) {
            (_, Some(e)) => MichellParams::spherical(self.complexity, self.r0, beta, phi, e),
            (d, None) => {
                MichellParams::cylindrical(self.complexity, self.r0, beta, phi, d.unwrap_or(0.0))
            }
        };
        let layout = match (self.extended, self.wheel) {
            (Some(offset), _) => Layout::Extended { offset },
            (None, true) => Layout::Wheel,
            (None, false) => Layout::Tread,
        };
        let base = match self.bar_base {
            BarBaseArg::Rim => BarBase::Rim,
            BarBaseArg::Chord => BarBase::Chord,
        };
        let mut req = TbarRequest::new(
            TbarParams::tread(m)
                .with_layout(layout)
                .with_bar_base(base)
                .with_rim(self.rim.into()),
        );
        req.load = self.load;
        req.ea = self.ea;
        req.prestress = self.prestress;
        req.directions = self.directions;
        req.material = self.material.clone();
        req
    }
}

/// Entry point of `tensegrity tbar`.
pub fn run(args: &TbarArgs) -> Result<()> {
    if let Some(TbarCommand::Roll(roll)) = &args.command {
        return super::tbar_roll::run(roll);
    }
    let req = args.request();
    if args.loop_study {
        return run_loop_study(args, &req);
    }
    if args.mass_sweep {
        return super::tbar_mass::run(
            &req,
            &args.sweep_complexities,
            &args.sweep_deltas,
            args.json,
        );
    }
    let outputs = outputs::open(args)?;
    let report = tbar_wheel::tbar_report(&req)?;
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    outputs.write(&req)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_report(&report);
    }
    Ok(())
}

/// `--loop-study`: the six cases of [`tbar_wheel::standing::loop_study`].
fn run_loop_study(args: &TbarArgs, req: &TbarRequest) -> Result<()> {
    let offset = args.extended.unwrap_or(0.5 * args.r0);
    let rows = tbar_wheel::standing::loop_study(&req.params, offset)?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&rows)?);
        return Ok(());
    }
    println!("structure       stance  contacts  rank  self-stress  mechanisms  in-plane  out-of-plane  internal  margin");
    for r in &rows {
        println!(
            "{:<15} {:<7} {:>8} {:>5} {:>12} {:>11} {:>9.3} {:>13.3} {:>9.3} {:>7.4}",
            r.structure,
            r.stance.as_str(),
            r.contacts,
            r.rank,
            r.self_stress_dim,
            r.mechanisms,
            r.in_plane,
            r.out_of_plane,
            r.internal,
            r.prestress_margin
        );
    }
    Ok(())
}

fn print_report(r: &TbarReport) {
    println!(
        "T-bar {} q = {} (bar base {}, rim {}): {} treads, {} nodes, {} bars, {} strings",
        r.params.layout.name(),
        r.params.michell.complexity,
        r.params.bar_base.as_str(),
        r.rim.as_str(),
        r.treads,
        r.nodes,
        r.bars,
        r.strings
    );
    println!("level sizes {:?}", r.level_sizes);
    println!(
        "rank {}  self-stress states {}  mechanisms {}  internal mechanisms {}",
        r.rank, r.self_stress_dim, r.mechanisms, r.internal_mechanisms
    );
    if r.prestressable {
        println!("prestressable: yes, margin {:.6}", r.prestress_margin);
    } else {
        println!("prestressable: no");
    }
    if let (Some(p), Some(c)) = (r.min_prestress, &r.critical_member) {
        println!(
            "min prestress {p:.9e} N for w0 = {} N from every direction",
            r.load
        );
        println!(
            "critical member: {} {} ({}–{}), worst direction [{:.6}, {:.6}, {:.6}]",
            c.kind, c.index, c.nodes[0], c.nodes[1], c.direction[0], c.direction[1], c.direction[2]
        );
    }
    if let (Some(p), Some(f)) = (r.prestress, r.slack_fraction) {
        println!("at prestress {p} N: slack fraction {f:.6}");
    }
    if let Some(m) = &r.mass {
        println!(
            "mass {:.6e} kg ({}), Michell truss {:.6e} kg, ratio per tread {:.4}",
            m.mass_kg, m.material, m.michell_mass_kg, m.mass_ratio
        );
    }
}
