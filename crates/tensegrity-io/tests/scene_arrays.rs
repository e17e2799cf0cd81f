//! A scene as data ([`SceneArrays`], [`Scene::from_arrays`]): the structure built from its
//! columns is the one read from the same scene's TOML, and the data is validated as a file
//! is — errors name the item and give no line.

use tensegrity_io::scene::{Scene, SceneArrays};

/// A loaded, supported prism-like scene with every column and the dynamics tables.
const TEXT: &str = r#"
nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.5, 0.0], [1.0, 0.5, 1.0]]
velocities = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.5]]
[materials.alu]
density = 2700.0
youngs_modulus = 60e9
yield_strength = 110e6
[[bars]]
nodes = [0, 3]
mass = 1.0
material = "alu"
radius = 0.01
[[bars]]
nodes = [1, 3]
[[strings]]
nodes = [0, 1]
stiffness = 100.0
rest_length = 1.9
damping = 0.5
[[strings]]
nodes = [1, 2]
stiffness = 200.0
[[strings]]
nodes = [2, 0]
material = "steel"
[[strings]]
nodes = [2, 3]
[[supports]]
node = 0
[[supports]]
node = 1
fixed = [false, true, true]
[[loads]]
node = 3
force = [0.0, 0.0, -10.0]
[gravity]
acceleration = [0.0, 0.0, -9.81]
[simulation]
t_end = 0.5
[ground]
point = [0.0, 0.0, -1.0]
stiffness = 1e4
mu_static = 0.5
[[actuation]]
string = 3
times = [0.0, 1.0]
rest_lengths = [1.2, 1.1]
"#;

const DATA: &str = r#"{
  "nodes": [[0, 0, 0], [2, 0, 0], [1, 1.5, 0], [1, 0.5, 1]],
  "velocities": [[0, 0, 0], [0, 0, 0], [0, 0, 0], [0, 0, 0.5]],
  "materials": {"alu": {"density": 2700, "youngs_modulus": 60e9, "yield_strength": 110e6}},
  "bars": [[0, 3], [1, 3]],
  "strings": [[0, 1], [1, 2], [2, 0], [2, 3]],
  "bar_mass": [1.0, null], "bar_material": ["alu", null], "bar_radius": [0.01, null],
  "stiffness": [100, 200, null, null], "rest_length": [1.9, null, null, null],
  "damping": [0.5, null, null, null], "string_material": [null, null, "steel", null],
  "supports": [[0, [true, true, true]], [1, [false, true, true]]],
  "loads": [[3, [0, 0, -10]]],
  "gravity": [0, 0, -9.81],
  "simulation": {"t_end": 0.5},
  "ground": {"point": [0, 0, -1], "stiffness": 1e4, "mu_static": 0.5},
  "actuation": [{"string": 3, "times": [0, 1], "rest_lengths": [1.2, 1.1]}]
}"#;

fn data() -> SceneArrays {
    serde_json::from_str(DATA).unwrap()
}

fn error(arrays: SceneArrays) -> String {
    Scene::from_arrays(arrays, "data").unwrap_err().to_string()
}

#[test]
fn a_structure_from_arrays_is_the_one_read_from_toml() {
    let read = Scene::from_str_named(TEXT, "scene.toml").unwrap();
    let given = Scene::from_arrays(data(), "data").unwrap();
    let (a, b) = (&given.structure, &read.structure);
    assert_eq!(a.nodes(), b.nodes());
    assert_eq!(a.velocities(), b.velocities());
    assert_eq!((a.bars(), a.strings()), (b.bars(), b.strings()));
    assert_eq!((a.supports(), a.loads()), (b.supports(), b.loads()));
    assert_eq!(a.gravity(), b.gravity());
    assert_eq!(a, b);
    // the dynamics tables are the file's
    assert_eq!(given.file.simulation, read.file.simulation);
    let (ga, gb) = (given.file.ground.as_ref(), read.file.ground.as_ref());
    assert_eq!(ga.unwrap().get_ref(), gb.unwrap().get_ref());
    assert_eq!(given.file.actuation.len(), 1);
    // and the columns of either scene give the same data back
    assert_eq!(SceneArrays::of(&read), SceneArrays::of(&given));
    let back = SceneArrays::of(&read);
    assert_eq!(
        Scene::from_arrays(back, "again").unwrap().structure,
        read.structure
    );
}

#[test]
fn the_serde_form_round_trips_and_refuses_unknown_keys() {
    let a = SceneArrays::of(&Scene::from_str_named(TEXT, "scene.toml").unwrap());
    let json = serde_json::to_value(&a).unwrap();
    assert_eq!(
        serde_json::from_value::<SceneArrays>(json.clone()).unwrap(),
        a
    );
    assert!(json.get("velocities").is_some() && json["bars"][0] == serde_json::json!([0, 3]));
    let mut bad = json;
    bad["bar_masses"] = serde_json::json!([1.0, 1.0]);
    let e = serde_json::from_value::<SceneArrays>(bad)
        .unwrap_err()
        .to_string();
    assert!(e.contains("bar_masses"), "{e}");
}

#[test]
fn bad_items_are_named_without_a_line() {
    let mut a = data();
    a.bars[1] = [1, 7];
    let e = error(a);
    assert_eq!(
        e,
        "data: bar 1: node index 7 is out of range (the structure has 4 nodes, 0-based)"
    );
    let mut a = data();
    a.strings[2] = [-2, 0];
    let e = error(a);
    assert_eq!(
        e,
        "data: string 2: node index -2 is out of range (the structure has 4 nodes, 0-based)"
    );
    let mut a = data();
    a.supports[1].0 = -1;
    assert!(error(a).starts_with("data: support 1: node index -1"));
    let mut a = data();
    a.stiffness = Some(vec![Some(100.0), Some(-5.0), None, None]);
    let e = error(a);
    assert!(
        e.starts_with("data: string 1:") && e.contains("stiffness") && e.contains("-5"),
        "{e}"
    );
    assert!(!e.contains("line"), "{e}");
    // the same error read from text names the line
    let text = TEXT.replace("stiffness = 200.0", "stiffness = -5.0");
    let e = Scene::from_str_named(&text, "scene.toml")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("scene.toml (line 20): string 1:"), "{e}");
}

#[test]
fn a_non_finite_number_given_as_its_text_is_named_by_the_structures_check() {
    let mut json: serde_json::Value = serde_json::from_str(DATA).unwrap();
    json["nodes"][2][1] = serde_json::json!("NaN");
    let e = error(serde_json::from_value(json.clone()).unwrap());
    assert!(
        e.starts_with("data: node 2:") && e.contains("not finite"),
        "{e}"
    );
    json["nodes"][2][1] = serde_json::json!(1.5);
    json["loads"][0][1][2] = serde_json::json!("-inf");
    let e = error(serde_json::from_value(json.clone()).unwrap());
    assert!(e.starts_with("data: load 0:"), "{e}");
    json["loads"][0][1][2] = serde_json::json!("ten");
    let e = serde_json::from_value::<SceneArrays>(json)
        .unwrap_err()
        .to_string();
    assert!(e.contains("\"ten\""), "{e}");
}

#[test]
fn a_column_of_the_wrong_length_is_named() {
    let mut a = data();
    a.rest_length = Some(vec![Some(1.0)]);
    assert_eq!(
        error(a),
        "data: rest_length: expected one entry per string (4), got 1"
    );
    let mut a = data();
    a.bar_material = Some(vec![None, None, None]);
    assert_eq!(
        error(a),
        "data: bar_material: expected one entry per bar (2), got 3"
    );
}

#[test]
fn the_dynamics_tables_are_checked_as_a_files() {
    // μ_k > μ_s
    let mut a = data();
    a.ground.as_mut().unwrap().mu_kinetic = Some(0.9);
    let e = error(a);
    assert!(
        e.starts_with("data: ground: mu_kinetic (0.9) exceeds"),
        "{e}"
    );
    // a node below the ground
    let mut a = data();
    a.ground.as_mut().unwrap().point = [0.0, 0.0, 0.5];
    let e = error(a);
    assert!(
        e.starts_with("data: ground: node 2 starts 0.5 m below"),
        "{e}"
    );
    // two rest-length tables of one string
    let mut a = data();
    a.actuation.push(a.actuation[0].clone());
    let e = error(a);
    assert!(e.contains("actuation 1: string 3 already has"), "{e}");
    assert!(!e.contains("line"), "{e}");
}
