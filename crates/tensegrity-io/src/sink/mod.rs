//! Output sinks: every file a command writes goes through one of them.
//!
//! | sink | target | streamed | on an interrupt or a failed run |
//! |---|---|---|---|
//! | [`CsvSink`] | a table: header with units, rows | row by row | rows so far + `# incomplete: <reason>` |
//! | [`VtkSeriesSink`] | `frame_NNNNN.vtu` + `series.pvd` in a directory | frame by frame | complete frames, `series.pvd` listing them, `<!-- incomplete: … -->` |
//! | [`FileSink`] | any bytes (scene TOML, one `.vtu`, a table written at once) | through [`std::io::Write`] | removed |
//! | [`FigureSink`] | SVG or PNG by the extension | drawn at the end | removed |
//! | [`JsonSink`] | one JSON document | written at the end | removed |
//! | [`GifSink`], [`WebmSink`] ([`AnimationSink`] picks by extension) | an animation (`.gif`; `.webm`: AV1 in WebM) | frames drawn in parallel batches; a GIF streamed, a video's coded frames held and written at the end | removed |
//! | [`OutputDir`] | a directory that outputs go into | — | removed if this run created it and it is empty |
//!
//! A run's outputs together: [`SimulationOutputs`] (a simulation's trajectory CSV and VTK
//! series, the core's sample sink) and [`RollingOutputs`] (a rolling run's history CSV and VTK
//! series, wheel-rolling's observer); each stops its run at the next step on an interrupt.
//!
//! ## The protocol: open → stream → finish (or finish incomplete, or drop) → rename
//!
//! 1. **Open, before any work.** `open` takes an exclusive lock on the target ([`PathLock`]:
//!    `.NAME.lock` beside it, held by the operating system until the process ends, `kill -9`
//!    included) and creates the temporary file `.NAME.tmp` beside the target. A missing or
//!    read-only directory, a target that is a directory, an unknown figure extension or
//!    another run writing the same path fail here, with an [`IoError`](crate::IoError) that
//!    names the path (and, for [`IoError::Busy`](crate::IoError::Busy), the other run): a
//!    command opens all its sinks before it computes anything.
//! 2. **Stream.** Rows and frames go to the temporary file as they are produced; memory does
//!    not grow with the run.
//! 3. **Finish.** `finish` flushes, renames the temporary file onto the target (atomic within
//!    a file system: a reader sees the old file or the whole new one) and releases the lock.
//!    `finish_incomplete(reason)` does the same after a trailer that says why the file is
//!    short (CSV, VTK series). Dropping a sink unfinished (an error elsewhere) removes its
//!    temporary file: nothing appears at the target.
//! 4. **Interrupts.** Every sink registers with [`crate::interrupt`]; on SIGINT / SIGTERM the
//!    command either finishes its sinks itself (when it polls the stop flag) or the signal
//!    handler finishes them all as incomplete before the process exits with code 130. A
//!    killed process (`kill -9`) leaves its temporary file and no file at the target (the VTK
//!    series: the frames named by its last `series.pvd`).
//!
//! Libraries speak of their own parameters: a sink names paths, never command-line flags (a
//! front end adds those).
//!
//! ```
//! use tensegrity_io::sink::CsvSink;
//! let dir = std::env::temp_dir().join(format!("sink-doc-{}", std::process::id()));
//! # let _ = std::fs::remove_dir_all(&dir);
//! std::fs::create_dir(&dir).unwrap();
//! let path = dir.join("history.csv");
//! // 1. open before the work: a bad path would fail here
//! let mut sink = CsvSink::with_header(&path, "history CSV", &["t [s]", "x [m]"])?;
//! // a second run writing the same path is refused at once
//! assert!(CsvSink::open(&path, "history CSV").unwrap_err().to_string().contains("another run"));
//! // 2. stream
//! for k in 0..3 {
//!     sink.record([format!("{}", k as f64 * 0.5), format!("{}", k * k)])?;
//! }
//! assert!(!path.exists()); // still in `.history.csv.tmp`
//! // 3. finish: renamed into place
//! assert_eq!(sink.finish()?, 3);
//! assert_eq!(std::fs::read_to_string(&path).unwrap(), "t [s],x [m]\n0,0\n0.5,1\n1,4\n");
//! assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1); // no temporary or lock file left
//! # std::fs::remove_dir_all(&dir).unwrap();
//! # Ok::<(), tensegrity_io::IoError>(())
//! ```

mod animation;
mod csv;
mod dir;
mod file;
mod gif;
mod lock;
pub mod lzw;
mod rolling;
mod simulation;
pub(crate) mod staged;
mod video;
mod vtk;
pub mod webm;
pub mod yuv;

pub use self::animation::{AnimationSink, MP4_REFUSED};
pub use self::csv::CsvSink;
pub use self::dir::OutputDir;
pub use self::file::{FigureSink, FileSink, ImageFormat, JsonSink};
pub use self::gif::GifSink;
pub use self::lock::PathLock;
pub use self::rolling::RollingOutputs;
pub use self::simulation::{NodeFrames, SimulationOutputs, Written};
pub use self::video::WebmSink;
pub use self::vtk::{VtkSeriesSink, PVD_INTERVAL};

#[cfg(test)]
mod tests;
