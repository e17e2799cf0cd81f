//! Strict scene files (issue 26): a member with other than two node indices, two rest-length
//! tables for one string, a structure starting inside the ground and μ_k > μ_s are refused,
//! each naming the file, the item and its line; an oversized or endless file is refused
//! without being read into memory.

use tensegrity_io::read::{read_text, MAX_SCENE_BYTES};
use tensegrity_io::scene::{Scene, GROUND_START_TOLERANCE};
use tensegrity_io::IoError;

/// Two bars 0.1 m and more above the plane z = 0, three strings, a penalty ground.
const BASE: &str = "nodes = [[0.0, 0.0, 0.1], [1.0, 0.0, 0.1], [0.5, 1.0, 0.1], [0.5, 1.0, 1.1]]
[[bars]]
nodes = [0, 1]
mass = 1.0
[[bars]]
nodes = [2, 3]
mass = 1.0
[[strings]]
nodes = [1, 2]
stiffness = 10.0
[[strings]]
nodes = [2, 0]
stiffness = 10.0
[[strings]]
nodes = [3, 0]
stiffness = 10.0
[ground]
stiffness = 1e4
mu_static = 0.8
mu_kinetic = 0.6
";

fn refused(text: &str) -> String {
    let e = Scene::from_str_named(text, "bad.toml").unwrap_err();
    assert_eq!(
        tensegrity_core::request::Categorized::category(&e),
        tensegrity_core::request::Category::Input
    );
    e.to_string()
}

#[test]
fn the_base_scene_reads() {
    let scene = Scene::from_str_named(BASE, "ok.toml").unwrap();
    assert_eq!(scene.structure.n_strings(), 3);
    scene.simulation().unwrap();
}

#[test]
fn a_member_with_three_node_indices_is_refused_naming_it_and_its_line() {
    let e = refused(&BASE.replace("nodes = [0, 1]", "nodes = [0, 1, 2]"));
    assert_eq!(
        e,
        "bad.toml (line 2): bar 0: `nodes` must hold exactly two node indices, got 3 ([0, 1, 2])"
    );
    let e = refused(&BASE.replace("nodes = [2, 0]", "nodes = [2]"));
    assert!(
        e.starts_with("bad.toml (line 11): string 1:") && e.contains("got 1"),
        "{e}"
    );
    let e = refused(&BASE.replace("nodes = [1, 2]", "nodes = []"));
    assert!(e.contains("string 0") && e.contains("got 0"), "{e}");
}

#[test]
fn two_rest_length_tables_for_one_string_are_refused() {
    let table = "[[actuation]]\nstring = 1\ntimes = [0.0, 1.0]\nrest_lengths = [1.0, 0.9]\n";
    let text = format!("{BASE}{table}{table}");
    let e = refused(&text);
    assert_eq!(
        e,
        "bad.toml (line 25): actuation 1: string 1 already has a rest-length table \
         (actuation 0); give one table per string"
    );
    // one table per string, and two load tables for one node (they add), are fine
    let other = table.replace("string = 1", "string = 0");
    Scene::from_str_named(&format!("{BASE}{table}{other}"), "ok.toml").unwrap();
    let load = "[[actuation]]\nnode = 1\ntimes = [0.0]\nforces = [[0.0, 0.0, -1.0]]\n";
    Scene::from_str_named(&format!("{BASE}{load}{load}"), "ok.toml")
        .unwrap()
        .simulation()
        .unwrap();
}

#[test]
fn a_structure_starting_inside_the_ground_is_refused_naming_the_node_and_depth() {
    let text = BASE.replace("[0.5, 1.0, 0.1]", "[0.5, 1.0, -0.5]");
    let e = refused(&text);
    assert!(
        e.starts_with("bad.toml (line 1): ground: node 2 starts 0.5 m below the ground plane"),
        "{e}"
    );
    // within the tolerance it reads; a node that cannot touch the ground is not checked
    let depth = GROUND_START_TOLERANCE / 2.0;
    Scene::from_str_named(
        &BASE.replace("[0.5, 1.0, 0.1]", &format!("[0.5, 1.0, -{depth}]")),
        "ok.toml",
    )
    .unwrap();
    let only = text.replace("mu_kinetic = 0.6\n", "mu_kinetic = 0.6\nnodes = [0, 1]\n");
    Scene::from_str_named(&only, "ok.toml").unwrap();
    // a tilted plane: the depth is measured along its normal
    let tilted = BASE.replace(
        "[ground]\n",
        "[ground]\npoint = [0.0, 0.0, 1.0]\nnormal = [0.0, 0.0, 2.0]\n",
    );
    let e = refused(&tilted);
    assert!(e.contains("node 2 starts 0.9 m below"), "{e}");
}

#[test]
fn kinetic_friction_above_static_friction_is_refused() {
    let e = refused(&BASE.replace("mu_kinetic = 0.6", "mu_kinetic = 0.9"));
    assert_eq!(
        e,
        "bad.toml (line 17): ground: mu_kinetic (0.9) exceeds mu_static (0.8); \
         kinetic friction must not exceed static friction"
    );
    // equal is fine
    Scene::from_str_named(
        &BASE.replace("mu_kinetic = 0.6", "mu_kinetic = 0.8"),
        "ok.toml",
    )
    .unwrap();
}

#[test]
fn an_endless_or_oversized_file_is_refused_before_it_is_read() {
    let e = Scene::from_path("/dev/zero".as_ref()).unwrap_err();
    assert!(matches!(e, IoError::TooLarge { size: None, .. }), "{e:?}");
    assert_eq!(
        e.to_string(),
        format!("/dev/zero: more than {MAX_SCENE_BYTES} bytes, over the limit of {MAX_SCENE_BYTES} bytes for a scene file")
    );
    // a regular file is judged by its size (a sparse file: nothing is written or read)
    let path = std::env::temp_dir().join(format!("huge-scene-{}.toml", std::process::id()));
    let f = std::fs::File::create(&path).unwrap();
    f.set_len(MAX_SCENE_BYTES + 1).unwrap();
    let e = Scene::from_path(&path).unwrap_err().to_string();
    std::fs::remove_file(&path).unwrap();
    assert!(
        e.contains(&format!("{} bytes, over the limit", MAX_SCENE_BYTES + 1)),
        "{e}"
    );
    // not UTF-8
    let path = std::env::temp_dir().join(format!("binary-scene-{}.toml", std::process::id()));
    std::fs::write(&path, b"nodes = [\xff]").unwrap();
    let e = read_text(&path, 100, "a scene file")
        .unwrap_err()
        .to_string();
    std::fs::remove_file(&path).unwrap();
    assert!(e.contains("not UTF-8 text"), "{e}");
}

#[test]
fn a_ground_key_the_chosen_model_does_not_read_is_refused() {
    // the thesis model has no friction and no stiffness: its mu_* would be ignored
    let thesis = BASE.replace("stiffness = 1e4\n", "model = \"thesis\"\n");
    let e = refused(&thesis);
    assert!(
        e.starts_with("bad.toml (line 17): ground: `mu_static` is not read by the thesis model"),
        "{e}"
    );
    let bare = thesis
        .replace("mu_static = 0.8\n", "")
        .replace("mu_kinetic = 0.6\n", "");
    Scene::from_str_named(&bare, "ok.toml")
        .unwrap()
        .simulation()
        .unwrap();
    // and the penalty model has no contact distance
    let e = refused(&BASE.replace("[ground]\n", "[ground]\ntolerance = 1e-6\n"));
    assert!(
        e.contains("ground: `tolerance` is not read by the penalty model"),
        "{e}"
    );
}
