//! The resource guard of every command: before a command allocates anything it estimates its
//! peak memory, work and output from its inputs ([`tensegrity_core::budget`],
//! `toroid::budget`) and refuses an estimate above the limits with an error that names the
//! parameter, the estimate, the limit and the flag that raises it (exit code 2).
//!
//! The limits are global flags of the binary: `--max-memory` (default: the smaller of 8 GiB
//! and 3/4 of the memory this process may use — cgroup limit, address-space limit, available
//! memory), `--max-work` (estimated seconds, default 60) and `--max-output` (bytes written,
//! default 1 GiB). Work estimated above a few seconds shows an elapsed-time spinner on stderr
//! when it is a terminal.

use anyhow::Result;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::OnceLock;
use std::time::Duration;
use tensegrity_core::budget::{self, Estimate, Limits, OverBudget, Resource};

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
    let limits = Limits {
        memory_bytes: args.max_memory.unwrap_or_else(default_memory_limit),
        work_s: args.max_work.unwrap_or(budget::DEFAULT_MAX_WORK_S),
        output_bytes: args.max_output.unwrap_or(budget::DEFAULT_MAX_OUTPUT_BYTES),
    };
    let _ = LIMITS.set(limits);
}

/// The limits in force.
pub fn limits() -> Limits {
    *LIMITS.get_or_init(|| Limits {
        memory_bytes: default_memory_limit(),
        ..Limits::default()
    })
}

/// A refused estimate, with the flag that raises the limit.
#[derive(Debug, thiserror::Error)]
#[error(
    "{over}; raise the limit with {flag} (e.g. {flag} {suggested}) or make the request smaller"
)]
pub struct Refused {
    /// The estimate over its limit.
    #[source]
    pub over: OverBudget,
    /// The flag that raises the limit.
    pub flag: &'static str,
    /// A flag value that would admit the estimate.
    pub suggested: String,
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

/// [`check`], with the spinner shown on a terminal whatever the estimate when
/// `work_unknown` (an adaptive integration's steps are not known in advance).
fn check_with(estimate: Estimate, work_unknown: bool) -> Result<Progress> {
    if let Err(over) = limits().check(&estimate) {
        let (flag, suggested) = match over.resource {
            Resource::Memory => ("--max-memory", size_flag(over.estimated)),
            Resource::Output => ("--max-output", size_flag(over.estimated)),
            Resource::Work => ("--max-work", format!("{:.0}", over.estimated.ceil())),
        };
        return Err(Refused {
            over,
            flag,
            suggested,
        }
        .into());
    }
    Ok(progress(&estimate, work_unknown))
}

fn progress(estimate: &Estimate, work_unknown: bool) -> Progress {
    if (estimate.work_s < SPINNER_AFTER_S && !work_unknown) || !std::io::stderr().is_terminal() {
        return Progress(None);
    }
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template("{spinner} {elapsed_precise} {msg}") {
        bar.set_style(style);
    }
    bar.set_message(format!(
        "{} (estimated {})",
        estimate.what,
        budget::human_seconds(estimate.work_s)
    ));
    bar.enable_steady_tick(Duration::from_millis(200));
    Progress(Some(bar))
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
    let (num, scale) = match t.char_indices().find(|(_, c)| c.is_ascii_alphabetic()) {
        Some((i, _)) => {
            let scale = match t[i..].to_ascii_uppercase().as_str() {
                "K" => 1e3,
                "M" => 1e6,
                "G" => 1e9,
                "T" => 1e12,
                "KI" => 1024.0,
                "MI" => 1024f64.powi(2),
                "GI" => 1024f64.powi(3),
                "TI" => 1024f64.powi(4),
                _ => return Err(format!("invalid size \"{s}\": use e.g. 500M, 16G, 2T")),
            };
            (&t[..i], scale)
        }
        None => (t, 1.0),
    };
    match num.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v * scale),
        _ => Err(format!("invalid size \"{s}\": use e.g. 500M, 16G, 2T")),
    }
}

/// The default memory limit: min(8 GiB, 3/4 of what this process may use), where that is the
/// smallest of the cgroup limit (less its usage), the address-space limit and the available
/// memory (Linux; 8 GiB elsewhere).
fn default_memory_limit() -> f64 {
    let read = |p: &str| std::fs::read_to_string(p).ok();
    let mut avail = f64::INFINITY;
    if let Some(meminfo) = read("/proc/meminfo") {
        if let Some(kb) = meminfo
            .lines()
            .find(|l| l.starts_with("MemAvailable:"))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|v| v.parse::<f64>().ok())
        {
            avail = avail.min(kb * 1024.0);
        }
    }
    let number = |t: Option<String>| t.and_then(|t| t.trim().parse::<f64>().ok());
    if let Some(max) = number(read("/sys/fs/cgroup/memory.max")) {
        let used = number(read("/sys/fs/cgroup/memory.current")).unwrap_or(0.0);
        avail = avail.min((max - used).max(0.0));
    }
    if let Some(limits) = read("/proc/self/limits") {
        if let Some(v) = limits
            .lines()
            .find(|l| l.starts_with("Max address space"))
            .and_then(|l| l.split_whitespace().nth(3))
            .and_then(|v| v.parse::<f64>().ok())
        {
            avail = avail.min(v);
        }
    }
    (0.75 * avail).min(budget::DEFAULT_MAX_MEMORY_BYTES)
}

/// `tensegrity toroid`.
pub fn toroid(request: &toroid::ToroidRequest) -> Result<Progress> {
    check(toroid::budget::statics(request))
}

/// `tensegrity roll`.
pub fn roll(request: &toroid::RollRequest) -> Result<Progress> {
    check(toroid::budget::roll(request))
}

/// `tensegrity fig-rolling`: the wheels roll at once, one thread each
/// ([`tensegrity_figures::fig_rolling`]), estimated by the library.
pub fn rolling_series(request: &toroid::RollRequest, sides: &[usize]) -> Result<Progress> {
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    match toroid::budget::rolling_series(request, sides, cores) {
        Some(e) => check(e),
        None => Ok(Progress(None)),
    }
}

/// `tensegrity simulate`: the run with its outputs (CSV numbers ~25 bytes, VTK ~40), named by
/// the settings that drive its size (from the scene or the flags).
pub fn simulation(sim: &tensegrity_core::Simulation, csv: bool, vtk: bool) -> Result<Progress> {
    // settings the core refuses anyway (a step that cannot finish, a bad value) get its error
    sim.validate()?;
    let s = &sim.settings;
    let mut parameter = format!("t_end = {} s, dt = {} s", s.t_end, s.dt);
    if let Some(dt_out) = s.output_interval {
        parameter.push_str(&format!(", output interval {dt_out} s"));
    }
    let bytes_per_number = 25.0 * f64::from(u8::from(csv)) + 40.0 * f64::from(u8::from(vtk));
    let written = csv || vtk;
    // an adaptive run's steps are at least t_end / dt; how many more is not known up front
    let adaptive = s.integrator.is_adaptive();
    check_with(
        budget::simulation(sim, true, written, bytes_per_number, parameter),
        adaptive,
    )
}

/// `tensegrity michell`: the sign maps, if asked for (the truss itself is bounded by the
/// library's complexity limit).
pub fn michell(args: &super::michell::MichellArgs) -> Result<Progress> {
    sign_map(
        args.map_grid,
        args.map_members.len(),
        args.sign_map.is_some(),
    )
}

/// `tensegrity michell --sign-map`: azimuth × polar points × mapped members, kept in memory
/// (8 bytes a value) and written (~80 bytes a row); nothing without `--sign-map`.
pub fn sign_map(grid: (usize, usize), members: usize, requested: bool) -> Result<Progress> {
    if !requested {
        return Ok(Progress(None));
    }
    let points = grid.0 as f64 * grid.1 as f64 * members.max(1) as f64;
    let parameter = format!("--map-grid {}x{}", grid.0, grid.1);
    let e = Estimate::new(
        format!("a sign map of {points:.3e} (member, load direction) values"),
        parameter,
    )
    .memory(16.0 * points)
    .output(80.0 * points)
    .work(30.0 * points / budget::SCALAR_FLOP_RATE);
    check(e)
}

/// `tensegrity tipover --grid`: n × n rows of (σ, ε, F_f/F_e), kept in memory (24 bytes) and
/// written (~75 bytes).
pub fn friction_grid(n: usize) -> Result<Progress> {
    let rows = n as f64 * n as f64;
    let e = budget::table(rows, 24.0, true, format!("--grid-points {n}"));
    check(Estimate {
        output_bytes: 75.0 * rows,
        work_s: 200.0 * rows / budget::SCALAR_FLOP_RATE,
        ..e
    })
}

/// `tensegrity sweep`: one CSV row per case (~200 bytes).
pub fn sweep(cases: usize) -> Result<Progress> {
    // work is not estimated: a sweep shows its own progress bar and can be resumed
    check(budget::table(
        cases as f64,
        200.0,
        false,
        format!("{cases} sweep cases"),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_decimal_and_binary_units() {
        assert_eq!(parse_size("500M").unwrap(), 5e8);
        assert_eq!(parse_size("16G").unwrap(), 16e9);
        assert_eq!(parse_size("2GiB").unwrap(), 2.0 * 1024f64.powi(3));
        assert_eq!(parse_size("1234").unwrap(), 1234.0);
        assert!(parse_size("-1G").is_err());
        assert!(parse_size("12Q").is_err());
        assert!(parse_size("G").is_err());
    }

    #[test]
    fn the_suggested_flag_value_admits_the_estimate() {
        // 6.208e13 B = 56.46 TiB, +10 %: 63Ti
        assert_eq!(size_flag(6.208e13), "63Ti");
        assert_eq!(size_flag(1.5e9), "2Gi");
        assert!(parse_size(&size_flag(3.3e10)).unwrap() > 3.3e10);
    }
}
