//! Streamed outputs of `tensegrity simulate`: the trajectory CSV and the VTK series are
//! written sample by sample while the run goes on (bounded memory), their paths are opened
//! before the run starts, and Ctrl-C (SIGINT) or SIGTERM ends the run with the rows so far
//! kept as a complete file marked incomplete (exit code 130).

use anyhow::{Context, Result};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use tensegrity_core::dynamics::{Sample, SampleSink};
use tensegrity_core::{CoreError, Structure};
use tensegrity_io::trajectory::TrajectoryWriter;
use tensegrity_io::vtk::{FrameData, SeriesWriter};
use tensegrity_io::IoError;

static STOP: AtomicBool = AtomicBool::new(false);

/// Makes SIGINT and SIGTERM ask the running simulation to stop at its next sample.
pub fn stop_on_signals() {
    // a second call (or a handler set elsewhere) keeps the first: nothing to do then
    let _ = ctrlc::set_handler(|| STOP.store(true, Ordering::SeqCst));
}

/// The open outputs of one run.
pub struct Outputs<'a> {
    csv: Option<TrajectoryWriter>,
    vtk: Option<SeriesWriter<'a>>,
    /// An output error that stopped the run.
    failed: Option<IoError>,
    last_t: f64,
}

impl<'a> Outputs<'a> {
    /// Opens `--out` and `--vtk` now, so a bad path fails before any work.
    pub fn open(csv: Option<&Path>, vtk: Option<&Path>, structure: &'a Structure) -> Result<Self> {
        let csv = csv
            .map(|p| TrajectoryWriter::create(p, structure))
            .transpose()
            .context("opening --out")?;
        let vtk = vtk
            .map(|d| SeriesWriter::create(d, structure))
            .transpose()
            .context("opening --vtk")?;
        Ok(Self {
            csv,
            vtk,
            failed: None,
            last_t: 0.0,
        })
    }

    fn write(&mut self, s: &Sample) -> Result<(), IoError> {
        if let Some(w) = self.csv.as_mut() {
            w.write(s)?;
        }
        if let (Some(w), Some(nodes)) = (self.vtk.as_mut(), s.nodes.as_deref()) {
            let data = FrameData {
                velocities: s.velocities.as_deref(),
                member_forces: s.member_forces.as_deref(),
            };
            w.frame_with(s.t, nodes, &data)?;
        }
        Ok(())
    }

    /// Closes the outputs after the run ended with `outcome`; an interrupted or failed run
    /// keeps its rows in a complete file with a `# incomplete: …` trailer. Returns (rows,
    /// frames).
    pub fn finish(mut self, outcome: Option<&CoreError>) -> Result<(usize, usize)> {
        if let Some(e) = self.failed.take() {
            return Err(e.into());
        }
        let rows = match (self.csv.take(), outcome) {
            (Some(w), None) => w.finish()?,
            // nothing computed: leave no file behind (dropping removes the temporary one)
            (Some(w), Some(_)) if w.rows() == 0 => 0,
            (Some(w), Some(e)) => w.finish_incomplete(&e.to_string())?,
            (None, _) => 0,
        };
        let frames = match self.vtk.take() {
            Some(w) => w.finish()?,
            None => 0,
        };
        Ok((rows, frames))
    }
}

impl SampleSink for Outputs<'_> {
    fn accept(&mut self, sample: Sample) -> Result<(), CoreError> {
        if STOP.load(Ordering::SeqCst) {
            return Err(CoreError::Interrupted { t: self.last_t });
        }
        if let Err(e) = self.write(&sample) {
            self.failed = Some(e);
            return Err(CoreError::Interrupted { t: self.last_t });
        }
        self.last_t = sample.t;
        Ok(())
    }

    fn keep_going(&mut self) -> bool {
        !STOP.load(Ordering::SeqCst)
    }
}
