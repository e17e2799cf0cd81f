//! The outputs of a simulation as the core's [`SampleSink`]: every recorded sample goes to the
//! trajectory CSV, the VTK series and any [`NodeFrames`] (an animation) while the run goes on,
//! the simulated time to a [`Progress`] report after every step, and the run stops at its
//! next sample (or step) once an interrupt is [requested](crate::interrupt::requested).

use crate::error::{IoError, Result};
use crate::progress::Progress;
use crate::sink::VtkSeriesSink;
use crate::trajectory::TrajectoryWriter;
use crate::vtk::FrameData;
use nalgebra::Vector3;
use tensegrity_core::CoreError;
use tensegrity_dynamics::{Sample, SampleSink};

/// What takes the node positions of a run as it goes (an animation: it keeps the frames it
/// needs and draws them at its end).
pub trait NodeFrames {
    /// The nodes (file numbering) at time `t` (s); an error stops the run.
    fn frame(&mut self, t: f64, nodes: &[Vector3<f64>]) -> Result<()>;
}

/// What a finished run wrote.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Written {
    /// Trajectory rows (0 without a CSV).
    pub rows: usize,
    /// VTK frames (0 without a series).
    pub frames: usize,
}

/// The open outputs of one simulation (either may be absent).
///
/// ```
/// use tensegrity_dynamics::{Simulation, SimulationSettings};
/// use tensegrity_core::{Bar, Structure};
/// use tensegrity_io::sink::{SimulationOutputs, VtkSeriesSink};
/// use tensegrity_io::trajectory::TrajectoryWriter;
/// let s = Structure::builder().nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1).mass(1.0)).build().unwrap();
/// let mut settings = SimulationSettings { t_end: 0.1, output_interval: Some(0.05), ..Default::default() };
/// settings.quantities.nodes = true;
/// let dir = std::env::temp_dir().join(format!("sim-outputs-doc-{}", std::process::id()));
/// # let _ = std::fs::remove_dir_all(&dir);
/// std::fs::create_dir(&dir).unwrap();
/// let csv = TrajectoryWriter::create(&dir.join("traj.csv"), &s)?;   // opened before the run
/// let vtk = VtkSeriesSink::open(&dir.join("vtk"), &s)?;
/// let mut outputs = SimulationOutputs::new(Some(csv), Some(vtk));
/// let run = Simulation::new(&s, settings).unwrap().run_streaming(&mut outputs);
/// let written = outputs.finish(run.as_ref().err())?;
/// assert_eq!((written.rows, written.frames), (3, 3));
/// # std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
#[derive(Debug)]
pub struct SimulationOutputs<'a> {
    csv: Option<TrajectoryWriter>,
    vtk: Option<VtkSeriesSink<'a>>,
    frames: Option<&'a mut dyn NodeFrames>,
    progress: Progress,
    /// An output error that stopped the run.
    failed: Option<IoError>,
    last_t: f64,
}

impl std::fmt::Debug for dyn NodeFrames + '_ {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("NodeFrames")
    }
}

impl<'a> SimulationOutputs<'a> {
    /// The outputs, opened by the caller before the run (so each error names its own path).
    pub fn new(csv: Option<TrajectoryWriter>, vtk: Option<VtkSeriesSink<'a>>) -> Self {
        Self {
            csv,
            vtk,
            frames: None,
            progress: Progress::hidden(),
            failed: None,
            last_t: 0.0,
        }
    }

    /// Also hands every sample's nodes to `frames` (e.g. an animation).
    pub fn with_frames(mut self, frames: &'a mut dyn NodeFrames) -> Self {
        self.frames = Some(frames);
        self
    }

    /// Reports the simulated time to `progress` after every step.
    pub fn with_progress(mut self, progress: Progress) -> Self {
        self.progress = progress;
        self
    }

    fn write(&mut self, s: &Sample) -> Result<()> {
        if let Some(w) = self.csv.as_mut() {
            w.write(s)?;
        }
        if let (Some(w), Some(nodes)) = (self.vtk.as_mut(), s.nodes.as_deref()) {
            let data = FrameData {
                velocities: s.velocities.as_deref(),
                member_forces: s.member_forces.as_deref(),
                contact_forces: s.contact_forces.as_deref(),
            };
            w.frame_with(s.t, nodes, &data)?;
        }
        if let (Some(f), Some(nodes)) = (self.frames.as_mut(), s.nodes.as_deref()) {
            f.frame(s.t, nodes)?;
        }
        Ok(())
    }

    /// Closes the outputs after the run ended with `outcome`: renamed into place on success;
    /// after an error (an interrupt included) the rows and frames so far are kept, marked
    /// incomplete with the error's message (a run stopped before its first sample leaves no
    /// CSV). An output error that stopped the run is returned first.
    pub fn finish(mut self, outcome: Option<&CoreError>) -> Result<Written> {
        if outcome.is_none() {
            self.progress.finish();
        }
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        let reason = outcome.map(ToString::to_string);
        let rows = match (self.csv.take(), &reason) {
            (Some(w), None) => w.finish()?,
            (Some(w), Some(r)) => w.finish_incomplete(r)?,
            (None, _) => 0,
        };
        let frames = match (self.vtk.take(), &reason) {
            (Some(w), None) => w.finish()?,
            (Some(w), Some(r)) => w.finish_incomplete(r)?,
            (None, _) => 0,
        };
        Ok(Written { rows, frames })
    }
}

impl SampleSink for SimulationOutputs<'_> {
    fn accept(&mut self, sample: Sample) -> std::result::Result<(), CoreError> {
        if crate::interrupt::requested() {
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
        !crate::interrupt::requested()
    }

    fn stop_flag(&self) -> Option<&'static std::sync::atomic::AtomicBool> {
        Some(crate::interrupt::flag())
    }

    fn progress(&mut self, t: f64) {
        self.progress.set(t);
    }
}
