//! `sweep`: a spec (TOML text, a dict turned into it, or a file) run by [`sweeps::run`] into a
//! CSV file, as `tensegrity sweep SPEC --out FILE` does (the output estimate checked first,
//! every case against the limits, workers stopping on the interrupt flag, the cases written
//! counted for a progress report through the sweeps crate's own [`sweeps::Progress`] hook,
//! the one the CLI's bar is fed by); the caller reads the rows back from the file.

use crate::errors::Failure;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use sweeps::{RunOptions, Shard, Silent, Spec};
use tensegrity_core::budget::Limits;
use tensegrity_core::request::{Categorized, Category};

/// Where the spec comes from.
pub enum Source {
    /// A spec file.
    Path(PathBuf),
    /// TOML text.
    Text(String),
}

/// How to run it (the CLI's flags).
pub struct Options {
    /// Worker threads (`None`: one per core; capped at the cores).
    pub threads: Option<usize>,
    /// Run shard `k` of `n` (1-based `k`).
    pub shard: Option<(usize, usize)>,
    /// Continue the rows already in the output file.
    pub resume: bool,
    /// Write the `# units:` line.
    pub units: bool,
    /// The limits of every case.
    pub limits: Limits,
}

fn failure(e: sweeps::SweepError, what: &str) -> Failure {
    Failure::raw(e.category(), format!("sweep {what}: {e}"))
}

/// Reads the spec (a bad spec is bad input, its message naming the item).
pub fn spec(source: &Source) -> Result<(Spec, String), Failure> {
    match source {
        Source::Path(p) => {
            let what = p.display().to_string();
            Spec::read(p)
                .map(|s| (s, what.clone()))
                .map_err(|e| Failure::raw(e.category(), e.to_string()))
        }
        Source::Text(t) => Spec::parse(t)
            .map(|s| (s, "spec".to_string()))
            .map_err(|e| Failure::raw(e.category(), e.to_string())),
    }
}

/// Checks the sweep's output against the limits (before any case runs) and the shard: the
/// shard and the number of its cases (the total of a progress report).
pub fn admit(spec: &Spec, opts: &Options) -> Result<(Shard, usize), Failure> {
    let cases = spec
        .case_count()
        .map_err(|e| Failure::raw(e.category(), e.to_string()))?;
    opts.limits
        .check(&sweeps::limits::output(cases))
        .map_err(|over| Failure::over_budget(&over))?;
    let shard = match opts.shard {
        None => Shard::ALL,
        Some((k, n)) => format!("{k}/{n}")
            .parse::<Shard>()
            .map_err(|e| Failure::raw(Category::Input, format!("shard: {e}")))?,
    };
    Ok((shard, shard.len(cases)))
}

/// The columns of the sweep's CSV and their units, as its header and its `# units:` line
/// name them (an empty unit where the line has `-`).
pub fn columns(spec: &Spec) -> Vec<(String, String)> {
    let units = sweeps::table::units(spec);
    sweeps::table::header(spec)
        .into_iter()
        .zip(units)
        .map(|(name, unit)| (name, if unit == "-" { String::new() } else { unit }))
        .collect()
}

/// The sweeps crate's progress hook counting the cases in the file (resumed ones included)
/// into a counter (f64 bits) that a [`crate::worker::Watch`] reads.
struct Counted(Arc<AtomicU64>);

impl sweeps::Progress for Counted {
    fn start(&mut self, _total: usize, done: usize) {
        self.0.store((done as f64).to_bits(), Ordering::Relaxed);
    }

    fn row(&mut self, _error: bool) {
        let done = f64::from_bits(self.0.load(Ordering::Relaxed)) + 1.0;
        self.0.store(done.to_bits(), Ordering::Relaxed);
    }
}

/// Runs the sweep into `out` (on the worker thread): the number of rows written, or the
/// failure (an interrupted sweep keeps its rows, marked incomplete, as on the command line);
/// `progress`: where the number of cases in the file goes.
pub fn run(
    spec: &Spec,
    what: &str,
    out: &Path,
    shard: Shard,
    opts: &Options,
    progress: Option<Arc<AtomicU64>>,
) -> Result<usize, Failure> {
    // at most one thread per core, as on the command line without --oversubscribe
    let threads = sweeps::run::Threads::choose(opts.threads, false).used;
    let run_opts = RunOptions {
        threads: Some(threads),
        shard,
        resume: opts.resume,
        units: opts.units,
        limits: Some(opts.limits),
    };
    let (mut counted, mut silent) = (progress.map(Counted), Silent);
    let report: &mut dyn sweeps::Progress = match counted.as_mut() {
        Some(c) => c,
        None => &mut silent,
    };
    sweeps::run(spec, out, &run_opts, report)
        .map(|s| s.resumed + s.written)
        .map_err(|e| failure(e, what))
}
