//! The outputs of a wheel rolling run as wheel-rolling's [`Observer`]: every sample goes to the
//! history CSV ([`RollingRow`]: the bytes of [`crate::csv::write_rolling_history`]) and every
//! node frame to the VTK series while the run goes on, and the run stops at its next step once
//! an interrupt is [requested](crate::interrupt::requested) or an output fails.
//!
//! Each frame goes to the series once per time (the first of several at the same time), with
//! the node velocities as point data and the member forces as cell data when the model gives
//! them ([`FrameData`]: the full model both, the rigid model velocities only).
//!
//! The run keeps no frame (bounded memory: a frame is the whole wheel): the observer keeps
//! only those a figure needs ([`RollingOutputs::keeping`]: the frames within a tolerance of
//! given times), handed back by [`RollingOutputs::take_frames`].

use super::{CsvSink, NodeFrames, VtkSeriesSink, Written};
use crate::csv::RollingRow;
use crate::error::{IoError, Result};
use crate::progress::Progress;
use crate::vtk::FrameData;
use wheel_rolling::{Flow, Observer, RollingSample, WheelFrame};

/// The open outputs of one rolling run (either may be absent).
///
/// ```
/// use tensegrity_core::{Bar, Structure};
/// use tensegrity_io::sink::{CsvSink, RollingOutputs, VtkSeriesSink};
/// use wheel_rolling::{roll_wheel, FidelityChoice, Polygon, RunSpec};
/// let octagon = Polygon { sides: 8, outer_radius: 1.0, mass: 12.0, i1: 7.5 };
/// let spec = RunSpec { fidelity: FidelityChoice::Rigid, t_end: 0.1, ..RunSpec::default() };
/// let dir = std::env::temp_dir().join(format!("rolling-outputs-doc-{}", std::process::id()));
/// # let _ = std::fs::remove_dir_all(&dir);
/// std::fs::create_dir(&dir).unwrap();
/// // opened before the run: a bad path fails here
/// let csv = CsvSink::open(&dir.join("history.csv"), "rolling history CSV")?;
/// let mut outputs = RollingOutputs::new(Some(csv), None);
/// let run = roll_wheel(&octagon, &spec, &[], Some(&mut outputs)).unwrap();
/// let written = outputs.finish(None)?;
/// assert_eq!(written.rows, run.result.samples.len()); // 101 samples, 1 ms apart
/// # std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
#[derive(Debug)]
pub struct RollingOutputs<'a> {
    csv: Option<CsvSink>,
    vtk: Option<VtkSeriesSink<'a>>,
    /// Times whose frames are kept, and how near a frame must be.
    keep: Vec<f64>,
    tolerance: f64,
    kept: Vec<WheelFrame>,
    /// Time of the last frame written to the VTK series (a frame at the same time is not
    /// written again).
    last_vtk: Option<f64>,
    /// An animation, handed every frame.
    frames: Option<&'a mut dyn NodeFrames>,
    /// The simulated time of every sample.
    progress: Progress,
    /// An output error that stopped the run.
    failed: Option<IoError>,
}

impl<'a> RollingOutputs<'a> {
    /// The outputs, opened by the caller before the run (so each error names its own path).
    pub fn new(csv: Option<CsvSink>, vtk: Option<VtkSeriesSink<'a>>) -> Self {
        Self {
            csv,
            vtk,
            keep: Vec::new(),
            tolerance: 0.0,
            kept: Vec::new(),
            last_vtk: None,
            frames: None,
            progress: Progress::hidden(),
            failed: None,
        }
    }

    /// Also hands every frame's nodes to `frames` (an animation; the run's frame times must
    /// include the times it wants).
    pub fn with_frames(mut self, frames: &'a mut dyn NodeFrames) -> Self {
        self.frames = Some(frames);
        self
    }

    /// Reports the simulated time of every sample to `progress` (finished with the outputs).
    pub fn with_progress(mut self, progress: Progress) -> Self {
        self.progress = progress;
        self
    }

    /// Also keeps every frame within `tolerance` (s) of one of `times` (e.g. for drawings).
    pub fn keeping(mut self, times: &[f64], tolerance: f64) -> Self {
        self.keep = times.to_vec();
        self.tolerance = tolerance;
        self
    }

    /// The frames kept (see [`RollingOutputs::keeping`]), in time order.
    pub fn take_frames(&mut self) -> Vec<WheelFrame> {
        std::mem::take(&mut self.kept)
    }

    /// Closes the outputs: renamed into place when `incomplete` is `None`, else the rows and
    /// frames so far kept, marked incomplete with that reason (e.g. `interrupted at t = 1.5 s`).
    /// An output error that stopped the run is returned first.
    pub fn finish(mut self, incomplete: Option<&str>) -> Result<Written> {
        if incomplete.is_none() {
            self.progress.finish();
        }
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        let rows = match (self.csv.take(), incomplete) {
            (Some(w), None) => w.finish()?,
            (Some(w), Some(r)) => w.finish_incomplete(r)?,
            (None, _) => 0,
        };
        let frames = match (self.vtk.take(), incomplete) {
            (Some(w), None) => w.finish()?,
            (Some(w), Some(r)) => w.finish_incomplete(r)?,
            (None, _) => 0,
        };
        Ok(Written { rows, frames })
    }

    /// Records an output error (the run stops at its next check).
    fn flow(&mut self, written: Result<()>) -> Flow {
        match written {
            Ok(()) => Flow::Continue,
            Err(e) => {
                self.failed.get_or_insert(e);
                Flow::Stop
            }
        }
    }
}

impl Observer for RollingOutputs<'_> {
    fn sample(&mut self, sample: &RollingSample) -> Flow {
        self.progress.set(sample.t);
        let written = match self.csv.as_mut() {
            Some(csv) => csv.serialize(&RollingRow::from(sample)),
            None => Ok(()),
        };
        self.flow(written)
    }

    fn frame(&mut self, frame: &WheelFrame) -> Flow {
        if self
            .keep
            .iter()
            .any(|t| (frame.t - t).abs() <= self.tolerance)
        {
            self.kept.push(frame.clone());
        }
        if let Some(f) = self.frames.as_mut() {
            let drawn = f.frame(frame.t, &frame.nodes);
            if self.flow(drawn) == Flow::Stop {
                return Flow::Stop;
            }
        }
        // each time once in the series (a frame asked twice, or two asked times that fall
        // on the same step, is written once)
        if self.last_vtk.is_some_and(|t| frame.t <= t) {
            return Flow::Continue;
        }
        let data = FrameData {
            velocities: (!frame.velocities.is_empty()).then_some(&frame.velocities[..]),
            member_forces: (!frame.member_forces.is_empty()).then_some(&frame.member_forces[..]),
            contact_forces: None,
        };
        let written = match self.vtk.as_mut() {
            Some(vtk) => {
                self.last_vtk = Some(frame.t);
                vtk.frame_with(frame.t, &frame.nodes, &data)
            }
            None => Ok(()),
        };
        self.flow(written)
    }

    fn keep_going(&mut self) -> bool {
        self.failed.is_none() && !crate::interrupt::requested()
    }

    fn stop_flag(&self) -> Option<&'static std::sync::atomic::AtomicBool> {
        Some(crate::interrupt::flag())
    }

    fn keeps_frames(&self) -> bool {
        false
    }
}
