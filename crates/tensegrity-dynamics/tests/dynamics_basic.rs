//! Must-show dynamics tests that need only the fixed-step RK4 (and RK45 for the pendulum).
//!
//! All run in a few seconds in the test profile, the MOTES-size D-bar run included.

use nalgebra::Vector3;
use tensegrity_core::Structure;
use tensegrity_dynamics::test_models::{
    dbar, dbar_chain, double_pendulum, oscillating_prism as oscillating_prism_model, snelson_prism,
    spinning_bar, PrismParams, DOUBLE_PENDULUM_TIP_5S,
};
use tensegrity_dynamics::{IntegratorKind, Model, Quantities, Simulation, SimulationSettings};

fn settings(t_end: f64, integrator: IntegratorKind, dt: f64) -> SimulationSettings {
    SimulationSettings {
        t_end,
        integrator,
        dt,
        ..Default::default()
    }
}

#[test]
fn free_bar_spins_exactly() {
    let (l, omega) = (2.0, 3.0);
    let s = spinning_bar(l, omega).unwrap();
    let mut set = settings(1.0, IntegratorKind::Rk4, 1e-3);
    set.output_interval = Some(0.05);
    set.quantities = Quantities {
        nodes: true,
        velocities: true,
        ..Default::default()
    };
    let r = Simulation::new(&s, set).unwrap().run().unwrap();
    assert_eq!(r.samples.len(), 21);
    let mut worst: f64 = 0.0;
    for smp in &r.samples {
        let th = omega * smp.t;
        let exact = Vector3::new(th.cos(), th.sin(), 0.0) * (l / 2.0);
        let nodes = smp.nodes.as_ref().unwrap();
        worst = worst.max((nodes[1] - exact).norm());
        worst = worst.max((nodes[0] + exact).norm());
        let v_exact = Vector3::new(-th.sin(), th.cos(), 0.0) * (omega * l / 2.0);
        worst = worst.max((smp.velocities.as_ref().unwrap()[1] - v_exact).norm());
    }
    eprintln!("spinning bar: max error {worst:e}");
    assert!(worst < 1e-10, "rotation error {worst:e}");
    assert!((r.t_end - 1.0).abs() < 1e-15);
    assert_eq!(r.steps, 1000);
    assert_eq!(r.rhs_evals, 4000);
}

fn max_accel(s: &Structure) -> f64 {
    let model = Model::new(s, None).unwrap();
    let y = model.initial_state(s).unwrap();
    let mut ws = model.workspace().unwrap();
    let mut dy = vec![0.0; y.len()];
    model.rhs(0.0, &y, &mut dy, &mut ws).unwrap();
    dy[y.len() / 2..].iter().fold(0.0f64, |m, a| m.max(a.abs()))
}

#[test]
fn prism_released_at_equilibrium_stays() {
    let s = snelson_prism(&PrismParams::default()).unwrap();
    let a = max_accel(&s);
    eprintln!("prism at equilibrium: max |N̈| = {a:e}");
    assert!(a < 1e-11, "|N̈| = {a:e}");
    // A non-equilibrium twist must accelerate (the test can fail).
    let mut p = s.nodes().to_vec();
    p[3].x += 0.01;
    let moved = s.with_nodes(p).unwrap();
    assert!(max_accel(&moved) > 1e-2);
    let r = Simulation::new(&s, settings(1.0, IntegratorKind::Rk4, 1e-3))
        .unwrap()
        .run()
        .unwrap();
    let drift = r
        .final_nodes
        .iter()
        .zip(s.nodes())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(drift < 1e-10, "equilibrium drift {drift:e}");
}

/// The prism with one vertical string shortened by 1 %: it oscillates (no string goes
/// slack; with 5 % one does and RK4 loses its order at the kink).
fn oscillating_prism() -> Structure {
    oscillating_prism_model().unwrap()
}

#[test]
fn prism_oscillation_conserves_energy_and_lengths() {
    let s = oscillating_prism();
    let mut set = settings(1.0, IntegratorKind::Rk4, 1e-3);
    set.output_times = vec![0.5, 1.0];
    set.quantities = Quantities {
        energy: true,
        nodes: true,
        ..Default::default()
    };
    let r = Simulation::new(&s, set).unwrap().run().unwrap();
    // it really moves
    let moved = r
        .final_nodes
        .iter()
        .zip(s.nodes())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(moved > 1e-3, "the prism should oscillate, moved {moved:e}");
    assert!(r.energy_drift <= 1e-6, "energy drift {:e}", r.energy_drift);
    assert!(
        r.bar_length_drift <= 1e-9,
        "bar drift {:e}",
        r.bar_length_drift
    );
    assert_eq!(r.samples.len(), 2);
    let (ke, e) = r.samples[1].energy.unwrap();
    assert!(ke > 0.0 && e.is_finite());
}

const TIP_REF: [f64; 2] = DOUBLE_PENDULUM_TIP_5S;

#[test]
fn double_pendulum_tip_matches_published_value_rk45() {
    let s = double_pendulum(std::f64::consts::FRAC_PI_4).unwrap();
    let mut set = settings(5.0, IntegratorKind::Rk45, 0.05);
    set.rtol = 1e-12;
    set.atol = 1e-12;
    let r = Simulation::new(&s, set).unwrap().run().unwrap();
    let tip = r.final_nodes[2];
    let err = ((tip.x - TIP_REF[0]).powi(2) + (tip.y - TIP_REF[1]).powi(2)).sqrt();
    eprintln!("pendulum RK45: tip error {err:e}");
    assert!(err < 1e-6, "tip {tip:?}, error {err:e}");
    assert!(tip.z.abs() < 1e-12);
    assert!(r.final_nodes[0].norm() < 1e-12, "pin moved");
    assert!(
        r.constraint_drift < 1e-12,
        "‖NP − D‖ = {:e}",
        r.constraint_drift
    );
    assert!(r.energy_drift < 1e-8, "energy drift {:e}", r.energy_drift);
}

#[test]
fn double_pendulum_tip_matches_published_value_rk4() {
    let s = double_pendulum(std::f64::consts::FRAC_PI_4).unwrap();
    let r = Simulation::new(&s, settings(5.0, IntegratorKind::Rk4, 5e-4))
        .unwrap()
        .run()
        .unwrap();
    let tip = r.final_nodes[2];
    let err = ((tip.x - TIP_REF[0]).powi(2) + (tip.y - TIP_REF[1]).powi(2)).sqrt();
    eprintln!("pendulum RK4 dt 5e-4: tip error {err:e}");
    assert!(err < 1e-6, "tip {tip:?}, error {err:e}");
}

fn dbar_run(steps: u64, dt: f64) -> tensegrity_dynamics::SimulationResult {
    let s = dbar(2.0, 0.5, 1.0, 1000.0, 0.05).unwrap();
    assert_eq!(s.class(), 2);
    let r = Simulation::new(&s, settings(steps as f64 * dt, IntegratorKind::Rk4, dt))
        .unwrap()
        .run()
        .unwrap();
    assert_eq!(r.steps, steps);
    r
}

#[test]
fn dbar_class_k_keeps_np_equals_d() {
    let r = dbar_run(500, 1e-3);
    eprintln!(
        "D-bar 500 steps: ‖NP − D‖ {:e}, bar drift {:e}, energy drift {:e}",
        r.constraint_drift, r.bar_length_drift, r.energy_drift
    );
    assert_joints_hold(&r, 1e-5);
    // it moves: the strings are prestressed away from equilibrium
    let s = dbar(2.0, 0.5, 1.0, 1000.0, 0.05).unwrap();
    let moved = r
        .final_nodes
        .iter()
        .zip(s.nodes())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(moved > 1e-3);
}

/// The MOTES comparison size: 5000 RK4 steps of the D-bar.
#[test]
fn dbar_class_k_5000_steps() {
    let r = dbar_run(5000, 1e-3);
    assert!(
        r.constraint_drift <= 1e-12,
        "‖NP − D‖ = {:e}",
        r.constraint_drift
    );
    eprintln!(
        "D-bar 5000 RK4 steps: {:.3} ms, energy drift {:e}, bar drift {:e}",
        r.wall_time_s * 1e3,
        r.energy_drift,
        r.bar_length_drift
    );
}

#[test]
fn dbar_chain_sparse_omega_keeps_np_equals_d() {
    // 4 D-bars: class-2 ends (2·3 rows), three class-4 joints (3·9), eight class-2 mid nodes
    // (8·3): 57 rows > 48, so the sparse Cholesky path with symbolic reuse is exercised.
    let s = dbar_chain(4).unwrap();
    let model = Model::new(&s, None).unwrap();
    assert!(
        model.n_constraint_rows() == 57,
        "{}",
        model.n_constraint_rows()
    );
    let r = Simulation::new(&s, settings(0.2, IntegratorKind::Rk4, 1e-3))
        .unwrap()
        .run()
        .unwrap();
    assert_joints_hold(&r, 1e-6);
    let moved = r
        .final_nodes
        .iter()
        .zip(s.nodes())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(moved > 1e-4, "moved {moved:e}");
}

/// ‖NP − D‖ ≤ 1e-12, bar lengths to 1e-9 and relative energy drift ≤ `energy_tol`.
fn assert_joints_hold(r: &tensegrity_dynamics::SimulationResult, energy_tol: f64) {
    assert!(
        r.constraint_drift <= 1e-12,
        "‖NP − D‖ = {:e}",
        r.constraint_drift
    );
    assert!(
        r.bar_length_drift <= 1e-9,
        "bar drift {:e}",
        r.bar_length_drift
    );
    assert!(
        r.energy_drift <= energy_tol,
        "energy drift {:e}",
        r.energy_drift
    );
}
