//! The flags of `tensegrity michell` ([`MichellArgs`], with its `optimize` subcommand) and of
//! `tensegrity michell-table` ([`MichellTableArgs`]): each request's fields
//! ([`RequestArgs`]) and the outputs.

use crate::cli::figure_args::{FigureArgs, StructureArgs};
use crate::cli::michell_optimize::OptimizeArgs;
use crate::cli::request_args::RequestArgs;
use michell3d::{MichellRequest, MichellTableRequest};
use std::path::PathBuf;

/// Arguments of `tensegrity michell`: the request's flags ([`MichellRequest`]: `--complexity`,
/// `--beta`, `--phi` and one of `--planar`, `--cylindrical`, `--spherical` required), the
/// outputs, and the `optimize` subcommand.
#[derive(clap::Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct MichellArgs {
    // before the subcommand, which parsing takes out of the matches: the request is not
    // checked when a subcommand is given
    #[command(flatten)]
    pub(super) request: RequestArgs<MichellRequest>,
    /// `optimize`: the mass-optimal β, φ (and q) for a given radius ratio.
    #[command(subcommand)]
    pub action: Option<MichellAction>,
    /// Print JSON instead of a readable report.
    #[arg(long)]
    pub json: bool,
    /// Also write sign maps (Figs. 4.14–4.16) of the `--map-members` over the load azimuth
    /// [0, 2π] × polar angle [0, π] to this CSV (3-D trusses).
    #[arg(long, value_name = "FILE")]
    pub sign_map: Option<PathBuf>,
    /// Members of the sign map (indices as in the report; default the three tip members).
    #[arg(
        long,
        value_name = "LIST",
        value_delimiter = ',',
        default_value = "0,1,2"
    )]
    pub map_members: Vec<usize>,
    /// Sign-map grid, azimuth × polar points.
    #[arg(long, value_name = "NAxNP", default_value = "361x181", value_parser = parse_grid)]
    pub map_grid: (usize, usize),
    /// Draw the truss to FILE (.svg, .png or .pdf): members coloured by force (tension
    /// dashed), supports and the tip load; planar trusses in the yz plane, 3-D ones isometric
    /// unless --view is given.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
    #[command(flatten)]
    pub(super) figure: FigureArgs,
    #[command(flatten)]
    pub(super) drawing: StructureArgs,
    /// With --extra-strings: write member forces over γ ∈ [0, 2π] (Fig. 4.20) to this CSV.
    #[arg(long, value_name = "FILE", requires = "extra_strings")]
    pub gamma_sweep: Option<PathBuf>,
}

fn parse_grid(s: &str) -> Result<(usize, usize), String> {
    let bad = || format!("invalid grid \"{s}\": expected e.g. 361x181 (both at least 2)");
    let (a, b) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let a: usize = a.trim().parse().map_err(|_| bad())?;
    let b: usize = b.trim().parse().map_err(|_| bad())?;
    if a < 2 || b < 2 {
        return Err(bad());
    }
    Ok((a, b))
}

/// Subcommands of `tensegrity michell`.
#[derive(clap::Subcommand, Debug)]
pub enum MichellAction {
    /// Mass-optimal design for a given radius ratio ρ = r_q/r₀ (Skelton's setting).
    Optimize(OptimizeArgs),
}

/// Arguments of `tensegrity michell-table`: the request's flags ([`MichellTableRequest`]) and
/// the outputs.
#[derive(clap::Args, Debug)]
pub struct MichellTableArgs {
    #[command(flatten)]
    pub(super) request: RequestArgs<MichellTableRequest>,
    /// Write the table to this CSV (else print it).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Also plot yield + buckling mass against complexity (Fig. 4.18) to this figure (SVG,
    /// PNG or PDF by the extension).
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
    /// Print the table as JSON (`rows`: the CSV's columns as keys) instead of CSV text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub figure: FigureArgs,
}
