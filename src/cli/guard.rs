//! The resource limits of every command: the engine estimates a command's peak memory, work
//! and output before it allocates ([`tensegrity_engine::estimate`]) and knows the default
//! limits ([`tensegrity_engine::limits`]); here the limits are the global flags
//! `--max-memory` (default: the smaller of 8 GiB and 3/4 of the memory this process may use),
//! `--max-work` (estimated seconds, default 60) and `--max-output` (bytes written, default
//! 1 GiB); an estimate above them is refused (exit code 2) naming the parameter, the
//! estimate, the limit, the flag that raises it and the flags of the parameters
//! ([`tensegrity_engine::spelling::flag_of`]). Long work shows its progress
//! ([`tensegrity_io::progress`]: a bar on a terminal, plain lines with percent and ETA
//! otherwise): counted where the work counts (cases, figures, simulated time), else the
//! elapsed time against the estimate for work estimated above a few seconds.

use anyhow::Result;
use std::sync::OnceLock;
use tensegrity_core::budget::{Estimate, Limits, OverBudget, Resource};
use tensegrity_core::CoreError;
use tensegrity_engine::spelling::parameter_flags;
use tensegrity_engine::{estimate, limits, Estimated, SceneError};
use tensegrity_io::progress::{self, Measure};

static LIMITS: OnceLock<Limits> = OnceLock::new();

/// Estimated work above which a spinner shows on a terminal (s).
const SPINNER_AFTER_S: f64 = 2.0;

/// The global limit flags.
#[derive(clap::Args, Debug, Clone)]
pub struct LimitArgs {
    /// Refuse a command whose estimated peak memory exceeds SIZE (e.g. 500M, 16Gi, 2T; default:
    /// the smaller of 8 GiB and 3/4 of the memory available to this process).
    #[arg(long, global = true, value_name = "SIZE", value_parser = limits::parse_size)]
    pub max_memory: Option<f64>,
    /// Refuse a command whose estimated work exceeds SECONDS (default 60).
    #[arg(long, global = true, value_name = "SECONDS", value_parser = super::values::positive)]
    pub max_work: Option<f64>,
    /// Refuse a command whose estimated output (files written) exceeds SIZE (default 1Gi).
    #[arg(long, global = true, value_name = "SIZE", value_parser = limits::parse_size)]
    pub max_output: Option<f64>,
}

/// Sets the limits of this process from the flags (first call wins).
pub fn init(args: &LimitArgs) {
    let defaults = limits::for_this_process();
    let _ = LIMITS.set(Limits {
        memory_bytes: args.max_memory.unwrap_or(defaults.memory_bytes),
        work_s: args.max_work.unwrap_or(defaults.work_s),
        output_bytes: args.max_output.unwrap_or(defaults.output_bytes),
    });
}

/// The limits in force (also every sweep case's).
pub fn limits() -> Limits {
    *LIMITS.get_or_init(limits::for_this_process)
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

/// The progress report of a command's work ([`tensegrity_io::progress`]): a bar on a
/// terminal, plain lines with percent and ETA in a log; it ends when dropped.
pub struct Progress(progress::Progress);

impl Progress {
    /// A handle for the work's counter (a clone of the report).
    pub fn handle(&self) -> progress::Progress {
        self.0.clone()
    }
}

/// Checks `estimate` against the limits; returns the progress indicator of the work.
pub fn check(estimate: Estimate) -> Result<Progress> {
    check_with(estimate, false)
}

/// [`check`] of an estimate if there is one.
pub fn optional(estimate: Option<Estimate>) -> Result<Progress> {
    estimate.map_or(Ok(Progress(progress::Progress::hidden())), check)
}

/// [`check`], with the progress shown whatever the estimate when `work_unknown` (the rank
/// of a sparse statics is not known in advance); work estimated under a few seconds shows
/// none; the percent is the elapsed time against the estimate.
pub fn check_with(estimate: Estimate, work_unknown: bool) -> Result<Progress> {
    let measure = Measure::Estimated {
        work_s: estimate.work_s,
    };
    let what = estimate.what.clone();
    let shown = estimate.work_s >= SPINNER_AFTER_S || work_unknown;
    counted(estimate, &what, measure, shown)
}

/// [`check`] of a work that counts its progress by `measure` (cases, figures, simulated
/// time), reported as `what` when `shown`.
pub fn counted(estimate: Estimate, what: &str, measure: Measure, shown: bool) -> Result<Progress> {
    if let Err(over) = limits().check(&estimate) {
        return Err(refusal(over).into());
    }
    Ok(Progress(progress::Progress::auto(what, measure, !shown)))
}

/// The refusal of an estimate over its limit: the flag that raises it, a value that would
/// admit it, the flags of its parameters.
fn refusal(over: OverBudget) -> Refused {
    let (flag, suggested) = match over.resource {
        Resource::Memory => ("--max-memory", limits::suggest_size(over.estimated)),
        Resource::Output => ("--max-output", limits::suggest_size(over.estimated)),
        Resource::Work => ("--max-work", format!("{:.0}", over.estimated.ceil())),
    };
    let flags = parameter_flags(&over.estimate.parameters);
    let flags = if flags.is_empty() {
        flags
    } else {
        format!(" ({flags})")
    };
    Refused {
        over,
        flag,
        suggested,
        flags,
    }
}

/// A library's own refusal of a computation found over the limits once part of it ran (the
/// sparse statics once its rank is known), as a refusal naming the flag; other errors as
/// they are.
pub fn refused_later(e: anyhow::Error) -> anyhow::Error {
    let over = e.chain().find_map(|c| {
        let core = c
            .downcast_ref::<SceneError>()
            .and_then(|s| match s {
                SceneError::Core(core) => Some(core),
                _ => None,
            })
            .or_else(|| c.downcast_ref::<CoreError>());
        match core {
            Some(CoreError::OverBudget(over)) => Some((**over).clone()),
            _ => None,
        }
    });
    over.map_or(e, |over| refusal(over).into())
}

/// The engine's estimate of any request (`toroid`, `roll`, `statics`, …), checked.
pub fn estimated<R: Estimated>(request: &R) -> Result<Progress> {
    optional(request.estimate()?)
}

/// `tensegrity toroid`.
pub fn toroid(request: &toroid::ToroidRequest) -> Result<Progress> {
    estimated(request)
}

/// `tensegrity roll`: its simulated time.
pub fn roll(request: &toroid::RollRequest) -> Result<Progress> {
    let measure = Measure::Simulated {
        t_end: request.t_end,
    };
    match request.estimate()? {
        Some(e) => {
            let shown = e.work_s >= SPINNER_AFTER_S;
            counted(e, "roll", measure, shown)
        }
        None => optional(None),
    }
}

/// `tensegrity fig-rolling`: the wheels roll at once, one thread each.
pub fn rolling_series(request: &toroid::RollRequest, sides: &[usize]) -> Result<Progress> {
    optional(estimate::rolling_series(request, sides))
}

/// `tensegrity simulate`, with its outputs: its simulated time (shown for an adaptive run
/// whatever the estimate: its steps are not known up front).
pub fn simulation(
    command: &tensegrity_engine::simulate::SimulateCommand,
    sim: &tensegrity_dynamics::Simulation,
    csv: bool,
    vtk: bool,
) -> Result<Progress> {
    let e = tensegrity_engine::simulate::estimate_checked(command, sim, csv, vtk)?;
    let shown = e.work_s >= SPINNER_AFTER_S || sim.settings.integrator.is_adaptive();
    let t_end = sim.settings.t_end;
    counted(e, "simulate", Measure::Simulated { t_end }, shown)
}

/// `tensegrity simulate` of an elastic scene: its estimate
/// ([`tensegrity_engine::simulate::elastic::ElasticRun::estimate`]) checked, its simulated
/// time shown as for a rigid run.
pub fn elastic_simulation(
    e: Estimate,
    settings: &tensegrity_dynamics::SimulationSettings,
) -> Result<Progress> {
    let shown = e.work_s >= SPINNER_AFTER_S || settings.integrator.is_adaptive();
    let t_end = settings.t_end;
    counted(e, "simulate", Measure::Simulated { t_end }, shown)
}

/// `tensegrity michell --sign-map` (nothing without it).
pub fn sign_map(grid: (usize, usize), members: usize, requested: bool) -> Result<Progress> {
    optional(requested.then(|| estimate::sign_map(grid, members)))
}

/// `tensegrity tipover --grid`.
pub fn friction_grid(n: usize) -> Result<Progress> {
    check(estimate::friction_grid(n))
}

/// `tensegrity sweep`: its CSV (each case is checked by the sweep itself); the progress of
/// its cases (the sweep sets the total of its shard).
pub fn sweep(cases: usize, quiet: bool) -> Result<Progress> {
    let measure = Measure::Count {
        total: cases,
        unit: "cases",
    };
    counted(sweeps::limits::output(cases), "sweep", measure, !quiet)
}

#[cfg(test)]
mod tests {
    use super::*;
    use tensegrity_core::budget::Parameters;

    #[test]
    fn parameters_become_flags() {
        let p = Parameters::default()
            .and("t_end", 1e9)
            .and("dt", "0.0001 s")
            .and("sides", 8)
            .and("", "10 sweep cases");
        assert_eq!(
            parameter_flags(&p),
            "--t-end 1000000000 --dt 0.0001 --sides 8"
        );
    }
}
