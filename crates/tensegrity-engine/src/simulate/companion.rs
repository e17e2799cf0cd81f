//! The companion run of `simulate`'s convergence check: at which resolution it runs
//! ([`choose`]), with which documented order its change is extrapolated
//! ([`documented_order`]), and what it cost.
//!
//! **Which companion.** A fixed-step run (rk4, rattle, imex, imex-ark, rk4-flight) is
//! compared with a *coarse* companion at 2 dt (half the run's work) where that step stays
//! well inside the method's stability: 2 dt·λ ≤ [`STABILITY_MARGIN`] × the method's bound
//! ([`stability_bound`]), λ the model's fastest rate
//! ([`tensegrity_dynamics::estimate::fastest_rate`]: the strings' and a penalty ground's
//! stiffness and damping), and 2 dt ≤ t_end. Otherwise, and for the adaptive methods (rk45,
//! sdirk: tolerances / 10, whose change is not a step ratio), the companion is *refined*
//! (dt / 2, twice the work), as before. The margin keeps the coarse run in the regime where
//! its error behaves as C (2 dt)ᵖ: near the edge of the stability region the amplification
//! of the fastest mode, not the truncation error, sets the difference. The coarse companion
//! writes nothing, so it samples nothing: its steps are not cut at the output times, and it
//! runs the clean 2 dt grid (where the run's own steps are cut at sample times they are
//! shorter than dt, and the estimate below only over-states the run's error). So 2 dt may
//! exceed the output interval. Either companion starts from the step the run took (a default
//! step shortened to the interval of the samples a front end writes, too).
//!
//! The implicit parts need accuracy, not stability: the stiff contact of imex (ROS2) and
//! imex-ark (an L-stable ESDIRK) damps whatever step it takes, so only their explicit part
//! (the strings, the ground's spring; RK4 for imex, ARK3's explicit tableau for imex-ark) is
//! held to a bound. λ includes the ground's damping, which those two treat implicitly: a
//! conservative choice (a scene whose ground damping alone sets λ keeps the refined
//! companion). `rk4-flight` takes steps of FLIGHT_RATIO·dt in flight, bounded by the strings
//! alone, and of dt in contact: both are held to the bound with λ (strings and ground), which
//! is again conservative. sdirk is L-stable and adaptive: its companion is refined.
//!
//! **When the coarse run fails.** A coarse run that errs, ends with a state that is not
//! finite or carries a drift warning (an invariant past its limit: the coarse run left the
//! method's stable, accurate regime) is not compared: the refined companion runs after it, on
//! the same thread, and `refinement` says so; the cost is then 2½ runs. This holds also where
//! the run itself drifts: a coarse run that drifts further is a poor companion (the split
//! IMEX on the dropped prism chatters on its creeping contact at 0.5 ms, on 20 % of its
//! contact steps, and at 1 ms on 52 %: its final nodes move 1.1 % from the run's where the
//! run's error against dt/4 is 0.13 %).
//!
//! **Order** ([`documented_order`]): the order p with which a change r becomes an error
//! e = r/(2ᵖ − 1) (coarse) or r·2ᵖ/(2ᵖ − 1) (refined) ([`Convergence`]).
//!
//! **Cost** ([`Convergence::cost`]): ½ for a coarse companion, 2 for a refined one, 2½ for a
//! coarse one that failed and the refined one after it; the companion runs on a thread of its
//! own beside the run.

use tensegrity_core::CoreError;
use tensegrity_dynamics::convergence::Companion;
use tensegrity_dynamics::estimate::fastest_rate;
use tensegrity_dynamics::flight::FLIGHT_RATIO;
use tensegrity_dynamics::{
    Convergence, IntegratorKind, Simulation, SimulationResult, SimulationSettings,
};
use tensegrity_io::scene::Scene;

/// The fraction of a method's stability bound a coarse companion's step may use
/// (2 dt·λ ≤ margin × bound, module docs), and the largest h·λ of each fixed-step method:
/// shared with the rolling checks (`wheel_rolling::convergence`), so defined beside
/// [`Convergence`].
pub use tensegrity_dynamics::convergence::{stability_bound, STABILITY_MARGIN};

/// Whether a run of `simulation` (of `scene`) is smooth: no ground (no landings, no
/// contact switching), no events and no actuation (its tables are piecewise linear in time:
/// kinks in the forcing between grid points).
pub fn smooth(scene: &Scene, simulation: &Simulation) -> bool {
    simulation.model.ground().is_none()
        && simulation.events.is_empty()
        && scene.file.actuation.is_empty()
}

/// The documented order p of `simulate`'s convergence check (module docs), the one place it
/// is chosen: 1 for every run, for three reasons.
///
/// * An adaptive run (rk45, sdirk) refines its tolerances by 10, not its step by 2: its error
///   falls about tenfold, so the refined companion's order-1 rule (e = 2r) over-states it
///   (≈ 1.1 r).
/// * A scene that is not [`smooth`] (a ground, events, actuation) is first order: a landing,
///   a switch of contact or a kink of the forcing falls between grid points.
/// * On a smooth scene the methods' orders (rk4 4, rattle 2, imex 2, imex-ark 3, rk4-flight
///   4: [`IntegratorKind::facts`]) are not borne out on the bundled scenes, measured against
///   a run at dt/4 (`tests/simulate_companion.rs`,
///   `measured_orders_on_the_bundled_examples`; the table in docs/notes/ROLLING.md, "simulate's
///   companion run"): the order observed from the coarse change, log₂(1 + r/error), is 3.5
///   for rk4 on the MOTES D-bar (strings that go slack and taut: kinks of the force between
///   grid points), 1.7 for rk4-flight there (its 5 dt flight steps), 0.7 for rattle there; e
///   at the method's order would under-state the error. With p = 1 e bounds the error in
///   every case but two whose error is far inside τ: RATTLE on the MOTES D-bar (error
///   1.1·10⁻⁵ of L against e = 7.1·10⁻⁶, τ = 10⁻²) and rk4-flight's final velocities on the
///   dropped prism (7.8·10⁻³ against 5.6·10⁻³, τ = 2·10⁻²), where the final state of a
///   structure sliding and rocking on its friction ground moves irregularly with the step
///   (changes of 1–10·10⁻³ at every step from 2 to 0.125 ms: no order is observed).
///
/// With p = 1 a coarse companion's rule (e = r ≤ τ) is the old one (a refined companion's
/// change r ≤ τ/2) at half the step: the change from 2 dt to dt is twice that from dt to dt/2.
///
/// ```
/// use tensegrity_dynamics::IntegratorKind;
/// use tensegrity_engine::simulate::companion::documented_order;
/// assert_eq!(documented_order(IntegratorKind::Rk4, true), 1.0);
/// assert_eq!(documented_order(IntegratorKind::Imex, false), 1.0);
/// ```
pub fn documented_order(kind: IntegratorKind, smooth: bool) -> f64 {
    match (kind.is_adaptive(), smooth) {
        // tolerances / 10: the order-1 rule of a refined companion over-states the error
        (true, _) => 1.0,
        // landings, contact switches, events and actuation between grid points
        (false, false) => 1.0,
        // the methods' own orders are not borne out on the bundled smooth scenes (above)
        (false, true) => 1.0,
    }
}

/// Why a coarse companion at 2 dt does not serve `simulation` (module docs), or `None` when it
/// does.
pub fn coarse_refused(simulation: &Simulation) -> Option<String> {
    let s = &simulation.settings;
    let Some(bound) = stability_bound(s.integrator) else {
        return Some(format!(
            "{} is adaptive: its tolerances are refined",
            s.integrator
        ));
    };
    if 2.0 * s.dt > s.t_end {
        return Some("2 dt exceeds t_end".into());
    }
    // rk4-flight's steps in flight are FLIGHT_RATIO·dt long
    let (ratio, step) = match s.integrator {
        IntegratorKind::Rk4Flight => (f64::from(FLIGHT_RATIO), "its flight step 2·5 dt"),
        _ => (1.0, "2 dt"),
    };
    let reach = 2.0 * ratio * s.dt * fastest_rate(&simulation.model);
    // (a NaN rate refuses it too)
    if reach.is_nan() || reach > STABILITY_MARGIN * bound {
        return Some(format!(
            "{step} times λ, {reach:.3}, exceeds {STABILITY_MARGIN} × {}'s stability bound {bound}",
            s.integrator
        ));
    }
    None
}

/// The companion of `simulation`'s convergence check (module docs): coarse where 2 dt
/// serves ([`coarse_refused`]), else refined.
pub fn choose(simulation: &Simulation) -> Companion {
    match coarse_refused(simulation) {
        None => Companion::Coarse,
        Some(_) => Companion::Refined,
    }
}

/// The coarse resolution of `settings`: the step doubled, no samples (module docs). Returns
/// what changed.
pub fn coarsen(settings: &mut SimulationSettings) -> &'static str {
    settings.dt *= 2.0;
    // it writes nothing: its steps are not cut at sample times
    settings.output_interval = None;
    settings.output_times.clear();
    settings.sample_every_step = false;
    "2 dt"
}

/// Why a coarse companion's result cannot be compared (module docs): its run failed, its
/// final state is not finite, or it drifted; `None` when it can.
pub fn coarse_failure(result: &Result<SimulationResult, CoreError>) -> Option<String> {
    let r = match result {
        Err(e) => return Some(format!("its run failed: {e}")),
        Ok(r) => r,
    };
    let finite = r
        .final_nodes
        .iter()
        .chain(&r.final_velocities)
        .all(|p| p.iter().all(|x| x.is_finite()));
    if !finite {
        return Some("its final state is not finite".into());
    }
    if r.warnings.is_empty() {
        return None;
    }
    let drifted: Vec<String> = r
        .warnings
        .iter()
        .map(|w| {
            let name = serde_json::to_value(w.quantity)
                .ok()
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or_else(|| format!("{:?}", w.quantity));
            format!("{name} {:.3e} > {:.0e}", w.value, w.limit)
        })
        .collect();
    Some(format!("it drifted ({})", drifted.join(", ")))
}

/// An empty convergence of a run against its coarse companion of order `order`.
pub fn coarse(order: f64) -> Convergence {
    Convergence::with("2 dt (coarse companion)", Companion::Coarse, order)
}

/// Why a run's companion is refined (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refined<'a> {
    /// An adaptive run: its tolerances are refined.
    Adaptive,
    /// A fixed step whose 2 dt does not serve ([`coarse_refused`]): why.
    Refused(&'a str),
    /// A coarse companion ran and failed ([`coarse_failure`]): why.
    AfterCoarse(&'a str),
}

/// An empty convergence of a run against its refined companion (`what`: the refinement,
/// [`SimulateCommand::refine`](super::SimulateCommand::refine)) of order `order`, labelled
/// with `why` (an adaptive run's label is its refinement alone, as it always read); a coarse
/// run that failed adds its cost.
pub fn refined(what: &str, order: f64, why: Refined<'_>) -> Convergence {
    let label = match why {
        Refined::Adaptive => what.to_string(),
        Refined::Refused(why) => format!("{what} (refined companion: {why})"),
        Refined::AfterCoarse(why) => {
            format!("{what} (refined companion, run after the coarse one at 2 dt: {why})")
        }
    };
    let mut c = Convergence::with(label, Companion::Refined, order);
    if matches!(why, Refined::AfterCoarse(_)) {
        c.cost += Companion::Coarse.cost();
    }
    c
}
