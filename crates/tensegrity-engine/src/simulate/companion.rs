//! The companion run of `simulate`'s convergence check: at which resolution it runs
//! ([`choose`]), with which documented order its change is extrapolated
//! ([`documented_order`]), and what it cost.
//!
//! **Which companion.** A fixed-step run (rk4, rattle, imex, imex-ark, rk4-flight) is
//! compared with a *coarse* companion at k dt, the coarsest of 4 dt (a quarter of the run's
//! work) and 2 dt (half of it) whose step stays well inside the method's stability: k dt·λ ≤
//! [`STABILITY_MARGIN`] × the method's bound ([`stability_bound`]), λ the model's fastest rate
//! ([`tensegrity_dynamics::estimate::fastest_rate`]: the strings' and a penalty ground's
//! stiffness and damping), and k dt ≤ t_end ([`coarse_refused_at`], [`choose`]). Otherwise,
//! and for the adaptive methods (rk45, sdirk: tolerances / 10, whose change is not a step
//! ratio), the companion is *refined* (dt / 2, twice the work), as before 2026-12-07 every
//! coarse one was 2 dt. The margin keeps the coarse run in the regime where
//! its error behaves as C (k dt)ᵖ: near the edge of the stability region the amplification
//! of the fastest mode, not the truncation error, sets the difference. The coarse companion
//! writes nothing, so it samples nothing: its steps are not cut at the output times, and it
//! runs the clean k dt grid (where the run's own steps are cut at sample times they are
//! shorter than dt, and the estimate below only over-states the run's error). So k dt may
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
//! **A 4 dt estimate past its tolerance.** The order-1 rule (below) over-states the error of
//! a higher-order method, the more the coarser the companion: on the double pendulum under
//! RK4 e is 85 times the error against dt/8 at 4 dt, 15 times at 2 dt. Where a quantity's e
//! exceeds its tolerance at 4 dt, the companion runs again at 2 dt after the run
//! (`SimulateCommand::run_beside`), and its verdict stands: `refinement` names the quantity and
//! the cost is ¾ (a 2 dt run that fails or drifts leaves the 4 dt verdict, its label saying
//! so). (RATTLE on the MOTES prism: the final velocities' e is 6.6 % at 4 dt and
//! 4.8 % at 2 dt against τ = 2 %; not converged either way.)
//!
//! **When the coarse run fails.** A coarse run that errs, ends with a state that is not
//! finite or carries a drift warning (an invariant past its limit: the coarse run left the
//! method's stable, accurate regime) is not compared: the refined companion runs after it, on
//! the same thread, and `refinement` says so; the cost is then 2¼ or 2½ runs. This holds also where
//! the run itself drifts: a coarse run that drifts further is a poor companion (the split
//! IMEX on the dropped prism chatters on its creeping contact at 0.5 ms, on 20 % of its
//! contact steps, and at 1 ms on 52 %: its final nodes move 1.1 % from the run's where the
//! run's error against dt/4 is 0.13 %).
//!
//! **Order** ([`documented_order`]): the order p with which a change r becomes an error
//! e = r/(kᵖ − 1) (coarse, k = 4 or 2) or r·2ᵖ/(2ᵖ − 1) (refined) ([`Convergence`]). Over
//! every moving bundled scene and fixed-step integrator every quantity reported converged is
//! within τ of a run at dt/4, and e bounds that error but in one irregular case far inside τ
//! (`tests/simulate_companion.rs`, `measured_orders_on_the_bundled_examples`).
//!
//! **Cost** ([`Convergence::cost`]): ¼ for a companion at 4 dt, ½ at 2 dt, ¾ for 4 dt then
//! 2 dt, 2 for a refined one, 2¼ or 2½ for a coarse one that failed and the refined one after
//! it; the first companion runs on a thread of its own beside the run.

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
/// With p = 1 a coarse companion's rule at 2 dt (e = r ≤ τ) is the old one (a refined
/// companion's change r ≤ τ/2) at half the step: the change from 2 dt to dt is twice that from
/// dt to dt/2; at 4 dt it is e = r/3.
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
/// does: [`coarse_refused_at`] for [`Companion::Coarse`].
pub fn coarse_refused(simulation: &Simulation) -> Option<String> {
    coarse_refused_at(simulation, Companion::Coarse)
}

/// Why the coarse `companion` (k h, k its [`Companion::step_ratio`]) does not serve
/// `simulation` (module docs: k dt·λ within [`STABILITY_MARGIN`] × the method's bound, k dt ≤
/// t_end), or `None` when it does.
///
/// ```
/// use tensegrity_dynamics::convergence::Companion;
/// use tensegrity_engine::simulate::{companion::coarse_refused_at, SimulateCommand};
/// use tensegrity_engine::SceneSource;
/// let c = SimulateCommand {
///     scene: Some(SceneSource::parse(concat!(
///         env!("CARGO_MANIFEST_DIR"),
///         "/../../examples/anchors/double_pendulum_rk4.toml"
///     ))),
///     t_end: Some(0.003),
///     ..Default::default()
/// };
/// let (_, simulation) = c.prepare(false).unwrap();
/// // 1 ms steps: 2 dt fits in 3 ms, 4 dt does not
/// assert_eq!(coarse_refused_at(&simulation, Companion::Coarse), None);
/// let why = coarse_refused_at(&simulation, Companion::Coarser).unwrap();
/// assert_eq!(why, "4 dt exceeds t_end");
/// ```
pub fn coarse_refused_at(simulation: &Simulation, companion: Companion) -> Option<String> {
    let s = &simulation.settings;
    let Some(bound) = stability_bound(s.integrator) else {
        return Some(format!(
            "{} is adaptive: its tolerances are refined",
            s.integrator
        ));
    };
    let (k, label) = (companion.step_ratio(), companion.step_label());
    if k * s.dt > s.t_end {
        return Some(format!("{label} exceeds t_end"));
    }
    // rk4-flight's steps in flight are FLIGHT_RATIO·dt long
    let (ratio, step) = match s.integrator {
        IntegratorKind::Rk4Flight => (
            f64::from(FLIGHT_RATIO),
            format!("its flight step {k}·{FLIGHT_RATIO} dt"),
        ),
        _ => (1.0, label.to_string()),
    };
    let reach = k * ratio * s.dt * fastest_rate(&simulation.model);
    // (a NaN rate refuses it too)
    if reach.is_nan() || reach > STABILITY_MARGIN * bound {
        return Some(format!(
            "{step} times λ, {reach:.3}, exceeds {STABILITY_MARGIN} × {}'s stability bound {bound}",
            s.integrator
        ));
    }
    None
}

/// The companion of `simulation`'s convergence check (module docs): the coarsest of 4 dt and
/// 2 dt that serves ([`coarse_refused_at`]), else refined.
pub fn choose(simulation: &Simulation) -> Companion {
    [Companion::Coarser, Companion::Coarse]
        .into_iter()
        .find(|&c| coarse_refused_at(simulation, c).is_none())
        .unwrap_or(Companion::Refined)
}

/// The resolution of the coarse `companion` of `settings`: the step times its ratio, no
/// samples (module docs). Returns what changed.
pub fn coarsen(settings: &mut SimulationSettings, companion: Companion) -> &'static str {
    settings.dt *= companion.step_ratio();
    // it writes nothing: its steps are not cut at sample times
    settings.output_interval = None;
    settings.output_times.clear();
    settings.sample_every_step = false;
    companion.step_label()
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

/// An empty convergence of a run against its coarse `companion` (2 dt or 4 dt) of order
/// `order`.
pub fn coarse(order: f64, companion: Companion) -> Convergence {
    let label = format!("{} (coarse companion)", companion.step_label());
    Convergence::with(label, companion, order)
}

/// Why a run's companion is refined (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refined<'a> {
    /// An adaptive run: its tolerances are refined.
    Adaptive,
    /// A fixed step whose 2 dt does not serve ([`coarse_refused`]): why.
    Refused(&'a str),
    /// A coarse companion (2 dt or 4 dt) ran and failed ([`coarse_failure`]): which, and why.
    AfterCoarse(Companion, &'a str),
}

/// An empty convergence of a run against its refined companion (`what`: the refinement,
/// [`SimulateCommand::refine`](super::SimulateCommand::refine)) of order `order`, labelled
/// with `why` (an adaptive run's label is its refinement alone, as it always read); a coarse
/// run that failed adds its cost.
pub fn refined(what: &str, order: f64, why: Refined<'_>) -> Convergence {
    let label = match why {
        Refined::Adaptive => what.to_string(),
        Refined::Refused(why) => format!("{what} (refined companion: {why})"),
        Refined::AfterCoarse(coarse, why) => format!(
            "{what} (refined companion, run after the coarse one at {}: {why})",
            coarse.step_label()
        ),
    };
    let mut c = Convergence::with(label, Companion::Refined, order);
    if let Refined::AfterCoarse(coarse, _) = why {
        c.cost += coarse.cost();
    }
    c
}
