//! `tensegrity michell`: a planar or 3-D discrete Michell truss under a tip load — member
//! forces, member types, masses (thesis chapter 4, ERRATA ch. 4).
//!
//! ```text
//! tensegrity michell --complexity Q (--planar | --cylindrical DELTA | --spherical EPS)
//!     --beta B --phi P [--r0 R] [--load W0] [--azimuth A] [--polar G] [--material NAME]
//!     [--extra-strings PRESTRESS] [--method recursive|global] [--json]
//! ```

use super::output;
use crate::cli::angle::parse_angle;
use anyhow::{Context, Result};
use clap::{ArgGroup, ValueEnum};
use michell3d::signmap::AngleGrid;
use michell3d::{
    AnalysisRequest, MemberKind, Method, MichellAnalysis, MichellParams, MichellReport,
    MichellTruss,
};
use std::path::PathBuf;
use tensegrity_io::figure::{Figure, Panel, Series};
use tensegrity_io::sink::{FigureSink, FileSink};

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

/// `--sign-map` and `--gamma-sweep`, opened before the analysis.
fn open_outputs(args: &MichellArgs) -> Result<(Option<FileSink>, Option<FileSink>)> {
    Ok((
        output::open("--sign-map", args.sign_map.as_deref(), FileSink::open)?,
        output::open("--gamma-sweep", args.gamma_sweep.as_deref(), FileSink::open)?,
    ))
}

fn member_row(s: &mut String, m: &michell3d::report::MemberReport) {
    use std::fmt::Write;
    let _ = writeln!(
        s,
        "{:>16} {:>16} {:>12.6} {:>16.6e} {:>14.6e} {:>6} {:>9}",
        tuple(&m.parent),
        tuple(&m.child),
        m.length,
        m.force_density,
        m.force,
        m.kind.as_str(),
        m.governing
    );
}

fn tuple(t: &[usize]) -> String {
    let parts: Vec<String> = t.iter().map(|v| v.to_string()).collect();
    format!("({})", parts.join(","))
}

/// The readable report.
pub fn text_report(r: &MichellReport) -> String {
    use std::fmt::Write;
    let mut s = text_header(r);
    let _ = writeln!(
        s,
        "\n{:>16} {:>16} {:>12} {:>16} {:>14} {:>6} {:>9}",
        "parent", "child", "length [m]", "q [N/m]", "force [N]", "kind", "governs"
    );
    for m in &r.members {
        member_row(&mut s, m);
    }
    if let Some(t) = r.prestress {
        let _ = writeln!(s, "\nExtra strings (prestress {t} N each):");
        for m in &r.extra_strings {
            member_row(&mut s, m);
        }
    }
    let _ = writeln!(
        s,
        "\nMass: yield {:.6e} kg, yield + buckling {:.6e} kg",
        r.mass_kg.yield_only, r.mass_kg.yield_buckling
    );
    let _ = writeln!(
        s,
        "Normalised yield mass Σ|q|l²/(w0 r0) = {:.9}",
        r.normalized_yield_mass
    );
    let _ = writeln!(s, "Buckling-governed bars: {}", r.buckling_governed.len());
    s
}

/// Geometry, load and counts: the first lines of the readable report.
fn text_header(r: &MichellReport) -> String {
    use std::fmt::Write;
    let p = &r.params;
    let mut s = String::new();
    let geometry = match p.geometry {
        michell3d::Geometry::Planar => "planar (Skelton)".to_string(),
        michell3d::Geometry::Cylindrical { delta } => format!("3-D cylindrical, δ = {delta}"),
        michell3d::Geometry::Spherical { epsilon } => format!("3-D spherical, ε = {epsilon} rad"),
    };
    let _ = writeln!(
        s,
        "Michell truss: {geometry}, complexity q = {}",
        p.complexity
    );
    let _ = writeln!(
        s,
        "  r0 = {} m, β = {:.6} rad ({:.4}°), φ = {:.6} rad ({:.4}°), a = {:.6}, c = {:.6}",
        p.r0,
        p.beta,
        p.beta.to_degrees(),
        p.phi,
        p.phi.to_degrees(),
        p.a(),
        p.c()
    );
    let method = match r.method {
        Method::Recursive => "recursive",
        Method::Global => "global",
    };
    let _ = writeln!(
        s,
        "  tip load w = [{:.6}, {:.6}, {:.6}] N; method {method}; material {}",
        r.load[0], r.load[1], r.load[2], r.material
    );
    let count = |k: MemberKind| r.members.iter().filter(|m| m.kind == k).count();
    let supports = r.nodes.iter().filter(|n| n.support).count();
    let _ = writeln!(
        s,
        "  {} nodes ({} supports), {} members: {} strings, {} bars, {} none",
        r.nodes.len(),
        supports,
        r.members.len(),
        count(MemberKind::String),
        count(MemberKind::Bar),
        count(MemberKind::None)
    );
    s
}

/// Computes the sign maps of `--map-members` on the analysed truss (rows on threads through
/// [`sweeps::grids::sign_maps`]) and writes their CSV.
fn write_sign_maps(
    args: &MichellArgs,
    request: &AnalysisRequest,
    truss: &MichellTruss,
    mut sink: FileSink,
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
        args.load,
        AngleGrid::new(0.0, 2.0 * std::f64::consts::PI, na),
        AngleGrid::new(0.0, std::f64::consts::PI, np),
        request.method,
    )?;
    sink.write_with(|w| tensegrity_io::csv::write_sign_maps(w, sign_map_rows(truss, &maps)))?;
    let path = sink.path().to_path_buf();
    sink.finish()?;
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
    mut sink: FileSink,
) -> Result<()> {
    use michell3d::extra_strings::{gamma_sweep, ExtraStrings};
    let strings = ExtraStrings::new(truss)?;
    let sweep = gamma_sweep(
        truss,
        &strings,
        args.load,
        args.azimuth,
        AngleGrid::new(0.0, 2.0 * std::f64::consts::PI, 721),
        prestress,
        request.method,
    )?;
    sink.write_with(|w| tensegrity_io::csv::write_gamma_sweep(w, sweep.rows()))?;
    let path = sink.path().to_path_buf();
    sink.finish()?;
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
    if args.max_complexity < 2 {
        anyhow::bail!(
            "--max-complexity must be at least 2, got {}",
            args.max_complexity
        );
    }
    let material =
        *tensegrity_core::MaterialTable::builtin().lookup(&args.material, "--material")?;
    let out = output::open("--out", args.out.as_deref(), FileSink::open)?;
    let svg = output::open("--svg", args.svg.as_deref(), FigureSink::open)?;
    let qs: Vec<usize> = (2..=args.max_complexity).collect();
    let rows = mass_vs_complexity(&qs, &FIG_4_18_DELTAS, args.load, &material)?;
    match out {
        Some(mut sink) => {
            sink.write_with(|w| write_mass_table(w, &rows))?;
            let path = sink.path().to_path_buf();
            sink.finish()?;
            println!("wrote {} rows to {}", rows.len(), path.display());
        }
        None => {
            write_mass_table(std::io::stdout().lock(), &rows)?;
        }
    }
    if let Some(sink) = svg {
        sink.finish(&Figure::new(vec![mass_panel(args, &rows)]))?;
    }
    Ok(())
}

/// Fig. 4.18: yield + buckling mass against complexity, planar and one line per δ.
fn mass_panel(args: &MichellTableArgs, rows: &[michell3d::MassRow]) -> Panel {
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
