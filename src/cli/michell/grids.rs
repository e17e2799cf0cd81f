//! `michell --sign-map`, `--gamma-sweep` and `michell-table`: the grids of Figs. 4.14–4.16,
//! 4.20 and 4.18, their output files opened (io sinks) before the grids are computed.

use super::args::{MichellArgs, MichellTableArgs};
use crate::cli::output;
use anyhow::Result;
use michell3d::signmap::AngleGrid;
use michell3d::{AnalysisRequest, MichellTableRequest, MichellTruss};
use tensegrity_io::sink::FileSink;

/// `--sign-map` and `--gamma-sweep`, opened before the analysis.
pub fn open_outputs(args: &MichellArgs) -> Result<(Option<FileSink>, Option<FileSink>)> {
    Ok((
        output::open("--sign-map", args.sign_map.as_deref(), FileSink::open)?,
        output::open("--gamma-sweep", args.gamma_sweep.as_deref(), FileSink::open)?,
    ))
}

/// Computes the sign maps of `--map-members` on the analysed truss (rows on threads through
/// [`sweeps::grids::sign_maps`]) and writes their CSV.
pub fn write_sign_maps(
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
        request.load,
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
pub fn write_gamma_sweep(
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
        request.load,
        request.azimuth,
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
    let request: MichellTableRequest = args.request.request()?;
    let material = request.material()?;
    let _progress = crate::cli::guard::estimated(&request)?;
    let out = output::open("--out", args.out.as_deref(), FileSink::open)?;
    let svg = args.figure.open("--svg", args.svg.as_deref())?;
    let qs = request.complexities();
    let rows = mass_vs_complexity(&qs, &FIG_4_18_DELTAS, request.load, &material)?;
    match out {
        Some(mut sink) => {
            sink.write_with(|w| write_mass_table(w, &rows))?;
            let path = sink.path().to_path_buf();
            sink.finish()?;
            if !args.json {
                println!("wrote {} rows to {}", rows.len(), path.display());
            }
        }
        None if args.json => {}
        None => {
            write_mass_table(std::io::stdout().lock(), &rows)?;
        }
    }
    if args.json {
        let json = serde_json::json!({ "rows": rows, "row_count": rows.len() });
        output::print_json(&json)?;
    }
    if let Some(sink) = svg {
        sink.finish(&tensegrity_figures::michell::mass_table_figure(
            &request, &rows,
        ))?;
    }
    Ok(())
}
