//! The resource limits of every command: the libraries estimate a command's peak memory, work
//! and output before it allocates ([`tensegrity_engine::estimate`]); here the limits are the
//! global flags `--max-memory` (default: the smaller of 8 GiB and 3/4 of the memory this
//! process may use — cgroup limit, address-space limit, available memory), `--max-work`
//! (estimated seconds, default 60) and `--max-output` (bytes written, default 1 GiB); an
//! estimate above them is refused (exit code 2) naming the parameter, the estimate, the limit,
//! the flag that raises it and the flags of the parameters ([`flag_of`]). Work estimated above
//! a few seconds shows an elapsed-time spinner on stderr when it is a terminal.

use super::request_args::flag_of;
use anyhow::Result;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::OnceLock;
use std::time::Duration;
use tensegrity_core::budget::{self, Estimate, Limits, OverBudget, Resource};
use tensegrity_engine::{estimate, Estimated};

static LIMITS: OnceLock<Limits> = OnceLock::new();

/// Estimated work above which a spinner shows on a terminal (s).
const SPINNER_AFTER_S: f64 = 2.0;

/// The global limit flags.
#[derive(clap::Args, Debug, Clone)]
pub struct LimitArgs {
    /// Refuse a command whose estimated peak memory exceeds SIZE (e.g. 500M, 16Gi, 2T; default:
    /// the smaller of 8 GiB and 3/4 of the memory available to this process).
    #[arg(long, global = true, value_name = "SIZE", value_parser = parse_size)]
    pub max_memory: Option<f64>,
    /// Refuse a command whose estimated work exceeds SECONDS (default 60).
    #[arg(long, global = true, value_name = "SECONDS", value_parser = super::values::positive)]
    pub max_work: Option<f64>,
    /// Refuse a command whose estimated output (files written) exceeds SIZE (default 1Gi).
    #[arg(long, global = true, value_name = "SIZE", value_parser = parse_size)]
    pub max_output: Option<f64>,
}

/// Sets the limits of this process from the flags (first call wins).
pub fn init(args: &LimitArgs) {
    let _ = LIMITS.set(Limits {
        memory_bytes: args.max_memory.unwrap_or_else(default_memory_limit),
        work_s: args.max_work.unwrap_or(budget::DEFAULT_MAX_WORK_S),
        output_bytes: args.max_output.unwrap_or(budget::DEFAULT_MAX_OUTPUT_BYTES),
    });
}

/// The limits in force (also every sweep case's).
pub fn limits() -> Limits {
    *LIMITS.get_or_init(|| Limits {
        memory_bytes: default_memory_limit(),
        ..Limits::default()
    })
}

/// A refused estimate, with the flag that raises the limit.
#[derive(Debug, thiserror::Error)]
#[error("{over}; raise the limit with {flag} (e.g. {flag} {suggested}) or make the request smaller{flags}")]
pub struct Refused {
    /// The estimate over its limit.
    #[source]
    pub over: OverBudget,
    /// The flag that raises the limit.
    pub flag: &'static str,
    /// A flag value that would admit the estimate.
    pub suggested: String,
    /// The flags of the estimate's parameters, as ` (--sides 100000)`, or empty.
    pub flags: String,
}

/// Shows elapsed time on stderr while a long computation runs (when stderr is a terminal);
/// drop it when the work is done.
pub struct Progress(Option<ProgressBar>);

impl Drop for Progress {
    fn drop(&mut self) {
        if let Some(bar) = self.0.take() {
            bar.finish_and_clear();
        }
    }
}

/// Checks `estimate` against the limits; returns the progress indicator of the work.
pub fn check(estimate: Estimate) -> Result<Progress> {
    check_with(estimate, false)
}

/// [`check`] of an estimate if there is one.
pub fn optional(estimate: Option<Estimate>) -> Result<Progress> {
    estimate.map_or(Ok(Progress(None)), check)
}

/// [`check`], with the spinner shown on a terminal whatever the estimate when
/// `work_unknown` (an adaptive integration's steps are not known in advance).
pub fn check_with(estimate: Estimate, work_unknown: bool) -> Result<Progress> {
    if let Err(over) = limits().check(&estimate) {
        let (flag, suggested) = match over.resource {
            Resource::Memory => ("--max-memory", size_flag(over.estimated)),
            Resource::Output => ("--max-output", size_flag(over.estimated)),
            Resource::Work => ("--max-work", format!("{:.0}", over.estimated.ceil())),
        };
        let flags = flags(&over.estimate.parameter);
        let flags = if flags.is_empty() {
            flags
        } else {
            format!(" ({flags})")
        };
        return Err(Refused {
            over,
            flag,
            suggested,
            flags,
        }
        .into());
    }
    let quick = estimate.work_s < SPINNER_AFTER_S && !work_unknown;
    if quick || !std::io::stderr().is_terminal() {
        return Ok(Progress(None));
    }
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template("{spinner} {elapsed_precise} {msg}") {
        bar.set_style(style);
    }
    let work = budget::human_seconds(estimate.work_s);
    bar.set_message(format!("{} (estimated {work})", estimate.what));
    bar.enable_steady_tick(Duration::from_millis(200));
    Ok(Progress(Some(bar)))
}

/// The flags of an estimate's parameters: `t_end = 1e9, dt = 0.001 s` → `--t-end 1e9 --dt
/// 0.001` (the parts that are not `name = value` left out).
fn flags(parameter: &str) -> String {
    let flag = |part: &str| {
        let (name, value) = part.split_once(" = ")?;
        let simple = name.chars().all(|c| c.is_ascii_lowercase() || c == '_');
        let value = value.split_whitespace().next()?;
        simple.then(|| format!("{} {value}", flag_of(name)))
    };
    let flags: Vec<String> = parameter.split(", ").filter_map(flag).collect();
    flags.join(" ")
}

/// A `--max-memory`/`--max-output` value a little above `bytes` (`12Gi`, `3Ti`).
fn size_flag(bytes: f64) -> String {
    let (scale, unit) = [(4, "Ti"), (3, "Gi"), (2, "Mi")]
        .into_iter()
        .map(|(power, unit)| (1024f64.powi(power), unit))
        .find(|&(scale, _)| bytes >= scale)
        .unwrap_or((1024.0, "Ki"));
    let v = (bytes / scale * 1.1).ceil();
    if v.is_finite() && v < 1e15 {
        format!("{v:.0}{unit}")
    } else {
        "<more than is available>".into()
    }
}

/// Parses a size: a number with an optional unit K, M, G, T (powers of 1000, or Ki, Mi, Gi,
/// Ti for powers of 1024; a trailing B is allowed).
pub fn parse_size(s: &str) -> Result<f64, String> {
    let t = s.trim().trim_end_matches(['B', 'b']);
    let at = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let units = ["", "K", "M", "G", "T"];
    let (unit, binary) = match t[at..].to_ascii_uppercase() {
        u if u.ends_with('I') => (u[..u.len() - 1].to_string(), true),
        u => (u, false),
    };
    let power = units
        .iter()
        .position(|u| *u == unit)
        .filter(|&p| p > 0 || !binary);
    match (power, t[..at].trim().parse::<f64>()) {
        (Some(p), Ok(v)) if v.is_finite() && v > 0.0 => {
            Ok(v * if binary { 1024f64 } else { 1000f64 }.powi(p as i32))
        }
        _ => Err(format!("invalid size \"{s}\": use e.g. 500M, 16G, 2T")),
    }
}

/// The default memory limit: min(8 GiB, 3/4 of what this process may use), where that is the
/// smallest of the cgroup limit (less its usage), the address-space limit and the available
/// memory (Linux; 8 GiB elsewhere).
fn default_memory_limit() -> f64 {
    let read = |p: &str| std::fs::read_to_string(p).ok();
    let number = |t: Option<String>| t.and_then(|t| t.trim().parse::<f64>().ok());
    let field = |file: &str, key: &str, at: usize| {
        let text = read(file)?;
        let line = text.lines().find(|l| l.starts_with(key))?;
        line.split_whitespace().nth(at)?.parse::<f64>().ok()
    };
    let mut avail = f64::INFINITY;
    if let Some(kb) = field("/proc/meminfo", "MemAvailable:", 1) {
        avail = avail.min(kb * 1024.0);
    }
    if let Some(max) = number(read("/sys/fs/cgroup/memory.max")) {
        let used = number(read("/sys/fs/cgroup/memory.current")).unwrap_or(0.0);
        avail = avail.min((max - used).max(0.0));
    }
    if let Some(v) = field("/proc/self/limits", "Max address space", 3) {
        avail = avail.min(v);
    }
    (0.75 * avail).min(budget::DEFAULT_MAX_MEMORY_BYTES)
}

/// The engine's estimate of any request (`toroid`, `roll`, `statics`, …), checked.
pub fn estimated<R: Estimated>(request: &R) -> Result<Progress> {
    optional(request.estimate()?)
}

/// `tensegrity toroid`.
pub fn toroid(request: &toroid::ToroidRequest) -> Result<Progress> {
    estimated(request)
}

/// `tensegrity roll`.
pub fn roll(request: &toroid::RollRequest) -> Result<Progress> {
    estimated(request)
}

/// `tensegrity fig-rolling`: the wheels roll at once, one thread each.
pub fn rolling_series(request: &toroid::RollRequest, sides: &[usize]) -> Result<Progress> {
    optional(estimate::rolling_series(request, sides))
}

/// `tensegrity simulate`, with its outputs (an adaptive run shows the spinner: its steps are
/// not known up front).
pub fn simulation(sim: &tensegrity_core::Simulation, csv: bool, vtk: bool) -> Result<Progress> {
    let e = tensegrity_engine::simulate::estimate(sim, csv, vtk)?;
    check_with(e, sim.settings.integrator.is_adaptive())
}

/// `tensegrity michell`: the sign maps, if asked for.
pub fn michell(args: &super::michell::MichellArgs) -> Result<Progress> {
    let members = args.map_members.len();
    sign_map(args.map_grid, members, args.sign_map.is_some())
}

/// `tensegrity michell --sign-map` (nothing without it).
pub fn sign_map(grid: (usize, usize), members: usize, requested: bool) -> Result<Progress> {
    optional(requested.then(|| estimate::sign_map(grid, members)))
}

/// `tensegrity tipover --grid`.
pub fn friction_grid(n: usize) -> Result<Progress> {
    check(estimate::friction_grid(n))
}

/// `tensegrity sweep`: its CSV (each case is checked by the sweep itself).
pub fn sweep(cases: usize) -> Result<Progress> {
    check(sweeps::limits::output(cases))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_decimal_and_binary_units() {
        assert_eq!(parse_size("500M").unwrap(), 5e8);
        assert_eq!(parse_size("16G").unwrap(), 16e9);
        assert_eq!(parse_size("2GiB").unwrap(), 2.0 * 1024f64.powi(3));
        assert_eq!(parse_size("1Ki").unwrap(), 1024.0);
        assert_eq!(parse_size("1234").unwrap(), 1234.0);
        for bad in ["-1G", "12Q", "G", "1i", "Ki"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_suggested_flag_value_admits_the_estimate() {
        // 6.208e13 B = 56.46 TiB, +10 %: 63Ti
        assert_eq!(size_flag(6.208e13), "63Ti");
        assert_eq!(size_flag(1.5e9), "2Gi");
        assert!(parse_size(&size_flag(3.3e10)).unwrap() > 3.3e10);
    }

    #[test]
    fn parameters_become_flags() {
        let p = "t_end = 1000000000, dt = 0.0001, sides = 8";
        assert_eq!(flags(p), "--t-end 1000000000 --dt 0.0001 --sides 8");
        assert_eq!(flags("t_end = 5 s, output interval 1e-9 s"), "--t-end 5");
        assert_eq!(flags("map_grid = 100x200"), "--map-grid 100x200");
        assert_eq!(flags("10 sweep cases"), "");
    }
}
