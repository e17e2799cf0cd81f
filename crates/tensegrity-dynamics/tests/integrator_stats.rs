//! Snapshot tests of the work counters (accepted steps, rejected steps, right-hand-side
//! evaluations) of every integrator on the test models, so that a silent performance
//! regression (more steps or force evaluations for the same answer) fails.
//!
//! The snapshots hold counts only (no timings), so they are the same on every machine. After
//! an intended change, review with `cargo insta review` (or rerun with `INSTA_UPDATE=always`)
//! and commit the new `.snap` files under `tests/snapshots/`.

use std::fmt::Write as _;
use tensegrity_core::{DynamicsError, Structure};
use tensegrity_dynamics::test_models;
use tensegrity_dynamics::{IntegratorKind, Simulation, SimulationSettings};

/// The integrators of the original snapshots (their files must not change).
const EXPLICIT: [IntegratorKind; 3] = [
    IntegratorKind::Rk4,
    IntegratorKind::Rk45,
    IntegratorKind::Rattle,
];

/// Runs `structure` with the explicit integrators (dt for the fixed-step ones, rtol for rk45
/// with atol = rtol/100 and maximum step t_end) and tabulates the counters.
fn table(
    structure: &Structure,
    ground: Option<tensegrity_dynamics::Ground>,
    t_end: f64,
    dt: f64,
    rtol: f64,
) -> String {
    table_of(&EXPLICIT, structure, ground, t_end, dt, rtol)
}

/// The table for `kinds` (adaptive ones: rtol, atol = rtol/100, maximum step `dt` for sdirk
/// and t_end for rk45).
fn table_of(
    kinds: &[IntegratorKind],
    structure: &Structure,
    ground: Option<tensegrity_dynamics::Ground>,
    t_end: f64,
    dt: f64,
    rtol: f64,
) -> String {
    let mut out = String::from("integrator  steps  rejected  rhs_evals\n");
    for &integrator in kinds {
        let adaptive = integrator == IntegratorKind::Rk45;
        let settings = SimulationSettings {
            t_end,
            integrator,
            dt: if adaptive { t_end } else { dt },
            rtol,
            atol: rtol * 1e-2,
            ..Default::default()
        };
        let mut sim = Simulation::new(structure, settings).unwrap();
        if let Some(g) = &ground {
            sim.model.set_ground(g.clone()).unwrap();
        }
        let s = sim.run().unwrap().stats();
        writeln!(
            out,
            "{:<10}  {:>5}  {:>8}  {:>9}",
            integrator.to_string(),
            s.steps,
            s.rejected_steps,
            s.rhs_evals
        )
        .unwrap();
    }
    out
}

/// SDIRK rows (maximum step 10 ms, rtol 1e-6): the smooth test models and the two stiff
/// scenes of the work–precision study.
#[test]
fn stats_sdirk() {
    let sd = [IntegratorKind::Sdirk];
    let mut out = String::new();
    let pendulum = test_models::double_pendulum(std::f64::consts::FRAC_PI_4).unwrap();
    let prism = test_models::oscillating_prism().unwrap();
    let dropped = test_models::dropped_prism(0.02, 50.0).unwrap();
    let ground = test_models::dropped_prism_ground(1e4, 100.0);
    let damped_ground = test_models::dropped_prism_ground(1e5, 3000.0);
    let rows = [
        (
            "double pendulum, 2 s",
            table_of(&sd, &pendulum, None, 2.0, 0.01, 1e-6),
        ),
        (
            "oscillating prism, 0.5 s",
            table_of(&sd, &prism, None, 0.5, 0.01, 1e-6),
        ),
        (
            "dropped prism, 0.3 s",
            table_of(&sd, &dropped, Some(ground), 0.3, 0.01, 1e-6),
        ),
        (
            "dropped prism, ground 3000 N s/m, 0.5 s",
            table_of(&sd, &dropped, Some(damped_ground), 0.5, 0.01, 1e-6),
        ),
    ];
    for (name, t) in rows {
        writeln!(out, "{name}\n{t}").unwrap();
    }
    insta::assert_snapshot!(out);
}

#[test]
fn stats_dbar() {
    let s = test_models::dbar(2.0, 0.5, 1.0, 1000.0, 0.05).unwrap();
    insta::assert_snapshot!(table(&s, None, 0.5, 1e-3, 1e-8));
}

#[test]
fn stats_snelson_prism_oscillating() {
    let s = test_models::oscillating_prism().unwrap();
    insta::assert_snapshot!(table(&s, None, 0.5, 1e-3, 1e-8));
}

#[test]
fn stats_double_pendulum() {
    let s = test_models::double_pendulum(std::f64::consts::FRAC_PI_4).unwrap();
    insta::assert_snapshot!(table(&s, None, 2.0, 1e-3, 1e-8));
}

#[test]
fn stats_motes_dbar() {
    let s = test_models::motes_dbar(1.0).unwrap();
    let t_end = test_models::MOTES_DBAR_STEPS as f64 * test_models::MOTES_DBAR_DT;
    insta::assert_snapshot!(table(&s, None, t_end, test_models::MOTES_DBAR_DT, 1e-8));
}

#[test]
fn stats_dropped_prism() {
    let s = test_models::dropped_prism(0.02, 50.0).unwrap();
    let ground = test_models::dropped_prism_ground(1e4, 100.0);
    insta::assert_snapshot!(table(&s, Some(ground), 0.3, 5e-4, 1e-6));
}

/// The MOTES D-bar keeps its reference invariants: N P = D (joints and pin) to round-off
/// over the full 5000-step RK4 run, and the pinned node stays put.
#[test]
fn motes_dbar_keeps_its_invariants() {
    let s = test_models::motes_dbar(1.0).unwrap();
    assert_eq!(s.class(), 2);
    let settings = SimulationSettings {
        t_end: test_models::MOTES_DBAR_STEPS as f64 * test_models::MOTES_DBAR_DT,
        dt: test_models::MOTES_DBAR_DT,
        ..Default::default()
    };
    let r = Simulation::new(&s, settings).unwrap().run().unwrap();
    assert_eq!(r.steps, test_models::MOTES_DBAR_STEPS);
    assert!(
        r.constraint_drift <= 1e-12,
        "‖NP − D‖ = {:e}",
        r.constraint_drift
    );
    assert!(r.final_nodes[0].norm() <= 1e-12, "the pin moved");
    assert!(
        r.bar_length_drift <= 1e-8,
        "bar drift {:e}",
        r.bar_length_drift
    );
    assert!(r.energy_drift <= 1e-5, "energy drift {:e}", r.energy_drift);
    let moved = (r.final_nodes[3] - s.nodes()[3]).norm();
    assert!(
        moved > 1e-3,
        "the strings should move the D-bar, moved {moved:e}"
    );
}

/// A step budget that is too small is reported as such: before the run for fixed steps
/// (t_end/dt is known), with the time reached for adaptive ones.
#[test]
fn step_budget_is_reported_as_max_steps_exceeded() {
    let s = test_models::double_pendulum(1.0).unwrap();
    let settings = SimulationSettings {
        t_end: 1.0,
        max_steps: 10,
        ..Default::default()
    };
    let e = Simulation::new(&s, settings.clone())
        .unwrap()
        .run()
        .unwrap_err();
    match e {
        tensegrity_core::CoreError::InvalidParameter(p) => {
            assert_eq!(p.name, "dt");
            assert!(p.reason.contains("1e3 fixed steps"), "{}", p.reason);
        }
        other => panic!("unexpected {other}"),
    }
    let adaptive = SimulationSettings {
        integrator: IntegratorKind::Rk45,
        rtol: 1e-12,
        atol: 1e-12,
        ..settings
    };
    let e = Simulation::new(&s, adaptive).unwrap().run().unwrap_err();
    match e {
        tensegrity_core::CoreError::Dynamics(DynamicsError::MaxStepsExceeded { t, max_steps }) => {
            assert_eq!(max_steps, 10);
            assert!(t > 0.0 && t < 1.0, "t = {t}");
        }
        other => panic!("unexpected {other}"),
    }
}
