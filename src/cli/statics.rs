//! `tensegrity statics SCENE.toml [--json]`.

use anyhow::Result;
use serde::Serialize;
use std::path::PathBuf;
use tensegrity_core::{sizing, Statics, StaticsSettings, Structure};
use tensegrity_io::scene::Scene;

/// Arguments of `tensegrity statics`.
#[derive(clap::Args, Debug)]
pub struct StaticsArgs {
    /// The scene file (TOML).
    pub scene: PathBuf,
    /// Print JSON instead of a readable report.
    #[arg(long)]
    pub json: bool,
    /// Relative rank tolerance of the SVD (default: max(rows, cols) · machine epsilon).
    #[arg(long, value_name = "REL")]
    pub rank_tol: Option<f64>,
    /// Also report the K lowest natural frequencies about the current state (strings need
    /// stiffness and rest length, bars mass, material and radius).
    #[arg(long, value_name = "K")]
    pub modes: Option<usize>,
    /// Mass matrix of the modes: lumped (half of each bar at each end) or consistent (the
    /// rigid-bar mass matrix of the dynamics).
    #[arg(long, value_enum, default_value_t = MassArg::Lumped)]
    pub mass: MassArg,
}

/// `--mass` values.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum MassArg {
    /// Diagonal: m/2 at each bar end.
    Lumped,
    /// m [[1/3, 1/6], [1/6, 1/3]] per bar, as in the dynamics.
    Consistent,
}

/// A support reaction.
#[derive(Debug, Serialize)]
pub struct Reaction {
    /// The supported node.
    pub node: usize,
    /// Reaction force (N).
    pub force: [f64; 3],
}

/// Everything `tensegrity statics` reports.
#[derive(Debug, Serialize)]
pub struct StaticsReport {
    /// Number of nodes.
    pub nodes: usize,
    /// Number of bars.
    pub bars: usize,
    /// Number of strings.
    pub strings: usize,
    /// Rank of the equilibrium matrix.
    pub rank: usize,
    /// Dimension of the self-stress space.
    pub self_stress_dim: usize,
    /// First-order mechanisms (rigid-body motions included when unsupported).
    pub mechanisms: usize,
    /// Internal mechanisms: mechanisms beyond the rigid-body motions the supports allow.
    pub internal_mechanisms: usize,
    /// Whether a self-stress puts every string in tension and every bar in compression.
    pub prestressable: bool,
    /// The prestressability LP margin (0 when not prestressable).
    pub prestress_margin: f64,
    /// Prestress stability with the max-margin stress (only when prestressable).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prestress_stable: Option<bool>,
    /// Orthonormal self-stress basis, members bars then strings.
    pub self_stress: Vec<Vec<f64>>,
    /// The max-margin self-stress scaled to max|q| = 1 (only when prestressable).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prestress: Option<Vec<f64>>,
    /// Smallest singular value of the equilibrium matrix.
    pub smallest_singular_value: f64,
    /// Absolute rank tolerance used.
    pub rank_tolerance: f64,
    /// Force densities for the loads (N/m, tension positive).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub force_density: Option<Vec<f64>>,
    /// Member forces for the loads (N, tension positive).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub member_force: Option<Vec<f64>>,
    /// Support reactions.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reactions: Option<Vec<Reaction>>,
    /// ‖A q − w‖₂ (N).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub residual: Option<f64>,
    /// Total minimum mass for the loads (kg), when members have materials.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mass_kg: Option<f64>,
    /// Minimum radius of each member for the loads (m), when sized.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub member_radius_m: Option<Vec<f64>>,
    /// Minimum mass of each member for the loads (kg), when sized.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub member_mass_kg: Option<Vec<f64>>,
    /// Failure mode setting each member's size: "yield", "buckling" or "unloaded".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub governing: Option<Vec<&'static str>>,
    /// Set when the mass was computed but the design is not buildable as is (strings in
    /// compression).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sizing_warning: Option<String>,
    /// The lowest natural frequencies (Hz) about the current state, with `--modes`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub natural_frequencies_hz: Option<Vec<f64>>,
    /// Why the modes could not be computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modal_error: Option<String>,
    /// Why the mass could not be computed, when members have materials but sizing failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sizing_error: Option<String>,
}

/// Runs every statics analysis of one structure.
pub fn analyse(structure: &Structure, settings: StaticsSettings) -> Result<StaticsReport> {
    let statics = Statics::with_settings(structure, settings)?;
    let basis = statics.self_stress_basis();
    let pre = statics.prestressability()?;
    let flexes = statics.flexes()?;
    let prestress_stable = if pre.prestressable {
        Some(statics.prestress_stability(&pre.stress)?.stable)
    } else {
        None
    };
    let mut report = StaticsReport {
        nodes: structure.n_nodes(),
        bars: structure.n_bars(),
        strings: structure.n_strings(),
        rank: statics.rank(),
        self_stress_dim: statics.self_stress_dim(),
        mechanisms: statics.mechanisms(),
        internal_mechanisms: flexes.internal.ncols(),
        prestressable: pre.prestressable,
        prestress_margin: pre.margin,
        prestress_stable,
        self_stress: basis
            .column_iter()
            .map(|c| c.iter().copied().collect())
            .collect(),
        prestress: pre
            .prestressable
            .then(|| pre.stress.iter().copied().collect()),
        smallest_singular_value: statics.singular_values().last().copied().unwrap_or(0.0),
        rank_tolerance: statics.tolerance(),
        force_density: None,
        member_force: None,
        reactions: None,
        residual: None,
        mass_kg: None,
        member_radius_m: None,
        member_mass_kg: None,
        governing: None,
        sizing_warning: None,
        natural_frequencies_hz: None,
        modal_error: None,
        sizing_error: None,
    };
    if structure.is_loaded() {
        let sol = statics.solve_loads();
        let has_materials = (0..structure.n_members())
            .any(|k| structure.member_material(structure.member_id(k)).is_some());
        if has_materials {
            match sizing::size_structure_lenient(structure, &sol.member_force) {
                Ok((s, compressed)) => {
                    if !compressed.is_empty() {
                        let names: Vec<String> =
                            compressed.iter().map(|id| id.to_string()).collect();
                        report.sizing_warning = Some(format!(
                            "the minimal-norm solution puts {} in compression; sized for yield on |force|, but a string cannot carry compression: add prestress (a self-stress) or make it a bar",
                            names.join(", ")
                        ));
                    }
                    report.mass_kg = Some(s.total_mass);
                    report.member_radius_m = Some(s.members.iter().map(|m| m.radius).collect());
                    report.member_mass_kg = Some(s.members.iter().map(|m| m.mass).collect());
                    report.governing = Some(
                        s.members
                            .iter()
                            .map(|m| match m.governing {
                                sizing::Governing::Yield => "yield",
                                sizing::Governing::Buckling => "buckling",
                                sizing::Governing::Unloaded => "unloaded",
                            })
                            .collect(),
                    );
                }
                Err(e) => report.sizing_error = Some(e.to_string()),
            }
        }
        report.force_density = Some(sol.force_density.iter().copied().collect());
        report.member_force = Some(sol.member_force.iter().copied().collect());
        report.reactions = Some(
            sol.reactions
                .iter()
                .map(|(node, r)| Reaction {
                    node: *node,
                    force: [r.x, r.y, r.z],
                })
                .collect(),
        );
        report.residual = Some(sol.residual);
    }
    Ok(report)
}

/// Prints a readable report.
pub fn print_report(structure: &Structure, r: &StaticsReport) {
    println!("nodes {}  bars {}  strings {}", r.nodes, r.bars, r.strings);
    println!(
        "rank {}  self-stress states {}  mechanisms {} ({} internal)",
        r.rank, r.self_stress_dim, r.mechanisms, r.internal_mechanisms
    );
    println!(
        "smallest singular value {:.3e} (rank tolerance {:.3e})",
        r.smallest_singular_value, r.rank_tolerance
    );
    if r.prestressable {
        println!(
            "prestressable: yes, margin {:.6} ({})",
            r.prestress_margin,
            if r.prestress_stable == Some(true) {
                "prestress stable"
            } else {
                "NOT prestress stable"
            }
        );
    } else {
        println!("prestressable: no");
    }
    if let Some(q) = &r.prestress {
        println!("max-margin prestress (force density, max|q| = 1):");
        for (k, v) in q.iter().enumerate() {
            println!("  {:<10} {:>12.6}", structure.member_id(k).to_string(), v);
        }
    }
    if let (Some(q), Some(f)) = (&r.force_density, &r.member_force) {
        println!("load solve (residual {:.3e} N):", r.residual.unwrap_or(0.0));
        println!("  {:<10} {:>14} {:>14}", "member", "q [N/m]", "force [N]");
        for k in 0..q.len() {
            println!(
                "  {:<10} {:>14.6} {:>14.6}",
                structure.member_id(k).to_string(),
                q[k],
                f[k]
            );
        }
        for rc in r.reactions.iter().flatten() {
            println!(
                "  reaction at node {}: [{:.6}, {:.6}, {:.6}] N",
                rc.node, rc.force[0], rc.force[1], rc.force[2]
            );
        }
    }
    if let (Some(m), Some(radii), Some(masses), Some(gov)) = (
        r.mass_kg,
        &r.member_radius_m,
        &r.member_mass_kg,
        &r.governing,
    ) {
        println!("minimum-mass sizing:");
        println!(
            "  {:<10} {:>12} {:>12} {:>10}",
            "member", "radius [mm]", "mass [kg]", "governed"
        );
        for k in 0..radii.len() {
            println!(
                "  {:<10} {:>12.4} {:>12.6} {:>10}",
                structure.member_id(k).to_string(),
                radii[k] * 1e3,
                masses[k],
                gov[k]
            );
        }
        println!("minimum mass for these loads: {m:.6} kg");
    }
    if let Some(f) = &r.natural_frequencies_hz {
        let list: Vec<String> = f.iter().map(|x| format!("{x:.4}")).collect();
        println!("lowest natural frequencies [Hz]: {}", list.join(", "));
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
}

/// Entry point of `tensegrity statics`.
pub fn run(args: &StaticsArgs) -> Result<()> {
    let scene = Scene::from_path(&args.scene)?;
    let mut settings = StaticsSettings::default();
    if let Some(tol) = args.rank_tol {
        settings = settings.rank_tolerance(tol)?;
    }
    let mut report = analyse(&scene.structure, settings)?;
    if let Some(k) = args.modes {
        let modes = tensegrity_core::stiffness::equilibrium_force_densities(&scene.structure)
            .and_then(|(q, _)| {
                let mass = match args.mass {
                    MassArg::Lumped => tensegrity_core::stiffness::MassModel::Lumped,
                    MassArg::Consistent => tensegrity_core::stiffness::MassModel::Consistent,
                };
                tensegrity_core::stiffness::modal_analysis_with(&scene.structure, &q, mass)
            });
        match modes {
            Ok(m) => {
                report.natural_frequencies_hz = Some(m.frequencies_hz.into_iter().take(k).collect())
            }
            Err(e) => report.modal_error = Some(e.to_string()),
        }
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_report(&scene.structure, &report);
    }
    Ok(())
}
