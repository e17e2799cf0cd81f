//! The observer of a run: it receives every sample and every node frame as the run produces
//! them (a front end streams them to CSV or VTK), and may ask the run to stop (e.g. on
//! SIGINT).
//!
//! A run stopped by its observer is not an error: it returns what it computed up to the stop,
//! with [`crate::RollValidity::stopped_at`] set to the time of the last sample and a warning
//! that says it was interrupted (so the run is not valid). Nothing already handed to the
//! observer is lost, and the returned samples are exactly those the observer received.
//!
//! The samples are always kept (the run's summary is computed from them: a few dozen bytes a
//! millisecond); the node frames, a whole wheel each, are kept only while the observer wants
//! them ([`Observer::keeps_frames`]).

use crate::frame::WheelFrame;
use crate::sample::RollingSample;
use tensegrity_core::Warning;

/// What an observer asks of the run after each item.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Flow {
    /// Go on.
    #[default]
    Continue,
    /// Stop after this item; the run returns what it has.
    Stop,
}

/// Receives a run's samples and node frames as they are produced.
pub trait Observer {
    /// A new sample (every output interval). Return [`Flow::Stop`] to end the run with this
    /// sample as its last.
    fn sample(&mut self, sample: &RollingSample) -> Flow {
        let _ = sample;
        Flow::Continue
    }

    /// A new node frame (at the requested frame times).
    fn frame(&mut self, frame: &WheelFrame) -> Flow {
        let _ = frame;
        Flow::Continue
    }

    /// Asked between samples (after every integration step of the full model): `false` stops
    /// the run at once (e.g. an interrupt flag).
    fn keep_going(&mut self) -> bool {
        true
    }

    /// Whether the run also keeps the frames it hands to this observer in its result (the
    /// default). An observer that streams them elsewhere (a VTK series) answers `false`: the
    /// run then holds no frame, and its memory does not grow with the number of frames.
    fn keeps_frames(&self) -> bool {
        true
    }
}

/// The observer that watches nothing.
impl Observer for () {}

/// The sentence of the warning of a run its observer stopped.
pub(crate) fn interrupted_warning(t: f64, t_end: f64) -> Warning {
    Warning::Interrupted { t, t_end }
}
