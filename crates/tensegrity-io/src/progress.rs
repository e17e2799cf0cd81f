//! Progress of long work on stderr, one reporter for every front end and command: a bar on a
//! terminal, and when stderr is not a terminal (a batch log, a Slurm job) a plain line every
//! few seconds and one at the end, each with the fraction done, the elapsed time and the
//! remaining time (ETA) — e.g.
//!
//! ```text
//! sweep: 42 % (42/100 cases), elapsed 12.0 s, ETA 16.6 s
//! simulate: 7 % (t = 0.07 of 1 s simulated), elapsed 3.0 s, ETA 39.9 s
//! ```
//!
//! What is counted ([`Measure`]): items of a known total (cases, figures, wheels), simulated
//! time of a run of known end time (an adaptive run's steps are not known in advance, its
//! simulated time is), or, for work with no counter, the elapsed time against the work
//! estimated before it started (the percent is then the estimate's, said so on the line).
//!
//! The ETA is the elapsed time scaled by what is left: elapsed·(total − done)/done. The
//! counter is a lock-free store, so a hot loop (every integration step) may update it; a
//! ticker thread draws the bar (every 100 ms) or prints a line (every
//! [`line_interval`]: 5 s, or `TENSEGRITY_PROGRESS_INTERVAL` seconds). Setting
//! `TENSEGRITY_PROGRESS=off` (or a command's quiet option, [`Target::Hidden`]) silences both.
//!
//! ```
//! use tensegrity_io::progress::{Measure, Progress, Target};
//! let p = Progress::new("cases", Measure::Count { total: 4, unit: "cases" }, Target::Lines);
//! p.inc(3.0);
//! assert_eq!(p.fraction(), 0.75);
//! p.finish();
//! // hidden: nothing is counted, nothing drawn
//! let q = Progress::new("cases", Measure::Count { total: 4, unit: "cases" }, Target::Hidden);
//! q.inc(3.0);
//! assert_eq!(q.fraction(), 0.0);
//! ```

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{channel, RecvTimeoutError, Sender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// The default time between two plain progress lines (s).
pub const LINE_INTERVAL_S: f64 = 5.0;

/// What a progress report counts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Measure {
    /// Items of a known total.
    Count {
        /// How many there are.
        total: usize,
        /// Their name, plural (`cases`).
        unit: &'static str,
    },
    /// Simulated seconds of a run from 0 to `t_end`.
    Simulated {
        /// The end time (s).
        t_end: f64,
    },
    /// Elapsed time against the work estimated before the start (s); the counter is unused.
    Estimated {
        /// The estimated work (s).
        work_s: f64,
    },
}

/// Where the report goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// A bar when stderr is a terminal, else plain lines; nothing with
    /// `TENSEGRITY_PROGRESS=off`.
    Auto,
    /// A bar on stderr.
    Bar,
    /// Plain lines on stderr.
    Lines,
    /// Nothing.
    Hidden,
}

impl Target {
    /// [`Target::Auto`] resolved for this process; `quiet` hides it.
    pub fn resolve(self, quiet: bool) -> Target {
        let off = std::env::var("TENSEGRITY_PROGRESS").is_ok_and(|v| v == "off" || v == "0");
        match self {
            _ if quiet || off => Target::Hidden,
            Target::Auto if std::io::stderr().is_terminal() => Target::Bar,
            Target::Auto => Target::Lines,
            t => t,
        }
    }
}

/// The time between two plain lines: `TENSEGRITY_PROGRESS_INTERVAL` (seconds, > 0) or
/// [`LINE_INTERVAL_S`].
pub fn line_interval() -> Duration {
    let s = std::env::var("TENSEGRITY_PROGRESS_INTERVAL")
        .ok()
        .and_then(|v| v.trim().parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0)
        .unwrap_or(LINE_INTERVAL_S);
    Duration::from_secs_f64(s.min(3600.0))
}

/// The shared state of one report.
#[derive(Debug)]
struct Shared {
    what: String,
    measure: Measure,
    start: Instant,
    /// The counter (f64 bits): items or simulated seconds.
    done: AtomicU64,
    /// The total of a count (may change: a sweep's shard).
    total: AtomicU64,
    finished: AtomicBool,
    message: Mutex<String>,
    bar: Option<ProgressBar>,
    lines: bool,
}

impl Shared {
    fn done(&self) -> f64 {
        f64::from_bits(self.done.load(Ordering::Relaxed))
    }

    fn total(&self) -> u64 {
        self.total.load(Ordering::Relaxed)
    }

    /// The fraction done in [0, 1] (by the estimate for [`Measure::Estimated`], at most 0.99
    /// until finished; a count or a time stays what it is when finished early).
    fn fraction(&self) -> f64 {
        let f = match self.measure {
            Measure::Count { .. } => self.done() / (self.total().max(1) as f64),
            Measure::Simulated { t_end } => self.done() / t_end,
            Measure::Estimated { work_s } => self.start.elapsed().as_secs_f64() / work_s,
        };
        let cap = match self.measure {
            // work without a counter: done when it says so
            Measure::Estimated { .. } if self.finished.load(Ordering::Relaxed) => return 1.0,
            Measure::Estimated { .. } => 0.99,
            _ => 1.0,
        };
        if f.is_finite() {
            f.clamp(0.0, cap)
        } else {
            0.0
        }
    }

    /// The plain line of the current state.
    fn line(&self) -> String {
        let elapsed = self.start.elapsed().as_secs_f64();
        let f = self.fraction();
        let eta = if f >= 1.0 {
            "0 s".to_string()
        } else if f > 0.0 {
            duration(elapsed * (1.0 - f) / f)
        } else {
            "unknown".to_string()
        };
        let what = match self.measure {
            Measure::Count { unit, .. } => {
                let total = self.total();
                format!("({}/{total} {unit})", self.done().round() as u64)
            }
            Measure::Simulated { t_end } => {
                format!("(t = {} of {t_end} s simulated)", short(self.done()))
            }
            Measure::Estimated { work_s } => {
                format!("(by the estimate of {})", duration(work_s))
            }
        };
        let message = self.message.lock().map(|m| m.clone()).unwrap_or_default();
        let message = if message.is_empty() {
            message
        } else {
            format!(" {message}")
        };
        let percent = (100.0 * f).floor();
        format!(
            "{}: {percent:.0} % {what}{message}, elapsed {}, ETA {eta}",
            self.what,
            duration(elapsed)
        )
    }

    /// Draws the bar from the counter.
    fn draw(&self) {
        if let Some(bar) = &self.bar {
            match self.measure {
                Measure::Count { .. } => {
                    bar.set_length(self.total());
                    bar.set_position(self.done().round() as u64);
                }
                Measure::Simulated { t_end } => {
                    bar.set_position((1000.0 * self.fraction()) as u64);
                    bar.set_message(format!("t = {} of {t_end} s", short(self.done())));
                }
                Measure::Estimated { .. } => bar.set_position((1000.0 * self.fraction()) as u64),
            }
        }
    }
}

/// A number in few digits (`0.0421`, `12.5`, `1.2e-5`).
fn short(v: f64) -> String {
    if v == 0.0 || (1e-3..1e5).contains(&v.abs()) {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        format!("{v:.3e}")
    }
}

/// A duration as `12.3 s`, `4 min 05 s` or `2 h 03 min`.
pub fn duration(s: f64) -> String {
    if !s.is_finite() {
        return "unknown".into();
    }
    let s = s.max(0.0);
    if s < 60.0 {
        format!("{s:.1} s")
    } else if s < 3600.0 {
        let m = (s / 60.0).floor();
        format!("{m:.0} min {:02.0} s", (s - 60.0 * m).floor())
    } else {
        let h = (s / 3600.0).floor();
        format!("{h:.0} h {:02.0} min", ((s - 3600.0 * h) / 60.0).floor())
    }
}

/// A progress report (cheap to clone: the clones share the counter; the report ends with
/// [`Progress::finish`], or when the last clone is dropped, which says where it stopped).
#[derive(Debug, Clone)]
pub struct Progress {
    shared: Option<Arc<Shared>>,
    ticker: Option<Arc<Ticker>>,
}

/// The thread that draws the bar or prints the lines.
#[derive(Debug)]
struct Ticker {
    stop: Mutex<Option<(Sender<()>, JoinHandle<()>)>>,
    shared: Arc<Shared>,
}

impl Ticker {
    /// Stops the thread and says the last word: the bar cleared, or the last line.
    fn end(&self) {
        let taken = self.stop.lock().ok().and_then(|mut s| s.take());
        let Some((tx, handle)) = taken else { return };
        drop(tx);
        let _ = handle.join();
        let s = &self.shared;
        s.draw();
        if let Some(bar) = &s.bar {
            bar.finish_and_clear();
        }
        if s.lines {
            match (s.finished.load(Ordering::Relaxed), s.measure) {
                (true, _) => eprintln!("{}", s.line()),
                // work without a counter ends with its command's own output (a refusal
                // stays one line)
                (false, Measure::Estimated { .. }) => {}
                // stopped before it began (an output refused): nothing to report
                (false, _) if s.done() <= 0.0 => {}
                (false, _) => eprintln!("{}", s.line().replacen(": ", ": stopped at ", 1)),
            }
        }
    }
}

impl Drop for Ticker {
    fn drop(&mut self) {
        self.end();
    }
}

impl Progress {
    /// No report.
    pub fn hidden() -> Self {
        Self {
            shared: None,
            ticker: None,
        }
    }

    /// A report on `what` (`sweep`, `figures`, `simulate`) to `target`
    /// ([`Target::resolve`]d, so [`Target::Auto`] picks a bar or lines).
    pub fn new(what: impl Into<String>, measure: Measure, target: Target) -> Self {
        let target = target.resolve(false);
        if target == Target::Hidden {
            return Self::hidden();
        }
        let bar = (target == Target::Bar).then(|| bar(measure));
        let shared = Arc::new(Shared {
            what: what.into(),
            measure,
            start: Instant::now(),
            done: AtomicU64::new(0f64.to_bits()),
            total: AtomicU64::new(match measure {
                Measure::Count { total, .. } => total as u64,
                _ => 0,
            }),
            finished: AtomicBool::new(false),
            message: Mutex::new(String::new()),
            bar,
            lines: target == Target::Lines,
        });
        let every = match target {
            Target::Bar => Duration::from_millis(100),
            _ => line_interval(),
        };
        let (tx, rx) = channel::<()>();
        let s = Arc::clone(&shared);
        let handle = std::thread::spawn(move || loop {
            match rx.recv_timeout(every) {
                Err(RecvTimeoutError::Timeout) if s.lines => eprintln!("{}", s.line()),
                Err(RecvTimeoutError::Timeout) => s.draw(),
                _ => break,
            }
        });
        let ticker = Ticker {
            stop: Mutex::new(Some((tx, handle))),
            shared: Arc::clone(&shared),
        };
        Self {
            shared: Some(shared),
            ticker: Some(Arc::new(ticker)),
        }
    }

    /// [`Progress::new`] to [`Target::Auto`], or hidden when `quiet`.
    pub fn auto(what: impl Into<String>, measure: Measure, quiet: bool) -> Self {
        match quiet {
            true => Self::hidden(),
            false => Self::new(what, measure, Target::Auto),
        }
    }

    /// Whether anything is shown.
    pub fn is_shown(&self) -> bool {
        self.shared.is_some()
    }

    /// Sets the counter (items, or simulated seconds).
    pub fn set(&self, done: f64) {
        if let Some(s) = &self.shared {
            s.done.store(done.to_bits(), Ordering::Relaxed);
        }
    }

    /// Sets the total of a count (e.g. a sweep's shard once known).
    pub fn set_total(&self, total: usize) {
        if let Some(s) = &self.shared {
            s.total.store(total as u64, Ordering::Relaxed);
        }
    }

    /// Adds `n` to the counter.
    pub fn inc(&self, n: f64) {
        if let Some(s) = &self.shared {
            let _ = s
                .done
                .fetch_update(Ordering::Relaxed, Ordering::Relaxed, |b| {
                    Some((f64::from_bits(b) + n).to_bits())
                });
        }
    }

    /// A note after the counts (e.g. `(with error rows)`).
    pub fn set_message(&self, message: &str) {
        if let Some(s) = &self.shared {
            if let Ok(mut m) = s.message.lock() {
                *m = message.to_string();
            }
            if let (Some(bar), Measure::Count { .. }) = (&s.bar, s.measure) {
                bar.set_message(message.to_string());
            }
        }
    }

    /// The fraction done (0 when hidden).
    pub fn fraction(&self) -> f64 {
        self.shared.as_ref().map_or(0.0, |s| s.fraction())
    }

    /// The current plain line (empty when hidden).
    pub fn line(&self) -> String {
        self.shared.as_ref().map_or(String::new(), |s| s.line())
    }

    /// The work is done: the bar is cleared, or the last line (100 %) printed.
    pub fn finish(&self) {
        if let Some(s) = &self.shared {
            s.finished.store(true, Ordering::Relaxed);
        }
        if let Some(t) = &self.ticker {
            t.end();
        }
    }
}

/// The terminal bar of `measure`.
fn bar(measure: Measure) -> ProgressBar {
    let (len, template) = match measure {
        Measure::Count { total, unit } => (
            total as u64,
            format!("{{elapsed_precise}} [{{wide_bar}}] {{pos}}/{{len}} {unit}, ETA {{eta_precise}} {{msg}}"),
        ),
        Measure::Simulated { .. } => (
            1000,
            "{elapsed_precise} [{wide_bar}] {percent} % {msg}, ETA {eta_precise}".to_string(),
        ),
        Measure::Estimated { .. } => (
            1000,
            "{elapsed_precise} [{wide_bar}] {percent} % of the estimate, ETA {eta_precise}"
                .to_string(),
        ),
    };
    let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(&template) {
        bar.set_style(style);
    }
    bar
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_say_percent_counts_and_eta() {
        let p = Progress::new(
            "sweep",
            Measure::Count {
                total: 8,
                unit: "cases",
            },
            Target::Lines,
        );
        p.inc(2.0);
        let line = p.line();
        assert!(
            line.starts_with("sweep: 25 % (2/8 cases), elapsed "),
            "{line}"
        );
        assert!(line.contains(", ETA "), "{line}");
        p.inc(6.0);
        p.finish();
        assert!(p.line().contains("100 % (8/8 cases)"));
        assert!(p.line().ends_with("ETA 0 s"));
    }

    #[test]
    fn simulated_time_is_the_measure_of_a_run() {
        let p = Progress::new("simulate", Measure::Simulated { t_end: 2.0 }, Target::Lines);
        p.set(0.5);
        assert_eq!(p.fraction(), 0.25);
        assert!(p.line().contains("25 % (t = 0.5 of 2 s simulated)"));
        p.finish();
    }

    #[test]
    fn durations_read_as_a_person_would_say_them() {
        assert_eq!(duration(12.34), "12.3 s");
        assert_eq!(duration(245.0), "4 min 05 s");
        assert_eq!(duration(7380.0), "2 h 03 min");
        assert_eq!(duration(f64::NAN), "unknown");
        assert_eq!(short(0.0421), "0.0421");
    }
}
