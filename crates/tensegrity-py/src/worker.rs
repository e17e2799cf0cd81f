//! Long work off the interpreter: the work runs on a Rust thread while the calling thread
//! waits with the GIL released, waking every [`POLL`] to run Python's signal handlers
//! (`Python::check_signals`). When a handler raises (Ctrl-C: `KeyboardInterrupt`), the io
//! crate's stop flag is set ([`interrupt::request`]) so that a command that polls it
//! (a simulation, a rolling run, a sweep) stops at its next step with its results so far;
//! the caller waits at most [`STOP_WAIT`] for them and raises. Control is back within POLL +
//! STOP_WAIT (0.35 s) whatever the command: one that is slower to stop, or does not poll the
//! flag at all, is left to end on its thread and its result is dropped.
//!
//! The flag is process-wide, so it is cleared only when no polling work is left running (the
//! last one to end clears it); a new call that finds it still set waits for the polling work
//! to stop (it was told to: a sweep finishes its case in progress, writes its trailer and
//! releases its file) before it clears the flag and starts.

use pyo3::prelude::*;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::sync::Arc;
use std::sync::Mutex;
use std::time::{Duration, Instant};
use tensegrity_io::interrupt;

/// How often the waiting thread runs the signal handlers.
pub const POLL: Duration = Duration::from_millis(50);
/// How long an interrupted command is given to stop and hand back its results so far.
pub const STOP_WAIT: Duration = Duration::from_millis(300);

/// Polling work still running (its thread alive).
static POLLING: AtomicUsize = AtomicUsize::new(0);

/// Ends the count of one polling work; the last one clears a stop that was requested.
struct Polling;

impl Polling {
    fn start() -> Self {
        POLLING.fetch_add(1, Ordering::SeqCst);
        Polling
    }
}

impl Drop for Polling {
    fn drop(&mut self) {
        if POLLING.fetch_sub(1, Ordering::SeqCst) == 1 {
            interrupt::clear();
        }
    }
}

/// Before new work: a stop still requested for polling work that has not ended yet is waited
/// out (signals still run: a second Ctrl-C raises here), then cleared.
fn settle(py: Python<'_>) -> PyResult<()> {
    while interrupt::requested() && POLLING.load(Ordering::SeqCst) > 0 {
        py.detach(|| std::thread::sleep(POLL));
        py.check_signals()?;
    }
    if POLLING.load(Ordering::SeqCst) == 0 {
        interrupt::clear();
    }
    Ok(())
}

/// How a run ended when it did not finish.
pub enum Stopped<T> {
    /// A signal handler raised (`KeyboardInterrupt`, or the handler's own exception); the
    /// work's result if it stopped within [`STOP_WAIT`] (its partial results).
    Signal(PyErr, Option<T>),
    /// The work panicked.
    Panic(String),
}

/// The progress of long work as Python sees it: the work stores how far it is (an f64's
/// bits: simulated time, cases) in `done`; the waiting thread calls `callback(done, total)`
/// at most every [`POLL`] when it moved forward, and once at the end (never with a `done`
/// below one already reported).
///
/// Work that cannot count as it goes (a library call that runs in one piece) is *paced*
/// ([`Watch::paced`]): while it runs, `done` is the elapsed time against the engine's work
/// estimate, scaled to `total` and held below [`PACED_CAP`] of it; at its end, what the work
/// stored (its end).
pub struct Watch {
    /// How far the work is (f64 bits), written by the work.
    pub done: Arc<AtomicU64>,
    /// Where it ends.
    pub total: f64,
    /// `callback(done, total)`; an exception it raises stops the work as Ctrl-C does.
    pub callback: Py<PyAny>,
    /// Paced work: when it started and its estimated work (s).
    paced: Option<(Instant, f64)>,
}

/// The largest fraction of its total a paced work reports before it ends.
pub const PACED_CAP: f64 = 0.99;

impl Watch {
    /// A watch of work that ends at `total`, reporting to `callback`.
    pub fn new(total: f64, callback: Py<PyAny>) -> Self {
        Self {
            done: Arc::new(AtomicU64::new(0f64.to_bits())),
            total,
            callback,
            paced: None,
        }
    }

    /// A watch of work that cannot count as it goes, estimated at `work_s` seconds
    /// (`None`: no report before its end).
    pub fn paced(total: f64, work_s: Option<f64>, callback: Py<PyAny>) -> Self {
        let start = Instant::now();
        Self {
            paced: work_s
                .filter(|w| w.is_finite() && *w > 0.0)
                .map(|w| (start, w)),
            ..Self::new(total, callback)
        }
    }

    /// The counter the work writes.
    pub fn counter(&self) -> Arc<AtomicU64> {
        self.done.clone()
    }

    /// Calls the callback if the work moved forward since `last` (its bits; `ended`: the
    /// work's own count, paced or not); returns the bits reported last.
    fn report(&self, py: Python<'_>, last: u64, ended: bool) -> PyResult<u64> {
        let bits = match self.paced {
            Some((start, work_s)) if !ended => {
                let fraction = (start.elapsed().as_secs_f64() / work_s).min(PACED_CAP);
                (fraction * self.total).to_bits()
            }
            _ => self.done.load(Ordering::Relaxed),
        };
        let (now, before) = (f64::from_bits(bits), f64::from_bits(last));
        if bits == last || now.is_nan() || now < before {
            return Ok(last);
        }
        self.callback.call1(py, (now, self.total))?;
        Ok(bits)
    }
}

/// Runs `work` on its own thread with the GIL released (module docs); `polls`: the work
/// stops on the interrupt flag.
pub fn run<T, F>(py: Python<'_>, polls: bool, work: F) -> Result<T, Stopped<T>>
where
    T: Send + 'static,
    F: FnOnce() -> T + Send + 'static,
{
    run_watched(py, polls, work, None)
}

/// [`run`] with its progress reported to a Python callback ([`Watch`]).
pub fn run_watched<T, F>(
    py: Python<'_>,
    polls: bool,
    work: F,
    watch: Option<&Watch>,
) -> Result<T, Stopped<T>>
where
    T: Send + 'static,
    F: FnOnce() -> T + Send + 'static,
{
    // a stop left by an earlier interrupted call must not stop this one
    if let Err(e) = settle(py) {
        return Err(Stopped::Signal(e, None));
    }
    let (tx, rx) = channel();
    let polling = polls.then(Polling::start);
    let spawned = std::thread::Builder::new()
        .name("tensegrity".into())
        .spawn(move || {
            let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work));
            let _ = tx.send(result);
            drop(polling);
        });
    // the receiver crosses into the GIL-free closures by reference: a Mutex makes it Sync
    let rx = Mutex::new(rx);
    let recv = |wait: Duration| {
        rx.lock()
            .map_err(|_| RecvTimeoutError::Disconnected)
            .and_then(|r| r.recv_timeout(wait))
    };
    if let Err(e) = spawned {
        return Err(Stopped::Panic(format!("no thread for the work: {e}")));
    }
    let panicked = |p: Box<dyn std::any::Any + Send>| {
        let msg = p
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        Stopped::Panic(msg)
    };
    let mut last = 0f64.to_bits();
    loop {
        match py.detach(|| recv(POLL)) {
            Ok(result) => {
                if let Some(w) = watch {
                    // the last report: where the work ended (an error here is the caller's)
                    let _ = w.report(py, last, true);
                }
                return result.map_err(panicked);
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(Stopped::Panic("the work ended without a result".into()))
            }
            Err(RecvTimeoutError::Timeout) => {}
        }
        let reported = match watch {
            Some(w) => w.report(py, last, false).map(|bits| last = bits),
            None => Ok(()),
        };
        if let Err(signal) = reported.and_then(|()| py.check_signals()) {
            interrupt::request();
            let partial = py.detach(|| recv(STOP_WAIT)).ok();
            if POLLING.load(Ordering::SeqCst) == 0 {
                interrupt::clear();
            }
            let partial = partial.and_then(Result::ok);
            return Err(Stopped::Signal(signal, partial));
        }
    }
}
