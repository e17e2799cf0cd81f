//! Convergence of a rolling run ([`roll_checked`]): the run is repeated at a companion
//! resolution, 8, 4 or 2 times the step where that serves ([`coarse_by`],
//! [`coarse_refused_at`]) and else half of it ([`refined`]), from a start turned by 10⁻⁶ rad
//! (the twin's, [`twin`]) in a thread beside the run, and each headline quantity of the two summaries is compared
//! ([`of_summaries`], the rules of [`tensegrity_dynamics::convergence`]). A second run follows
//! only where some quantity moved by more than τ/8 (the lazy twin, below).
//!
//! **Which companion.** The coarse one at k dt (k = 8 for the rigid model alone, an eighth
//! of the run's work; 4 for the full model where 4 dt is within half its default step, a
//! quarter; else 2, half of it; the rules below with k dt for 2 dt; 4 dt, then 2 dt, where
//! 8 dt does not serve) where
//!
//! * k dt is no longer than the 1 ms output interval (both models cut their steps at the
//!   sample times: a longer step would not be the step that runs) nor than t_end;
//! * the rigid model (if the plan runs it): its events (impacts, lift-off, stick–slip, a
//!   neighbour touching) are located by bisection to round-off whatever the step, and its
//!   smooth phases are RK4 steps of a pendulum-like motion whose rates are of order
//!   √(g/R_o) (the pivot's is √(m g R_o/(I₁ + m R_o²)) ≤ √(g/R_o)): k dt·√(g/R_o) ≤
//!   [`STABILITY_MARGIN`] × 2.6, RK4's bound ([`stability_bound`]), which every step the
//!   output interval allows meets (10⁻³ s on R_o = 1 m: 3·10⁻³ against 1.3). Its step error
//!   is round-off either way (the first impact of the default wheel moves by 10⁻¹⁴ of its
//!   time from dt to 2 dt), so 8 dt (⅛ of the run's work) serves as well as 2 dt, and the
//!   order-1 rule e = r/7 only over-states it;
//! * the full model (if the plan runs it): k = 4 at most, and 4 dt within half the default
//!   step (at a quarter of the default step 4 dt reaches the default step, where the error
//!   is not C dtᵖ: on 1 s of the default wheel under IMEX-ARK at 6.25·10⁻⁵ s, 4 dt would
//!   estimate the first impact's ω⁻ 1.3·10⁻³ where dt/2 estimates 3.7·10⁻⁵, the values
//!   below, it under-states the mean speed's error of a 2 s roll, 4.0·10⁻³ against 8.6·10⁻³
//!   at dt/4, and the final speed's after 1 s 4.3-fold, 0.64 % against 2.7 %; at an eighth
//!   and a sixteenth of it, on the 12 rolls below and with their rule, every quantity
//!   reported converged lay within its tolerance of a run at a quarter of the step or
//!   less); a fixed-step integrator other
//!   than the split IMEX
//!   (its creep bias survives a change of its own step: below); 2 dt no longer than the
//!   model's default step for its integrator, contact and strings
//!   ([`crate::defaults::full_dt`]: the
//!   longest step measured to be accurate), since beyond it the error need not behave as
//!   C dtᵖ: on 1 s of the default wheel under IMEX-ARK the first impact's ω⁻ reads 2.1163,
//!   2.1159, 2.1099, 2.1078, 2.1078 rad/s at 5, 2.5, 1.25, 0.625, 0.3125·10⁻⁴ s, so at the
//!   default 2.5·10⁻⁴ s the coarse companion would estimate an error of 2·10⁻⁴ where it is
//!   3.8·10⁻³ (the refined one: 5.6·10⁻³); so a full run gets a coarse companion only at a
//!   step of half its default or less (at 1.25·10⁻⁴ s the same ω⁻ is estimated 2.8·10⁻³ at
//!   2 dt and 2.0·10⁻³ at dt/2, for an error of 1.0·10⁻³); and 2 dt·λ ≤
//!   [`STABILITY_MARGIN`] × the method's bound, λ the fastest rate its explicit part must
//!   resolve ([`FullRolling::explicit_rate`](crate::full::FullRolling::explicit_rate): the
//!   strings and the ground's spring √(2k/m) with m a quarter of the lightest bar; the
//!   ground's dampers too under RK4, RATTLE and rk4-flight, not under IMEX-ARK, which takes
//!   them implicitly). Under RK4 the default 10⁵ N/m ground's critical damper makes
//!   λ = 3.1·10⁴ 1/s (2c/m) on the default wheel, so 2 dt must be within 4·10⁻⁵ s.
//!
//! Otherwise the companion is refined (dt/2, twice the run's work), as before, and the label
//! says why. A coarse run that fails, stops early, or carries a warning of a kind the run
//! does not (it left the regime where its error is a step's: an energy budget that does not
//! close, a drift) is followed by the refined one, and its half run is added to the cost.
//!
//! **The lazy twin.** The companion starts from the twin's start, so its change r of a
//! quantity holds both the step's bias and the start's effect
//! ([`tensegrity_dynamics::convergence`], "The lazy twin"). Where every quantity has r ≤ τ/8,
//! every one is converged and none chaotic, and nothing more runs: the check costs 1/k
//! (coarse: ⅛ rigid, ½ full) or 2 (refined). A step change alone would not do: the rigid
//! model's error at its step is
//! 10⁻¹⁴ of the first impact's time, far below the twin's 5·10⁻⁷, and on the default n = 8
//! wheel on 50° the impact count agreed at dt and dt/2 (16) while the twin's was 17. Where some
//! quantity moved by more than τ/8, a second run separates the two effects: with a coarse
//! companion the companion again at k dt from the run's own start (1/k), the first run then
//! being the twin, compared with it at the same step (cost 2/k in all: ¼ rigid, ½ full at 4 dt, 1 at 2 dt); with
//! a refined one the
//! twin at the run's step (1, compared with the run: cost 3 in all, the refined companion
//! keeping the turned start, whose effect on a quantity that is not chaotic is at most τ/8).
//! The two runs (or the run and the twin) are then three draws, and a chaotic quantity gets
//! its prediction interval as before.
//!
//! **A coarse estimate past its tolerance.** The order-1 rule over-states the error of a
//! method of higher order, and the coarse companion's more than the refined one's (on 1 s of
//! the default wheel under IMEX-ARK at 1.25·10⁻⁴ s the mean speed's error, 2.2·10⁻⁴ against a
//! run at dt/4, is estimated 1.1·10⁻³ at 2 dt and 6.6·10⁻⁴ at dt/2). Where a quantity that
//! is not chaotic is past its tolerance at k dt, the check of a refined companion runs after
//! the coarse one and decides ([`escalated`]): the refined companion (dt/2, from the run's
//! start) and the twin at the run's step, in two threads, as without a coarse companion,
//! whose verdicts replace the coarse check's (the two twins need not agree: each is one draw
//! of a chaotic quantity's sensitivity). Such a run costs 3 + 2/k runs (4 for the full
//! model, ½ + ½ + 2 + 1) where it cost 3; a run whose quantities hold at k dt costs 1/k or
//! 2/k.
//!
//! **A coarse estimate near its tolerance (the full model).** Through a contact event the
//! full model's error need not shrink from k dt to dt: an instantaneous value after an
//! impact can land as close to the right one at k dt as at dt, and then r under-states the
//! run's error. Over 12 full rolls (n = 8, 12, 24 on 15°–50°, 1 and 2 s) at 1.25·10⁻⁴,
//! 6.25·10⁻⁵ and 3.125·10⁻⁵ s, against runs at 3.9·10⁻⁶ s (7.8·10⁻⁶ s for three 2 s rolls
//! of the n = 12 and 24 wheels), the estimate at 2 dt of a
//! quantity that is not chaotic under-stated its error up to 2.7-fold and the refined one at
//! most 1.7-fold, and once the coarse rule called converged what was not: the default wheel's
//! final speed after 1 s at 6.25·10⁻⁵ s, estimated 1.4 % (within its 2 %) and 2.7 % off. So
//! the full model's coarse estimate decides only a quantity it puts within
//! [`FULL_COARSE_DECIDES`] (½) of its tolerance; one between τ/2 and τ goes to the refined
//! check as one past τ does ([`undecided`]). With that rule no quantity of those 12 rolls
//! at those steps and at 1.5625·10⁻⁵ s (432 verdicts) was reported converged and found
//! beyond its tolerance. The rigid model's events are located to round-off and keep the rule
//! at τ.
//!
//! **What is refined.** The step only (refined or coarse): the ground's stiffness and
//! damping are the model's (a penalty ground is a soft ground the user chose; its
//! `max_penetration` is a validity figure). Doubling the stiffness with the step, as before 2026-12-06, measured a different
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
//! step is given): two methods that agree within τ, or a bias reported as not converged. For
//! the same reason a split-IMEX run gets no coarse companion.
//!
//! **Order.** p = 1 (every fixed-step scheme is first order through a landing): the error
//! of a value is estimated as its change at k times the step (e = r/(kᵖ − 1)), or twice its
//! change at half the step (e = r·2ᵖ/(2ᵖ − 1)), and it is `converged` when that is within its
//! tolerance τ.
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
//! The check costs 1/k of the run's work with a coarse companion at k dt and no twin, 2/k
//! with the second run at k dt, 3 + 2/k when the refined check runs after that; 2 with a
//! refined companion and 3 with its twin, and 1/k more after a coarse run that failed
//! ([`Convergence::cost`]); the
//! first companion runs on a thread beside the run,
//! the second after both. An unconverged quantity that is not chaotic adds a warning, so the
//! run is not `valid`. A run that stopped early (interrupted, or its integration failed) is
//! not compared; a companion or second run that failed makes the result unconverged, with
//! the failure in the label.

use crate::contact::ContactKind;
use crate::defaults as d;
use crate::error::RollingError;
use crate::fidelity::{Decision, Fidelity, Plan};
use crate::full::{FullRolling, WheelScene};
use crate::observer::Observer;
use crate::rigid::Polygon;
use crate::run::{roll_decided, Rolled, Wheel};
use crate::settings::RunSpec;
use crate::summary::{headline, RunSummary};
use nalgebra::Vector3;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use tensegrity_dynamics::convergence::{
    stability_bound, Companion, STABILITY_MARGIN, TWIN_PERTURBATION,
};
use tensegrity_dynamics::flight::FLIGHT_RATIO;
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

/// The coarse run of `spec`: twice the step of either model, where [`coarse_refused`] says it
/// serves (module docs).
///
/// ```
/// use wheel_rolling::{convergence::coarse, RunSpec};
/// let c = coarse(&RunSpec::default());
/// assert_eq!((c.step_scale, c.rigid_dt()), (2.0, 2e-4));
/// ```
pub fn coarse(spec: &RunSpec) -> RunSpec {
    coarse_by(spec, Companion::Coarse)
}

/// The run of `spec` at the coarse `companion`'s step (2, 4 or 8 dt) of either model.
///
/// ```
/// use tensegrity_dynamics::convergence::Companion;
/// use wheel_rolling::{convergence::coarse_by, RunSpec};
/// let c = coarse_by(&RunSpec::default(), Companion::Coarser);
/// assert_eq!((c.step_scale, c.rigid_dt()), (4.0, 4e-4));
/// ```
pub fn coarse_by(spec: &RunSpec, companion: Companion) -> RunSpec {
    let mut r = *spec;
    r.step_scale *= companion.step_ratio();
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

/// Why a coarse companion (2 dt) does not serve a run of `spec` whose plan is `plan` on the
/// wheel `polygon`, judged before any run (module docs: the output interval, t_end, the
/// rigid model's rate, the full model's integrator); `None` when it may. The full model's
/// rate needs its scene and is judged when the coarse run builds it
/// ([`coarse_refused_full`]).
///
/// ```
/// use tensegrity_dynamics::IntegratorKind;
/// use wheel_rolling::fidelity::Plan;
/// use wheel_rolling::{convergence::coarse_refused, Polygon, RollSettings, RunSpec};
/// let octagon = Polygon { sides: 8, outer_radius: 1.0, mass: 12.0, i1: 7.5 };
/// assert_eq!(coarse_refused(&RunSpec::default(), Plan::Rigid, &octagon), None);
/// // 2 dt past the 1 ms output interval would not be the step that runs
/// let long = RunSpec {
///     settings: RollSettings { dt: Some(8e-4), ..RollSettings::default() },
///     ..RunSpec::default()
/// };
/// assert!(coarse_refused(&long, Plan::Rigid, &octagon).unwrap().contains("output interval"));
/// let split = RunSpec { integrator: IntegratorKind::Imex, ..RunSpec::default() };
/// assert!(coarse_refused(&split, Plan::Full, &octagon).unwrap().contains("imex"));
/// ```
pub fn coarse_refused(spec: &RunSpec, plan: Plan, polygon: &Polygon) -> Option<String> {
    coarse_refused_at(spec, plan, polygon, Companion::Coarse)
}

/// As [`coarse_refused`] for the coarse `companion` (2, 4 or 8 dt: k dt in each rule; the
/// full model's at most 4 dt, and 4 dt within half its default step, module docs).
///
/// ```
/// use tensegrity_dynamics::convergence::Companion;
/// use wheel_rolling::fidelity::Plan;
/// use wheel_rolling::{convergence::coarse_refused_at, Polygon, RollSettings, RunSpec};
/// let octagon = Polygon { sides: 8, outer_radius: 1.0, mass: 12.0, i1: 7.5 };
/// let rigid = |c| coarse_refused_at(&RunSpec::default(), Plan::Rigid, &octagon, c);
/// assert_eq!(rigid(Companion::Coarser), None);
/// // at 3·10⁻⁴ s, 4 dt passes the 1 ms output interval and 2 dt does not
/// let long = RunSpec {
///     settings: RollSettings { dt: Some(3e-4), ..RollSettings::default() },
///     ..RunSpec::default()
/// };
/// let at = |c| coarse_refused_at(&long, Plan::Rigid, &octagon, c);
/// assert!(at(Companion::Coarser).unwrap().contains("4 dt"));
/// assert_eq!(at(Companion::Coarse), None);
/// ```
pub fn coarse_refused_at(
    spec: &RunSpec,
    plan: Plan,
    polygon: &Polygon,
    companion: Companion,
) -> Option<String> {
    let (k, label) = (companion.step_ratio(), companion.step_label());
    if k > 4.0 && plan.may_run_full() {
        return Some(format!(
            "the full model's coarse companion is at most 4 dt, not {label} (module docs)"
        ));
    }
    let steps = |dt: f64, model: &str| {
        if k * dt > spec.output_dt {
            Some(format!(
                "the {model} model's {label}, {:.3e} s, exceeds the output interval {} s",
                k * dt,
                spec.output_dt
            ))
        } else if k * dt > spec.t_end {
            Some(format!("{label} exceeds t_end"))
        } else {
            None
        }
    };
    if plan.runs_rigid() {
        let dt = spec.rigid_dt();
        if let Some(why) = steps(dt, "rigid") {
            return Some(why);
        }
        let rate = (spec.settings.gravity / polygon.outer_radius).sqrt();
        let reach = k * dt * rate;
        let bound = STABILITY_MARGIN * 2.6;
        if reach.is_nan() || reach > bound {
            return Some(format!(
                "the rigid model's {label} times sqrt(g/R_o), {reach:.3}, exceeds {bound}"
            ));
        }
    }
    if plan.may_run_full() {
        if spec.integrator == IntegratorKind::Imex {
            return Some(
                "imex is checked against imex-ark at dt/2 (its creep bias survives a change of its own step)"
                    .into(),
            );
        }
        if stability_bound(spec.integrator).is_none() {
            return Some(format!(
                "{} is adaptive: its largest step is refined",
                spec.integrator
            ));
        }
        let dt = spec.full_dt();
        if let Some(why) = steps(dt, "full") {
            return Some(why);
        }
        let default = d::full_dt(
            spec.integrator,
            spec.contact,
            spec.settings.string_stiffness,
        );
        // 2 dt may reach the default step, 4 dt half of it (module docs)
        let reach = if k > 2.0 { 0.5 * default } else { default };
        if k * dt > reach * (1.0 + 1e-12) {
            let what = if k > 2.0 {
                "half its default step"
            } else {
                "its default step"
            };
            return Some(format!(
                "the full model's {label}, {:.3e} s, exceeds {what} {reach:.3e} s under {}, the longest measured to be accurate",
                k * dt,
                spec.integrator
            ));
        }
    }
    None
}

/// Why the full model's coarse run (`coarse`, its spec at the `companion`'s step) does not
/// serve on the wheel of `scene`: k dt·λ past [`STABILITY_MARGIN`] × its
/// integrator's bound, λ [`FullRolling::explicit_rate`] (module docs); `None` when it does.
pub fn coarse_refused_full(
    coarse: &RunSpec,
    scene: &WheelScene,
    companion: Companion,
) -> Option<String> {
    let label = companion.step_label();
    let model = FullRolling::new(coarse, &scene.polygon());
    let Some(bound) = stability_bound(model.integrator) else {
        return Some(format!("{} is adaptive", model.integrator));
    };
    let rate = match model.explicit_rate(scene) {
        Ok(rate) => rate,
        Err(e) => return Some(format!("its fastest rate is unknown: {e}")),
    };
    // rk4-flight's steps in flight are FLIGHT_RATIO·dt long
    let (ratio, step) = match model.integrator {
        IntegratorKind::Rk4Flight => (
            f64::from(FLIGHT_RATIO),
            format!(
                "its flight step {}·{FLIGHT_RATIO} dt",
                companion.step_ratio()
            ),
        ),
        _ => (1.0, label.to_string()),
    };
    let reach = ratio * model.dt * rate;
    // (a NaN rate refuses it too)
    if reach.is_nan() || reach > STABILITY_MARGIN * bound {
        return Some(format!(
            "{step} times λ, {reach:.3}, exceeds {STABILITY_MARGIN} × {}'s stability bound {bound}",
            model.integrator
        ));
    }
    None
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

/// What [`coarse_by`] changed for a run of `fidelity` at the coarse `companion`.
pub fn coarsening(spec: &RunSpec, fidelity: Fidelity, companion: Companion) -> String {
    let step = companion.step_label();
    match (fidelity, spec.contact) {
        (Fidelity::Full, ContactKind::Penalty | ContactKind::Stick) => {
            format!("{step} (coarse companion; the ground's stiffness is the model's)")
        }
        _ => format!("{step} (coarse companion)"),
    }
}

/// A headline quantity: its key, how to read it, its tolerance and its scale floor.
type Headline = (&'static str, fn(&RunSummary) -> f64, f64, f64);

/// The headline quantities of `main` against `refined` (a refined companion, module docs),
/// and, when given, against the `twin` run (at the run's step) that tells the chaotic ones.
pub fn of_summaries(
    main: &RunSummary,
    refined: &RunSummary,
    twin: Option<&RunSummary>,
    refinement: &str,
) -> Convergence {
    let mut c = compared(
        main,
        refined,
        Convergence::with(refinement, Companion::Refined, 1.0),
    );
    if let Some(twin) = twin {
        let values = headline(twin);
        c.twin(|name| values.iter().find(|(n, _)| *n == name).and_then(|v| v.1));
        bound_intervals(&mut c);
    }
    c
}

/// The headline quantities of `main` against `companion` (module docs), into the empty `c`.
fn compared(main: &RunSummary, companion: &RunSummary, mut c: Convergence) -> Convergence {
    let first = |s: &RunSummary| s.first_impact;
    c.compare(
        "first_impact.t",
        first(main).map(|i| i.t),
        first(companion).map(|i| i.t),
        d::CONVERGENCE_FIRST_IMPACT,
        0.0,
    )
    .compare(
        "first_impact.omega_before",
        first(main).map(|i| i.omega_before),
        first(companion).map(|i| i.omega_before),
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
        c.compare(
            name,
            Some(get(main)),
            Some(get(companion)),
            tolerance,
            scale,
        );
    }
    c
}

/// Counts, heights, magnitudes and fractions: the intervals stay where values can be.
fn bound_intervals(c: &mut Convergence) {
    let non_negative = [
        "impacts",
        "mean_axle_height",
        "axle_height_oscillation",
        "final_speed",
    ];
    c.bound(&non_negative, [0.0, f64::INFINITY])
        .bound(&["airborne_fraction", "slip_fraction"], [0.0, 1.0]);
}

/// The convergence of `main` against a `companion` of the given resolution, both summaries,
/// with the lazy twin's rule (module docs): `second` runs the second run when some quantity
/// moved by more than τ/8 (the companion at 2 dt from the run's start where the companion is
/// coarse, else the twin at the run's step) and gives its summary, or why it has none.
pub fn of_companion(
    main: &RunSummary,
    companion: &RunSummary,
    kind: Companion,
    label: &str,
    second: impl FnOnce() -> Result<RunSummary, String>,
) -> Convergence {
    let empty = |label: String| Convergence::with(label, kind, 1.0);
    let c = compared(main, companion, empty(label.to_string()));
    if !c.twin_needed() {
        let mut c = c;
        c.refinement = format!(
            "{label}, from a start turned by {TWIN_PERTURBATION:e} rad; no quantity moved by an eighth of its tolerance: no twin"
        );
        return c;
    }
    match (kind, second()) {
        (Companion::Coarse | Companion::Coarser | Companion::Coarsest, Ok(clean)) => {
            // the clean run is the companion, the first one the twin at its step
            let mut c = compared(
                main,
                &clean,
                empty(format!(
                    "{label}; twin at {} from a start turned by {TWIN_PERTURBATION:e} rad",
                    kind.step_label()
                )),
            );
            let values = headline(companion);
            c.twin_of_companion(|name| values.iter().find(|(n, _)| *n == name).and_then(|v| v.1));
            bound_intervals(&mut c);
            c
        }
        (Companion::Refined, Ok(twin)) => {
            let mut c = compared(
                main,
                companion,
                empty(format!(
                    "{label}, from a start turned by {TWIN_PERTURBATION:e} rad; twin at dt"
                )),
            );
            let values = headline(&twin);
            c.twin(|name| values.iter().find(|(n, _)| *n == name).and_then(|v| v.1));
            bound_intervals(&mut c);
            c
        }
        (kind, Err(why)) => {
            let mut c = c;
            c.converged = false;
            c.cost += match kind {
                Companion::Coarse | Companion::Coarser | Companion::Coarsest => kind.cost(),
                Companion::Refined => 1.0,
            };
            c.refinement = format!(
                "{label}, from a start turned by {TWIN_PERTURBATION:e} rad; the second run failed: {why}"
            );
            c
        }
    }
}

/// Stops the companion runs once the run itself has stopped early, or once the run's
/// observer's [`Observer::stop_flag`] is set (a Ctrl-C during a run after the run).
struct StopWhen<'a>(&'a AtomicBool, Option<&'static AtomicBool>);

impl Observer for StopWhen<'_> {
    fn keep_going(&mut self) -> bool {
        !self.0.load(Ordering::Relaxed) && !self.1.is_some_and(|f| f.load(Ordering::Relaxed))
    }
}

/// A wheel whose full model refuses to run at a step its explicit part does not resolve
/// ([`coarse_refused_full`]), saying why in `refused`: the coarse companion's guard.
struct Guarded<'a, W> {
    wheel: &'a W,
    spec: RunSpec,
    companion: Companion,
    refused: Mutex<Option<String>>,
}

impl<W: Wheel> Wheel for Guarded<'_, W> {
    type Error = W::Error;

    fn polygon(&self) -> Polygon {
        self.wheel.polygon()
    }

    fn start_pose(&self) -> Vec<Vector3<f64>> {
        self.wheel.start_pose()
    }

    fn scene(&self) -> Result<WheelScene, W::Error> {
        let scene = self.wheel.scene()?;
        match coarse_refused_full(&self.spec, &scene, self.companion) {
            None => Ok(scene),
            Some(why) => {
                let e = RollingError::invalid("dt", self.spec.full_dt(), why.clone());
                if let Ok(mut r) = self.refused.lock() {
                    *r = Some(why);
                }
                Err(e.into())
            }
        }
    }
}

/// Why the companion is refined (module docs).
enum WhyRefined {
    /// Before any run ([`coarse_refused`]) or when its full model was built
    /// ([`coarse_refused_full`]).
    Refused(String),
    /// The coarse run (2 dt or 4 dt) failed or left its regime ([`coarse_failure`]).
    AfterCoarse(Companion, String),
}

/// Why a coarse companion's result cannot be compared with `main` (module docs): its run
/// failed, stopped early, or carries a warning of a kind the run does not; `None` when it
/// can.
fn coarse_failure<E: std::fmt::Display>(
    main: &Rolled,
    coarse: &Result<Rolled, E>,
) -> Option<String> {
    let r = match coarse {
        Err(e) => return Some(format!("its run failed: {e}")),
        Ok(r) => r,
    };
    if let Some(t) = r.result.validity.stopped_at {
        return Some(format!("it stopped at t = {t} s"));
    }
    let kinds: Vec<&str> = main
        .result
        .validity
        .warnings
        .iter()
        .map(|w| w.kind())
        .collect();
    let new: Vec<String> = r
        .result
        .validity
        .warnings
        .iter()
        .filter(|w| !kinds.contains(&w.kind()))
        .map(|w| w.to_string())
        .collect();
    if new.is_empty() {
        None
    } else {
        Some(format!(
            "it carries warnings the run does not: {}",
            new.join("; ")
        ))
    }
}

/// [`roll_decided`], and with `check` the same decision at a companion resolution (module
/// docs: coarse where it serves, else refined; from the twin's start) in a second thread,
/// then, where some quantity moved by more than τ/8, a second run: the run's result then
/// carries the [`Convergence`] of its headline quantities and a warning per unconverged one.
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
    let stop = AtomicBool::new(false);
    let external = observer.as_ref().and_then(|o| o.stop_flag());
    let companion = |run: &RunSpec| {
        let mut watch = StopWhen(&stop, external);
        roll_decided(wheel, run, decision, &[], Some(&mut watch))
    };
    // the first companion, from the twin's start: coarse where it serves, else refined
    // (the coarsest that serves: 4 dt, else 2 dt; the reason 2 dt does not, else)
    let first = || -> (Companion, Option<WhyRefined>, Result<Rolled, W::Error>) {
        let mut why_not = String::new();
        for kind in Companion::COARSE {
            if let Some(why) = coarse_refused_at(spec, decision.plan, &wheel.polygon(), kind) {
                why_not = why;
                continue;
            }
            let guarded = Guarded {
                wheel,
                spec: coarse_by(spec, kind),
                companion: kind,
                refused: Mutex::new(None),
            };
            let mut watch = StopWhen(&stop, external);
            let run = roll_decided(
                &guarded,
                &twin(&guarded.spec),
                decision,
                &[],
                Some(&mut watch),
            );
            match guarded.refused.into_inner().ok().flatten() {
                Some(why) => why_not = why,
                None => return (kind, None, run),
            }
        }
        (
            Companion::Refined,
            Some(WhyRefined::Refused(why_not)),
            companion(&twin(&refined(spec))),
        )
    };
    let (main, first_run) = std::thread::scope(|s| {
        let handle = s.spawn(first);
        let main = roll_decided(wheel, spec, decision, frame_times, observer);
        if !matches!(&main, Ok(m) if m.result.validity.stopped_at.is_none()) {
            stop.store(true, Ordering::Relaxed);
        }
        (main, handle.join())
    });
    let main = main?;
    if main.result.validity.stopped_at.is_some() {
        return Ok(main);
    }
    let Ok((mut kind, mut why, mut run)) = first_run else {
        return Ok(attach(main, failed("the companion", "its thread panicked")));
    };
    if kind != Companion::Refined {
        if let Some(failure) = coarse_failure(&main, &run) {
            why = Some(WhyRefined::AfterCoarse(kind, failure));
            kind = Companion::Refined;
            run = companion(&twin(&refined(spec)));
        }
    }
    let base = match kind {
        Companion::Coarse | Companion::Coarser | Companion::Coarsest => {
            coarsening(spec, main.fidelity, kind)
        }
        Companion::Refined => {
            let what = refinement(spec, main.fidelity);
            match &why {
                None => what.to_string(),
                Some(WhyRefined::Refused(why)) => format!("{what} (refined companion: {why})"),
                Some(WhyRefined::AfterCoarse(coarse, why)) => format!(
                    "{what} (refined companion, run after the coarse one at {}: {why})",
                    coarse.step_label()
                ),
            }
        }
    };
    let after_coarse = match &why {
        Some(WhyRefined::AfterCoarse(coarse, _)) => coarse.cost(),
        _ => 0.0,
    };
    let convergence = match run {
        Ok(r) if r.result.validity.stopped_at.is_none() => {
            let a = RunSummary::of(&main.result, spec.t_end);
            let b = RunSummary::of(&r.result, spec.t_end);
            let second_spec = match kind {
                Companion::Coarse | Companion::Coarser | Companion::Coarsest => {
                    coarse_by(spec, kind)
                }
                Companion::Refined => twin(spec),
            };
            let main_fidelity = main.fidelity;
            let second = || match companion(&second_spec) {
                Ok(s) if s.result.validity.stopped_at.is_some() => Err(format!(
                    "it stopped at t = {:?} s",
                    s.result.validity.stopped_at
                )),
                Ok(s) if s.fidelity != main_fidelity => {
                    Err(format!("it chose the {} model", s.fidelity.name()))
                }
                Ok(s) => Ok(RunSummary::of(&s.result, spec.t_end)),
                Err(e) => Err(e.to_string()),
            };
            let mut c = of_companion(&a, &b, kind, &base, second);
            if r.fidelity != main.fidelity {
                c.converged = false;
                c.refinement = format!(
                    "{base}; the companion run chose the {} model",
                    r.fidelity.name()
                );
            } else if kind != Companion::Refined && !undecided(&c, main.fidelity).is_empty() {
                // the coarse estimate exceeds a tolerance (the full model's: half of it):
                // the refined companion and the twin at the run's step decide, as without a
                // coarse one (module docs)
                let what = refinement(spec, main.fidelity);
                let (fine, other) = (refined(spec), twin(spec));
                let (f, t) = std::thread::scope(|s| {
                    let t = s.spawn(|| companion(&other));
                    (companion(&fine), t.join())
                });
                let usable = |run: &Result<Rolled, W::Error>| match run {
                    Ok(r)
                        if r.result.validity.stopped_at.is_none()
                            && r.fidelity == main.fidelity =>
                    {
                        Some(RunSummary::of(&r.result, spec.t_end))
                    }
                    _ => None,
                };
                let twin_summary = t.ok().as_ref().and_then(usable);
                c = match usable(&f) {
                    Some(f) => escalated(&a, &f, twin_summary.as_ref(), &c, main.fidelity, what),
                    None => {
                        let mut c = c;
                        c.converged = false;
                        c.cost += Companion::Refined.cost() + 1.0;
                        c.refinement = format!("{}; the refined run after it failed", c.refinement);
                        c
                    }
                };
            }
            c
        }
        Ok(r) => failed(
            &base,
            &format!("it stopped at t = {:?} s", r.result.validity.stopped_at),
        ),
        Err(e) => failed(&base, &e.to_string()),
    };
    let mut convergence = convergence;
    convergence.cost += after_coarse;
    Ok(attach(main, convergence))
}

/// The fraction of its tolerance τ within which the full model's coarse estimate decides a
/// quantity (module docs, "A coarse estimate near its tolerance"): one it puts between
/// τ/2 and τ is checked again at dt/2. Over 12 rolls (n = 8, 12, 24 on 15°–50°, 1 and 2 s)
/// at 1.25·10⁻⁴, 6.25·10⁻⁵ and 3.125·10⁻⁵ s, the error at 2 dt of a quantity that is not
/// chaotic reached 1.9 times its estimate where that decided (the final speed of the
/// default wheel after 1 s at 6.25·10⁻⁵ s: estimated 1.4 %, 2.7 % off a run at 3.9·10⁻⁶ s).
pub const FULL_COARSE_DECIDES: f64 = 0.5;

/// The quantities a coarse check `c` of a run of `fidelity` does not decide (module docs):
/// past their tolerance, and for the full model converged beyond
/// [`FULL_COARSE_DECIDES`] of it.
///
/// ```
/// use tensegrity_dynamics::{convergence::Companion, Convergence};
/// use wheel_rolling::{convergence::undecided, Fidelity};
/// let mut c = Convergence::with("2 dt", Companion::Coarse, 1.0);
/// c.compare("mean_speed", Some(1.0), Some(1.015), 0.02, 0.0);
/// assert!(undecided(&c, Fidelity::Rigid).is_empty());
/// assert_eq!(undecided(&c, Fidelity::Full), ["mean_speed"]);
/// ```
pub fn undecided(c: &Convergence, fidelity: Fidelity) -> Vec<&str> {
    use tensegrity_dynamics::convergence::Status;
    let margin = match fidelity {
        Fidelity::Full => FULL_COARSE_DECIDES,
        _ => 1.0,
    };
    c.quantities
        .iter()
        .filter(|q| match q.status {
            Status::NotConverged => true,
            Status::Converged => q.estimated_error.is_some_and(|e| e > margin * q.tolerance),
            Status::Chaotic => false,
        })
        .map(|q| q.name.as_str())
        .collect()
}

/// The convergence of `main` against its `refined` companion (dt/2) and its `twin` at the
/// run's step, run after the coarse check `coarse` of a run of `fidelity` left a quantity
/// [`undecided`] (module docs): [`of_summaries`], as without a coarse companion, whose
/// verdicts replace the coarse check's; the cost both checks'.
pub fn escalated(
    main: &RunSummary,
    refined: &RunSummary,
    twin: Option<&RunSummary>,
    coarse: &Convergence,
    fidelity: Fidelity,
    what: &str,
) -> Convergence {
    let past = match fidelity {
        Fidelity::Full => "past half its tolerance",
        _ => "past its tolerance",
    };
    let label = format!(
        "{what} (refined companion and twin at dt, run after the coarse check at {} found {} {past})",
        coarse.companion.step_label(),
        undecided(coarse, fidelity).join(", ")
    );
    let mut c = of_summaries(main, refined, twin, &label);
    if twin.is_none() {
        c.converged = false;
        c.refinement = format!("{label}; the twin run (start turned by 1e-6 rad) failed");
    }
    c.cost += coarse.cost;
    c
}

/// `main` with `convergence` and its warnings.
fn attach(mut main: Rolled, convergence: Convergence) -> Rolled {
    let v = &mut main.result.validity;
    v.warnings.extend(convergence.warnings());
    v.convergence = Some(convergence);
    main
}

/// The convergence of a companion run that gave no result.
fn failed(label: &str, why: &str) -> Convergence {
    let mut c = Convergence::new(format!("{label}: the companion run failed: {why}"));
    c.converged = false;
    c
}
