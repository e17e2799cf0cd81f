//! The split IMEX's creep chatter is flagged: a bar creeping down a slope under the
//! regularised friction, at a step long against the friction's relaxation time, makes the
//! split's velocity error about the slaved creep flip sign at every step (module docs of
//! `dynamics::imex`, "A limit: creep under regularised friction" and "Detecting the chatter").
//! The run then counts its chattering contact node-steps above
//! `DriftLimits::contact_chatter` and carries a `creep_chatter` warning naming IMEX-ARK;
//! IMEX-ARK at the same step, and the split at its default step, follow the creep and carry
//! none.

use nalgebra::Vector3;
use tensegrity_core::warning::Warning;
use tensegrity_core::{Bar, Structure};
use tensegrity_dynamics::drift::CONTACT_CHATTER_LIMIT;
use tensegrity_dynamics::{
    DriftQuantity, Ground, GroundModel, IntegratorKind, Simulation, SimulationResult,
    SimulationSettings,
};

const G: f64 = 9.81;
const MASS: f64 = 2.0;
const K: f64 = 1e5;
const MU_S: f64 = 0.5;
const MU_K: f64 = 0.4;
/// The slope: tan φ = 0.36 < μ_s, so the bar creeps (it would rest under stick friction).
const PHI_DEG: f64 = 20.0;

/// A 1 m bar of 2 kg lying across the slope at its static penetration (the plane z = 0 with
/// gravity tilted towards +y), on the penalty ground with regularised Coulomb friction
/// (v_reg = 1 mm/s): the scene of `dynamics_stick::imex_follows_the_slaved_creep_of_the_regularised_friction`.
fn run(integrator: IntegratorKind, dt: f64, t_end: f64) -> SimulationResult {
    let phi = PHI_DEG.to_radians();
    let lift = -MASS * G * phi.cos() / (2.0 * K);
    let s = Structure::builder()
        .nodes([[-0.5, 0.0, lift], [0.5, 0.0, lift]])
        .bar(Bar::new(0, 1).mass(MASS))
        .gravity([0.0, G * phi.sin(), -G * phi.cos()])
        .build()
        .unwrap();
    let settings = SimulationSettings {
        t_end,
        dt,
        integrator,
        project: true,
        ..Default::default()
    };
    let mut sim = Simulation::new(&s, settings).unwrap();
    let ground = GroundModel::Penalty {
        stiffness: K,
        damping: 400.0,
        mu_static: MU_S,
        mu_kinetic: MU_K,
        regularization_velocity: 1e-3,
        stribeck_velocity: 1e-2,
    };
    sim.model
        .set_ground(Ground::new(Vector3::zeros(), Vector3::z(), ground))
        .unwrap();
    sim.run().unwrap()
}

/// The run from 0 to 2 s and its creep over the second second relative to the closed form
/// v_reg artanh(tan φ / μ_s) · 1 s.
fn creep_run(integrator: IntegratorKind, dt: f64) -> (SimulationResult, f64) {
    let expected = 1e-3 * (PHI_DEG.to_radians().tan() / MU_S).atanh();
    let first = run(integrator, dt, 1.0);
    let both = run(integrator, dt, 2.0);
    let creep = both.final_nodes[0].y - first.final_nodes[0].y;
    (both, creep / expected)
}

fn fraction((node_steps, chattering): (u64, u64)) -> f64 {
    chattering as f64 / node_steps as f64
}

/// At 4·10⁻³ s (β h / 2m ≈ 18 on a bar end, far in ROS2's stiff limit) the split creeps 9.6×
/// too fast, and 28.6 % of its 998 contact node-steps chatter (measured: 285): the run carries
/// the warning, with the fraction as its value.
#[test]
fn the_split_at_a_step_where_it_chatters_is_flagged_with_imex_ark_as_the_remedy() {
    let (r, creep) = creep_run(IntegratorKind::Imex, 4e-3);
    let (node_steps, chattering) = r.contact_chatter;
    let f = fraction(r.contact_chatter);
    eprintln!("split 4e-3: {chattering} of {node_steps} node-steps chatter ({f:.4}); creep {creep:.3}× the closed form");
    // two ends touching through 1000 steps: every step after the first two counts
    assert_eq!(node_steps, 998);
    assert!(
        (0.2..0.4).contains(&f) && f > 2.0 * CONTACT_CHATTER_LIMIT,
        "{f}"
    );
    assert!(creep > 5.0, "the flagged run is the biased one: {creep}");
    let w: Vec<_> = r
        .warnings
        .iter()
        .filter(|w| w.quantity == DriftQuantity::CreepChatter)
        .collect();
    assert_eq!(w.len(), 1, "{:?}", r.warnings);
    assert_eq!(w[0].value, f);
    assert_eq!(w[0].limit, CONTACT_CHATTER_LIMIT);
    let text = w[0].to_string();
    assert!(
        text.contains(&format!(
            "{:.1} % of their steps, above the limit 10 %",
            100.0 * f
        )) && text.contains("`integrator = imex-ark`"),
        "{text}"
    );
    let json = serde_json::to_value(Warning::from(*w[0])).unwrap();
    assert_eq!(json["kind"], "drift");
    assert_eq!(json["invariant"], "creep_chatter");
}

/// IMEX-ARK at the same 4·10⁻³ s follows the creep (within 0.5 %) and counts nothing (its
/// stages do not chatter: it does not implement the count); the split at its default
/// 5·10⁻⁴ s follows it too, and none of its 7998 node-steps chatter; at 10⁻³ and 2·10⁻³ s
/// two do (0.05 % and 0.1 %), far below the limit.
#[test]
fn imex_ark_and_the_split_at_a_short_step_are_not_flagged() {
    let (ark, creep) = creep_run(IntegratorKind::ImexArk, 4e-3);
    eprintln!("imex-ark 4e-3: {:?}, creep {creep:.4}", ark.contact_chatter);
    assert!(ark.warnings.is_empty(), "{:?}", ark.warnings);
    assert_eq!(ark.contact_chatter, (0, 0));
    assert!((creep - 1.0).abs() < 5e-3, "{creep}");
    for (dt, steps, most) in [(5e-4, 7998, 0), (1e-3, 3998, 2), (2e-3, 1998, 2)] {
        let (split, creep) = creep_run(IntegratorKind::Imex, dt);
        let (node_steps, chattering) = split.contact_chatter;
        eprintln!("split {dt:e}: {chattering} of {node_steps}, creep {creep:.4}");
        assert!(split.warnings.is_empty(), "{dt:e}: {:?}", split.warnings);
        assert_eq!(node_steps, steps, "{dt:e}");
        assert!(chattering <= most, "{dt:e}: {chattering}");
        assert!((creep - 1.0).abs() < 5e-3, "{dt:e}: {creep}");
    }
}
