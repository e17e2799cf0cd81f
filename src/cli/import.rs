//! `tensegrity import motes N C_b [C_s] [--bar-mass F] [--stiffness F] [--rest-length F]
//! [--pinned NODES] [--out SCENE.toml]` and `tensegrity import ntrt MODEL.yaml [--pinned
//! NODES] [--out SCENE.toml]`: another code's model as a scene: MOTES's and TsgFEM's node and
//! connectivity matrices as text or CSV ([`tensegrity_io::matrices`]), NTRT's YAML models
//! ([`tensegrity_io::ntrt`]), written as scene TOML (to stdout without `--out`). No
//! mechanics here.

use super::output;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use tensegrity_io::matrices::{read_values, structure_from_matrices, MatrixOptions};
use tensegrity_io::read::{read_text, MAX_SCENE_BYTES};
use tensegrity_io::sink::FileSink;

/// Arguments of `tensegrity import`.
#[derive(clap::Args, Debug)]
pub struct ImportArgs {
    #[command(subcommand)]
    format: ImportFormat,
}

/// The model formats `import` reads.
#[derive(clap::Subcommand, Debug)]
enum ImportFormat {
    /// MOTES's or TsgFEM's matrices: the node matrix N (3 × n, a node per column; or n × 3)
    /// and the connectivity matrices C_b and C_s (a member per row: −1 at its first node, +1
    /// at its second), as text or CSV (commas or spaces; `%` and `#` comment lines).
    Motes(MotesArgs),
    /// NTRT's YAML model: `nodes`, `pair_groups` and `builders` (rods: tgRodInfo's density
    /// and radius; strings: an actuator's stiffness, damping and pretension), and combined
    /// models: `substructures` (paths relative to the file, placed by rotation, scale,
    /// offset, translation) joined by `bond_groups` (node_node, node_edge); node names (a
    /// substructure's as `child.node`) are listed in a comment at the top of the scene, in
    /// order.
    Ntrt(NtrtArgs),
}

/// Arguments of `tensegrity import ntrt`.
#[derive(clap::Args, Debug)]
struct NtrtArgs {
    /// The NTRT model (YAML).
    #[arg(value_name = "MODEL.yaml")]
    model: PathBuf,
    /// Nodes held in all three directions (comma-separated, 0-based in the scene's order, as
    /// listed at its top: a substructure's nodes first, then the file's own).
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "NODES",
        conflicts_with = "topology"
    )]
    pinned: Vec<usize>,
    /// Write the connectivity as a form-finding topology instead (its nodes as the start,
    /// bars and strings with nothing else given), for `tensegrity formfind`.
    #[arg(long)]
    topology: bool,
    /// Write the scene (or the topology) here (default: print it).
    #[arg(long, value_name = "SCENE.toml")]
    out: Option<PathBuf>,
}

/// Arguments of `tensegrity import motes`.
#[derive(clap::Args, Debug)]
struct MotesArgs {
    /// The node matrix N.
    #[arg(value_name = "N")]
    nodes: PathBuf,
    /// The bar connectivity C_b.
    #[arg(value_name = "C_b")]
    bars: PathBuf,
    /// The string connectivity C_s (none: no strings).
    #[arg(value_name = "C_s")]
    strings: Option<PathBuf>,
    /// One mass per bar (kg), in a text file.
    #[arg(long, value_name = "FILE")]
    bar_mass: Option<PathBuf>,
    /// One stiffness per string (N/m), in a text file.
    #[arg(long, value_name = "FILE")]
    stiffness: Option<PathBuf>,
    /// One rest length per string (m), in a text file.
    #[arg(long, value_name = "FILE")]
    rest_length: Option<PathBuf>,
    /// Nodes held in all three directions (comma-separated, 0-based).
    #[arg(long, value_delimiter = ',', value_name = "NODES")]
    pinned: Vec<usize>,
    /// Write the scene here (default: print it).
    #[arg(long, value_name = "SCENE.toml")]
    out: Option<PathBuf>,
}

/// Entry point of `tensegrity import`.
pub fn run(args: &ImportArgs) -> Result<()> {
    match &args.format {
        ImportFormat::Motes(a) => motes(a),
        ImportFormat::Ntrt(a) => ntrt(a),
    }
}

fn ntrt(a: &NtrtArgs) -> Result<()> {
    let sink = output::open("--out", a.out.as_deref(), FileSink::open)?;
    let text = read_text(&a.model, MAX_SCENE_BYTES, "an NTRT model")
        .with_context(|| format!("reading {}", a.model.display()))?;
    let name = a.model.display().to_string();
    let model = tensegrity_io::ntrt::structure_from_ntrt(&text, &name, &a.pinned)?;
    let mut scene = format!("# imported from NTRT's {name}; its nodes in order:\n");
    for (k, n) in model.names.iter().enumerate() {
        scene += &format!("#   {k}: {n}\n");
    }
    scene += &match a.topology {
        true => tensegrity_io::topology::to_toml(&tensegrity_io::ntrt::topology_of(&model)),
        false => tensegrity_io::scene::to_toml(&model.structure),
    };
    write(sink, scene)
}

fn write(sink: Option<FileSink>, scene: String) -> Result<()> {
    match sink {
        Some(sink) => sink.finish_with(scene)?,
        None => print!("{scene}"),
    }
    Ok(())
}

fn motes(a: &MotesArgs) -> Result<()> {
    let sink = output::open("--out", a.out.as_deref(), FileSink::open)?;
    let text = |p: &Path| -> Result<String> {
        read_text(p, MAX_SCENE_BYTES, "a matrix file")
            .with_context(|| format!("reading {}", p.display()))
    };
    let values = |p: &Option<PathBuf>, name: &str| -> Result<Option<Vec<f64>>> {
        p.as_deref()
            .map(|p| Ok(read_values(&text(p)?, name)?))
            .transpose()
    };
    let options = MatrixOptions {
        bar_masses: values(&a.bar_mass, "bar masses")?,
        string_stiffness: values(&a.stiffness, "string stiffnesses")?,
        string_rest_lengths: values(&a.rest_length, "string rest lengths")?,
        pinned: a.pinned.clone(),
    };
    let c_s = a.strings.as_deref().map(text).transpose()?;
    let structure =
        structure_from_matrices(&text(&a.nodes)?, &text(&a.bars)?, c_s.as_deref(), &options)?;
    write(sink, tensegrity_io::scene::to_toml(&structure))
}
