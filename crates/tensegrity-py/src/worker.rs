//! Long work off the interpreter: the work runs on a Rust thread while the calling thread
//! waits with the GIL released, waking every [`POLL`] to run Python's signal handlers
//! (`Python::check_signals`). When a handler raises (Ctrl-C: `KeyboardInterrupt`), the io
//! crate's stop flag is set ([`interrupt::request`]) so that a command that polls it
//! (a simulation, a full rolling run, a sweep) stops at its next step with its results so far;
//! the caller waits at most [`STOP_WAIT`] for them, clears the flag and raises. Control is back
//! within POLL + STOP_WAIT (0.35 s) whatever the command: one that does not poll the flag is
//! left to finish on its thread and its result is dropped.

use pyo3::prelude::*;
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::sync::Mutex;
use std::time::Duration;
use tensegrity_io::interrupt;

/// How often the waiting thread runs the signal handlers.
pub const POLL: Duration = Duration::from_millis(50);
/// How long an interrupted command is given to stop and hand back its results so far.
pub const STOP_WAIT: Duration = Duration::from_millis(300);

/// How a run ended when it did not finish.
pub enum Stopped<T> {
    /// A signal handler raised (`KeyboardInterrupt`, or the handler's own exception); the
    /// work's result if it stopped within [`STOP_WAIT`] (its partial results).
    Signal(PyErr, Option<T>),
    /// The work panicked.
    Panic(String),
}

/// Runs `work` on its own thread with the GIL released (module docs).
pub fn run<T, F>(py: Python<'_>, work: F) -> Result<T, Stopped<T>>
where
    T: Send + 'static,
    F: FnOnce() -> T + Send + 'static,
{
    // a stop left by an earlier interrupted call must not stop this one
    interrupt::clear();
    let (tx, rx) = channel();
    let spawned = std::thread::Builder::new()
        .name("tensegrity".into())
        .spawn(move || {
            let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work));
            let _ = tx.send(result);
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
    loop {
        match py.detach(|| recv(POLL)) {
            Ok(result) => return result.map_err(panicked),
            Err(RecvTimeoutError::Disconnected) => {
                return Err(Stopped::Panic("the work ended without a result".into()))
            }
            Err(RecvTimeoutError::Timeout) => {}
        }
        if let Err(signal) = py.check_signals() {
            interrupt::request();
            let partial = py.detach(|| recv(STOP_WAIT)).ok();
            interrupt::clear();
            let partial = partial.and_then(Result::ok);
            return Err(Stopped::Signal(signal, partial));
        }
    }
}
