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
use std::sync::atomic::AtomicBool;
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

    /// A flag whose setting stops the convergence check's companion runs as well, those
    /// beside the run and those after it, which do not report to this observer (e.g. the
    /// process's interrupt flag, which [`Observer::keep_going`] reads for the run itself).
    /// `None` (the default): they stop only when the run itself stopped early.
    fn stop_flag(&self) -> Option<&'static AtomicBool> {
        None
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

/// The observer that watches nothing and stops the run once its flag is set (a run beside
/// another whose observer's [`Observer::stop_flag`] it is).
///
/// ```
/// use std::sync::atomic::{AtomicBool, Ordering};
/// use wheel_rolling::{observer::StopOn, Observer};
/// let flag = AtomicBool::new(false);
/// let mut watch = StopOn(&flag);
/// assert!(watch.keep_going());
/// flag.store(true, Ordering::Relaxed);
/// assert!(!watch.keep_going());
/// ```
#[derive(Debug, Clone, Copy)]
pub struct StopOn<'a>(pub &'a AtomicBool);

impl Observer for StopOn<'_> {
    fn keep_going(&mut self) -> bool {
        !self.0.load(std::sync::atomic::Ordering::Relaxed)
    }
}

/// The sentence of the warning of a run its observer stopped.
pub(crate) fn interrupted_warning(t: f64, t_end: f64) -> Warning {
    Warning::Interrupted { t, t_end }
}
