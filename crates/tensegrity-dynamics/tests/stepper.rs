//! The stepped simulation: a controller's rest lengths applied period by period reproduce a
//! simulation of the same actuation table (bit for bit under RK4, to the tolerance under
//! RK45), the actuator limits hold, saved states restore exactly, a turned reset is a rigid
//! motion, and bad actions and actuators are refused by name.

use nalgebra::Vector3;
use tensegrity_dynamics::test_models::{self, dropped_prism_ground};
use tensegrity_dynamics::{
    Action, Actuator, IntegratorKind, Simulation, SimulationSettings, Stepper,
};

/// The dropped prism (z₀ = 0.02 m, string damping 5) on the penalty ground, with `kind`.
fn prism(kind: IntegratorKind, dt: f64) -> Simulation {
    let s = test_models::dropped_prism(0.02, 5.0).unwrap();
    let settings = SimulationSettings {
        integrator: kind,
        dt,
        ..Default::default()
    };
    let mut sim = Simulation::new(&s, settings).unwrap();
    sim.model
        .set_ground(dropped_prism_ground(1e4, 50.0))
        .unwrap();
    sim
}

/// The rest lengths of strings 0 and 7 at the end of period p (a pull and a release).
fn targets(p: usize, r0: [f64; 2]) -> [f64; 2] {
    let p = p as f64;
    [r0[0] * (1.0 - 0.02 * p), r0[1] * (1.0 + 0.01 * p)]
}

fn string_rest(sim: &Simulation) -> [f64; 2] {
    let rest = sim.model.rest_lengths_at(0.0);
    [rest[0], rest[7]]
}

/// Runs `periods` periods of `n` steps with the targets above through a stepper.
fn stepped(kind: IntegratorKind, dt: f64, periods: usize, n: u64) -> (Stepper, Vec<f64>) {
    let sim = prism(kind, dt);
    let r0 = string_rest(&sim);
    let mut st = Stepper::new(sim, vec![Actuator::string(0), Actuator::string(7)]).unwrap();
    for p in 1..=periods {
        st.step(Action::RestLengths(&targets(p, r0)), n).unwrap();
    }
    let y = st.y().to_vec();
    (st, y)
}

/// The same actuation as a table (the times computed as the stepper's, k·n·dt), simulated.
fn tabled(kind: IntegratorKind, dt: f64, periods: usize, n: u64) -> Vec<f64> {
    let mut sim = prism(kind, dt);
    let r0 = string_rest(&sim);
    let times: Vec<f64> = (0..=periods).map(|p| (p as u64 * n) as f64 * dt).collect();
    let values: Vec<[f64; 2]> = (0..=periods).map(|p| targets(p, r0)).collect();
    sim.settings.t_end = *times.last().unwrap();
    let (ts, vs) = (times.clone(), values.clone());
    sim.model.set_rest_length_schedule(Box::new(move |t, rest| {
        let j = ts.partition_point(|&x| x <= t);
        let (i, j, w) = if t <= ts[0] {
            (0, 0, 0.0)
        } else if j >= ts.len() {
            (ts.len() - 1, ts.len() - 1, 0.0)
        } else {
            (j - 1, j, (t - ts[j - 1]) / (ts[j] - ts[j - 1]))
        };
        rest[0] = vs[i][0] * (1.0 - w) + vs[j][0] * w;
        rest[7] = vs[i][1] * (1.0 - w) + vs[j][1] * w;
    }));
    sim.run().unwrap().final_state
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn rk4_steps_reproduce_the_actuation_table_bit_for_bit() {
    let (st, y) = stepped(IntegratorKind::Rk4, 1e-3, 8, 50);
    let y_table = tabled(IntegratorKind::Rk4, 1e-3, 8, 50);
    assert_eq!(max_diff(&y, &y_table), 0.0);
    assert!((st.time() - 0.4).abs() < 1e-15);
    // the prism moved: the comparison is not between two resting states
    let start = prism(IntegratorKind::Rk4, 1e-3).y0;
    assert!(max_diff(&y, &start) > 1e-3);
    let r0 = string_rest(&prism(IntegratorKind::Rk4, 1e-3));
    assert_eq!(st.rest_lengths(), &targets(8, r0)[..]);
}

#[test]
fn rk45_steps_agree_with_the_table_to_the_tolerance() {
    let (st, y) = stepped(IntegratorKind::Rk45, 1e-2, 4, 10);
    let y_table = tabled(IntegratorKind::Rk45, 1e-2, 4, 10);
    let d = max_diff(&y, &y_table);
    assert!(d < 1e-5, "RK45 stepped vs table: {d:e}");
    assert!(st.stats().steps > 0);
}

#[test]
fn rate_and_length_limits_bound_the_rest_lengths() {
    let sim = prism(IntegratorKind::Rk4, 1e-3);
    let r0 = string_rest(&sim)[0];
    let a = Actuator::string(0).max_rate(0.2).min_length(r0 - 0.03);
    let mut st = Stepper::new(sim, vec![a]).unwrap();
    // a far target: 0.2 m/s for 0.1 s
    st.step(Action::RestLengths(&[0.0]), 100).unwrap();
    assert!((st.rest_lengths()[0] - (r0 - 0.02)).abs() < 1e-12);
    // the minimum length stops the next pull after 0.01 m
    st.step(Action::RestLengths(&[0.0]), 100).unwrap();
    assert!((st.rest_lengths()[0] - (r0 - 0.03)).abs() < 1e-12);
    // a rate above the limit moves at the limit
    st.step(Action::Rates(&[5.0]), 50).unwrap();
    assert!((st.rest_lengths()[0] - (r0 - 0.03 + 0.2 * 0.05)).abs() < 1e-12);
    // holding keeps it
    st.step(Action::Hold, 10).unwrap();
    assert!((st.rest_lengths()[0] - (r0 - 0.02)).abs() < 1e-12);
}

#[test]
fn a_saved_state_restores_the_run_exactly() {
    let sim = prism(IntegratorKind::Rk4, 1e-3);
    let r0 = string_rest(&sim);
    let mut st = Stepper::new(sim, vec![Actuator::string(0), Actuator::string(7)]).unwrap();
    st.step(Action::RestLengths(&targets(1, r0)), 60).unwrap();
    let saved = st.state();
    st.step(Action::RestLengths(&targets(2, r0)), 90).unwrap();
    let (y_a, t_a) = (st.y().to_vec(), st.time());
    st.reset().unwrap();
    assert_eq!(st.time(), 0.0);
    st.set_state(&saved).unwrap();
    st.step(Action::RestLengths(&targets(2, r0)), 90).unwrap();
    assert_eq!(st.time(), t_a);
    assert_eq!(max_diff(st.y(), &y_a), 0.0);
}

#[test]
fn an_unactuated_run_conserves_energy_and_reports_no_drift() {
    // the undamped prism in space: energy is conserved, observations are consistent
    let s = test_models::dropped_prism(0.5, 0.0).unwrap();
    let settings = SimulationSettings {
        integrator: IntegratorKind::Rk45,
        rtol: 1e-10,
        atol: 1e-12,
        dt: 1e-2,
        ..Default::default()
    };
    let sim = Simulation::new(&s, settings).unwrap();
    let mut st = Stepper::new(sim, vec![Actuator::string(0)]).unwrap();
    let (_, e0) = st.energy();
    for _ in 0..20 {
        st.step(Action::Hold, 5).unwrap();
    }
    let (ke, e1) = st.energy();
    assert!(ke > 0.0 || e0.abs() > 0.0);
    assert!((e1 - e0).abs() <= 1e-7 * e0.abs().max(1.0), "{e0} {e1}");
    assert!(st.warnings().is_empty(), "{:?}", st.warnings());
    // member forces: the strings' γ‖s‖ from the law, bars' forces balance the strings
    let f = st.member_forces().unwrap();
    assert_eq!(f.len(), 3 + 9);
    assert!(
        f[..3].iter().all(|&b| b < 0.0),
        "bars in compression: {f:?}"
    );
}

#[test]
fn a_turned_reset_is_a_rigid_turn_about_the_vertical() {
    let mut st = Stepper::new(prism(IntegratorKind::Rk4, 1e-3), vec![]).unwrap();
    let n0 = st.nodes();
    let e0 = st.energy().1;
    let angle = 0.7_f64;
    st.reset_turned(angle).unwrap();
    let n1 = st.nodes();
    let c: Vector3<f64> = n0.iter().sum::<Vector3<f64>>() / n0.len() as f64;
    for (p, q) in n0.iter().zip(&n1) {
        let (a, b) = (p - c, q - c);
        assert!((a.z - b.z).abs() < 1e-14);
        let expect = Vector3::new(
            a.x * angle.cos() - a.y * angle.sin(),
            a.x * angle.sin() + a.y * angle.cos(),
            a.z,
        );
        assert!((expect - b).norm() < 1e-12);
    }
    assert!((st.energy().1 - e0).abs() < 1e-9 * e0.abs().max(1.0));
}

#[test]
fn bad_actions_and_actuators_are_named() {
    let mut st = Stepper::new(prism(IntegratorKind::Rk4, 1e-3), vec![Actuator::string(2)]).unwrap();
    let e = st.step(Action::RestLengths(&[1.0, 2.0]), 1).unwrap_err();
    assert!(e.to_string().contains("expected 1 entries, got 2"), "{e}");
    let e = st.step(Action::Rates(&[f64::NAN]), 1).unwrap_err();
    assert!(e.to_string().contains("actuator 0"), "{e}");
    assert_eq!(st.time(), 0.0, "a refused action takes no step");
    let e = st.step(Action::Hold, 0).unwrap_err();
    assert!(e.to_string().contains("n_steps"), "{e}");
    let sim = || prism(IntegratorKind::Rk4, 1e-3);
    let e = Stepper::new(sim(), vec![Actuator::string(99)]).unwrap_err();
    assert!(
        e.to_string()
            .contains("actuator 0: string 99 does not exist"),
        "{e}"
    );
    let e = Stepper::new(sim(), vec![Actuator::string(1), Actuator::string(1)]).unwrap_err();
    assert!(
        e.to_string()
            .contains("actuator 1: drives the same rest length as actuator 0"),
        "{e}"
    );
    let e = Stepper::new(sim(), vec![Actuator::string(1).min_length(50.0)]).unwrap_err();
    assert!(e.to_string().contains("outside its limits"), "{e}");
    let e = Stepper::new(sim(), vec![Actuator::string(1).max_rate(0.0)]).unwrap_err();
    assert!(e.to_string().contains("max_rate"), "{e}");
}

#[test]
fn resets_and_restores_repeat_a_projected_run_exactly() {
    // IMEX projects onto the constraints after every step, keeping a factor between steps
    let mut st = Stepper::new(prism(IntegratorKind::Rk4, 1e-3), vec![Actuator::string(4)]).unwrap();
    let run = |st: &mut Stepper| {
        st.step(Action::Rates(&[-0.2]), 150).unwrap();
        st.step(Action::Hold, 150).unwrap();
        st.y().to_vec()
    };
    let mut sim = prism(IntegratorKind::Imex, 5e-4);
    sim.settings.project = true;
    let mut st_p = Stepper::new(sim, vec![Actuator::string(4)]).unwrap();
    for st in [&mut st, &mut st_p] {
        let a = run(st);
        st.reset().unwrap();
        let b = run(st);
        assert_eq!(max_diff(&a, &b), 0.0, "a reset repeats the run");
        let saved = st.state();
        let c = run(st);
        st.set_state(&saved).unwrap();
        let d = run(st);
        assert_eq!(max_diff(&c, &d), 0.0, "a restored state repeats the run");
    }
}

#[test]
fn an_actuation_table_drives_a_rest_length_until_an_action_takes_it_over() {
    let mut sim = prism(IntegratorKind::Rk4, 1e-3);
    let r0 = string_rest(&sim)[0];
    // string 0 shortened by 10 % over the first second by the scene's table
    sim.model.set_rest_length_schedule(Box::new(move |t, rest| {
        rest[0] = r0 * (1.0 - 0.1 * t.clamp(0.0, 1.0));
    }));
    let mut st = Stepper::new(sim, vec![Actuator::string(0)]).unwrap();
    st.step(Action::Hold, 500).unwrap();
    assert!(
        (st.rest_lengths()[0] - 0.95 * r0).abs() < 1e-12,
        "the table at t = 0.5"
    );
    // an action starts from where the table left it, and holds from then on
    st.step(Action::Rates(&[0.0]), 100).unwrap();
    assert!((st.rest_lengths()[0] - 0.95 * r0).abs() < 1e-12);
    st.step(Action::Hold, 400).unwrap();
    assert!(
        (st.rest_lengths()[0] - 0.95 * r0).abs() < 1e-12,
        "the action holds it"
    );
}
