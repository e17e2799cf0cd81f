//! `sweep`: a spec (TOML text, a dict turned into it, or a file) run by [`sweeps::run`] into a
//! CSV file, as `tensegrity sweep SPEC --out FILE` does (the output estimate checked first,
//! every case against the limits, workers stopping on the interrupt flag); the caller reads
//! the rows back from the file.

use crate::errors::Failure;
use std::path::{Path, PathBuf};
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

/// Checks the sweep's output against the limits (before any case runs) and the shard.
pub fn admit(spec: &Spec, opts: &Options) -> Result<Shard, Failure> {
    let cases = spec
        .case_count()
        .map_err(|e| Failure::raw(e.category(), e.to_string()))?;
    opts.limits
        .check(&sweeps::limits::output(cases))
        .map_err(|over| Failure::over_budget(&over))?;
    match opts.shard {
        None => Ok(Shard::ALL),
        Some((k, n)) => format!("{k}/{n}")
            .parse::<Shard>()
            .map_err(|e| Failure::raw(Category::Input, format!("shard: {e}"))),
    }
}

/// Runs the sweep into `out` (on the worker thread): the number of rows written, or the
/// failure (an interrupted sweep keeps its rows, marked incomplete, as on the command line).
pub fn run(
    spec: &Spec,
    what: &str,
    out: &Path,
    shard: Shard,
    opts: &Options,
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
    sweeps::run(spec, out, &run_opts, &mut Silent)
        .map(|s| s.resumed + s.written)
        .map_err(|e| failure(e, what))
}
