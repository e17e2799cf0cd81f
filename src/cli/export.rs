//! `tensegrity export mjcf SCENE.toml [--out MODEL.xml] [--timestep F] [--ground-height F]`:
//! a scene as another code's model file — MuJoCo's MJCF ([`tensegrity_io::mjcf`]: bars as
//! bodies with free joints, strings as spatial tendons with a slack dead band);
//! `tensegrity export json SCENE.toml [--out SCENE.json]`: the scene as JSON of the same
//! shape; `tensegrity export schema [--out scene.schema.json]`: the JSON Schema of scenes
//! ([`tensegrity_io::scene::json_schema`]). Printed to stdout without `--out`. No mechanics
//! here.

use super::output;
use anyhow::Result;
use std::path::PathBuf;
use tensegrity_io::mjcf::{scene_to_mjcf, MjcfGround, MjcfOptions, DEFAULT_TIMESTEP};
use tensegrity_io::scene::Scene;
use tensegrity_io::sink::FileSink;

/// Arguments of `tensegrity export`.
#[derive(clap::Args, Debug)]
pub struct ExportArgs {
    #[command(subcommand)]
    format: ExportFormat,
}

/// The model formats `export` writes.
#[derive(clap::Subcommand, Debug)]
enum ExportFormat {
    /// MuJoCo's MJCF (XML): every bar a body with a free joint (its mass, the rod inertia
    /// m l²/12, a capsule, a site at each end), shared and pinned nodes tied by
    /// `<connect>`, every string and cluster a spatial tendon (stiffness, damping, no force
    /// below its rest length), the scene's gravity. Loads, partial or elastic supports, free
    /// nodes on no bar, pulley friction and actuation tables are refused, naming the item.
    Mjcf(MjcfArgs),
    /// The scene as JSON of the same shape as its TOML (read back by every command: a scene
    /// file whose name ends in `.json`).
    Json(JsonArgs),
    /// The JSON Schema of scene files (TOML or JSON), generated from the scene description.
    Schema(SchemaArgs),
}

/// Arguments of `tensegrity export json`.
#[derive(clap::Args, Debug)]
struct JsonArgs {
    /// The scene file (TOML or JSON).
    #[arg(value_name = "SCENE.toml")]
    scene: PathBuf,
    /// Write the JSON here (default: print it).
    #[arg(long, value_name = "SCENE.json")]
    out: Option<PathBuf>,
}

/// Arguments of `tensegrity export schema`.
#[derive(clap::Args, Debug)]
struct SchemaArgs {
    /// Write the schema here (default: print it).
    #[arg(long, value_name = "scene.schema.json")]
    out: Option<PathBuf>,
}

/// Arguments of `tensegrity export mjcf`.
#[derive(clap::Args, Debug)]
struct MjcfArgs {
    /// The scene file (TOML).
    #[arg(value_name = "SCENE.toml")]
    scene: PathBuf,
    /// Write the model here (default: print it).
    #[arg(long, value_name = "MODEL.xml")]
    out: Option<PathBuf>,
    /// MuJoCo's time step (s).
    #[arg(long, value_name = "F", default_value_t = DEFAULT_TIMESTEP, allow_negative_numbers = true)]
    timestep: f64,
    /// A ground plane z = F (m) that the bars' capsules touch (default: the scene's
    /// `[ground]` plane, if any).
    #[arg(long, value_name = "F", allow_negative_numbers = true)]
    ground_height: Option<f64>,
}

/// Entry point of `tensegrity export`.
pub fn run(args: &ExportArgs) -> Result<()> {
    match &args.format {
        ExportFormat::Mjcf(a) => mjcf(a),
        ExportFormat::Json(a) => {
            let sink = output::open("--out", a.out.as_deref(), FileSink::open)?;
            let json = Scene::from_path(&a.scene)?.to_json();
            write(sink, json)
        }
        ExportFormat::Schema(a) => {
            let sink = output::open("--out", a.out.as_deref(), FileSink::open)?;
            let schema = tensegrity_io::scene::json_schema();
            write(sink, serde_json::to_string_pretty(&schema)? + "\n")
        }
    }
}

/// `text` to the sink, or printed.
fn write(sink: Option<FileSink>, text: String) -> Result<()> {
    match sink {
        Some(sink) => sink.finish_with(text)?,
        None => print!("{text}"),
    }
    Ok(())
}

fn mjcf(a: &MjcfArgs) -> Result<()> {
    let sink = output::open("--out", a.out.as_deref(), FileSink::open)?;
    let scene = Scene::from_path(&a.scene)?;
    let options = MjcfOptions {
        source: a.scene.display().to_string(),
        timestep: a.timestep,
        ground: a.ground_height.map(MjcfGround::height),
    };
    write(sink, scene_to_mjcf(&scene, &options)?)
}
