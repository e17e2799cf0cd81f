//! The dynamics tables of a scene (`[simulation]`, `[ground]`, `[[actuation]]`): parsing,
//! mapping onto the core's settings and ground, actuation schedules and their errors.

use tensegrity_core::test_models::{double_pendulum, snelson_prism, PrismParams};
use tensegrity_dynamics::{IntegratorKind, Quantities, SimulationSettings};
use tensegrity_io::scene::{build_simulation, ActuationSpec, GroundSpec, Scene, SimulationSpec};

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
    // the table maps onto the core's settings; what the recorder does with them is tested in
    // the core (`dynamics_features.rs`, the same run built without a file)
    let set = &sim.settings;
    assert_eq!((set.t_end, set.dt), (1.0, 0.01));
    assert_eq!(set.output_times, vec![0.333, 0.5, 2.0]);
    assert!(set.quantities.member_forces && !set.quantities.nodes && !set.quantities.energy);
    let r = sim.run().unwrap();
    // 2.0 is after t_end: dropped
    assert_eq!(r.samples.len(), 2);
}

#[test]
fn actuated_rest_length_changes_string_tension() {
    let s = snelson_prism(&PrismParams::default()).unwrap();
    let s0 = s.strings()[6].rest_length.unwrap();
    let act = ActuationSpec {
        cluster: None,
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
        cluster: None,
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
fn a_scene_builds_its_simulation_with_ground_and_actuation() {
    let text = "nodes = [[0.0, 0.0, 0.1], [1.0, 0.0, 0.1], [0.5, 1.0, 0.1], [0.5, 1.0, 1.1]]\n\
        [[bars]]\nnodes = [0, 1]\nmass = 1.0\n[[bars]]\nnodes = [2, 3]\nmass = 1.0\n\
        [[strings]]\nnodes = [1, 2]\nstiffness = 10.0\n[[strings]]\nnodes = [2, 0]\nstiffness = 10.0\n\
        [[strings]]\nnodes = [3, 0]\nstiffness = 10.0\n\
        [simulation]\nt_end = 0.5\nintegrator = \"rk45\"\n\
        [ground]\nstiffness = 1e4\nnodes = [0, 1]\n\
        [[actuation]]\nnode = 2\ntimes = [0.0, 1.0]\nforces = [[0.0, 0.0, 0.0], [0.0, 0.0, -1.0]]\n";
    let scene = Scene::from_str_named(text, "ok.toml").unwrap();
    let sim = scene.simulation().unwrap();
    assert_eq!(sim.settings.integrator, IntegratorKind::Rk45);
    assert_eq!(sim.settings.dt, 0.5); // rk45: the maximum step defaults to t_end
    assert_eq!(sim.model.ground().unwrap().nodes, Some(vec![0, 1]));
    // an actuation table naming a node that does not exist is refused, naming the table
    let bad = text.replace("node = 2\n", "node = 9\n");
    let e = Scene::from_str_named(&bad, "bad.toml")
        .unwrap()
        .simulation()
        .unwrap_err()
        .to_string();
    assert!(e.contains("actuation 0") && e.contains("node 9"), "{e}");
}
