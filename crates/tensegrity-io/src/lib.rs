//! # tensegrity-io
//!
//! File formats and pictures of the tensegrity toolkit: the only crate of the workspace that
//! knows TOML, CSV, VTK or plotting. The core and the topology crates return plain results and
//! `Serialize` reports; this crate reads scenes into the core's types and writes reports out.
//!
//! - [`scene`]: the TOML scene schema (nodes, materials, bars, strings, supports, loads,
//!   gravity, `[simulation]`, `[ground]`, `[[actuation]]`), parsed with line-numbered errors
//!   and mapped onto the core's builders; [`scene::to_toml`] writes a structure back;
//! - [`matrices`]: MOTES's and TsgFEM's matrix form of a model (N, C_b, C_s as text or CSV,
//!   per-member masses, stiffnesses and rest lengths) read into a structure; [`ntrt`]: NTRT's
//!   YAML models (nodes, pair groups, rod and actuator builders); [`mjcf`]: a structure
//!   written as a MuJoCo model (bars as free bodies, strings as spatial tendons with a slack
//!   dead band);
//! - [`csv`]: tables through the `csv` crate, with a header row whose column names carry the
//!   units (`t [s]`, `force_N`), e.g. trajectories, rolling histories, sign maps;
//! - [`vtk`]: ParaView `.vtu` frames and a `.pvd` series;
//! - [`figure`]: figures of one or more panels (line plots on linear or log axes, structure
//!   drawings with equal axes, legends placed off the data), written as SVG, PNG or PDF (with an
//!   embedded font) by file extension, at a chosen size and dpi;
//! - [`figure_data`]: the data of a figure as one table (header with units), written as CSV
//!   beside the figure;
//! - [`sink`]: the outputs of a command — CSV tables, VTK series, whole files, figures, JSON —
//!   opened (locked, temporary file created) before any work, streamed, renamed into place on
//!   success, kept with an `# incomplete` trailer when the run is interrupted or fails;
//! - [`topology`]: TOML topology files of form-finding (bars, strings, groups, fixed nodes)
//!   read into a [`formfind::Topology`] with line-numbered errors, and written back;
//! - [`read`]: input text files read under a size limit ([`read::MAX_SCENE_BYTES`]);
//! - [`interrupt`]: the SIGINT / SIGTERM stop flag that long computations poll, and the open
//!   sinks finished as incomplete when the process is interrupted.
//!
//! Files are written to a temporary file beside the target and renamed into place (the
//! [`sink`]s; [`write_file`] for a file written at once), so a failed or killed run never
//! leaves a truncated output behind.
//!
//! ```
//! use tensegrity_io::scene::Scene;
//! let text = "nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]\n[[bars]]\nnodes = [0, 1]\n";
//! let scene = Scene::from_str_named(text, "two-nodes.toml")?;
//! assert_eq!(scene.structure.n_bars(), 1);
//! # Ok::<(), tensegrity_io::IoError>(())
//! ```
#![warn(missing_docs)]

pub mod csv;
pub mod design;
pub mod error;
pub mod figure;
pub mod figure_data;
pub mod interrupt;
pub mod matrices;
pub mod mjcf;
pub mod ntrt;
pub mod progress;
pub mod read;
pub mod scene;
pub mod sink;
pub mod tables;
pub mod topology;
pub mod trajectory;
pub mod vtk;

pub use error::{IoError, Result};

use std::io::Write;
use std::path::Path;

/// Writes `text` to `path` atomically (see [`write_file`]); `what` names the content in errors.
///
/// ```
/// let path = std::env::temp_dir().join(format!("tensegrity-io-text-{}.toml", std::process::id()));
/// tensegrity_io::write_text(&path, "scene", "nodes = []\n")?;
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "nodes = []\n");
/// # std::fs::remove_file(&path).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
pub fn write_text(path: &Path, what: &'static str, text: &str) -> Result<()> {
    write_file(path, |w| {
        w.write_all(text.as_bytes()).map_err(IoError::stream(what))
    })
}

/// Writes a file through `fill` at once: a [`sink::FileSink`] opened, filled and finished (the
/// bytes go to a temporary file beside `path`, renamed to `path` once `fill` and the flush
/// succeed, removed otherwise). Stream errors of `fill` come back as [`IoError::Write`]
/// naming `path`. A command that computes before it writes opens the sink first instead.
///
/// ```
/// use std::io::Write;
/// use tensegrity_io::{write_file, IoError};
/// let path = std::env::temp_dir().join(format!("tensegrity-io-doc-{}.txt", std::process::id()));
/// write_file(&path, |w| w.write_all(b"hello\n").map_err(|source| IoError::Stream {
///     what: "greeting",
///     source,
/// }))?;
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "hello\n");
/// # std::fs::remove_file(&path).unwrap();
/// # Ok::<(), IoError>(())
/// ```
pub fn write_file<T>(path: &Path, fill: impl FnOnce(&mut dyn Write) -> Result<T>) -> Result<T> {
    let mut sink = sink::FileSink::open(path)?;
    let value = sink.write_with(fill)?;
    sink.finish()?;
    Ok(value)
}
