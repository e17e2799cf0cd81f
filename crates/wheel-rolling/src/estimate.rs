//! Resource estimates of rolling runs, from sizes alone (nothing is built or integrated), for
//! the guard of [`tensegrity_core::budget`].
//!
//! - **rigid** ([`rigid`]): t_end / dt steps of a one-degree-of-freedom hybrid model (one
//!   right-hand side of ~200 flops a step, and ~[`RIGID_FLOPS_PER_SIDE`] a side of the
//!   polygon for its contact search: a 3,600-sided wheel took 40 s for 10 s), and one
//!   [`RollingSample`] kept per output interval;
//! - **full** ([`full`]): t_end / dt steps of the core's class-1 model, `rhs_per_step`
//!   right-hand sides of [`budget::rhs_flops`] (bars, strings, constraint rows) plus the
//!   wheel's own extra flops each, a state of 12 numbers a bar; one sample and its node
//!   positions (48 bytes a node) kept per output interval;
//! - a **plan** ([`plan`]): what the [`Plan`] may run — the rigid run, the full run, or the
//!   rigid run and then the full one ([`Plan::RigidThenFullIfInvalid`]) — so the estimate and
//!   the run follow the one decision of [`crate::fidelity`].
//!
//! Every estimate names the parameters that drive it as the request spells them
//! (`t_end = 10, dt = 0.0001, sides = 8`).

use crate::defaults;
use crate::fidelity::Plan;
use crate::sample::RollingSample;
use tensegrity_core::budget::{self, Estimate};

/// What the cost of a full run depends on: the sizes of the wheel's class-1 model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FullSizes {
    /// Nodes of the structure.
    pub nodes: usize,
    /// Bars (rigid, with mass).
    pub bars: usize,
    /// Strings.
    pub strings: usize,
    /// Rows of the joint constraints N P = D.
    pub constraint_rows: usize,
    /// Right-hand sides per step: 4 for RK4, 6 counting the projection onto the bar
    /// lengths and joints as two more.
    pub rhs_per_step: f64,
    /// Flops per right-hand side beyond the core's per-member cost (e.g. a hub's banded
    /// block of the Ω system).
    pub extra_flops: f64,
}

/// The sizes of a run: its time and step, and the parameter text the estimate names.
#[derive(Debug, Clone, PartialEq)]
pub struct RunSize {
    /// Simulated time (s).
    pub t_end: f64,
    /// Step (s).
    pub dt: f64,
    /// Sides of the wheel's polygon.
    pub sides: usize,
    /// The parameters that drive the size, as the request names them.
    pub parameter: String,
}

impl RunSize {
    /// A run of `t_end` s at `dt` for a wheel of `sides` sides: the parameter text
    /// `t_end = …, dt = …, sides = …`.
    ///
    /// ```
    /// use wheel_rolling::estimate::RunSize;
    /// assert_eq!(RunSize::new(10.0, 1e-4, 8).parameter, "t_end = 10, dt = 0.0001, sides = 8");
    /// ```
    pub fn new(t_end: f64, dt: f64, sides: usize) -> Self {
        Self {
            t_end,
            dt,
            sides,
            parameter: format!("t_end = {t_end}, dt = {dt}, sides = {sides}"),
        }
    }

    fn steps(&self) -> f64 {
        (self.t_end / self.dt).ceil()
    }

    fn samples(&self) -> f64 {
        (self.t_end / defaults::ROLL_OUTPUT_DT).floor() + 2.0
    }
}

/// Flops a step of the rigid model spends per side of the polygon (its contact search).
pub const RIGID_FLOPS_PER_SIDE: f64 = 120.0;

/// A rigid run (module docs).
///
/// ```
/// use wheel_rolling::estimate::{rigid, RunSize};
/// let e = rigid(&RunSize::new(10.0, 1e-4, 8));
/// assert!(e.work_s < 0.2 && e.memory_bytes < 1e6);
/// // a 3,600-sided polygon searches its contacts every step: tens of seconds
/// assert!(rigid(&RunSize::new(10.0, 1e-4, 3600)).work_s > 30.0);
/// ```
pub fn rigid(size: &RunSize) -> Estimate {
    let flops = 200.0 + RIGID_FLOPS_PER_SIDE * size.sides as f64;
    let run = budget::integration(size.steps(), 1.0, flops, 3, size.parameter.clone());
    let sample = std::mem::size_of::<RollingSample>() as f64;
    run.then(budget::table(
        size.samples(),
        sample,
        true,
        size.parameter.clone(),
    ))
}

/// A full run (module docs).
pub fn full(size: &RunSize, sizes: &FullSizes) -> Estimate {
    let flops =
        budget::rhs_flops(sizes.bars, sizes.strings, sizes.constraint_rows) + sizes.extra_flops;
    let run = budget::integration(
        size.steps(),
        sizes.rhs_per_step,
        flops,
        12 * sizes.bars,
        size.parameter.clone(),
    );
    let sample = std::mem::size_of::<RollingSample>() as f64 + 48.0 * sizes.nodes as f64;
    run.then(budget::table(
        size.samples(),
        sample,
        true,
        size.parameter.clone(),
    ))
}

/// What `plan` may run: the rigid run, the full run, or both one after the other.
///
/// ```
/// use wheel_rolling::estimate::{full, plan, rigid, FullSizes, RunSize};
/// use wheel_rolling::fidelity::Plan;
/// let size = RunSize::new(2.0, 1e-4, 8);
/// let sizes = FullSizes { nodes: 42, bars: 25, strings: 128, constraint_rows: 24,
///     rhs_per_step: 4.0, extra_flops: 0.0 };
/// let both = plan(Plan::RigidThenFullIfInvalid, &size, &sizes);
/// assert!(both.work_s >= full(&size, &sizes).work_s + rigid(&size).work_s - 1e-12);
/// assert_eq!(plan(Plan::Full, &size, &sizes), full(&size, &sizes));
/// ```
pub fn plan(plan: Plan, size: &RunSize, sizes: &FullSizes) -> Estimate {
    match plan {
        Plan::Rigid => rigid(size),
        Plan::Full => full(size, sizes),
        Plan::RigidThenFullIfInvalid => rigid(size).then(full(size, sizes)),
    }
}

/// Independent runs on `workers` threads at once (e.g. the wheels of a figure): memory and
/// output add, the wall time is the total work shared by the workers but never less than the
/// longest run; named by the first run's parameter.
///
/// ```
/// use tensegrity_core::budget::Estimate;
/// use wheel_rolling::estimate::parallel;
/// // the fig-rolling wheels: 7.6 + 15.2 + 27.1 + 16.9 s
/// let runs: Vec<Estimate> = [7.6, 15.2, 27.1, 16.9]
///     .iter()
///     .map(|&w| Estimate::new("a wheel", "sides = 8").work(w))
///     .collect();
/// assert!((parallel(&runs, 1, "four wheels").unwrap().work_s - 66.8).abs() < 1e-12);
/// assert!((parallel(&runs, 2, "four wheels").unwrap().work_s - 33.4).abs() < 1e-12);
/// assert_eq!(parallel(&runs, 4, "four wheels").unwrap().work_s, 27.1);
/// assert!((parallel(&runs, 0, "four wheels").unwrap().work_s - 66.8).abs() < 1e-12);
/// assert!(parallel(&[], 2, "nothing").is_none());
/// ```
pub fn parallel(runs: &[Estimate], workers: usize, what: impl Into<String>) -> Option<Estimate> {
    let first = runs.first()?;
    let total: f64 = runs.iter().map(|e| e.work_s).sum();
    let longest = runs.iter().map(|e| e.work_s).fold(0.0, f64::max);
    Some(Estimate {
        what: what.into(),
        parameters: first.parameters.clone(),
        memory_bytes: runs.iter().map(|e| e.memory_bytes).sum(),
        work_s: (total / workers.max(1) as f64).max(longest),
        output_bytes: runs.iter().map(|e| e.output_bytes).sum(),
    })
}
