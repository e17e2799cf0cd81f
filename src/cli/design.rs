//! `tensegrity design DESIGN.toml [--max-iterations N] [--method lbfgsb|levenberg_marquardt]
//! [--out SCENE.toml] [--form FORM.toml] [--history HISTORY.csv] [--json]`: the engine's `design` request ([`DesignRequest`], the
//! design file positional): inverse form-finding, the force densities whose form best meets
//! the file's goals. Prints the objective (start and designed, each term), the optimiser's
//! verdict (a run that did not converge is a warning, and its best point is still written),
//! the designed force densities, nodes and forces. `--out` writes the designed structure as a
//! scene (the same synthesis as `formfind --out`), `--form` the designed topology (every
//! member's force density; `tensegrity formfind FORM.toml` finds the designed form again),
//! `--history` one CSV row per iteration (objective, each term, projected gradient, step,
//! evaluations).

use super::output;
use super::request_args::RequestArgs;
use anyhow::Result;
use std::path::PathBuf;
use tensegrity_engine::design::{self, DesignReport, DesignRequest};
use tensegrity_io::sink::{CsvSink, FileSink};

/// Arguments of `tensegrity design`: the request's flags and the outputs.
#[derive(clap::Args, Debug)]
pub struct DesignArgs {
    #[command(flatten)]
    request: RequestArgs<DesignRequest>,
    /// Write the designed structure as a scene (rest lengths and stiffnesses realising the
    /// designed forces; supports and loads kept) that `statics`, `simulate` and every other
    /// command read.
    #[arg(long, value_name = "SCENE.toml")]
    out: Option<PathBuf>,
    /// Write the designed topology: the design file's topology with every member's designed
    /// force density (no [design] table), for `tensegrity formfind`.
    #[arg(long, value_name = "FORM.toml")]
    form: Option<PathBuf>,
    /// Write the optimisation history (one row per iteration).
    #[arg(long, value_name = "HISTORY.csv")]
    history: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// Entry point of `tensegrity design`.
pub fn run(args: &DesignArgs) -> Result<()> {
    let request: DesignRequest = args.request.request()?;
    let scene = output::open("--out", args.out.as_deref(), FileSink::open)?;
    let form = output::open("--form", args.form.as_deref(), FileSink::open)?;
    let history = output::open("--history", args.history.as_deref(), |p| {
        CsvSink::open_records(p, "design history CSV")
    })?;
    let report = design::design(&request)?;
    let d = &report.designed;
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    if let Some(sink) = history {
        write_history(sink, d)?;
    }
    if let Some(sink) = form {
        sink.finish_with(tensegrity_io::topology::to_toml(&d.topology))?;
    }
    if let Some(sink) = scene {
        let found = design::designed_form(&request, &report)?;
        for w in &found.report.warnings {
            eprintln!("warning: {w}");
        }
        let Some(structure) = found.structure.as_ref() else {
            anyhow::bail!(
                "--out: the designed form has no structure to write (see the warning above)"
            );
        };
        sink.finish_with(tensegrity_io::scene::to_toml(structure))?;
    }
    if args.json {
        return output::print_json(&report);
    }
    print_report(&report);
    for (what, path) in [
        ("scene", &args.out),
        ("form", &args.form),
        ("history", &args.history),
    ] {
        if let Some(p) = path {
            println!("wrote {what} {}", p.display());
        }
    }
    Ok(())
}

/// The history as CSV: iteration, objective, each term, projected gradient, step, evaluations.
fn write_history(
    mut sink: CsvSink,
    d: &tensegrity_engine::formfind::design::Designed,
) -> Result<()> {
    let mut header = vec!["iteration".to_string(), "objective".to_string()];
    header.extend(d.term_names.iter().cloned());
    header.extend(["projected_gradient", "step [N/m]", "evaluations"].map(String::from));
    sink.record(&header)?;
    for it in &d.history {
        let mut row = vec![it.iteration.to_string(), format!("{:?}", it.objective)];
        row.extend(it.terms.iter().map(|t| format!("{t:?}")));
        row.extend([
            format!("{:?}", it.projected_gradient),
            format!("{:?}", it.step),
            it.evaluations.to_string(),
        ]);
        sink.record(&row)?;
    }
    sink.finish()?;
    Ok(())
}

fn print_report(r: &DesignReport) {
    let d = &r.designed;
    println!(
        "{}: {} variables, {} terms; objective {:.9e} → {:.9e} ({}: {} iterations, {} evaluations, {} by {})",
        r.source,
        d.variables.len(),
        d.term_names.len(),
        d.initial_objective,
        d.objective,
        d.method,
        d.iterations,
        d.evaluations,
        if d.converged { "converged" } else { "NOT converged" },
        d.stop
    );
    let start = d
        .history
        .first()
        .map(|h| h.terms.clone())
        .unwrap_or_default();
    println!("terms (start → designed):");
    for (i, name) in d.term_names.iter().enumerate() {
        let s = start.get(i).copied().unwrap_or(f64::NAN);
        println!("  {name:<24} {s:>16.9e} → {:>16.9e}", d.terms[i]);
    }
    println!("members: designed q [N/m], length [m], force q·L [N]:");
    for (k, q) in d.force_density.iter().enumerate() {
        println!(
            "  {k:5} {q:>16.9} {:>14.9} {:>14.9}",
            d.length[k], d.force[k]
        );
    }
    println!("nodes (m):");
    let c = |x: f64| if x.abs() < 5e-10 { 0.0 } else { x };
    for (i, p) in d.nodes.iter().enumerate() {
        println!("  {i:4}  {:+.9} {:+.9} {:+.9}", c(p[0]), c(p[1]), c(p[2]));
    }
    if !d.reactions.is_empty() {
        println!("reactions at the held nodes (N):");
        for (j, r) in d.reactions.iter().enumerate() {
            println!("  {j:4}  {:+.9} {:+.9} {:+.9}", c(r[0]), c(r[1]), c(r[2]));
        }
    }
}
