//! Recorder, projection and error reporting of the dynamics (the scene tables and actuation
//! tables are tested with their parser in crates/tensegrity-io/tests/scene_dynamics.rs).

use tensegrity_core::{
    Bar, CoreError, DynamicsError, MemberId, ModelError, StringMember, Structure, Support,
};
use tensegrity_dynamics::test_models::double_pendulum;
use tensegrity_dynamics::{Model, Quantities, Simulation, SimulationSettings};

#[test]
fn recorder_samples_only_requested_times_and_quantities() {
    let s = double_pendulum(0.5).unwrap();
    let settings = SimulationSettings {
        t_end: 1.0,
        dt: 0.01,
        output_times: vec![0.333, 0.5, 2.0],
        quantities: Quantities {
            member_forces: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let sim = Simulation::new(&s, settings).unwrap();
    let r = sim.run().unwrap();
    // 2.0 is after t_end: dropped
    assert_eq!(r.samples.len(), 2);
    assert!((r.samples[0].t - 0.333).abs() < 1e-15);
    assert!(r.samples[0].nodes.is_none() && r.samples[0].energy.is_none());
    let f = r.samples[0].member_forces.as_ref().unwrap();
    assert_eq!(f.len(), 2);
    // the upper rod carries more than the lower one, both in tension while hanging
    assert!(f[0] > f[1] && f[1] > 0.0, "{f:?}");
    // the fixed grid is kept: 100 grid steps + 1 extra step to hit t = 0.333
    assert_eq!(r.steps, 101);
}

#[test]
fn static_pendulum_member_forces_match_statics() {
    // A single rod hanging straight down from a pin carries its own weight: the closed-form λ
    // with Ω gives a tension of m g / 2 at rest (the lower half-weight hangs from the bar).
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [0.0, -1.0, 0.0]])
        .bar(Bar::new(0, 1).mass(2.0))
        .support(Support::pinned(0))
        .gravity([0.0, -9.8, 0.0])
        .build()
        .unwrap();
    let model = Model::new(&s, None).unwrap();
    let y = model.initial_state(&s).unwrap();
    let mut ws = model.workspace().unwrap();
    let f = model.member_forces(0.0, &y, &mut ws).unwrap();
    assert!((f[0] - 9.8).abs() < 1e-12, "{f:?}");
}

#[test]
fn projection_removes_bar_drift_of_rk4() {
    let s = double_pendulum(std::f64::consts::FRAC_PI_4).unwrap();
    let mut set = SimulationSettings {
        t_end: 2.0,
        dt: 0.02,
        ..Default::default()
    };
    let plain = Simulation::new(&s, set.clone()).unwrap().run().unwrap();
    set.project = true;
    let projected = Simulation::new(&s, set).unwrap().run().unwrap();
    assert!(
        plain.bar_length_drift > 1e-9,
        "{:e}",
        plain.bar_length_drift
    );
    assert!(
        projected.bar_length_drift < 1e-12,
        "{:e}",
        projected.bar_length_drift
    );
}

#[test]
fn errors_name_the_member_and_time() {
    // bar without mass
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1))
        .build()
        .unwrap();
    let e = Model::new(&s, None).unwrap_err();
    assert_eq!(
        e,
        CoreError::Model(ModelError::MissingProperty {
            member: MemberId::Bar(0),
            analysis: "dynamics",
            property: "mass"
        })
    );
    assert_eq!(
        e.to_string(),
        "bar 0: dynamics needs its mass, which is not given"
    );
    // ... unless a material and a radius give it: steel (7862 kg/m³), r = 1 cm, l = 1 m.
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1).material("steel").radius(0.01))
        .gravity([0.0, 0.0, -9.81])
        .build()
        .unwrap();
    let m = 7862.0 * std::f64::consts::PI * 1e-4;
    let mut sim = Simulation::new(&s, SimulationSettings::default()).unwrap();
    sim.settings.t_end = 0.1;
    let r = sim.run().unwrap();
    let ke = sim.model.kinetic_energy(&r.final_state);
    let v = 9.81 * 0.1;
    assert!(
        (ke - 0.5 * m * v * v).abs() < 1e-9 * ke,
        "KE {ke} vs {}",
        0.5 * m * v * v
    );
    // string without stiffness
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
        .bar(Bar::new(0, 1).mass(1.0))
        .string(StringMember::new(1, 2))
        .support(Support::pinned(2))
        .build()
        .unwrap();
    assert!(matches!(
        Model::new(&s, None).unwrap_err(),
        CoreError::Model(ModelError::MissingProperty {
            member: MemberId::String(0),
            analysis: "dynamics",
            property: "stiffness"
        })
    ));
    // massless free node
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
        .bar(Bar::new(0, 1).mass(1.0))
        .string(StringMember::new(1, 2).stiffness(1.0))
        .build()
        .unwrap();
    assert_eq!(
        Model::new(&s, None).unwrap_err(),
        CoreError::Dynamics(DynamicsError::FreeNodeWithoutBar { node: 2 })
    );
    // a bar pinned at both ends: redundant constraints
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1).mass(1.0))
        .support(Support::pinned(0))
        .support(Support::pinned(1))
        .build()
        .unwrap();
    let sim = Simulation::new(&s, SimulationSettings::default()).unwrap();
    assert!(matches!(
        sim.run().unwrap_err(),
        CoreError::Dynamics(DynamicsError::SingularConstraint { expected: 6, .. })
    ));
    // blow-up: a pendulum with a tiny blow-up distance stops with the time and the bar
    let s = double_pendulum(1.0).unwrap();
    let set = SimulationSettings {
        t_end: 1.0,
        blowup_distance: Some(0.05),
        ..Default::default()
    };
    let e = Simulation::new(&s, set).unwrap().run().unwrap_err();
    match e {
        ref e @ CoreError::Dynamics(DynamicsError::BlowUp { t, distance, .. }) => {
            assert!(t > 0.0 && t < 1.0);
            assert!(distance > 0.05);
            let msg = e.to_string();
            assert!(
                msg.starts_with(&format!("blow-up at t = {t} s: bar ")),
                "{msg}"
            );
            // the fixed-step run names its remedy in the library's terms
            assert!(
                msg.ends_with("; the step (0.001 s) is likely too large for the stiffness of the strings or the ground: use a smaller `dt`, or `integrator = sdirk` (implicit, for stiff strings and contact) or `integrator = rk45` (adaptive)"),
                "{msg}"
            );
        }
        other => panic!("unexpected {other}"),
    }
    // inconsistent initial velocity: a bar that would stretch
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
        .velocities([[0.0; 3], [1.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1).mass(1.0))
        .build()
        .unwrap();
    let e = Simulation::new(&s, SimulationSettings::default()).unwrap_err();
    assert!(e.to_string().starts_with("bar 0:"), "{e}");
    // invalid settings
    let s = double_pendulum(1.0).unwrap();
    let set = SimulationSettings {
        dt: -1.0,
        ..Default::default()
    };
    assert!(matches!(
        Simulation::new(&s, set).unwrap().run().unwrap_err(),
        CoreError::InvalidParameter(p) if p.name == "dt"
    ));
}

#[test]
fn nan_in_the_state_is_reported_with_time_and_member() {
    let s = double_pendulum(1.0).unwrap();
    let mut sim = Simulation::new(&s, SimulationSettings::default()).unwrap();
    sim.model.set_load_schedule(Box::new(|t, loads| {
        if t > 0.25 {
            loads[2].x = f64::NAN;
        }
    }));
    match sim.run().unwrap_err() {
        CoreError::Dynamics(DynamicsError::NonFiniteState { t, member, .. }) => {
            assert!((0.25..0.252).contains(&t), "t = {t}");
            assert_eq!(member, MemberId::Bar(1));
        }
        other => panic!("unexpected {other}"),
    }
}
