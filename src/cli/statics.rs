//! `tensegrity statics SCENE.toml [--json] [--rank-tol REL] [--modes K] [--mass M]
//! [--least-squares] [--response] [--method M] [--svg FILE [--view V] [--color-by BY] [--labels L]
//! [--size WxH] [--dpi D]]`: the engine's `statics` request ([`StaticsCommand`]), one
//! call ([`statics::admitted`]: the scene read, its estimate checked against the limits, one
//! report, with the linear response when asked or when a support has a `displacement`)
//! printed as text or JSON; `--svg` draws the structure coloured by force with its
//! reactions ([`tensegrity_figures::structures::statics_figure`]), or with `--modes K` the K
//! lowest mode shapes ([`tensegrity_figures::structures::modes_figure`]).

use super::figure_args::{FigureArgs, StructureArgs};
use super::request_args::RequestArgs;
use anyhow::Result;
use std::path::PathBuf;
use tensegrity_core::budget::Estimate;
use tensegrity_core::Structure;
use tensegrity_engine::statics::{self, StaticsCommand};
use tensegrity_figures::draw::default_view;
use tensegrity_figures::structures;
use tensegrity_statics::report::Reaction;
use tensegrity_statics::StaticsReport;
use tensegrity_statics::{column_name, Factorization};

/// Arguments of `tensegrity statics`: the request's flags ([`StaticsCommand`], the scene
/// positional) and the output.
#[derive(clap::Args, Debug)]
pub struct StaticsArgs {
    #[command(flatten)]
    request: RequestArgs<StaticsCommand>,
    /// Print JSON instead of a readable report.
    #[arg(long)]
    pub json: bool,
    /// Draw the structure to FILE (.svg, .png or .pdf): members coloured by force (or by the
    /// prestress force density when nothing is loaded), supports, loads and reactions; with
    /// --modes K the K lowest mode shapes (or mechanisms) instead.
    #[arg(long, value_name = "FILE")]
    pub svg: Option<PathBuf>,
    #[command(flatten)]
    figure: FigureArgs,
    #[command(flatten)]
    drawing: StructureArgs,
}

/// Entry point of `tensegrity statics`.
pub fn run(args: &StaticsArgs) -> Result<()> {
    let command: StaticsCommand = args.request.request()?;
    let figure = args.figure.open("--svg", args.svg.as_deref())?;
    let limits = super::guard::limits();
    let drawn = modes_estimate(args, &command);
    // the sparse path's cost after its QR grows with the self-stresses it finds, which no
    // estimate before the run knows: the spinner shows whatever the estimate
    let admit = |e: Option<Estimate>| match with_figure(e, drawn.clone()) {
        Some(e) => {
            let rank_dependent = e.what.starts_with("the sparse statics");
            super::guard::check_with(e, rank_dependent)
        }
        None => super::guard::optional(None),
    };
    let (scene, report) =
        statics::admitted(&command, Some(&limits), admit).map_err(super::guard::refused_later)?;
    if report.load_carried == Some(false) {
        eprintln!(
            "warning: the loads are not carried (residual {:.6e} N at nodes {:?}): least-squares force densities, no sizing",
            report.residual.unwrap_or(f64::NAN),
            report.unbalanced_nodes.as_deref().unwrap_or(&[])
        );
    }
    for w in report.linear_response.iter().flat_map(|r| &r.warnings) {
        eprintln!("warning: {w}");
    }
    if args.json {
        if let Some(w) = &report.statics_warning {
            eprintln!("warning: {}", super::spell::flags(w));
        }
        super::output::print_json(&report)?;
    } else {
        print_report(&scene.structure, &report);
    }
    if let Some(sink) = figure {
        let style = args.drawing.style(default_view(scene.structure.nodes()));
        let fig = match command.modes {
            Some(k) => {
                let panels = structures::mode_panels(k);
                if panels < k {
                    eprintln!("note: --svg draws the {panels} lowest of the {k} modes of --modes (at most {} panels)", structures::MAX_MODE_PANELS);
                }
                structures::modes_figure(&scene.structure, k, command.mass, &style)?
            }
            None => structures::statics_figure(&scene.structure, &report, &style),
        };
        sink.finish(&fig)?;
    }
    Ok(())
}

/// The estimate of the `--svg` figure of `--modes K` (its dense modes and its panels,
/// [`structures::modes_figure_estimate`]), checked with the statics' before any work; none
/// without it, or for a scene that cannot be read (the statics then says why).
fn modes_estimate(args: &StaticsArgs, command: &StaticsCommand) -> Option<Estimate> {
    let k = command.modes.filter(|_| args.svg.is_some())?;
    let scene = command.source().ok()?.load().ok()?;
    Some(structures::modes_figure_estimate(&scene.structure, k))
}

/// The statics' estimate and the figure's, one after the other, named by both.
fn with_figure(statics: Option<Estimate>, figure: Option<Estimate>) -> Option<Estimate> {
    match (statics, figure) {
        (Some(s), Some(f)) => {
            let parameters = f
                .parameters
                .0
                .iter()
                .fold(s.parameters.clone(), |p, (n, v)| p.and(n.clone(), v));
            Some(Estimate {
                parameters,
                ..s.then(f)
            })
        }
        (s, f) => s.or(f),
    }
}

/// Prints a readable report.
pub fn print_report(structure: &Structure, r: &StaticsReport) {
    print_summary(r);
    if let Some(q) = &r.prestress {
        println!("max-margin prestress (force density, max|q| = 1):");
        for (k, v) in q.iter().enumerate() {
            println!("  {:<10} {:>12.6}", column_name(structure, k), v);
        }
    }
    print_load_solve(structure, r);
    print_response(structure, r);
    print_sizing(structure, r);
    print_notes(r);
}

fn print_summary(r: &StaticsReport) {
    let clusters = match r.clusters {
        0 => String::new(),
        n => format!("  clusters {n}"),
    };
    println!(
        "nodes {}  bars {}  strings {}{clusters}",
        r.nodes, r.bars, r.strings
    );
    println!(
        "rank {}  self-stress states {}  mechanisms {} ({} internal)",
        r.rank, r.self_stress_dim, r.mechanisms, r.internal_mechanisms
    );
    println!(
        "smallest singular value {:.3e} (rank tolerance {:.3e})",
        r.smallest_singular_value, r.rank_tolerance
    );
    if r.prestressable {
        let stable = if r.prestress_stable == Some(true) {
            "prestress stable"
        } else {
            "NOT prestress stable"
        };
        println!(
            "prestressable: yes, margin {:.6} ({stable})",
            r.prestress_margin
        );
    } else {
        println!("prestressable: no");
    }
}

fn print_load_solve(structure: &Structure, r: &StaticsReport) {
    let (Some(q), Some(f)) = (&r.force_density, &r.member_force) else {
        return;
    };
    println!("load solve (residual {:.3e} N):", r.residual.unwrap_or(0.0));
    println!("  {:<10} {:>14} {:>14}", "member", "q [N/m]", "force [N]");
    for k in 0..q.len() {
        println!(
            "  {:<10} {:>14.6} {:>14.6}",
            column_name(structure, k),
            q[k],
            f[k]
        );
    }
    print_reactions(r.reactions.iter().flatten());
}

/// One line per reaction: its force and, for a support along directions of any orientation,
/// its force along each of them.
fn print_reactions<'a>(reactions: impl Iterator<Item = &'a Reaction>) {
    for rc in reactions {
        let along = if rc.along.is_empty() {
            String::new()
        } else {
            let parts: Vec<String> = rc.along.iter().map(|a| format!("{a:.6}")).collect();
            format!(" (along its given directions: {} N)", parts.join(", "))
        };
        println!(
            "  reaction at node {}: [{:.6}, {:.6}, {:.6}] N{along}",
            rc.node, rc.force[0], rc.force[1], rc.force[2]
        );
    }
}

/// The linear response: the largest displacement, each member's force change, the moved
/// nodes and the reactions (its warnings go to stderr).
fn print_response(structure: &Structure, r: &StaticsReport) {
    let Some(lr) = &r.linear_response else {
        return;
    };
    println!(
        "linear response at this geometry (largest displacement {:.6e} m):",
        lr.max_displacement
    );
    println!("  {:<10} {:>14} {:>14}", "member", "t0 [N]", "change [N]");
    for (k, dt) in lr.member_force_change.iter().enumerate() {
        let id = column_name(structure, k);
        println!("  {id:<10} {:>14.6} {dt:>14.6}", lr.initial_force[k]);
    }
    for (i, u) in lr.displacements.iter().enumerate() {
        if u.iter().any(|&v| v != 0.0) {
            println!(
                "  node {i} moves [{:.6e}, {:.6e}, {:.6e}] m",
                u[0], u[1], u[2]
            );
        }
    }
    print_reactions(lr.reactions.iter());
    if !lr.slack.is_empty() {
        println!("  strings that would go slack: {:?}", lr.slack);
    }
    if !lr.slack_clusters.is_empty() {
        println!("  clusters that would go slack: {:?}", lr.slack_clusters);
    }
}

fn print_sizing(structure: &Structure, r: &StaticsReport) {
    let (Some(m), Some(radii), Some(masses), Some(gov)) = (
        r.mass_kg,
        &r.member_radius_m,
        &r.member_mass_kg,
        &r.governing,
    ) else {
        return;
    };
    println!("minimum-mass sizing:");
    println!(
        "  {:<10} {:>12} {:>12} {:>10}",
        "member", "radius [mm]", "mass [kg]", "governed"
    );
    for k in 0..radii.len() {
        println!(
            "  {:<10} {:>12.4} {:>12.6} {:>10}",
            column_name(structure, k),
            radii[k] * 1e3,
            masses[k],
            gov[k]
        );
    }
    println!("minimum mass for these loads: {m:.6} kg");
}

fn print_notes(r: &StaticsReport) {
    if let Some(f) = &r.natural_frequencies_hz {
        let list: Vec<String> = f.iter().map(|x| format!("{x:.4}")).collect();
        let skipped = match r.zero_modes_skipped {
            Some(n) if n > 0 => format!(" ({n} zero-frequency modes skipped)"),
            _ => String::new(),
        };
        println!(
            "lowest natural frequencies [Hz]{skipped}: {}",
            list.join(", ")
        );
    }
    if let Some(e) = &r.modal_error {
        println!("modes not computed: {e}");
    }
    if let Some(w) = &r.sizing_warning {
        println!("warning: {w}");
    }
    if let Some(e) = &r.sizing_error {
        println!("sizing not possible: {e}");
    }
    if let Some(method) = r.statics_method {
        let estimated = method == Factorization::SparseQr;
        let note = if estimated {
            " (smallest singular value estimated)"
        } else {
            ""
        };
        println!("factorisation: {}{note}", method.describe());
    }
    if let Some(w) = &r.statics_warning {
        let w = super::spell::flags(w);
        println!("warning: {w}");
        eprintln!("warning: {w}");
    }
}
