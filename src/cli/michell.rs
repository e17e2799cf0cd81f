//! `tensegrity michell`: a planar or 3-D discrete Michell truss under a tip load — member
//! forces, member types, masses (thesis chapter 4, ERRATA ch. 4).
//!
//! ```text
//! tensegrity michell --complexity Q (--planar | --cylindrical DELTA | --spherical EPS)
//!     --beta B --phi P [--r0 R] [--load W0] [--azimuth A] [--polar G] [--material NAME]
//!     [--extra-strings PRESTRESS|auto] [--method recursive|global] [--json]
//! ```
//!
//! The flags are the fields of [`MichellRequest`] ([`RequestArgs`]); one library call
//! ([`MichellRequest::run`]) and the report printed ([`super::michell_text`]).

use super::request_args::RequestArgs;
use anyhow::{Context, Result};
use michell3d::signmap::AngleGrid;
use michell3d::{AnalysisRequest, MichellRequest, MichellTableRequest, MichellTruss};
use std::path::{Path, PathBuf};
use tensegrity_io::figure::{Figure, Panel, Series};

/// Arguments of `tensegrity michell`: the request's flags ([`MichellRequest`]: `--complexity`,
/// `--beta`, `--phi` and one of `--planar`, `--cylindrical`, `--spherical` required), the
/// outputs, and the `optimize` subcommand.
#[derive(clap::Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct MichellArgs {
    // before the subcommand, which parsing takes out of the matches: the request is not
    // checked when a subcommand is given
    #[command(flatten)]
    request: RequestArgs<MichellRequest>,
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

/// Arguments of `tensegrity michell-table`: the request's flags ([`MichellTableRequest`]) and
/// the outputs.
#[derive(clap::Args, Debug)]
pub struct MichellTableArgs {
    #[command(flatten)]
    request: RequestArgs<MichellTableRequest>,
    /// Write the table to this CSV (else print it).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Also plot yield + buckling mass against complexity (Fig. 4.18) to this SVG file.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
}

/// Runs `tensegrity michell`: one analysis (the truss is built once and reused by the sign
/// maps and the γ sweep).
pub fn run(args: &MichellArgs) -> Result<()> {
    if let Some(MichellAction::Optimize(opt)) = &args.action {
        return super::michell_optimize::run(opt);
    }
    let _progress = super::guard::michell(args)?;
    let request: MichellRequest = args.request.request()?;
    let run = request.run().context("michell truss analysis failed")?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&run)?);
    } else {
        print!("{}", super::michell_text::report(&run));
    }
    if let Some(path) = &args.sign_map {
        write_sign_maps(args, &run.request, &run.analysis.truss, path)?;
    }
    if let (Some(path), Some(prestress)) = (&args.gamma_sweep, run.request.extra_strings) {
        write_gamma_sweep(args, &run.request, &run.analysis.truss, prestress, path)?;
    }
    Ok(())
}

/// Computes the sign maps of `--map-members` on the analysed truss (rows on threads through
/// [`sweeps::grids::sign_maps`]) and writes their CSV.
fn write_sign_maps(
    args: &MichellArgs,
    request: &AnalysisRequest,
    truss: &MichellTruss,
    path: &Path,
) -> Result<()> {
    use michell3d::signmap::sign_map_rows;
    use sweeps::grids::sign_maps;
    let n_members = truss.members().len();
    if let Some(&bad) = args.map_members.iter().find(|&&m| m >= n_members) {
        anyhow::bail!("--map-members: member {bad} does not exist (the truss has {n_members})");
    }
    let (na, np) = args.map_grid;
    let maps = sign_maps(
        truss,
        &args.map_members,
        request.load,
        AngleGrid::new(0.0, 2.0 * std::f64::consts::PI, na),
        AngleGrid::new(0.0, std::f64::consts::PI, np),
        request.method,
    )?;
    tensegrity_io::write_file(path, |w| {
        tensegrity_io::csv::write_sign_maps(w, sign_map_rows(truss, &maps))
    })?;
    if !args.json {
        for m in &maps {
            println!(
                "sign map of member {}: in tension for {:.1} % of the load directions",
                m.member,
                100.0 * m.tension_fraction()
            );
        }
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Sweeps the load polar angle γ over [0, 2π] with prestressed extra strings (Fig. 4.20)
/// on the analysed truss and writes the CSV.
fn write_gamma_sweep(
    args: &MichellArgs,
    request: &AnalysisRequest,
    truss: &MichellTruss,
    prestress: f64,
    path: &Path,
) -> Result<()> {
    use michell3d::extra_strings::{gamma_sweep, ExtraStrings};
    let strings = ExtraStrings::new(truss)?;
    let sweep = gamma_sweep(
        truss,
        &strings,
        request.load,
        request.azimuth,
        AngleGrid::new(0.0, 2.0 * std::f64::consts::PI, 721),
        prestress,
        request.method,
    )?;
    tensegrity_io::write_file(path, |w| {
        tensegrity_io::csv::write_gamma_sweep(w, sweep.rows())
    })?;
    if !args.json {
        let changers: Vec<usize> = (0..sweep.base_keeps_sign.len())
            .filter(|&j| !sweep.base_keeps_sign[j])
            .collect();
        println!(
            "over γ ∈ [0, 2π] with {prestress} N in the extra strings, members changing sign: {changers:?}; extra strings keeping their sign: {}/{}",
            sweep.extra_keeps_sign.iter().filter(|&&k| k).count(),
            sweep.extra_keeps_sign.len()
        );
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Runs `tensegrity michell-table` (Fig. 4.18: mass against complexity), a thin wrapper over
/// [`sweeps::grids::mass_vs_complexity`].
pub fn run_table(args: &MichellTableArgs) -> Result<()> {
    use michell3d::complexity::FIG_4_18_DELTAS;
    use sweeps::grids::mass_vs_complexity;
    use tensegrity_io::csv::write_mass_table;
    let request: MichellTableRequest = args.request.request()?;
    let material = request.material()?;
    let qs = request.complexities();
    let rows = mass_vs_complexity(&qs, &FIG_4_18_DELTAS, request.load, &material)?;
    match &args.out {
        Some(path) => {
            tensegrity_io::write_file(path, |w| write_mass_table(w, &rows))?;
            println!("wrote {} rows to {}", rows.len(), path.display());
        }
        None => {
            write_mass_table(std::io::stdout().lock(), &rows)?;
        }
    }
    if let Some(path) = &args.svg {
        Figure::new(vec![mass_panel(&request, &rows)])
            .save(path)
            .with_context(|| format!("writing the figure {}", path.display()))?;
    }
    Ok(())
}

/// Fig. 4.18: yield + buckling mass against complexity, planar and one line per δ.
fn mass_panel(args: &MichellTableRequest, rows: &[michell3d::MassRow]) -> Panel {
    let series = |delta: f64, label: String| {
        let points = rows
            .iter()
            .filter(|r| r.delta == delta)
            .map(|r| (r.complexity as f64, r.yield_buckling_mass_kg))
            .collect();
        Series::new(label, points)
    };
    let mut all = vec![series(0.0, "planar".into())];
    all.extend(
        michell3d::complexity::FIG_4_18_DELTAS
            .iter()
            .map(|&d| series(d, format!("δ = {d}"))),
    );
    let mut panel = Panel::new(
        format!(
            "{} yield + buckling mass, w0 = {} N (Fig. 4.18)",
            args.material, args.load
        ),
        "complexity q",
        "mass [kg]",
    );
    panel.series = all;
    panel
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

    fn request(argv: &[&str]) -> MichellRequest {
        parse(argv).unwrap().request.request().unwrap()
    }

    #[test]
    fn parses_the_documented_flags() {
        let argv = "--complexity 4 --cylindrical 0.25 --beta pi/6 --phi 22.5deg --azimuth -pi/4 \
                    --polar 3pi/4 --method global --json";
        let r = request(&argv.split_whitespace().collect::<Vec<_>>());
        assert_eq!((r.complexity, r.cylindrical), (Some(4), Some(0.25)));
        assert!((r.phi.unwrap() - std::f64::consts::PI / 8.0).abs() < 1e-15);
        assert!((r.azimuth + std::f64::consts::FRAC_PI_4).abs() < 1e-15);
        assert_eq!((r.r0, r.load, r.material.as_str()), (1.0, 1000.0, "steel"));
        assert_eq!(r.method, michell3d::Method::Global);
        assert!(michell3d::analyse(&r.analysis()).is_ok());
    }

    #[test]
    fn geometry_is_required_and_exclusive() {
        let base = ["--complexity", "2", "--beta", "pi/6", "--phi", "pi/8"];
        assert!(parse(&base)
            .unwrap_err()
            .to_string()
            .contains("give one of planar"));
        let mut both = base.to_vec();
        both.extend(["--planar", "--spherical", "pi/24"]);
        let e = parse(&both).unwrap_err().to_string();
        assert!(e.contains("--planar") && e.contains("spherical"), "{e}");
        let mut planar = base.to_vec();
        planar.push("--planar");
        let r = michell3d::analyse(&request(&planar).analysis()).unwrap();
        assert_eq!(r.members.len(), 6);
        assert!(super::super::michell_text::report_text(&r).contains("planar"));
        let mut bad = base.to_vec();
        bad.extend(["--cylindrical", "0"]);
        let err = michell3d::analyse(&request(&bad).analysis()).unwrap_err();
        assert!(err.to_string().contains("delta"));
        assert!(parse(&["--planar", "--beta", "1", "--phi", "1"]).is_err());
    }
}
