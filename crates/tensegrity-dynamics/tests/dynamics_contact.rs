//! Ground contact: a prism dropped on a penalty ground comes to rest with the penetration
//! (load per contact node)/(ground stiffness); the thesis ground model holds a structure up;
//! RK45 event location finds the touchdown time of a free fall.

use nalgebra::Vector3;
use tensegrity_dynamics::test_models::{self, DROPPED_PRISM_G};
use tensegrity_dynamics::{
    Event, Ground, GroundModel, IntegratorKind, Quantities, Simulation, SimulationSettings,
};

const G: f64 = DROPPED_PRISM_G;

fn dropped_prism(z0: f64, damping: f64) -> tensegrity_core::Structure {
    // A stiff prestress (300 N/m) so that the soft twist mode is damped within seconds.
    test_models::dropped_prism(z0, damping).unwrap()
}

fn penalty_ground(k: f64) -> Ground {
    let model = GroundModel::Penalty {
        stiffness: k,
        damping: 100.0,
        mu_static: 0.6,
        mu_kinetic: 0.5,
        // A soft regularisation: the feet creep out of the tangential prestress quickly
        // (viscous slope μ f_n / v_reg ≈ 50 N·s/m), so the prism really comes to rest.
        regularization_velocity: 0.1,
        stribeck_velocity: 0.2,
    };
    Ground::new(Vector3::zeros(), Vector3::z(), model)
}

/// A simulation of `s` with default settings, on `ground` if given.
fn simulation(s: &tensegrity_core::Structure, ground: Option<Ground>) -> Simulation {
    let mut sim = Simulation::new(s, SimulationSettings::default()).unwrap();
    if let Some(g) = ground {
        sim.model.set_ground(g).unwrap();
    }
    sim
}

#[test]
fn dropped_prism_rests_with_static_penetration() {
    let k = 1e4;
    let s = dropped_prism(0.02, 50.0);
    let mut sim = simulation(&s, Some(penalty_ground(k)));
    sim.settings = SimulationSettings {
        t_end: 8.0,
        integrator: IntegratorKind::Rk45,
        dt: 0.01,
        rtol: 1e-8,
        atol: 1e-10,
        output_times: vec![8.0],
        quantities: Quantities {
            contact_forces: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let r = sim.run().unwrap();
    let vmax = r
        .final_velocities
        .iter()
        .map(|v| v.norm())
        .fold(0.0, f64::max);
    assert!(vmax < 1e-7, "not at rest: max speed {vmax:e}");
    // 3 bars of 1 kg on 3 contact nodes: 9.81 N each.
    let expected = test_models::dropped_prism_penetration(k);
    assert_eq!(expected, 3.0 * G / 3.0 / k);
    for i in 0..3 {
        let pen = -r.final_nodes[i].z;
        eprintln!("node {i}: penetration {pen:e} (expected {expected:e}), max speed {vmax:e}");
        assert!(
            (pen - expected).abs() < 1e-6 * expected,
            "node {i}: penetration {pen:e}, expected {expected:e}"
        );
    }
    for i in 3..6 {
        assert!(r.final_nodes[i].z > 1.0, "top node {i} must stay up");
    }
    // contact forces carry the weight
    let cf = r.samples[0].contact_forces.as_ref().unwrap();
    let total: Vector3<f64> = cf.iter().map(|(_, f)| *f).sum();
    assert!(
        (total.z - 3.0 * G).abs() < 1e-3 * 3.0 * G,
        "total {total:?}"
    );
    assert!(r.bar_length_drift < 1e-6);
}

#[test]
fn thesis_ground_supports_and_damps() {
    // A 1 kg bar lying on the plane: the thesis model's normal reaction is the weight shared
    // by the two contact nodes, so it does not fall; the contact damping −c v on both ends
    // gives m v' = −2 c v for a sliding bar: v = v0 e^{−2ct/m}, x = v0 m/(2c) (1 − e^{−2ct/m}).
    let (m, c, v0, t_end) = (1.0, 2.0, 1.0, 0.5);
    let s = tensegrity_core::Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
        .velocities([[v0, 0.0, 0.0], [v0, 0.0, 0.0]])
        .bar(tensegrity_core::Bar::new(0, 1).mass(m))
        .gravity([0.0, 0.0, -G])
        .build()
        .unwrap();
    let ground = Ground::new(
        Vector3::zeros(),
        Vector3::z(),
        GroundModel::Thesis {
            damping: c,
            tolerance: 1e-6,
        },
    );
    let mut sim = simulation(&s, Some(ground));
    sim.settings = SimulationSettings {
        t_end,
        integrator: IntegratorKind::Rk4,
        dt: 1e-3,
        ..Default::default()
    };
    let r = sim.run().unwrap();
    let decay = (-2.0 * c * t_end / m).exp();
    let x = v0 * m / (2.0 * c) * (1.0 - decay);
    assert!((r.final_velocities[0].x - v0 * decay).abs() < 1e-10);
    assert!(
        (r.final_nodes[0].x - x).abs() < 1e-10,
        "{} vs {x}",
        r.final_nodes[0].x
    );
    assert!(r.final_nodes[0].z.abs() < 1e-12 && r.final_nodes[1].z.abs() < 1e-12);
    // without the ground it falls freely: ½ g t² = 1.226 m
    let mut free = simulation(&s, None);
    free.settings = sim.settings.clone();
    let rf = free.run().unwrap();
    assert!((rf.final_nodes[0].z + 0.5 * G * t_end * t_end).abs() < 1e-9);
}

#[test]
fn rk45_locates_touchdown_event() {
    let z0 = 0.3;
    let s = dropped_prism(z0, 0.0);
    let mut sim = simulation(&s, None);
    sim.settings = SimulationSettings {
        t_end: 1.0,
        integrator: IntegratorKind::Rk45,
        dt: 0.1,
        ..Default::default()
    };
    sim.events.push(Event {
        name: "touchdown".into(),
        function: Box::new(|_, st| {
            (0..st.n_nodes())
                .map(|i| st.node(i).z)
                .fold(f64::MAX, f64::min)
        }),
        terminal: true,
    });
    let r = sim.run().unwrap();
    let exact = (2.0 * z0 / G).sqrt();
    assert_eq!(r.events.len(), 1);
    assert!(
        (r.events[0].t - exact).abs() < 1e-9,
        "{} vs {exact}",
        r.events[0].t
    );
    assert!((r.t_end - exact).abs() < 1e-9);
    assert!(r.final_nodes[0].z.abs() < 1e-9);
}
