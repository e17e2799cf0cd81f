//! Running a sweep: the cases of one shard fanned out over a local rayon pool, their rows
//! streamed to the CSV in case order.
//!
//! Workers take case numbers from a shared counter, in order, and never run more than a
//! window of `8 × threads + 8` cases ahead of the last row written; the writer keeps the
//! finished rows that arrive early in a reorder buffer (at most a window of rows) and appends
//! each run of consecutive rows to the file with one write, so the file always holds whole
//! rows in case order, whatever the thread count: the bytes do not depend on it.
//!
//! With [`RunOptions::resume`] the run reads the file back: the preamble must be the one this spec writes, every
//! complete row must be the next case of the shard (its id and axis values), and a partial
//! last line (a write cut by a kill) is cut off; the sweep then continues after the last
//! complete row. A case whose study fails, or panics, is an `error` row; it never stops the
//! sweep.
//!
//! The file is the sweep's journal, written in place (not renamed at the end) so that a killed
//! sweep can be resumed; it is locked while a sweep writes it ([`PathLock`]: a second sweep of
//! the same file is refused at once). On an interrupt ([`tensegrity_io::interrupt`]) the workers
//! take no new case, the rows finished in order are written, and the file ends with an
//! `# incomplete: interrupted after N of M cases …` line, which `resume` cuts off.

use crate::case_error::CaseError;
use crate::error::{Result, SweepError};
pub use crate::shard::Shard;
use crate::spec::Spec;
use crate::table;
pub use crate::table::INCOMPLETE;
use crate::Context;
use std::collections::BTreeMap;
use std::fs::File;
use std::io::Write;
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{mpsc, Condvar, Mutex};
use tensegrity_core::budget::Limits;
use tensegrity_io::interrupt;
use tensegrity_io::sink::PathLock;

/// How to run a sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    /// Worker threads (`None`: one per core); run as given (a front end caps a request
    /// above the cores with [`Threads::choose`]).
    pub threads: Option<usize>,
    /// The shard to run.
    pub shard: Shard,
    /// Continue an existing output file instead of starting it anew.
    pub resume: bool,
    /// Write the `# units: …` line before the header.
    pub units: bool,
    /// Refuse every case whose estimate is over these limits (an `error` row naming the
    /// limit, [`crate::limits`]); `None`: no check.
    pub limits: Option<Limits>,
}

impl Default for RunOptions {
    fn default() -> Self {
        Self {
            threads: None,
            shard: Shard::ALL,
            resume: false,
            units: false,
            limits: None,
        }
    }
}

/// The worker threads of a sweep: those asked for, those that run, the machine's cores
/// ([`std::thread::available_parallelism`]). A sweep's cases are CPU-bound: more workers
/// than cores only share the cores (and each holds a case's memory), so a request above the
/// cores is capped at them unless oversubscribing is asked for explicitly.
///
/// ```
/// use sweeps::run::Threads;
/// let cores = Threads::cores();
/// let t = Threads::choose(Some(65535), false);
/// assert_eq!((t.used, t.capped()), (cores, cores < 65535));
/// assert_eq!(Threads::choose(Some(65535), true).used, 65535);
/// assert_eq!(Threads::choose(None, false).used, cores);
/// assert!(!Threads::choose(Some(1), false).capped());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Threads {
    /// The threads asked for (`None`: one per core).
    pub requested: Option<usize>,
    /// The threads that run.
    pub used: usize,
    /// The machine's cores.
    pub cores: usize,
}

impl Threads {
    /// The cores of this machine (1 when unknown).
    pub fn cores() -> usize {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    }

    /// `requested` threads (at least 1; `None`: one per core), capped at the cores unless
    /// `oversubscribe`.
    pub fn choose(requested: Option<usize>, oversubscribe: bool) -> Threads {
        let cores = Self::cores();
        let asked = requested.unwrap_or(cores).max(1);
        let used = if oversubscribe {
            asked
        } else {
            asked.min(cores)
        };
        Threads {
            requested,
            used,
            cores,
        }
    }

    /// Whether fewer threads run than were asked for.
    pub fn capped(&self) -> bool {
        self.requested.is_some_and(|r| r > self.used)
    }
}

/// Progress of a sweep (the CLI draws a bar; the default does nothing).
pub trait Progress {
    /// `total` cases in this shard, `done` of them already in the file (resume).
    fn start(&mut self, total: usize, done: usize) {
        let _ = (total, done);
    }
    /// One more row written (`error`: it is an error row).
    fn row(&mut self, error: bool) {
        let _ = error;
    }
    /// The sweep is over.
    fn finish(&mut self) {}
}

/// No progress report.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Progress for Silent {}

/// The io crate's report counts the cases: a bar on a terminal, lines with percent and ETA
/// in a log.
impl Progress for tensegrity_io::progress::Progress {
    fn start(&mut self, total: usize, done: usize) {
        self.set_total(total);
        self.set(done as f64);
    }

    fn row(&mut self, error: bool) {
        if error {
            self.set_message("(with error rows)");
        }
        self.inc(1.0);
    }

    fn finish(&mut self) {
        tensegrity_io::progress::Progress::finish(self);
    }
}

/// What a sweep did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Summary {
    /// Cases in the full product.
    pub total_cases: usize,
    /// Cases of this shard.
    pub shard_cases: usize,
    /// Rows found complete in the file (resume).
    pub resumed: usize,
    /// Rows written by this run.
    pub written: usize,
    /// Error rows among them.
    pub errors: usize,
}

/// Runs the sweep, writing its rows to `out` (see the module docs).
pub fn run(
    spec: &Spec,
    out: &Path,
    opts: &RunOptions,
    progress: &mut dyn Progress,
) -> Result<Summary> {
    let total = spec.case_count()?;
    let shard_cases = opts.shard.len(total);
    // a shard's file starts with the spec's hash, which `merge` compares
    let legacy = table::preamble(spec, opts.units);
    let preamble = if opts.shard.count > 1 {
        [table::spec_line(spec), legacy.clone()].concat()
    } else {
        legacy.clone()
    };
    // one sweep per file: another run writing `out`, or an unwritable directory, is refused
    // here, before any case
    let _lock = PathLock::acquire(out)?;
    let (mut file, resumed) = if opts.resume && out.exists() {
        crate::resume::resume(spec, out, [&preamble, &legacy], opts.shard)?
    } else {
        let mut f = File::create(out).map_err(SweepError::io("creating", out))?;
        f.write_all(&preamble)
            .map_err(SweepError::io("writing", out))?;
        (f, 0)
    };
    progress.start(shard_cases, resumed);
    let threads = opts.threads.unwrap_or_else(Threads::cores).max(1);
    let (written, errors) = if resumed < shard_cases {
        execute(
            spec,
            opts,
            resumed..shard_cases,
            threads,
            &mut file,
            out,
            progress,
        )?
    } else {
        (0, 0)
    };
    progress.finish();
    if resumed + written < shard_cases && interrupt::requested() {
        return Err(interrupted(&mut file, out, resumed + written, shard_cases));
    }
    Ok(Summary {
        total_cases: total,
        shard_cases,
        resumed,
        written,
        errors,
    })
}

/// Ends the file of an interrupted sweep with its `# incomplete` line (cut off by `resume`).
fn interrupted(file: &mut File, out: &Path, done: usize, total: usize) -> SweepError {
    let trailer = format!(
        "{INCOMPLETE} interrupted after {done} of {total} cases; run the sweep again with resume to continue\n"
    );
    if let Err(e) = file.write_all(trailer.as_bytes()) {
        return SweepError::io("writing", out)(e);
    }
    SweepError::Interrupted {
        path: out.to_path_buf(),
        done,
        total,
    }
}

/// The state shared by the workers and the writer.
struct Shared<'a> {
    spec: &'a Spec,
    ctx: Context,
    shard: Shard,
    limits: Option<Limits>,
    next: AtomicUsize,
    end: usize,
    window: usize,
    written: Mutex<usize>,
    moved: Condvar,
    stop: AtomicBool,
}

impl Shared<'_> {
    /// Runs cases until none are left (or the writer stopped, or an interrupt came), sending
    /// their rows.
    fn work(&self, tx: mpsc::Sender<(usize, Vec<u8>, bool)>) {
        while !self.halted() {
            let j = self.next.fetch_add(1, Ordering::Relaxed);
            if j >= self.end || !self.wait_for_window(j) {
                break;
            }
            let (row, failed) = self.row(self.shard.id(j));
            if tx.send((j, row, failed)).is_err() {
                break;
            }
        }
    }

    /// Whether the workers stop: the writer failed, or an interrupt was requested.
    fn halted(&self) -> bool {
        self.stop.load(Ordering::Relaxed) || interrupt::requested()
    }

    /// Waits until case `j` lies within the window after the last row written; false when
    /// the workers stop meanwhile (polled, so that an interrupt is seen while waiting).
    fn wait_for_window(&self, j: usize) -> bool {
        let mut w = self.written.lock().unwrap_or_else(|e| e.into_inner());
        while j >= *w + self.window {
            if self.halted() {
                return false;
            }
            w = self
                .moved
                .wait_timeout(w, std::time::Duration::from_millis(50))
                .unwrap_or_else(|e| e.into_inner())
                .0;
        }
        true
    }

    /// The row of case `id` (an `error` row when the study fails or panics).
    fn row(&self, id: usize) -> (Vec<u8>, bool) {
        let case = self.spec.case(id);
        let result = case.params.and_then(|p| {
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                if let Some(limits) = &self.limits {
                    crate::limits::admit(self.spec.study, &p, limits)?;
                }
                self.spec.study.run(p, &self.ctx).map_err(|e| {
                    let message = match e {
                        tensegrity_engine::RunError::InvalidParameter(p) => {
                            SweepError::from(p).to_string()
                        }
                        other => other.to_string(),
                    };
                    CaseError::Analysis { message }
                })
            }))
            .unwrap_or_else(|panic| {
                let msg = panic
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                Err(CaseError::Panicked { message: msg })
            })
        });
        (
            table::row(self.spec, id, &case.axis_texts, &result),
            result.is_err(),
        )
    }

    fn advance(&self, to: usize) {
        *self.written.lock().unwrap_or_else(|e| e.into_inner()) = to;
        self.moved.notify_all();
    }
}

/// Runs the shard's cases `range` on `threads` workers and appends their rows in order.
fn execute(
    spec: &Spec,
    opts: &RunOptions,
    range: std::ops::Range<usize>,
    threads: usize,
    file: &mut File,
    out: &Path,
    progress: &mut dyn Progress,
) -> Result<(usize, usize)> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("sweep-{i}"))
        .build()
        .map_err(|e| SweepError::Io {
            what: "starting the worker threads for",
            path: out.to_path_buf(),
            source: std::io::Error::other(e.to_string()),
        })?;
    let shared = Shared {
        spec,
        ctx: opts.limits.map(Context::within).unwrap_or_default(),
        shard: opts.shard,
        limits: opts.limits,
        next: AtomicUsize::new(range.start),
        end: range.end,
        window: 8 * threads + 8,
        written: Mutex::new(range.start),
        moved: Condvar::new(),
        stop: AtomicBool::new(false),
    };
    let (tx, rx) = mpsc::channel();
    let mut outcome = Ok((0, 0));
    pool.in_place_scope(|s| {
        for _ in 0..threads {
            let tx = tx.clone();
            let shared = &shared;
            s.spawn(move |_| shared.work(tx));
        }
        drop(tx);
        outcome = write_in_order(&shared, rx, range.start, file, out, progress);
        if outcome.is_err() {
            shared.stop.store(true, Ordering::Relaxed);
            shared.moved.notify_all();
        }
    });
    outcome
}

/// The writer: rows in case order through the reorder buffer.
fn write_in_order(
    shared: &Shared<'_>,
    rx: mpsc::Receiver<(usize, Vec<u8>, bool)>,
    start: usize,
    file: &mut File,
    out: &Path,
    progress: &mut dyn Progress,
) -> Result<(usize, usize)> {
    let mut pending: BTreeMap<usize, (Vec<u8>, bool)> = BTreeMap::new();
    let (mut next, mut errors) = (start, 0);
    for (j, row, failed) in rx {
        pending.insert(j, (row, failed));
        let mut batch = Vec::new();
        let mut flags = Vec::new();
        while let Some((row, failed)) = pending.remove(&next) {
            batch.extend_from_slice(&row);
            flags.push(failed);
            next += 1;
        }
        if batch.is_empty() {
            continue;
        }
        file.write_all(&batch)
            .map_err(SweepError::io("writing", out))?;
        shared.advance(next);
        for failed in flags {
            errors += usize::from(failed);
            progress.row(failed);
        }
    }
    file.flush().map_err(SweepError::io("writing", out))?;
    Ok((next - start, errors))
}
