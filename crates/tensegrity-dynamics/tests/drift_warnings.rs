//! A drifted trajectory never comes back without a warning: energy (conservative models
//! only), bar lengths and N P = D against `SimulationSettings::drift_limits`.

use tensegrity_dynamics::test_models::{double_pendulum, dropped_prism, dropped_prism_ground};
use tensegrity_dynamics::{
    DriftQuantity, IntegratorKind, Simulation, SimulationResult, SimulationSettings,
};

fn run(
    s: &tensegrity_core::Structure,
    integrator: IntegratorKind,
    dt: f64,
    t_end: f64,
) -> SimulationResult {
    let settings = SimulationSettings {
        t_end,
        dt,
        integrator,
        ..Default::default()
    };
    Simulation::new(s, settings).unwrap().run().unwrap()
}

fn quantities(r: &SimulationResult) -> Vec<DriftQuantity> {
    r.warnings.iter().map(|w| w.quantity).collect()
}

#[test]
fn a_coarse_rk4_pendulum_warns_with_the_remedy_and_a_fine_one_does_not() {
    let s = double_pendulum(std::f64::consts::FRAC_PI_4).unwrap();
    let coarse = run(&s, IntegratorKind::Rk4, 0.05, 20.0);
    assert!(coarse.energy_drift > 1e-3 && coarse.bar_length_drift > 1e-6);
    let q = quantities(&coarse);
    assert!(
        q.contains(&DriftQuantity::Energy) && q.contains(&DriftQuantity::BarLength),
        "{q:?}"
    );
    let text = coarse.warnings[0].to_string();
    // the library names its own parameters (the CLI writes them as flags)
    assert!(
        text.contains("`integrator = rattle`") && text.contains("`dt`") && !text.contains("--"),
        "{text}"
    );
    let fine = run(&s, IntegratorKind::Rk4, 1e-3, 2.0);
    assert!(fine.warnings.is_empty(), "{:?}", fine.warnings);
}

#[test]
fn rattle_keeps_lengths_and_joints_where_rk4_drifts() {
    let s = double_pendulum(std::f64::consts::FRAC_PI_4).unwrap();
    let r = run(&s, IntegratorKind::Rattle, 0.05, 20.0);
    let q = quantities(&r);
    assert!(
        !q.contains(&DriftQuantity::BarLength) && !q.contains(&DriftQuantity::Constraint),
        "{q:?}"
    );
}

#[test]
fn energy_is_not_judged_when_the_model_dissipates() {
    // a damped ground with friction: the energy falls legitimately, bars stay rigid
    let s = dropped_prism(0.1, 2.0).unwrap();
    let settings = SimulationSettings {
        t_end: 0.5,
        dt: 1e-4,
        ..Default::default()
    };
    let mut sim = Simulation::new(&s, settings).unwrap();
    sim.model
        .set_ground(dropped_prism_ground(1e4, 50.0))
        .unwrap();
    let r = sim.run().unwrap();
    assert!(r.energy_drift > 1e-3, "{}", r.energy_drift);
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
}

#[test]
fn projection_and_rattle_converge_far_from_the_origin() {
    // the double pendulum hung 1 km from the origin: b = x_b − x_a carries an absolute
    // round-off of ~ε·10³ m, so a fixed tolerance of 10⁻¹⁴ l² on ½(‖b‖² − l²) could never be
    // met and the constraint iteration failed on converged states (a wheel 100 m down a
    // slope did); the tolerance now has the round-off floor ε·max|x|·ℓ
    let s = double_pendulum(std::f64::consts::FRAC_PI_4).unwrap();
    let far: Vec<_> = s
        .nodes()
        .iter()
        .map(|p| p + nalgebra::Vector3::new(1e3, -2e3, 5e2))
        .collect();
    let s = s.with_nodes(far).unwrap();
    for (integrator, project) in [(IntegratorKind::Rk4, true), (IntegratorKind::Rattle, false)] {
        let settings = SimulationSettings {
            t_end: 2.0,
            dt: 1e-3,
            integrator,
            project,
            ..Default::default()
        };
        let r = Simulation::new(&s, settings).unwrap().run().unwrap();
        // the floor is ~10⁻¹¹ here: far below the drift limit 10⁻⁶
        assert!(
            r.bar_length_drift < 1e-10,
            "{integrator:?}: {}",
            r.bar_length_drift
        );
        assert!(
            r.constraint_drift < 1e-10,
            "{integrator:?}: {}",
            r.constraint_drift
        );
        assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    }
}
