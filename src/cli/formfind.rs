//! `tensegrity formfind (TOPOLOGY.toml | --builtin NAME) [--method fdm|adaptive|dr|auto]
//! [--prestress LEVEL] [--stiffness EA] [--analyse] [--out SCENE.toml] [--svg F] [--json]`:
//! the engine's
//! `formfind` request ([`FormfindRequest`], the topology positional), one call
//! ([`formfind::admitted`]: the estimate of the method that will run checked against the
//! limits, the form found and its prestress synthesised); the scene and the figure are opened
//! before the work. The statics of the form (self-stress states, prestressability,
//! stability) are printed with `--analyse` only (`not analysed (--analyse)` otherwise). What
//! `--method auto` chose, and why, is printed as a warning; the
//! tolerance an iterative method stopped at is printed beside its iterations. A topology with
//! `[[loads]]` (or members' `weight`) prints the loads, the reactions at the fixed nodes and
//! the equilibrium residual, and `--out` writes the loaded scene (its `[[supports]]` and
//! `[[loads]]` kept). Clustered strings (`[[clusters]]`, one tension each) are printed with
//! their tension, length, rest length and segment force densities, and written as the
//! scene's `[[clusters]]`.

use super::figure_args::StructureArgs;
use super::output;
use super::request_args::RequestArgs;
use anyhow::{Context, Result};
use std::path::PathBuf;
use tensegrity_engine::formfind::{self, FormfindReport, FormfindRequest, Formfound};
use tensegrity_io::sink::FileSink;

/// Arguments of `tensegrity formfind`: the request's flags and the outputs.
#[derive(clap::Args, Debug)]
pub struct FormfindArgs {
    #[command(flatten)]
    request: RequestArgs<FormfindRequest>,
    /// Write the prestressed structure as a scene (rest lengths and stiffnesses realising the
    /// prestress; a loaded form's supports and loads kept) that `statics`, `simulate` and every
    /// other command read.
    #[arg(long, value_name = "SCENE.toml")]
    out: Option<PathBuf>,
    /// Draw the found structure (SVG, PNG or PDF by the extension).
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    #[command(flatten)]
    figure: super::figure_args::FigureArgs,
    #[command(flatten)]
    style: super::figure_args::StructureArgs,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// Entry point of `tensegrity formfind`.
pub fn run(args: &FormfindArgs) -> Result<()> {
    let request: FormfindRequest = args.request.request()?;
    let scene = output::open("--out", args.out.as_deref(), FileSink::open)?;
    let figure = args.figure.open("--svg", args.svg.as_deref())?;
    let found = formfind::admitted(&request, super::guard::optional).map_err(as_flag)?;
    // the method `auto` chose is the report's first warning
    for w in &found.report.warnings {
        eprintln!("warning: {}", super::spell::flags(&w.to_string()));
    }
    if let Some(sink) = scene {
        let structure = found.structure.as_ref().context(
            "--out: the form has no prestressed structure to write (see the warning above)",
        )?;
        sink.finish_with(tensegrity_io::scene::to_toml(structure))?;
    }
    if let Some(sink) = figure {
        sink.finish(&drawing(&found, &args.style))?;
    }
    if args.json {
        super::output::print_json(&found.report)?;
        return Ok(());
    }
    print_report(
        &found.report,
        found.found.tolerance,
        found.topology.is_loaded(),
    );
    for (flag, path) in [("scene", &args.out), ("figure", &args.svg)] {
        if let Some(p) = path {
            println!("wrote {flag} {}", p.display());
        }
    }
    Ok(())
}

/// A request parameter the library refuses after reading the topology (a `--stiffness` or
/// `--prestress` whose numbers overflow or fall below precision) named as its flag.
fn as_flag(e: anyhow::Error) -> anyhow::Error {
    use tensegrity_engine::formfind::FormfindFailure;
    let parameter = match e.downcast_ref::<FormfindFailure>() {
        Some(FormfindFailure::FormFind(::formfind::FormFindError::InvalidParameter(p))) => {
            p.clone()
        }
        _ => return e,
    };
    super::request_args::usage(parameter)
}

/// The found form drawn by the figures crate: isometric and from above, or in the one view,
/// colouring and labels asked for.
fn drawing(found: &Formfound, how: &StructureArgs) -> tensegrity_io::figure::Figure {
    use tensegrity_figures::draw;
    let t = &found.topology;
    let bars: Vec<[usize; 2]> = t.bars.iter().map(|m| m.nodes).collect();
    // a cluster drawn as strings, segment by segment (after the strings)
    let segments = t.clusters.iter().flat_map(|c| c.segments());
    let strings: Vec<[usize; 2]> = t.strings.iter().map(|m| m.nodes).chain(segments).collect();
    if how.view.is_none() && how.color_by.is_none() && how.labels.is_empty() {
        let nodes = &found.found.nodes;
        return draw::structure_figure(&found.report.source, nodes, bars, strings);
    }
    // per segment: its cluster's tension and its own force density t / l
    let clusters = &found.report.loading.clusters;
    let per_segment = |f: &dyn Fn(&::formfind::ClusterReport, usize) -> f64| -> Vec<f64> {
        let each = clusters
            .iter()
            .map(|c| (0..c.segment_length.len()).map(|i| f(c, i)));
        each.flatten().collect()
    };
    let tension = per_segment(&|c, _| c.tension.unwrap_or(c.force));
    let q = per_segment(&|c, i| c.segment_force_density[i]);
    let d = draw::Drawing {
        nodes: found.found.nodes.clone(),
        bars,
        strings,
        force: (found.report.member_force.clone()).map(|f| [f, tension].concat()),
        force_density: Some([found.report.force_density.clone(), q].concat()),
        ..draw::Drawing::default()
    };
    let panel = draw::drawing_panel(&found.report.source, &d, &how.style(draw::View::Iso));
    draw::drawing_figure_of(vec![panel], 560)
}

fn print_report(r: &FormfindReport, tolerance: Option<f64>, loaded: bool) {
    let tolerance = tolerance.map_or(String::new(), |t| format!(" (tolerance {t:.1e})"));
    println!(
        "{}: {} nodes, {} bars, {} strings{}; method {}, iterations {}{tolerance}",
        r.source,
        r.n_nodes,
        r.n_bars,
        r.n_strings,
        match r.loading.clusters.len() {
            0 => String::new(),
            n => format!(", {n} clusters"),
        },
        r.method,
        r.iterations
    );
    match (r.self_stress_dim, r.prestressable, r.prestress_stable) {
        (Some(dim), Some(prestressable), Some(stable)) => println!(
            "self-stress states {dim}  prestressable {prestressable}  prestress stable {stable}  \
             residual {:.3e}",
            r.residual
        ),
        _ => println!(
            "self-stress states, prestressability, stability: not analysed (--analyse)  \
             residual {:.3e}",
            r.residual
        ),
    }
    println!("nodes (m):");
    // round-off below the printed digits shown as 0, not as -0.000000000
    let c = |x: f64| if x.abs() < 5e-10 { 0.0 } else { x };
    for (i, p) in r.nodes.iter().enumerate() {
        println!("  {i:4}  {:+.9} {:+.9} {:+.9}", c(p[0]), c(p[1]), c(p[2]));
    }
    let force = r.member_force.as_deref().unwrap_or(&[]);
    if loaded {
        println!("members: q [N/m], force q·L under the loads [N]:");
    } else {
        println!("members: q [N/m], force at prestress {} N:", r.prestress);
    }
    for (k, q) in r.force_density.iter().enumerate() {
        let name = match k.checked_sub(r.n_bars) {
            None => format!("bar {k}"),
            Some(j) => format!("string {j}"),
        };
        let f = force.get(k).map_or(String::new(), |f| format!("{f:>14.6}"));
        println!("  {name:<12} {q:>14.9} {f}");
    }
    print_clusters(&r.loading.clusters);
    print_forces("loads (N):", &r.loading.loads);
    print_forces("reactions at the fixed nodes (N):", &r.loading.reactions);
    if let Some(e) = r.loading.equilibrium_residual {
        println!("equilibrium residual at the free nodes {e:.3e} (relative)");
    }
}

/// The clustered strings: tension, length, rest length and the segments' force densities
/// (nothing without clusters).
fn print_clusters(clusters: &[::formfind::ClusterReport]) {
    if clusters.is_empty() {
        return;
    }
    println!("clusters: tension t [N] (at the prestress level), length L, rest length L0 [m]:");
    for (c, k) in clusters.iter().enumerate() {
        let t = k.tension.unwrap_or(k.force);
        let l0 = k
            .rest_length
            .map_or(String::new(), |l| format!("  L0 {l:.9}"));
        println!("  cluster {c:<4} t {t:.9}  L {:.9}{l0}", k.length);
        let q: Vec<String> = (k.segment_force_density.iter())
            .map(|q| format!("{q:.9}"))
            .collect();
        println!("    segment q = t/l [N/m]: {}", q.join(" "));
    }
}

/// A list of nodal forces under its heading (nothing for an empty list).
fn print_forces(heading: &str, forces: &[::formfind::NodeForce]) {
    if forces.is_empty() {
        return;
    }
    println!("{heading}");
    let c = |x: f64| if x.abs() < 5e-10 { 0.0 } else { x };
    for f in forces {
        let [x, y, z] = f.force;
        println!("  {:4}  {:+.9} {:+.9} {:+.9}", f.node, c(x), c(y), c(z));
    }
}
