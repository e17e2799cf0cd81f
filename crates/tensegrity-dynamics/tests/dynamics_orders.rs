//! Observed orders of convergence: RK4 → 4, Dormand–Prince 5(4) → ≥ 4 (5 expected),
//! RATTLE → 2, on the compound double pendulum (class-2 joint and a pinned support, so the Ω
//! closed form is exercised) and on the oscillating prism.

use tensegrity_dynamics::test_models::double_pendulum;
use tensegrity_dynamics::{IntegratorKind, Simulation, SimulationSettings};

fn final_nodes(integrator: IntegratorKind, dt: f64, rtol: f64) -> Vec<nalgebra::Vector3<f64>> {
    let s = double_pendulum(std::f64::consts::FRAC_PI_4).unwrap();
    let set = SimulationSettings {
        t_end: 1.0,
        integrator,
        dt,
        rtol,
        atol: rtol,
        ..Default::default()
    };
    Simulation::new(&s, set).unwrap().run().unwrap().final_nodes
}

fn err(a: &[nalgebra::Vector3<f64>], b: &[nalgebra::Vector3<f64>]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).norm())
        .fold(0.0, f64::max)
}

fn orders(integrator: IntegratorKind, dts: &[f64], rtol: f64) -> Vec<f64> {
    let reference = final_nodes(IntegratorKind::Rk4, 1e-4, 1e-8);
    let errors: Vec<f64> = dts
        .iter()
        .map(|&dt| err(&final_nodes(integrator, dt, rtol), &reference))
        .collect();
    eprintln!("{integrator}: dt {dts:?} errors {errors:?}");
    errors
        .windows(2)
        .zip(dts.windows(2))
        .map(|(e, h)| (e[0] / e[1]).ln() / (h[0] / h[1]).ln())
        .collect()
}

#[test]
fn rk4_is_fourth_order() {
    let p = orders(IntegratorKind::Rk4, &[0.04, 0.02, 0.01], 1e-8);
    eprintln!("RK4 observed orders {p:?}");
    for o in p {
        assert!((3.7..4.4).contains(&o), "RK4 order {o}");
    }
}

#[test]
fn dopri5_is_at_least_fourth_order() {
    // rtol huge: every step is accepted and the step is capped at dt, i.e. a fixed-step run.
    let p = orders(IntegratorKind::Rk45, &[0.08, 0.04, 0.02], 1e6);
    eprintln!("DP5 observed orders {p:?}");
    for o in p {
        assert!(o >= 4.0, "DP5 order {o}");
    }
}

#[test]
fn rattle_is_second_order() {
    let p = orders(IntegratorKind::Rattle, &[0.01, 0.005, 0.0025], 1e-8);
    eprintln!("RATTLE observed orders {p:?}");
    for o in p {
        assert!((1.8..2.3).contains(&o), "RATTLE order {o}");
    }
}

#[test]
fn rattle_keeps_constraints_to_round_off() {
    let s = double_pendulum(std::f64::consts::FRAC_PI_4).unwrap();
    let set = SimulationSettings {
        t_end: 2.0,
        integrator: IntegratorKind::Rattle,
        dt: 0.01,
        ..Default::default()
    };
    let r = Simulation::new(&s, set).unwrap().run().unwrap();
    assert!(
        r.bar_length_drift < 1e-12,
        "bar drift {:e}",
        r.bar_length_drift
    );
    assert!(
        r.constraint_drift < 1e-12,
        "‖NP − D‖ {:e}",
        r.constraint_drift
    );
    // symplectic: bounded energy error, small but not round-off
    assert!(r.energy_drift < 1e-2, "energy drift {:e}", r.energy_drift);
}

#[test]
fn dbar_omega_closed_form_agrees_with_rattle_multipliers() {
    // Two independent treatments of the class-2 joints: RK45 on the Ω closed form (bars rigid
    // through λ) against RATTLE (bar lengths and N P = D as holonomic constraints with
    // Lagrange multipliers from its own sparse system). Both converge to the same motion.
    let s = tensegrity_dynamics::test_models::dbar(2.0, 0.5, 1.0, 1000.0, 0.05).unwrap();
    let run = |integrator, dt, rtol| {
        let set = SimulationSettings {
            t_end: 0.3,
            integrator,
            dt,
            rtol,
            atol: rtol,
            ..Default::default()
        };
        Simulation::new(&s, set).unwrap().run().unwrap().final_nodes
    };
    let closed = run(IntegratorKind::Rk45, 0.01, 1e-11);
    let rattle = run(IntegratorKind::Rattle, 1e-4, 1e-8);
    let moved = err(&closed, s.nodes());
    let diff = err(&closed, &rattle);
    eprintln!("D-bar moved {moved:e}, closed form vs RATTLE {diff:e}");
    assert!(moved > 1e-3, "the D-bar should move ({moved:e})");
    assert!(diff < 1e-6, "closed form vs RATTLE: {diff:e}");
}
