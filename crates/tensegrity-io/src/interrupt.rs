//! SIGINT / SIGTERM: one process-wide stop flag, and the open outputs finished as incomplete.
//!
//! A front end calls [`install`] once (the command line does; a Python module would rather
//! call [`request`] from its own handler). From then on a signal
//!
//! 1. sets the stop flag: [`requested`] turns true, and libraries that cannot depend on this
//!    crate poll the same flag through [`flag`] (a `&'static AtomicBool`);
//! 2. if the running command declared that it polls the flag ([`polled`]), that is all: the
//!    command stops at its next check, finishes its sinks as incomplete and exits with the
//!    interrupted category (exit code 130 on the command line);
//! 3. otherwise — or on a second signal (more than [`REPEAT_DEBOUNCE`] after the first), when
//!    the polling command is slow to stop — every sink
//!    still open is finished at once from the handler's thread ([`finish_open_sinks`]): a CSV
//!    keeps its rows so far with a `# incomplete: interrupted` trailer, a VTK series its
//!    complete frames and a `series.pvd` that lists them, whole-file outputs (figures, JSON,
//!    scenes) are removed with their temporary files; then the front end's `report` is called
//!    with the paths kept and the process exits with code 130.
//!
//! Each sink registers itself here when it is opened (a weak reference: a finished or dropped
//! sink simply disappears), and guards its state with a mutex, so a row is either whole in the
//! file or not in it at all, whichever thread finishes the file.
//!
//! ```
//! use tensegrity_io::interrupt;
//! assert!(!interrupt::requested());
//! let polled = interrupt::polled(); // this command checks `requested()` and stops itself
//! assert!(interrupt::is_polled());
//! drop(polled);
//! assert!(!interrupt::is_polled());
//! ```

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, Weak};
use std::time::{Duration, Instant};

/// The stop flag.
static STOP: AtomicBool = AtomicBool::new(false);
/// Live [`Polled`] guards.
static POLLED: AtomicUsize = AtomicUsize::new(0);
/// The sinks opened so far (weak: a finished sink is gone).
static OPEN: Mutex<Vec<Weak<dyn Interruptible>>> = Mutex::new(Vec::new());
/// The lock files held now (removed when the handler ends the process).
static LOCKS: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
/// When the first signal arrived.
static FIRST: Mutex<Option<Instant>> = Mutex::new(None);

/// A second signal within this time of the first is the same request (e.g. `timeout` signals
/// the command and its process group), not a demand to stop at once.
pub const REPEAT_DEBOUNCE: Duration = Duration::from_millis(500);

/// The exit code of an interrupted run (128 + 2, the shell's convention for Ctrl-C).
pub const EXIT_CODE: i32 = 130;

/// An open output that can be ended from another thread when the process is interrupted.
pub(crate) trait Interruptible: Send + Sync {
    /// Ends the output as incomplete (`reason` in its trailer) or removes it; returns the path
    /// kept, if any. Further writes to the sink fail with [`crate::IoError::Closed`].
    fn interrupt(&self, reason: &str) -> Option<PathBuf>;
}

/// Registers an open sink (see the module documentation).
pub(crate) fn register<T: Interruptible + 'static>(sink: &Arc<T>) {
    let weak: Weak<dyn Interruptible> = Arc::downgrade(sink) as Weak<dyn Interruptible>;
    let mut open = OPEN.lock().unwrap_or_else(|e| e.into_inner());
    open.retain(|w| w.strong_count() > 0);
    open.push(weak);
}

/// Records a lock file held by this process.
pub(crate) fn hold_lock(path: &std::path::Path) {
    LOCKS
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .push(path.to_path_buf());
}

/// Forgets a lock file released.
pub(crate) fn release_lock(path: &std::path::Path) {
    let mut locks = LOCKS.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(k) = locks.iter().position(|p| p == path) {
        locks.swap_remove(k);
    }
}

/// Whether a stop was requested (a signal arrived, or [`request`] was called).
pub fn requested() -> bool {
    STOP.load(Ordering::SeqCst)
}

/// The stop flag itself, for libraries that poll an `&AtomicBool` without depending on this
/// crate (e.g. a rolling run's step loop).
pub fn flag() -> &'static AtomicBool {
    &STOP
}

/// Requests a stop, as a signal does (for front ends with their own signal handling, and for
/// tests).
pub fn request() {
    STOP.store(true, Ordering::SeqCst);
}

/// Clears the stop flag (a front end that runs several commands in one process, e.g. a
/// Python session, clears it before the next one).
pub fn clear() {
    STOP.store(false, Ordering::SeqCst);
    *FIRST.lock().unwrap_or_else(|e| e.into_inner()) = None;
}

/// While alive, the first signal only sets the flag: the current command polls
/// [`requested`] and finishes its own outputs (see the module documentation).
#[derive(Debug)]
#[must_use = "the command polls the flag only while the guard lives"]
pub struct Polled(());

/// Declares that the running command polls [`requested`] (until the guard is dropped).
pub fn polled() -> Polled {
    POLLED.fetch_add(1, Ordering::SeqCst);
    Polled(())
}

impl Drop for Polled {
    fn drop(&mut self) {
        POLLED.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Whether a [`Polled`] guard is alive.
pub fn is_polled() -> bool {
    POLLED.load(Ordering::SeqCst) > 0
}

/// Finishes every open sink as incomplete (newest first; see the module documentation) and
/// returns the paths kept. Sinks finished this way refuse further writes.
pub fn finish_open_sinks(reason: &str) -> Vec<PathBuf> {
    let open = std::mem::take(&mut *OPEN.lock().unwrap_or_else(|e| e.into_inner()));
    open.iter()
        .rev()
        .filter_map(Weak::upgrade)
        .filter_map(|sink| sink.interrupt(reason))
        .collect()
}

/// What the handler does when it ends the process: the open sinks finished as incomplete,
/// the lock files still held (e.g. a sweep's, whose file stays for resume) removed.
fn end_process(report: fn(&[PathBuf])) -> ! {
    let kept = finish_open_sinks("interrupted");
    for path in std::mem::take(&mut *LOCKS.lock().unwrap_or_else(|e| e.into_inner())) {
        // still locked by this process until it exits: removing it is safe (see `PathLock`)
        let _ = std::fs::remove_file(path);
    }
    report(&kept);
    std::process::exit(EXIT_CODE);
}

/// Installs the SIGINT / SIGTERM (and SIGHUP) handler once per process; later calls, or a
/// handler set elsewhere, keep the first. `report` is called with the paths kept just before
/// the process exits with [`EXIT_CODE`] (when no command polls the flag, or on a second
/// signal).
pub fn install(report: fn(&[PathBuf])) {
    // ctrlc runs the handler on a thread of its own, not in the signal context: it may lock,
    // write files and exit
    let _ = ctrlc::set_handler(move || {
        STOP.store(true, Ordering::SeqCst);
        let first = *FIRST
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .get_or_insert_with(Instant::now);
        if is_polled() && first.elapsed() < REPEAT_DEBOUNCE {
            return; // the first request (or its echo): the command stops by itself
        }
        end_process(report);
    });
}

/// A run stopped by a signal; its outputs so far were kept, marked incomplete.
///
/// ```
/// use tensegrity_io::interrupt::Interrupted;
/// let e = Interrupted { t: Some(1.5), note: Some("300 trajectory rows kept, marked incomplete".into()) };
/// assert_eq!(e.to_string(), "interrupted at t = 1.5 s; 300 trajectory rows kept, marked incomplete");
/// assert_eq!(Interrupted::default().to_string(), "interrupted");
/// ```
#[derive(Debug, Clone, Default, PartialEq, thiserror::Error)]
#[error("interrupted{}{}", t.map_or(String::new(), |t| format!(" at t = {t} s")), note.as_ref().map_or(String::new(), |n| format!("; {n}")))]
pub struct Interrupted {
    /// Simulated time reached (s), for a run in time.
    pub t: Option<f64>,
    /// What was kept.
    pub note: Option<String>,
}

impl tensegrity_core::request::Categorized for Interrupted {
    fn category(&self) -> tensegrity_core::request::Category {
        tensegrity_core::request::Category::Interrupted
    }
}
