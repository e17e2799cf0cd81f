//! `tensegrity michell`: a planar or 3-D discrete Michell truss under a tip load — member
//! forces, member types, masses (thesis chapter 4, ERRATA ch. 4).
//!
//! ```text
//! tensegrity michell --complexity Q (--planar | --cylindrical DELTA | --spherical EPS)
//!     --beta B --phi P [--r0 R] [--load W0] [--azimuth A] [--polar G] [--material NAME]
//!     [--extra-strings PRESTRESS] [--method recursive|global] [--json]
//! ```

use crate::cli::angle::parse_angle;
use anyhow::{Context, Result};
use clap::{ArgGroup, ValueEnum};
use michell3d::{AnalysisRequest, Method, MichellAnalysis, MichellParams};
use std::path::PathBuf;

mod grids;
mod text;
pub use grids::run_table;
use grids::{open_outputs, write_gamma_sweep, write_sign_maps};
pub use text::text_report;

/// Force propagation method.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum MethodArg {
    /// Level-by-level method of joints (one 3×3 solve per node).
    Recursive,
    /// One sparse LU solve of the whole equilibrium system.
    Global,
}

/// Arguments of `tensegrity michell`.
#[derive(clap::Args, Debug)]
#[command(group(
    ArgGroup::new("geometry")
        .required(true)
        .args(["planar", "cylindrical", "spherical"])
))]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct MichellArgs {
    /// `optimize`: the mass-optimal β, φ (and q) for a given radius ratio.
    #[command(subcommand)]
    pub action: Option<MichellAction>,
    /// Complexity q (number of member levels; level-q nodes are supports).
    #[arg(long, value_name = "Q", required = true)]
    pub complexity: Option<usize>,
    /// Skelton's planar truss in the y–z plane (two-index nodes n_ik).
    #[arg(long)]
    pub planar: bool,
    /// 3-D truss, cylindrical parameterisation with dimensionless offset δ (eq. 4.11).
    #[arg(long, value_name = "DELTA", allow_hyphen_values = true, value_parser = super::values::finite)]
    pub cylindrical: Option<f64>,
    /// 3-D truss, spherical parameterisation with angle ε (eq. 4.12), e.g. `pi/24`.
    #[arg(long, value_name = "EPS", value_parser = parse_angle, allow_hyphen_values = true)]
    pub spherical: Option<f64>,
    /// Departure angle β, e.g. `pi/6` or `30deg`.
    #[arg(long, value_name = "B", value_parser = parse_angle, required = true)]
    pub beta: Option<f64>,
    /// Segmentation angle φ, e.g. `pi/8`.
    #[arg(long, value_name = "P", value_parser = parse_angle, required = true)]
    pub phi: Option<f64>,
    /// Initial radius r₀ (m).
    #[arg(long, value_name = "R", default_value_t = 1.0, value_parser = super::values::positive)]
    pub r0: f64,
    /// Tip load magnitude w₀ (N).
    #[arg(long, value_name = "W0", default_value_t = 1000.0, value_parser = super::values::positive)]
    pub load: f64,
    /// Load azimuth φ_w (eq. 4.13); with the default polar angle the load is −ι̂₃.
    #[arg(long, value_name = "A", value_parser = parse_angle, default_value = "0", allow_hyphen_values = true)]
    pub azimuth: f64,
    /// Load polar angle γ from ι̂₃ (eq. 4.13).
    #[arg(long, value_name = "G", value_parser = parse_angle, default_value = "pi", allow_hyphen_values = true)]
    pub polar: f64,
    /// Material of bars and strings (aluminium, steel, titanium, carbon_fibre, nylon, uhmwpe).
    #[arg(long, value_name = "NAME", default_value = "steel")]
    pub material: String,
    /// Add the extra strings of §4.6 (q ≥ 2, 3-D), each pretensioned to PRESTRESS newtons, or
    /// `auto`: to the smallest prestress above which no member but the tip members changes
    /// sign over the nominal load region of complexity 1 (reported as min_extra_prestress).
    #[arg(long = "extra-strings", value_name = "PRESTRESS|auto", value_parser = super::michell_extra::parse)]
    pub extra_strings: Option<super::michell_extra::ExtraStringsArg>,
    /// Force propagation method.
    #[arg(long, value_enum, default_value_t = MethodArg::Recursive)]
    pub method: MethodArg,
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
    Optimize(super::michell_optimize::OptimizeArgs),
}

/// Arguments of `tensegrity michell-table`.
#[derive(clap::Args, Debug)]
pub struct MichellTableArgs {
    /// Largest complexity (the table runs q = 2..=Q).
    #[arg(long, value_name = "Q", default_value_t = 35)]
    pub max_complexity: usize,
    /// Tip load w₀ (N), along −ι̂₃.
    #[arg(long, value_name = "W0", default_value_t = 1000.0, value_parser = super::values::positive)]
    pub load: f64,
    /// Material of bars and strings.
    #[arg(long, value_name = "NAME", default_value = "steel")]
    pub material: String,
    /// Write the table to this CSV (else print it).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Also plot yield + buckling mass against complexity (Fig. 4.18) to this SVG file.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
}

impl MichellArgs {
    /// The analysis the arguments describe.
    pub fn request(&self) -> AnalysisRequest {
        // clap requires these without a subcommand; NaN and q = 0 are rejected by validation
        let (q, beta, phi) = (
            self.complexity.unwrap_or(0),
            self.beta.unwrap_or(f64::NAN),
            self.phi.unwrap_or(f64::NAN),
        );
        let params = match (self.cylindrical, self.spherical) {
            (Some(delta), _) => MichellParams::cylindrical(q, self.r0, beta, phi, delta),
            (None, Some(eps)) => MichellParams::spherical(q, self.r0, beta, phi, eps),
            (None, None) => MichellParams::planar(q, self.r0, beta, phi),
        };
        AnalysisRequest {
            params,
            load: self.load,
            azimuth: self.azimuth,
            polar: self.polar,
            material: self.material.clone(),
            extra_strings: match self.extra_strings {
                Some(super::michell_extra::ExtraStringsArg::Prestress(p)) => Some(p),
                _ => None,
            },
            method: match self.method {
                MethodArg::Recursive => Method::Recursive,
                MethodArg::Global => Method::Global,
            },
        }
    }
}

/// Runs `tensegrity michell`: one analysis (the truss is built once and reused by the sign
/// maps and the γ sweep).
pub fn run(args: &MichellArgs) -> Result<()> {
    if let Some(MichellAction::Optimize(opt)) = &args.action {
        return super::michell_optimize::run(opt);
    }
    let _progress = super::guard::michell(args)?;
    let (sign_map, gamma_sweep) = open_outputs(args)?;
    let (request, check) = match args.extra_strings {
        Some(arg) => {
            let (r, c) = super::michell_extra::resolve(arg, &args.request())?;
            (r, Some(c))
        }
        None => (args.request(), None),
    };
    let analysis = MichellAnalysis::run(&request).context("michell truss analysis failed")?;
    match (&check, args.json) {
        (Some(c), true) => println!("{}", super::michell_extra::json_with(&analysis.report, c)?),
        (None, true) => println!("{}", serde_json::to_string_pretty(&analysis.report)?),
        (Some(c), false) => print!(
            "{}{}",
            text_report(&analysis.report),
            super::michell_extra::text(c)
        ),
        (None, false) => print!("{}", text_report(&analysis.report)),
    }
    if let Some(sink) = sign_map {
        write_sign_maps(args, &request, &analysis.truss, sink)?;
    }
    if let (Some(sink), Some(prestress)) = (gamma_sweep, request.extra_strings) {
        write_gamma_sweep(args, &request, &analysis.truss, prestress, sink)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser, Debug)]
    struct Cli {
        #[command(flatten)]
        args: MichellArgs,
    }

    fn parse(argv: &[&str]) -> Result<MichellArgs, clap::Error> {
        let mut all = vec!["michell"];
        all.extend_from_slice(argv);
        Cli::try_parse_from(all).map(|c| c.args)
    }

    #[test]
    fn parses_the_documented_flags() {
        let a = parse(&[
            "--complexity",
            "4",
            "--cylindrical",
            "0.25",
            "--beta",
            "pi/6",
            "--phi",
            "22.5deg",
            "--azimuth",
            "-pi/4",
            "--polar",
            "3pi/4",
            "--method",
            "global",
            "--json",
        ])
        .unwrap();
        assert_eq!(a.complexity, Some(4));
        assert_eq!(a.cylindrical, Some(0.25));
        assert!((a.phi.unwrap() - std::f64::consts::PI / 8.0).abs() < 1e-15);
        assert!((a.azimuth + std::f64::consts::FRAC_PI_4).abs() < 1e-15);
        assert_eq!((a.r0, a.load, a.material.as_str()), (1.0, 1000.0, "steel"));
        assert_eq!(a.method, MethodArg::Global);
        let req = a.request();
        assert_eq!(req.method, Method::Global);
        assert!(michell3d::analyse(&req).is_ok());
    }

    #[test]
    fn geometry_is_required_and_exclusive() {
        let base = ["--complexity", "2", "--beta", "pi/6", "--phi", "pi/8"];
        assert!(parse(&base).is_err());
        let mut both = base.to_vec();
        both.extend(["--planar", "--spherical", "pi/24"]);
        assert!(parse(&both).is_err());
        let mut planar = base.to_vec();
        planar.push("--planar");
        let r = michell3d::analyse(&parse(&planar).unwrap().request()).unwrap();
        assert_eq!(r.members.len(), 6);
        assert!(text_report(&r).contains("planar"));
        let mut bad = base.to_vec();
        bad.extend(["--cylindrical", "0"]);
        let err = michell3d::analyse(&parse(&bad).unwrap().request()).unwrap_err();
        assert!(err.to_string().contains("delta"));
    }
}
