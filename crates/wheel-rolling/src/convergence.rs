//! Convergence of a rolling run ([`roll_checked`]): the run is repeated at a refined
//! resolution ([`refined`]: half the step of either model, and for the full model's penalty
//! contact twice the ground stiffness, its damping following from the restitution unless
//! given), in a second thread beside the run itself, and each headline quantity of the two
//! summaries is compared ([`of_summaries`], the rule of
//! [`tensegrity_dynamics::convergence`]: converged when it moves by at most half its
//! tolerance).
//!
//! The headline quantities and their tolerances τ ([`crate::defaults`]): `first_impact.t` and
//! `first_impact.omega_before` 1 %; `mean_speed`, `mean_axle_height` 2 %; `final_speed` 2 %;
//! `axle_height_oscillation` and `impacts` 10 %; `airborne_fraction` and `slip_fraction` 0.02
//! absolute. `max_reaction` is not checked: the peak of a penalty force grows with √k.
//!
//! An unconverged quantity adds a warning, so the run is not `valid`. A run that stopped
//! early (interrupted, or its integration failed) is not compared; a refined run that failed
//! makes the result unconverged, with the failure in the warning.

use crate::contact::ContactKind;
use crate::defaults as d;
use crate::fidelity::{Decision, Fidelity};
use crate::observer::Observer;
use crate::run::{roll_decided, Rolled, Wheel};
use crate::settings::RunSpec;
use crate::summary::RunSummary;
use std::sync::atomic::{AtomicBool, Ordering};
use tensegrity_dynamics::Convergence;

/// The refined run of `spec`: half the step; with a penalty contact also twice the ground
/// stiffness (used by the full model only).
pub fn refined(spec: &RunSpec) -> RunSpec {
    let mut r = *spec;
    r.step_scale *= 0.5;
    if spec.contact.is_penalty() {
        r.settings.ground_stiffness *= 2.0;
    }
    r
}

/// What [`refined`] changed for a run of `fidelity`.
pub fn refinement(spec: &RunSpec, fidelity: Fidelity) -> &'static str {
    match (fidelity, spec.contact) {
        (Fidelity::Full, ContactKind::Penalty | ContactKind::Stick) => "dt/2, ground stiffness x2",
        _ => "dt/2",
    }
}

/// A headline quantity: its key, how to read it, its tolerance and its scale floor.
type Headline = (&'static str, fn(&RunSummary) -> f64, f64, f64);

/// The headline quantities of `main` against `refined` (module docs).
pub fn of_summaries(main: &RunSummary, refined: &RunSummary, refinement: &str) -> Convergence {
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
    let fine = refined(spec);
    let stop = AtomicBool::new(false);
    let (main, refined_run) = std::thread::scope(|s| {
        let handle = s.spawn(|| {
            let mut watch = StopWhen(&stop);
            roll_decided(wheel, &fine, decision, &[], Some(&mut watch))
        });
        let main = roll_decided(wheel, spec, decision, frame_times, observer);
        if !matches!(&main, Ok(m) if m.result.validity.stopped_at.is_none()) {
            stop.store(true, Ordering::Relaxed);
        }
        (main, handle.join())
    });
    let mut main = main?;
    if main.result.validity.stopped_at.is_some() {
        return Ok(main);
    }
    let label = refinement(spec, main.fidelity);
    let convergence = match refined_run {
        Ok(Ok(r)) if r.result.validity.stopped_at.is_none() => {
            let a = RunSummary::of(&main.result, spec.t_end);
            let b = RunSummary::of(&r.result, spec.t_end);
            let mut c = of_summaries(&a, &b, label);
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
