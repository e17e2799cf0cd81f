//! Strict inputs end to end (issue 26, docs/ROBUSTNESS.md): each bad input the catalogue found
//! accepted silently is now refused by the binary with exit code 2 and a message naming the
//! file, the item and (in a scene) its line.

use crate::common;
use common::{run, scratch};
use std::path::{Path, PathBuf};
use std::process::Output;

/// Two bars above the plane z = 0, three strings, a penalty ground with friction.
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
[simulation]
t_end = 0.01
[ground]
stiffness = 1e4
mu_static = 0.8
mu_kinetic = 0.6
";

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

/// Asserts exit code 2 and returns stderr.
fn refused(out: &Output) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{err}");
    err
}

/// `statics` and `simulate` of the scene `text` both refuse it; the message of `statics`.
fn scene_refused(name: &str, text: &str) -> String {
    let dir = scratch("inputs", name);
    let path = write(&dir, "scene.toml", text);
    let p = path.to_str().unwrap();
    let err = refused(&run(&["statics", p]));
    assert!(err.contains(p), "{err}");
    let sim = refused(&run(&["simulate", p]));
    assert_eq!(sim, err);
    err
}

#[test]
fn the_base_scene_simulates() {
    let dir = scratch("inputs", "base");
    let path = write(&dir, "scene.toml", BASE);
    let out = run(&["simulate", path.to_str().unwrap(), "--json"]);
    common::assert_ok(&out);
}

#[test]
fn a_bar_with_three_node_indices_is_refused() {
    let err = scene_refused(
        "three",
        &BASE.replacen("nodes = [0, 1]", "nodes = [0, 1, 2]", 1),
    );
    assert!(
        err.contains("(line 2): bar 0: `nodes` must hold exactly two node indices, got 3"),
        "{err}"
    );
    let err = scene_refused("one", &BASE.replacen("nodes = [3, 0]", "nodes = [3]", 1));
    assert!(
        err.contains("(line 14): string 2:") && err.contains("got 1"),
        "{err}"
    );
}

#[test]
fn two_actuation_tables_for_one_string_are_refused() {
    let table = "[[actuation]]\nstring = 0\ntimes = [0.0, 1.0]\nrest_lengths = [1.0, 0.9]\n";
    let err = scene_refused("actuation", &format!("{BASE}{table}{table}"));
    assert!(
        err.contains(
            "(line 27): actuation 1: string 0 already has a rest-length table (actuation 0)"
        ),
        "{err}"
    );
}

#[test]
fn a_structure_starting_inside_the_ground_is_refused() {
    let err = scene_refused("ground", &BASE.replace("0.1]", "-0.4]"));
    assert!(
        err.contains("(line 1): ground: node 2 starts 0.4 m below the ground plane"),
        "{err}"
    );
}

#[test]
fn kinetic_friction_above_static_friction_is_refused() {
    let err = scene_refused(
        "friction",
        &BASE.replace("mu_kinetic = 0.6", "mu_kinetic = 0.9"),
    );
    assert!(
        err.contains("(line 19): ground: mu_kinetic (0.9) exceeds mu_static (0.8)"),
        "{err}"
    );
}

#[test]
fn statics_of_dev_zero_is_refused_at_once_without_growing_memory() {
    // under a 2 GB address-space cap (the file was read to 4.2 GB before)
    let start = std::time::Instant::now();
    let out = std::process::Command::new("bash")
        .arg("-c")
        .arg(format!(
            "ulimit -v 2000000 && exec {} statics /dev/zero",
            env!("CARGO_BIN_EXE_tensegrity")
        ))
        .output()
        .unwrap();
    let err = refused(&out);
    assert!(
        err.contains("/dev/zero: more than 67108864 bytes, over the limit of 67108864 bytes for a scene file"),
        "{err}"
    );
    assert!(start.elapsed().as_secs() < 5);
    // a large regular file: refused from its size, before reading it
    let dir = scratch("inputs", "huge");
    let path = dir.join("huge.toml");
    std::fs::File::create(&path)
        .unwrap()
        .set_len(1 << 30)
        .unwrap();
    let err = refused(&run(&["statics", path.to_str().unwrap()]));
    assert!(err.contains("1073741824 bytes, over the limit"), "{err}");
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn sweep_merge_refuses_shards_of_two_specs_sharing_a_header() {
    let dir = scratch("inputs", "merge");
    let spec = "study = \"tipover\"\n[fixed]\nouter_radius = 1.0\n[axes]\nsides = [6, 8]\n";
    let a = write(&dir, "a.toml", spec);
    let b = write(&dir, "b.toml", &spec.replace("1.0", "2.0"));
    let path = |n: &str| dir.join(n).to_string_lossy().into_owned();
    for (s, k, out) in [
        (&a, "1/2", "a1.csv"),
        (&b, "2/2", "b2.csv"),
        (&a, "2/2", "a2.csv"),
    ] {
        common::assert_ok(&run(&[
            "sweep",
            s.to_str().unwrap(),
            "--shard",
            k,
            "--out",
            &path(out),
            "--quiet",
        ]));
    }
    let out = run(&[
        "sweep",
        "merge",
        &path("a1.csv"),
        &path("b2.csv"),
        "--out",
        &path("m.csv"),
    ]);
    let err = refused(&out);
    assert!(
        err.contains(&format!(
            "cannot merge {}: it comes from another spec than {}",
            path("b2.csv"),
            path("a1.csv")
        )),
        "{err}"
    );
    assert!(!Path::new(&path("m.csv")).exists());
    // the shards of one spec still merge
    let out = run(&[
        "sweep",
        "merge",
        &path("a1.csv"),
        &path("a2.csv"),
        "--out",
        &path("m.csv"),
    ]);
    common::assert_ok(&out);
    let merged = std::fs::read_to_string(path("m.csv")).unwrap();
    assert!(merged.starts_with("case,sides,"), "{merged}");
    assert_eq!(merged.lines().count(), 3);
}
