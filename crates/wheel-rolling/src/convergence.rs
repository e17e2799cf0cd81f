//! Convergence of a rolling run ([`roll_checked`]): the run is repeated at half the step
//! ([`refined`]) and, from a start turned by 10⁻⁶ rad, at its own step (the twin,
//! [`twin`]), in two threads beside the run itself, and each headline quantity of the three
//! summaries is compared ([`of_summaries`], the rules of
//! [`tensegrity_dynamics::convergence`]).
//!
//! **What is refined.** The step only: the ground's stiffness and damping are the model's (a
//! penalty ground is a soft ground the user chose; its `max_penetration` is a validity
//! figure). Doubling the stiffness with the step, as before 2026-12-06, measured a different
//! limit — the rigid ground, reached as k^(−½) — and no affordable step converged it: the
//! default wheel's first ω⁻ read 2.116, 2.158, 2.172, 2.184 rad/s at (dt, k) = (5, 2.5, 1.25,
//! 0.625)·10⁻⁴ s × (1, 2, 4, 8)·10⁵ N/m under IMEX-ARK, against 2.116, 2.116, 2.110, 2.108 at
//! a fixed 10⁵ N/m. The rigid ground's answer is the rigid model's.
//!
//! **The split IMEX is checked against IMEX-ARK.** Its slaved friction creep carries a bias
//! that halving its own step does not move (the creeping pivot slips 0.103 of its run at
//! 5·10⁻⁵ s against 0.035; the n = 24 wheel on 50° 0.453 against IMEX-ARK's 0.396 at 2.5·10⁻⁴
//! and 10⁻⁴ s alike, with too little chatter for `creep_chatter`), so the refined run of a
//! full run under `imex` is IMEX-ARK at half the step (its default 2.5·10⁻⁴ s halved where no
//! step is given): two methods that agree within τ, or a bias reported as not converged.
//!
//! **Order.** p = 1 (every fixed-step scheme is first order through a landing): the error
//! of a value is estimated as twice its change at half the step, and it is `converged` when
//! that is within its tolerance τ.
//!
//! **Chaotic quantities.** A quantity the twin moves by more than τ/8 is `chaotic`: the hops
//! of a wheel on a steep slope amplify a 10⁻⁶ rad change of the start to percents of the
//! impact count, the final speed, the height oscillation, and a single run is one draw of
//! them. It is reported as such (not `converged`, no warning): its answer is an ensemble's
//! interval (`--ensemble K`), whose copies at two resolutions cover the step's bias.
//!
//! The headline quantities and their tolerances τ ([`crate::defaults`]): `first_impact.t` and
//! `first_impact.omega_before` 1 %; `mean_speed`, `mean_axle_height` 2 %; `final_speed` 2 %;
//! `axle_height_oscillation` and `impacts` 10 %; `airborne_fraction` and `slip_fraction` 0.02
//! absolute. `max_reaction` is not checked: the peak of a penalty force grows with √k.
//!
//! The check costs 3 runs' work (2 for the refined run, 1 for the twin), on three threads.
//! An unconverged quantity that is not chaotic adds a warning, so the run is not `valid`. A run
//! that stopped early (interrupted, or its integration failed) is not compared; a refined or
//! twin run that failed makes the result unconverged, with the failure in the warning.

use crate::contact::ContactKind;
use crate::defaults as d;
use crate::fidelity::{Decision, Fidelity};
use crate::observer::Observer;
use crate::run::{roll_decided, Rolled, Wheel};
use crate::settings::RunSpec;
use crate::summary::{headline, RunSummary};
use std::sync::atomic::{AtomicBool, Ordering};
use tensegrity_dynamics::convergence::TWIN_PERTURBATION;
use tensegrity_dynamics::{Convergence, IntegratorKind};

/// The refined run of `spec`: half the step of either model (module docs: the ground is the
/// model's); a split-IMEX run's under IMEX-ARK (module docs: its creep bias survives halving
/// its own step).
///
/// ```
/// use tensegrity_dynamics::IntegratorKind;
/// use wheel_rolling::{convergence::refined, RunSpec};
/// let split = RunSpec { integrator: IntegratorKind::Imex, ..RunSpec::default() };
/// let fine = refined(&split);
/// assert_eq!((fine.integrator, fine.step_scale), (IntegratorKind::ImexArk, 0.5));
/// assert_eq!(refined(&RunSpec::default()).integrator, IntegratorKind::Rk4);
/// ```
pub fn refined(spec: &RunSpec) -> RunSpec {
    let mut r = *spec;
    r.step_scale *= 0.5;
    if r.integrator == IntegratorKind::Imex {
        r.integrator = IntegratorKind::ImexArk;
    }
    r
}

/// The twin run of `spec`: its own step, the start turned by
/// [`TWIN_PERTURBATION`] rad relative to gravity (the incline φ + 10⁻⁶, as an ensemble's
/// first copy).
pub fn twin(spec: &RunSpec) -> RunSpec {
    let mut r = *spec;
    r.settings.incline += TWIN_PERTURBATION;
    r
}

/// What [`refined`] changed for a run of `fidelity`.
pub fn refinement(spec: &RunSpec, fidelity: Fidelity) -> &'static str {
    if fidelity == Fidelity::Full && spec.integrator == IntegratorKind::Imex {
        return "dt/2 under imex-ark (the split IMEX's creep bias survives halving its own step)";
    }
    match (fidelity, spec.contact) {
        (Fidelity::Full, ContactKind::Penalty | ContactKind::Stick) => {
            "dt/2 (the ground's stiffness is the model's)"
        }
        _ => "dt/2",
    }
}

/// A headline quantity: its key, how to read it, its tolerance and its scale floor.
type Headline = (&'static str, fn(&RunSummary) -> f64, f64, f64);

/// The headline quantities of `main` against `refined` (module docs), and, when given,
/// against the `twin` run that tells the chaotic ones.
pub fn of_summaries(
    main: &RunSummary,
    refined: &RunSummary,
    twin: Option<&RunSummary>,
    refinement: &str,
) -> Convergence {
    let mut c = Convergence::new(refinement);
    let first = |s: &RunSummary| s.first_impact;
    c.compare(
        "first_impact.t",
        first(main).map(|i| i.t),
        first(refined).map(|i| i.t),
        d::CONVERGENCE_FIRST_IMPACT,
        0.0,
    )
    .compare(
        "first_impact.omega_before",
        first(main).map(|i| i.omega_before),
        first(refined).map(|i| i.omega_before),
        d::CONVERGENCE_FIRST_IMPACT,
        0.0,
    );
    let pairs: [Headline; 7] = [
        ("impacts", |s| s.impacts as f64, d::CONVERGENCE_SPREAD, 1.0),
        (
            "mean_axle_height",
            |s| s.mean_axle_height,
            d::CONVERGENCE_MEAN,
            0.0,
        ),
        (
            "axle_height_oscillation",
            |s| s.axle_height_oscillation,
            d::CONVERGENCE_SPREAD,
            1e-3,
        ),
        ("mean_speed", |s| s.mean_speed, d::CONVERGENCE_MEAN, 1e-3),
        (
            "final_speed",
            |s| s.final_speed,
            d::CONVERGENCE_FINAL_SPEED,
            1e-3,
        ),
        (
            "airborne_fraction",
            |s| s.airborne_fraction,
            d::CONVERGENCE_FRACTION,
            1.0,
        ),
        (
            "slip_fraction",
            |s| s.slip_fraction,
            d::CONVERGENCE_FRACTION,
            1.0,
        ),
    ];
    for (name, get, tolerance, scale) in pairs {
        c.compare(name, Some(get(main)), Some(get(refined)), tolerance, scale);
    }
    if let Some(twin) = twin {
        let values = headline(twin);
        c.twin(|name| values.iter().find(|(n, _)| *n == name).and_then(|v| v.1));
        // counts, heights, magnitudes and fractions: the intervals stay where values can be
        let non_negative = [
            "impacts",
            "mean_axle_height",
            "axle_height_oscillation",
            "final_speed",
        ];
        c.bound(&non_negative, [0.0, f64::INFINITY])
            .bound(&["airborne_fraction", "slip_fraction"], [0.0, 1.0]);
    }
    c
}

/// Stops the refined run once the run itself has stopped early.
struct StopWhen<'a>(&'a AtomicBool);

impl Observer for StopWhen<'_> {
    fn keep_going(&mut self) -> bool {
        !self.0.load(Ordering::Relaxed)
    }
}

/// [`roll_decided`], and with `check` the same decision at the [`refined`] resolution in a
/// second thread: the run's result then carries the [`Convergence`] of its headline quantities
/// and a warning per unconverged one (module docs).
pub fn roll_checked<W>(
    wheel: &W,
    spec: &RunSpec,
    decision: &Decision,
    frame_times: &[f64],
    observer: Option<&mut dyn Observer>,
    check: bool,
) -> Result<Rolled, W::Error>
where
    W: Wheel + Sync,
    W::Error: Send + std::fmt::Display,
{
    if !check {
        return roll_decided(wheel, spec, decision, frame_times, observer);
    }
    let (fine, other) = (refined(spec), twin(spec));
    let stop = AtomicBool::new(false);
    let companion = |run: &RunSpec| {
        let mut watch = StopWhen(&stop);
        roll_decided(wheel, run, decision, &[], Some(&mut watch))
    };
    let (main, refined_run, twin_run) = std::thread::scope(|s| {
        let handle = s.spawn(|| companion(&fine));
        let twin_handle = s.spawn(|| companion(&other));
        let main = roll_decided(wheel, spec, decision, frame_times, observer);
        if !matches!(&main, Ok(m) if m.result.validity.stopped_at.is_none()) {
            stop.store(true, Ordering::Relaxed);
        }
        (main, handle.join(), twin_handle.join())
    });
    let mut main = main?;
    if main.result.validity.stopped_at.is_some() {
        return Ok(main);
    }
    let label = refinement(spec, main.fidelity);
    let twin_summary = match &twin_run {
        Ok(Ok(t)) if t.result.validity.stopped_at.is_none() && t.fidelity == main.fidelity => {
            Some(RunSummary::of(&t.result, spec.t_end))
        }
        _ => None,
    };
    let convergence = match refined_run {
        Ok(Ok(r)) if r.result.validity.stopped_at.is_none() => {
            let a = RunSummary::of(&main.result, spec.t_end);
            let b = RunSummary::of(&r.result, spec.t_end);
            let mut c = of_summaries(&a, &b, twin_summary.as_ref(), label);
            if twin_summary.is_none() {
                c.converged = false;
                c.refinement = format!("{label}; the twin run (start turned by 1e-6 rad) failed");
            }
            if r.fidelity != main.fidelity {
                c.converged = false;
                c.refinement = format!(
                    "{label}; the refined run chose the {} model",
                    r.fidelity.name()
                );
            }
            c
        }
        Ok(Ok(r)) => failed(
            label,
            &format!("it stopped at t = {:?} s", r.result.validity.stopped_at),
        ),
        Ok(Err(e)) => failed(label, &e.to_string()),
        Err(_) => failed(label, "its thread panicked"),
    };
    let v = &mut main.result.validity;
    v.warnings.extend(convergence.warnings());
    v.convergence = Some(convergence);
    Ok(main)
}

/// The convergence of a refined run that gave no result.
fn failed(label: &str, why: &str) -> Convergence {
    let mut c = Convergence::new(format!("{label}: the refined run failed: {why}"));
    c.converged = false;
    c
}
