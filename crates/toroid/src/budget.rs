//! Resource estimates of the toroid commands, from the parameters alone (O(1): nothing is
//! built), for the guard of [`tensegrity_core::budget`].
//!
//! Sizes (builder, thesis §3.1): 5n nodes + 2 axle ends with spokes; 3n bars + the axle;
//! 12n prism strings + 2n spokes + 2n inner + 2n outer ring strings; no supports, so the
//! equilibrium matrix is 3·nodes × members. [`statics`] estimates what [`crate::analyse`]
//! runs: [`dense_statics`] (O(n³) work, O(n²) memory) or, for the symmetry-adapted path,
//! [`cyclic_statics`] (O(n) work and memory). [`roll`] adds what the fidelity decision's plan
//! may run ([`RollRequest::decision`], the one the run follows), estimated by wheel-rolling
//! from the wheel's sizes ([`full_sizes`]). [`tipover_dynamic`] and [`tipover_rolling`]
//! estimate the timed runs of the prestressed wheel (`tipover --dynamic`, `--rolling`):
//! T / dt RK4 steps of the class-1 model (as [`full_sizes`]: four right-hand sides a step,
//! the projection after each within the per-step rate), T = settle + ramp + hold or t_end,
//! and the history kept (one sample per output interval), the integration's work scaled by
//! [`TIMED_RUN_CALIBRATION`]. Calibration (release, the project's 2-core VM): the generic
//! per-step rate counted these runs 4.7–7.3× their CPU time (`tipover --dynamic`, 4.5 s
//! simulated, n = 8: 3.4 s against 0.73 s; `tipover --rolling` with its check at 2.5·10⁻⁵ s,
//! n = 8, 12, 16, 24: 36.6, 72.8, 130, 80.9 s against 6.0, 12.2, 17.9, 24.1 s of CPU and 3.7,
//! 7.8, 11.0, 14.9 s of wall time); a third of it stays above the wall time of every one.

use crate::report::{ToroidRequest, WheelSpec};
use crate::request::{TipoverDynamicRequest, TipoverRollingRequest};
use crate::roll::RollRequest;
pub use crate::spec_mass::wheel_mass;
use tensegrity_core::budget::{self, Estimate};
use wheel_rolling::estimate::{FullSizes, RunSize};
use wheel_rolling::fidelity::Plan;

/// Node, bar and string counts of the wheel (or of the single prism).
pub fn counts(wheel: &WheelSpec, prism_only: bool) -> (usize, usize, usize) {
    if prism_only {
        return (6, 3, 12);
    }
    let n = wheel.params.sides;
    let s = &wheel.stabilize;
    let spokes = usize::from(s.spokes);
    let rings = 2 * usize::from(s.inner) + 2 * usize::from(s.outer);
    (
        5usize.saturating_mul(n).saturating_add(2 * spokes),
        3usize.saturating_mul(n).saturating_add(spokes),
        (12 + 2 * spokes + rings).saturating_mul(n),
    )
}

/// Estimate of the statics of the wheel (`tensegrity toroid`) along the path
/// [`crate::analyse`] takes: the symmetry-adapted blocks ([`cyclic_statics`]; the dense SVD
/// statics, [`dense_statics`], for a single prism).
///
/// ```
/// use toroid::{budget, ToroidRequest};
/// let mut r = ToroidRequest::default();
/// assert!(budget::statics(&r).work_s < 1.0);
/// r.wheel.params.sides = 100_000;
/// let e = budget::statics(&r);
/// assert!(e.memory_bytes < 8e9 && e.parameters.to_string() == "sides = 100000");
/// r.wheel.params.sides = 100_000_000;
/// assert!(budget::statics(&r).memory_bytes > 1e11);
/// ```
pub fn statics(request: &ToroidRequest) -> Estimate {
    cyclic_statics(request)
}

fn parameter(request: &ToroidRequest) -> String {
    if request.prism_only {
        "prism_only = true".to_string()
    } else {
        format!("sides = {}", request.wheel.params.sides)
    }
}

/// The dense statics: the SVD of the 3·nodes × members equilibrium matrix with full U and V,
/// the prestress LP and the flexes (O(n²) memory, O(n³) work).
pub fn dense_statics(request: &ToroidRequest) -> Estimate {
    let (nodes, bars, strings) = counts(&request.wheel, request.prism_only);
    budget::dense_statics(
        3usize.saturating_mul(nodes),
        bars.saturating_add(strings),
        parameter(request),
    )
}

/// The symmetry-adapted statics: n complex blocks of one sector's size (3·nodes/n rows ×
/// members/n columns; complex arithmetic ≈ 4 real flops a flop), O(n) memory for the
/// structure, its members and the blocks.
pub fn cyclic_statics(request: &ToroidRequest) -> Estimate {
    if request.prism_only {
        return dense_statics(request);
    }
    let (nodes, bars, strings) = counts(&request.wheel, false);
    let n = request.wheel.params.sides.max(1);
    // saturating: a library caller may ask for any number of sides; the estimate refuses it
    let members = bars.saturating_add(strings);
    let (rows, cols) = (
        3usize.saturating_mul(nodes).div_ceil(n),
        members.div_ceil(n),
    );
    let work = 4.0 * n as f64 * budget::svd_flops(rows, cols) * budget::DENSE_OVERHEAD;
    let memory = 256.0 * (nodes as f64 + members as f64)
        + n as f64 * budget::dense_statics_bytes(rows, cols) * 2.0;
    Estimate::new(
        format!("the symmetry-adapted statics ({n} blocks of {rows} × {cols})"),
        parameter(request),
    )
    .memory(memory)
    .work(work / budget::DENSE_FLOP_RATE)
}

/// The sizes of the wheel's full rolling model: the class-1 model of its bars and strings,
/// one constraint row per rim joint and direction, RK4's four right-hand sides a step.
pub fn full_sizes(wheel: &WheelSpec) -> FullSizes {
    let (nodes, bars, strings) = counts(wheel, false);
    FullSizes {
        nodes,
        bars,
        strings,
        constraint_rows: 3usize.saturating_mul(wheel.params.sides),
        rhs_per_step: 4.0,
        extra_flops: 0.0,
    }
}

/// Estimate of `roll`: the wheel's statics, then what the plan of the fidelity decision
/// ([`RollRequest::decision`]) may run — the rigid model (one degree of freedom), the full
/// model, or both — with their samples kept in memory (one per
/// [`crate::defaults::ROLL_OUTPUT_DT`]), with `convergence_check` the same plan again at
/// half the step and once more (the twin), and with `ensemble` K its K copies at the step and K at half of it, and the
/// other model's run; named `t_end = …, dt = …, sides = …`.
/// Each model is sized at its own step ([`wheel_rolling::RunSpec::rigid_dt`],
/// [`wheel_rolling::RunSpec::full_dt`]); an IMEX step is counted as an RK4 step, which stays
/// conservative: the default n = 24, 50°, 10 s full run with its check is estimated at 10.1 s
/// and took 5.2 s of CPU (release, 2-core VM; 1.7× the cost of an RK4 step per step).
pub fn roll(request: &RollRequest) -> Estimate {
    let wheel = &request.wheel;
    let statics = statics(&ToroidRequest {
        wheel: *wheel,
        ..ToroidRequest::default()
    });
    let plan = request.decision().plan;
    let spec = request.spec();
    let sides = wheel.params.sides;
    let sizes = full_sizes(wheel);
    // each model at its own step (the full model's is coarser under IMEX); `scale` halves
    // both for the refined run of the convergence check
    let at = |scale: f64| {
        let rigid = RunSize::new(request.t_end, scale * spec.rigid_dt(), sides);
        let full = RunSize::new(request.t_end, scale * spec.full_dt(), sides);
        let run = match plan {
            Plan::Rigid => wheel_rolling::estimate::rigid(&rigid),
            Plan::Full => wheel_rolling::estimate::full(&full, &sizes),
            Plan::RigidThenFullIfInvalid => wheel_rolling::estimate::rigid(&rigid)
                .then(wheel_rolling::estimate::full(&full, &sizes)),
        };
        (run, rigid, full)
    };
    let (one, rigid_size, full_size) = at(1.0);
    // the estimate is named by the step of the model that runs first
    let size = if plan == Plan::Full {
        full_size.clone()
    } else {
        rigid_size
    };
    let mut run = one.clone();
    if request.checks.convergence_check {
        // the refined companion (half the step, twice the steps) and the twin (the run
        // again from a start turned by 1e-6 rad): the check's cost where no coarse companion
        // serves; a coarse one costs ⅛ or ¼ run (rigid), ¼ to 1 (full)
        // (`wheel_rolling::convergence`)
        run = run.then(at(0.5).0).then(one.clone());
    }
    if request.ensemble >= 2 {
        // K copies of the plan at the step and K at half of it (twice the steps each), then
        // one run of the other model (at most the full one)
        let copies = Estimate {
            work_s: 3.0 * request.ensemble as f64 * one.work_s,
            ..one
        };
        let other = wheel_rolling::estimate::full(&full_size, &sizes);
        run = run.then(copies).then(other);
    }
    Estimate {
        parameters: size.parameter.into(),
        ..statics.then(run)
    }
}

/// Estimate of `fig-rolling`: one [`roll`] per wheel size in `sides`, the wheels rolled at
/// once on `cores` threads (at most one per wheel): see [`wheel_rolling::estimate::parallel`].
/// `None` for no wheel.
pub fn rolling_series(request: &RollRequest, sides: &[usize], cores: usize) -> Option<Estimate> {
    let wheels: Vec<Estimate> = sides
        .iter()
        .map(|&n| {
            let mut r = *request;
            r.wheel.params.sides = n;
            roll(&r)
        })
        .collect();
    let workers = cores.min(wheels.len()).max(1);
    let what = format!(
        "rolling the wheels n = {sides:?} at once on {workers} core(s) (statics, time steps, samples)"
    );
    wheel_rolling::estimate::parallel(&wheels, workers, what)
}

/// Bytes of one sample of a timed tip-over run's history (time, force or position, lean,
/// the contact forces) and its share of the report.
const TIMED_SAMPLE_BYTES: f64 = 64.0;

/// The factor on the generic integration estimate of a timed run of the prestressed wheel
/// (module docs: measured 1/4.7 … 1/7.3 of CPU; a third keeps it above the wall time).
pub const TIMED_RUN_CALIBRATION: f64 = 1.0 / 3.0;

/// A timed run of the prestressed wheel of `t_end` s at `dt`, its history kept every
/// `output_dt` (module docs), named `parameter`.
fn timed_run(
    wheel: &WheelSpec,
    t_end: f64,
    dt: f64,
    output_dt: f64,
    parameter: String,
) -> Estimate {
    let sizes = full_sizes(wheel);
    let flops = budget::rhs_flops(sizes.bars, sizes.strings, sizes.constraint_rows);
    let steps = (t_end / dt).ceil();
    let samples = (t_end / output_dt).floor() + 2.0;
    let mut run = budget::integration(
        steps,
        sizes.rhs_per_step,
        flops,
        12 * sizes.bars,
        parameter.clone(),
    );
    run.work_s *= TIMED_RUN_CALIBRATION;
    run.then(budget::table(samples, TIMED_SAMPLE_BYTES, true, parameter))
}

/// Estimate of `tipover --dynamic`: settle + ramp + hold at `dt` (module docs); named
/// `settle = …, ramp_time = …, hold = …, dt = …, output_dt = …, sides = …`.
///
/// ```
/// use toroid::{budget, TipoverDynamicRequest};
/// use tensegrity_core::budget::Limits;
/// let mut r = TipoverDynamicRequest::default();
/// assert!(Limits::default().check(&budget::tipover_dynamic(&r)).is_ok());
/// r.settings.hold = 1e9; // a billion seconds held: refused, not run for days
/// let e = budget::tipover_dynamic(&r);
/// assert!(e.parameters.to_string().contains("hold = 1000000000"));
/// assert!(Limits::default().check(&e).is_err());
/// ```
pub fn tipover_dynamic(request: &TipoverDynamicRequest) -> Estimate {
    let s = &request.settings;
    let parameter = format!(
        "settle = {}, ramp_time = {}, hold = {}, dt = {}, output_dt = {}, sides = {}",
        s.settle, s.ramp_time, s.hold, s.dt, s.output_dt, request.wheel.params.sides
    );
    let t_end = s.settle + s.ramp_time + s.hold;
    timed_run(&request.wheel, t_end, s.dt, s.output_dt, parameter)
}

/// Estimate of `tipover --rolling`: `t_end` at `dt` (module docs), with `convergence_check` again
/// at half the step and once more (the twin); named
/// `t_end = …, dt = …, output_dt = …, sides = …`.
///
/// ```
/// use toroid::{budget, TipoverRollingRequest};
/// use tensegrity_core::budget::Limits;
/// let mut r = TipoverRollingRequest::default();
/// assert!(Limits::default().check(&budget::tipover_rolling(&r)).is_ok());
/// r.t_end = 1e9;
/// assert!(Limits::default().check(&budget::tipover_rolling(&r)).is_err());
/// ```
pub fn tipover_rolling(request: &TipoverRollingRequest) -> Estimate {
    let parameter = format!(
        "t_end = {}, dt = {}, output_dt = {}, sides = {}",
        request.t_end, request.dt, request.output_dt, request.wheel.params.sides
    );
    let at = |dt: f64| {
        let output_dt = request.output_dt;
        timed_run(
            &request.wheel,
            request.t_end,
            dt,
            output_dt,
            parameter.clone(),
        )
    };
    let run = at(request.dt);
    if !request.checks.convergence_check {
        return run;
    }
    // the refined run (half the step) and the twin beside it
    run.then(at(0.5 * request.dt)).then(at(request.dt))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_match_the_builder() {
        for (stabilize, n) in [("spokes,inner", 8), ("none", 5), ("spokes,inner,outer", 12)] {
            let mut w = WheelSpec::default();
            w.params.sides = n;
            w.stabilize = stabilize.parse().unwrap();
            let t = crate::build(&w.params, w.stabilize, w.bar_density).unwrap();
            let s = &t.structure;
            assert_eq!(
                counts(&w, false),
                (s.n_nodes(), s.n_bars(), s.n_strings()),
                "{stabilize} n = {n}"
            );
            let m = crate::wheel_mass(s);
            assert!((wheel_mass(&w) - m).abs() <= 1e-12 * m, "{stabilize}");
        }
    }

    #[test]
    fn any_number_of_sides_is_estimated_without_overflow() {
        // found by the fuzz target `counts`: 3 · nodes overflowed for ~10¹⁸ sides
        for sides in [usize::MAX / 7, usize::MAX, 1 << 62] {
            let mut r = ToroidRequest::default();
            r.wheel.params.sides = sides;
            let e = cyclic_statics(&r);
            assert!(e.memory_bytes > 1e18 && e.work_s > 1e6, "{sides}: {e:?}");
            let _ = full_sizes(&r.wheel);
        }
    }

    #[test]
    fn a_billion_seconds_of_rolling_is_refused_for_its_samples_and_its_work() {
        let r = RollRequest {
            t_end: 1e9,
            ..RollRequest::default()
        };
        assert_eq!(
            roll(&r).parameters.to_string(),
            "t_end = 1000000000, dt = 0.00025, sides = 8"
        );
        let e = roll(&r);
        // 1e12 samples kept in memory
        assert!(e.memory_bytes > 1e13, "{}", e.memory_bytes);
        assert!(e.work_s > 1e6, "{}", e.work_s);
        assert!(tensegrity_core::budget::Limits::default()
            .check(&e)
            .is_err());
        // the default run is well inside the limits
        let e = roll(&RollRequest::default());
        assert!(tensegrity_core::budget::Limits::default().check(&e).is_ok());
    }

    #[test]
    fn the_estimate_budgets_exactly_what_the_run_may_do() {
        use wheel_rolling::{Fidelity, FidelityChoice, Plan};
        let with = |fidelity, string_stiffness: f64| {
            let mut r = RollRequest {
                fidelity,
                t_end: 0.2,
                ..RollRequest::default()
            };
            r.settings.string_stiffness = string_stiffness;
            r
        };
        // soft strings (the default 2·10⁴ N/m): auto is the full model, and so is the estimate
        let soft = with(FidelityChoice::Auto, 2e4);
        assert_eq!(soft.decision().plan, Plan::Full);
        assert_eq!(roll(&soft), roll(&with(FidelityChoice::Full, 2e4)));
        assert_eq!(crate::roll::roll(&soft).unwrap().fidelity, Fidelity::Full);
        // stiff strings: the rigid run may not be the answer (not valid, or its scene class
        // one where the models differ: the fidelity table), so the estimate covers the rigid
        // run and then the full one
        let stiff = with(FidelityChoice::Auto, 2e6);
        assert_eq!(stiff.decision().plan, Plan::RigidThenFullIfInvalid);
        let (both, full, rigid) = (
            roll(&stiff),
            roll(&with(FidelityChoice::Full, 2e6)),
            roll(&with(FidelityChoice::Rigid, 2e6)),
        );
        assert!(both.work_s >= full.work_s && both.work_s >= rigid.work_s);
        assert!((both.work_s - full.work_s - rigid.work_s + statics_work()).abs() < 1e-9);
        let ran = crate::roll::roll(&stiff).unwrap();
        // the run's decision is the estimate's: the same plan from the same mass, then the
        // model the table picks for the rigid run's class
        assert!(ran.fidelity_reason.contains("the wheel is stiff"));
        match ran.fidelity {
            Fidelity::Rigid => assert!(ran.fidelity_reason.ends_with("rigid run is valid: rigid")),
            Fidelity::Full => assert!(ran.fidelity_reason.contains("full")),
        }
    }

    /// The statics part of every roll estimate of the reference wheel (counted once).
    fn statics_work() -> f64 {
        statics(&ToroidRequest::default()).work_s
    }
}
