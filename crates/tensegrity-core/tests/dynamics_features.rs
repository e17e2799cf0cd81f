//! Scene tables, actuation, recorder, projection and error reporting of the dynamics.

use tensegrity_core::dynamics::{
    build_simulation, ActuationSpec, GroundSpec, IntegratorKind, Model, Quantities, Simulation,
    SimulationSettings, SimulationSpec,
};
use tensegrity_core::test_models::{double_pendulum, snelson_prism, PrismParams};
use tensegrity_core::{Bar, CoreError, MemberId, StringMember, Structure, Support};

#[test]
fn scene_tables_parse_and_reject_unknown_fields() {
    let sim: SimulationSpec = toml::from_str(
        r#"
        t_end = 2.0
        integrator = "rattle"
        dt = 0.002
        output_interval = 0.5
        record = ["nodes", "member_forces"]
        "#,
    )
    .unwrap();
    let set = sim.to_settings();
    assert_eq!(set.integrator, IntegratorKind::Rattle);
    assert_eq!(set.dt, 0.002);
    assert!(set.quantities.nodes && set.quantities.member_forces && !set.quantities.energy);
    // round trip through TOML
    let text = toml::to_string(&sim).unwrap();
    assert_eq!(toml::from_str::<SimulationSpec>(&text).unwrap(), sim);
    let rk45: SimulationSpec = toml::from_str("t_end = 3.0\nintegrator = \"rk45\"").unwrap();
    assert_eq!(rk45.to_settings().dt, 3.0); // maximum step defaults to t_end
    let bad = toml::from_str::<SimulationSpec>("t_end = 1.0\nintegrater = \"rk4\"");
    assert!(bad.unwrap_err().to_string().contains("integrater"));
    let g: GroundSpec = toml::from_str("stiffness = 1e5\nmu_static = 0.5").unwrap();
    assert_eq!(g.normal, [0.0, 0.0, 1.0]);
    assert!(toml::from_str::<GroundSpec>("stifness = 1.0").is_err());
    // penalty without stiffness is an error naming the ground
    let g: GroundSpec = toml::from_str("damping = 1.0").unwrap();
    let e = g.to_ground().unwrap_err();
    assert!(e.to_string().contains("ground"), "{e}");
    let a: ActuationSpec =
        toml::from_str("string = 0\ntimes = [0.0, 1.0]\nrest_lengths = [1.0, 0.9]").unwrap();
    assert_eq!(a.string, Some(0));
}

#[test]
fn recorder_samples_only_requested_times_and_quantities() {
    let s = double_pendulum(0.5).unwrap();
    let spec: SimulationSpec = toml::from_str(
        "t_end = 1.0\ndt = 0.01\noutput_times = [0.333, 0.5, 2.0]\nrecord = [\"member_forces\"]",
    )
    .unwrap();
    let sim = build_simulation(&s, Some(&spec), None, &[]).unwrap();
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
fn actuated_rest_length_changes_string_tension() {
    let s = snelson_prism(&PrismParams::default()).unwrap();
    let s0 = s.strings()[6].rest_length.unwrap();
    let act = ActuationSpec {
        string: Some(6),
        node: None,
        times: vec![0.0, 0.1],
        rest_lengths: Some(vec![s0, 0.98 * s0]),
        forces: None,
    };
    let mut sim = build_simulation(&s, None, None, &[act]).unwrap();
    sim.settings = SimulationSettings {
        t_end: 0.2,
        output_times: vec![0.0, 0.2],
        quantities: Quantities {
            member_forces: true,
            ..Default::default()
        },
        ..Default::default()
    };
    let r = sim.run().unwrap();
    let f0 = r.samples[0].member_forces.as_ref().unwrap()[3 + 6];
    let f1 = r.samples[1].member_forces.as_ref().unwrap()[3 + 6];
    assert!(f1 > f0 + 10.0, "actuated string tension {f0} → {f1}");
    // without actuation nothing moves
    let still = build_simulation(&s, None, None, &[]).unwrap();
    let mut still = still;
    still.settings.t_end = 0.2;
    let rs = still.run().unwrap();
    let moved = rs
        .final_nodes
        .iter()
        .zip(s.nodes())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(moved < 1e-10);
    // bad tables are rejected with the table named
    let bad = ActuationSpec {
        string: Some(6),
        node: None,
        times: vec![0.1, 0.0],
        rest_lengths: Some(vec![1.0, 1.0]),
        forces: None,
    };
    let e = build_simulation(&s, None, None, &[bad]).unwrap_err();
    assert!(e.to_string().contains("actuation 0"), "{e}");
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
        CoreError::MissingProperty {
            member: MemberId::Bar(0),
            analysis: "dynamics",
            property: "mass"
        }
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
        CoreError::MissingProperty {
            member: MemberId::String(0),
            analysis: "dynamics",
            property: "stiffness"
        }
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
        CoreError::FreeNodeWithoutBar { node: 2 }
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
        CoreError::SingularConstraint { expected: 6, .. }
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
        ref e @ CoreError::BlowUp { t, distance, .. } => {
            assert!(t > 0.0 && t < 1.0);
            assert!(distance > 0.05);
            let msg = e.to_string();
            assert!(
                msg.starts_with(&format!("blow-up at t = {t} s: bar ")),
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
        CoreError::InvalidParameter { name: "dt", .. }
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
        CoreError::NonFiniteState { t, member } => {
            assert!((0.25..0.252).contains(&t), "t = {t}");
            assert_eq!(member, MemberId::Bar(1));
        }
        other => panic!("unexpected {other}"),
    }
}
