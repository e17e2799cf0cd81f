//! `tensegrity tbar`: the T-bar tread, wheel or extended wheel of thesis chapter 5. Its flags
//! are the fields of [`TbarStaticRequest`] ([`RequestArgs`]), converted to a
//! [`tbar_wheel::TbarRequest`]; one library call
//! ([`tbar_wheel::tbar_report`]) and prints the report (text or JSON); `--export-scene`,
//! `--vtk` and `--svg` hand the structure or the drawing to tensegrity-io. `--loop-study`
//! prints the single loop against the extended wheel ([`tbar_wheel::standing`]);
//! `tensegrity tbar roll` rolls the wheel ([`super::tbar_roll`]).

mod outputs;

use super::request_args::RequestArgs;
use anyhow::Result;
use std::path::PathBuf;
use tbar_wheel::{TbarReport, TbarRequest, TbarStaticRequest};

/// Subcommands of `tensegrity tbar`.
#[derive(clap::Subcommand, Debug)]
pub enum TbarCommand {
    /// Roll the T-bar wheel down an incline (reduced rigid model) against the toroid of
    /// equal outer radius, over the number of treads π/φ; tip-over of the extended wheel.
    Roll(Box<super::tbar_roll::TbarRollArgs>),
}

/// Arguments of `tensegrity tbar`: the request's flags ([`TbarStaticRequest`]: `--beta`,
/// `--phi` and one of `--cylindrical`, `--spherical` required), the other studies of the
/// geometry, the outputs, and the `roll` subcommand.
#[derive(clap::Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct TbarArgs {
    // before the subcommand, which parsing takes out of the matches: the request is not
    // checked when a subcommand is given
    #[command(flatten)]
    request: RequestArgs<TbarStaticRequest>,
    /// `roll`: rolling and tip-over.
    #[command(subcommand)]
    command: Option<TbarCommand>,
    /// Instead of one analysis: the single loop against the extended wheel (copy at
    /// `--extended`, default 0.5 r₀) with a free rim body, free and standing on the ground.
    #[arg(long)]
    loop_study: bool,
    /// Instead of one analysis: the mass price against the Michell truss of single treads
    /// over `--sweep-complexities` × `--sweep-deltas` (δ, or ε with `--spherical`).
    #[arg(long)]
    mass_sweep: bool,
    /// Complexities q of `--mass-sweep`.
    #[arg(long, value_delimiter = ',', default_values_t = tbar_wheel::MASS_SWEEP_COMPLEXITIES)]
    sweep_complexities: Vec<usize>,
    /// Offsets δ (or angles ε, radians) of `--mass-sweep`.
    #[arg(long, value_delimiter = ',', default_values_t = tbar_wheel::MASS_SWEEP_OFFSETS)]
    sweep_deltas: Vec<f64>,
    /// Write the structure as a scene file.
    #[arg(long, value_name = "FILE")]
    export_scene: Option<PathBuf>,
    /// Write the structure as a VTK `.vtu` file.
    #[arg(long, value_name = "FILE")]
    vtk: Option<PathBuf>,
    /// Draw the side (yz) and top (yx) views, or the --view given (.svg, .png or .pdf).
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    #[command(flatten)]
    figure: super::figure_args::FigureArgs,
    #[command(flatten)]
    drawing: super::figure_args::StructureArgs,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// Entry point of `tensegrity tbar`.
pub fn run(args: &TbarArgs) -> Result<()> {
    if let Some(TbarCommand::Roll(roll)) = &args.command {
        return super::tbar_roll::run(roll);
    }
    let request: TbarStaticRequest = args.request.request()?;
    let req = request.request();
    if args.loop_study {
        let offset = request.extended.unwrap_or(0.5 * request.r0);
        return run_loop_study(args, &req, offset);
    }
    if args.mass_sweep {
        return super::tbar_mass::run(
            &req,
            &args.sweep_complexities,
            &args.sweep_deltas,
            args.json,
        );
    }
    let _progress = super::guard::estimated(&request)?;
    let outputs = outputs::open(args)?;
    let report = tbar_wheel::tbar_report(&req)?;
    for w in &report.warnings {
        eprintln!("warning: {}", super::spell::flags(&w.to_string()));
    }
    outputs.write(&req, report.prestress_force.as_deref())?;
    if args.json {
        super::output::print_json(&report)?;
    } else {
        print_report(&report);
    }
    Ok(())
}

/// `--loop-study`: the six cases of [`tbar_wheel::standing::loop_study`].
fn run_loop_study(args: &TbarArgs, req: &TbarRequest, offset: f64) -> Result<()> {
    let rows = tbar_wheel::standing::loop_study(&req.params, offset)?;
    if args.json {
        super::output::print_json(&rows)?;
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
        let invalid = if r.envelope_carried == Some(false) {
            " — NOT A VALID SIZING: the prestress is below the minimum, the envelope is not carried"
        } else {
            ""
        };
        println!(
            "mass {:.6e} kg ({}), Michell truss {:.6e} kg, ratio per tread {:.4}{invalid}",
            m.mass_kg, m.material, m.michell_mass_kg, m.mass_ratio
        );
    }
}
