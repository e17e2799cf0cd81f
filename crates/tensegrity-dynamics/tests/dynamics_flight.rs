//! Flight steps ([`IntegratorKind::Rk4Flight`]): a tilted bar dropped onto a penalty ground
//! falls without rotating (RK4 is exact for the constant acceleration, so the flight steps
//! reach the touch-down grid point with the state RK4 at dt has there), lands one end first
//! and is resolved at dt from there: the final state agrees with RK4 at dt (to 10⁻⁵ m), with
//! fewer steps.

use nalgebra::Vector3;
use tensegrity_core::{Bar, Structure};
use tensegrity_dynamics::{
    Ground, GroundModel, IntegratorKind, Simulation, SimulationResult, SimulationSettings,
};

fn dropped_bar(integrator: IntegratorKind, dt: f64) -> SimulationResult {
    let s = Structure::builder()
        .nodes([[-0.5, 0.0, 0.25], [0.5, 0.1, 0.35]])
        .bar(Bar::new(0, 1).mass(2.0))
        .gravity([0.0, 0.0, -9.81])
        .build()
        .unwrap();
    let settings = SimulationSettings {
        t_end: 0.6,
        dt,
        integrator,
        project: true,
        ..Default::default()
    };
    let mut sim = Simulation::new(&s, settings).unwrap();
    let ground = GroundModel::Penalty {
        stiffness: 1e5,
        damping: 300.0,
        mu_static: 0.8,
        mu_kinetic: 0.6,
        regularization_velocity: 1e-3,
        stribeck_velocity: 1e-2,
    };
    sim.model
        .set_ground(Ground::new(Vector3::zeros(), Vector3::z(), ground))
        .unwrap();
    sim.run().unwrap()
}

#[test]
fn flight_steps_agree_with_rk4_at_dt_through_a_landing() {
    let dt = 1e-4;
    let rk4 = dropped_bar(IntegratorKind::Rk4, dt);
    let flight = dropped_bar(IntegratorKind::Rk4Flight, dt);
    assert_eq!(flight.t_end, 0.6);
    // it landed: the lower end rests on the ground (static penetration m g / (2k) ≈ 0.1 mm)
    let low = rk4.final_nodes[0].z.min(rk4.final_nodes[1].z);
    assert!(low.abs() < 1e-3, "{low}");
    // the ends bounce (ζ ≈ 0.5) and fly again at 5 dt while rotating: O(H⁴) apart there,
    // measured 3.3·10⁻⁶ m after the regularised friction's creep
    for (a, b) in rk4.final_nodes.iter().zip(&flight.final_nodes) {
        assert!((a - b).norm() < 1e-5, "{a} against {b}");
    }
    // the fall (0.21 s to the first touch-down) took steps of 5 dt
    assert!(
        flight.steps + 1500 < rk4.steps,
        "{} flight steps against {} RK4 steps",
        flight.steps,
        rk4.steps
    );
}

#[test]
fn the_flight_integrator_is_named_and_parsed() {
    assert_eq!(IntegratorKind::Rk4Flight.to_string(), "rk4-flight");
    assert_eq!(
        "rk4-flight".parse::<IntegratorKind>(),
        Ok(IntegratorKind::Rk4Flight)
    );
    assert!(!IntegratorKind::Rk4Flight.is_adaptive());
}
