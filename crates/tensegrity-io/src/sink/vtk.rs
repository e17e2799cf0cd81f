//! The VTK series sink: `frame_NNNNN.vtu` files plus the `series.pvd` collection that indexes
//! them by time, in one directory, for ParaView.
//!
//! Each frame is written whole to a temporary file and renamed into place before the
//! collection names it, and `series.pvd` is rewritten atomically after the first frame, then at
//! most every [`PVD_INTERVAL`] and at every stop. So however the run ends — finished,
//! interrupted, failed, killed — the directory holds a readable `series.pvd` whose frames all
//! exist: every frame on a finish or an interrupt (then marked by an
//! `<!-- incomplete: reason -->` comment), the frames of the last rewrite after a `kill -9`.

use super::dir::OutputDir;
use super::lock::PathLock;
use super::staged::Staged;
use crate::error::{IoError, Result};
use crate::interrupt::{self, Interruptible};
use crate::vtk::{vtu_with, FrameData};
use nalgebra::Vector3;
use std::fmt::Write as _;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tensegrity_core::Structure;

/// The longest time between two rewrites of `series.pvd` while frames arrive.
pub const PVD_INTERVAL: Duration = Duration::from_secs(1);

/// The state shared with the interrupt handler.
#[derive(Debug)]
struct Series {
    dir: OutputDir,
    lock: Option<PathLock>,
    /// `<DataSet …/>` lines of the frames written.
    entries: String,
    count: usize,
    last_pvd: Option<Instant>,
}

impl Series {
    fn pvd(&self) -> PathBuf {
        self.dir.join("series.pvd")
    }

    /// Rewrites `series.pvd` over the frames so far (with an incomplete note if given).
    fn write_pvd(&mut self, note: Option<&str>) -> Result<()> {
        let mut text = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n",
        );
        if let Some(note) = note {
            // a comment may not hold `--`
            let note = note.replace("--", "- -").replace(['\n', '\r'], " ");
            let _ = writeln!(text, "<!-- incomplete: {note} -->");
        }
        text.push_str("<Collection>\n");
        text.push_str(&self.entries);
        text.push_str("</Collection>\n</VTKFile>\n");
        let mut staged = Staged::open_unlocked(&self.pvd(), std::io::BufWriter::new)?;
        let err = staged.write_error();
        staged.out()?.write_all(text.as_bytes()).map_err(&err)?;
        staged.commit(|w| w.into_inner().map_err(|e| e.into_error()), None)?;
        self.last_pvd = Some(Instant::now());
        Ok(())
    }

    fn is_open(&self) -> bool {
        self.lock.is_some()
    }

    /// Ends the series: the final collection, the lock released, the directory kept when
    /// it holds frames (an unstarted, interrupted series leaves nothing).
    fn close(&mut self, note: Option<&str>) -> Result<Option<PathBuf>> {
        if !self.is_open() {
            return Err(IoError::Closed { path: self.pvd() });
        }
        let kept = if self.count > 0 || note.is_none() {
            self.write_pvd(note)?;
            Some(self.pvd())
        } else {
            None
        };
        self.lock = None;
        if kept.is_some() {
            self.dir.mark_kept();
        }
        Ok(kept)
    }
}

impl Interruptible for Mutex<Series> {
    fn interrupt(&self, reason: &str) -> Option<PathBuf> {
        let mut series = self.lock().unwrap_or_else(|e| e.into_inner());
        if !series.is_open() {
            return None;
        }
        series.close(Some(reason)).ok().flatten()
    }
}

/// A ParaView series written frame by frame as a run produces it (bounded memory; see the
/// module documentation).
///
/// ```
/// use tensegrity_core::{Bar, Structure};
/// use tensegrity_io::sink::VtkSeriesSink;
/// let s = Structure::builder().nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1)).build().unwrap();
/// let dir = std::env::temp_dir().join(format!("vtk-sink-doc-{}", std::process::id()));
/// # let _ = std::fs::remove_dir_all(&dir);
/// let mut series = VtkSeriesSink::open(&dir, &s)?; // the directory exists from here on
/// series.frame(0.0, s.nodes())?;
/// series.frame(0.5, s.nodes())?;
/// assert_eq!(series.finish()?, 2);
/// assert!(dir.join("series.pvd").exists() && dir.join("frame_00001.vtu").exists());
/// # std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
#[derive(Debug)]
pub struct VtkSeriesSink<'a> {
    structure: &'a Structure,
    state: Arc<Mutex<Series>>,
    dir: PathBuf,
}

impl<'a> VtkSeriesSink<'a> {
    /// Creates `dir` if missing (its parent must exist) or checks it is writable, and locks
    /// its `series.pvd`, so a bad path or a second writer fails before the run.
    pub fn open(dir: &Path, structure: &'a Structure) -> Result<Self> {
        let out = OutputDir::create(dir)?;
        let lock = PathLock::acquire(&out.join("series.pvd"))?;
        let state = Arc::new(Mutex::new(Series {
            dir: out,
            lock: Some(lock),
            entries: String::new(),
            count: 0,
            last_pvd: None,
        }));
        interrupt::register(&state);
        Ok(Self {
            structure,
            state,
            dir: dir.to_path_buf(),
        })
    }

    /// [`VtkSeriesSink::open`] (the former name of the constructor).
    pub fn create(dir: &Path, structure: &'a Structure) -> Result<Self> {
        Self::open(dir, structure)
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Series> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Frames written so far.
    pub fn frames(&self) -> usize {
        self.lock().count
    }

    /// Writes the frame of time `t` with node positions `nodes` (file numbering).
    pub fn frame(&mut self, t: f64, nodes: &[Vector3<f64>]) -> Result<()> {
        self.frame_with(t, nodes, &FrameData::default())
    }

    /// Writes a frame with recorded quantities (see [`FrameData`]).
    pub fn frame_with(
        &mut self,
        t: f64,
        nodes: &[Vector3<f64>],
        data: &FrameData<'_>,
    ) -> Result<()> {
        let text = vtu_with(self.structure, nodes, data);
        let mut series = self.lock();
        if !series.is_open() {
            return Err(IoError::Closed { path: series.pvd() });
        }
        let name = format!("frame_{:05}.vtu", series.count);
        let mut staged = Staged::open_unlocked(&series.dir.join(&name), std::io::BufWriter::new)?;
        let err = staged.write_error();
        staged.out()?.write_all(text.as_bytes()).map_err(&err)?;
        staged.commit(|w| w.into_inner().map_err(|e| e.into_error()), None)?;
        let _ = writeln!(
            series.entries,
            r#"<DataSet timestep="{t:e}" part="0" file="{name}"/>"#
        );
        series.count += 1;
        if series
            .last_pvd
            .is_none_or(|at| at.elapsed() >= PVD_INTERVAL)
        {
            series.write_pvd(Some("the run is still writing frames"))?;
        }
        Ok(())
    }

    /// Writes the final `series.pvd` over the frames so far; returns their number.
    pub fn finish(self) -> Result<usize> {
        let mut series = self.lock();
        series.close(None)?;
        Ok(series.count)
    }

    /// Ends a run that stopped early: `series.pvd` over the frames so far with an
    /// `<!-- incomplete: {reason} -->` comment (no frames: nothing is left, and the directory
    /// goes if this run created it). Returns the number of frames.
    pub fn finish_incomplete(self, reason: &str) -> Result<usize> {
        let mut series = self.lock();
        series.close(Some(reason))?;
        Ok(series.count)
    }
}

impl Drop for VtkSeriesSink<'_> {
    /// A series dropped unfinished (an error elsewhere) keeps its frames under a `series.pvd`
    /// marked incomplete.
    fn drop(&mut self) {
        let mut series = self.lock();
        if series.is_open() {
            let _ = series.close(Some("the run ended before its outputs were finished"));
        }
    }
}
