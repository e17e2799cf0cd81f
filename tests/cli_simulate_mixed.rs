//! `tensegrity simulate` of scenes with rigid bars beside elastic ones (a bar's `elastic`
//! key): examples/mixed_bars.toml runs the node-mass model with its rigid bars as length
//! constraints — valid, the rigid lengths kept to round-off, Newmark and RK4 agreeing —; a
//! scene whose bars are all made rigid runs the rigid-bar dynamics unchanged; bad `elastic`
//! keys are errors naming the bar, and the commands that would ignore the key refuse it.

use crate::common;

use common::{json, points, run};

const SCENE: &str = "examples/mixed_bars.toml";

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|d| (a[d] - b[d]).powi(2)).sum::<f64>().sqrt()
}

fn gap(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(a, b)| distance(*a, *b))
        .fold(0.0, f64::max)
}

/// The example's nodes (as its file lists them).
const NODES: [[f64; 3]; 6] = [
    [1.0, 0.0, 0.0],
    [-0.4999999999999998, 0.8660254037844387, 0.0],
    [-0.5000000000000004, -0.8660254037844384, 0.0],
    [0.8660254037844386, 0.5, 1.0],
    [-0.8660254037844385, 0.5000000000000003, 1.0],
    [-1.8369701987210297e-16, -1.0, 1.0],
];

/// The example: Newmark at 0.1 ms is valid (its refined companion agrees), holds the rigid
/// bars 1–5 and 2–3 at their lengths to 1e-12 relative while the elastic bar 0–4 has
/// stretched, keeps the energy to 1e-5 (measured 4.3e-6), and lands within 1e-4 m of RK4
/// at the same step (measured 2.0e-5 m: Newmark's second-order phase error).
#[test]
fn the_mixed_example_runs_valid_with_its_rigid_lengths_kept() {
    let r = json(&["simulate", SCENE, "--json"]);
    assert_eq!(r["valid"], true, "{r}");
    assert_eq!(r["steps"], 5000);
    let drift = r["bar_length_drift"].as_f64().unwrap();
    assert!(drift < 1e-12, "{drift:e}");
    let energy = r["energy_drift"].as_f64().unwrap();
    assert!(energy < 1e-5, "{energy:e}");
    let x0 = NODES;
    let x = points(&r["final_nodes"]);
    for [i, j] in [[1, 5], [2, 3]] {
        let (l0, l) = (distance(x0[i], x0[j]), distance(x[i], x[j]));
        assert!((l - l0).abs() < 1e-12 * l0, "bar {i}-{j}: {l} against {l0}");
    }
    let (l0, l) = (distance(x0[0], x0[4]), distance(x[0], x[4]));
    assert!(
        (l - l0).abs() > 1e-6,
        "the elastic bar stretches: {l} against {l0}"
    );
    let rk4 = json(&["simulate", SCENE, "--integrator", "rk4", "--json"]);
    let d = gap(&x, &points(&rk4["final_nodes"]));
    assert!(d < 1e-4, "newmark against rk4: {d:e}");
    assert!(rk4["bar_length_drift"].as_f64().unwrap() < 1e-12);
}

/// Every bar made rigid by its own key (over `[simulation] bars = "elastic"`): the rigid-bar
/// dynamics runs, exactly as for the scene without the keys.
#[test]
fn a_scene_whose_bars_are_all_rigid_runs_the_rigid_dynamics() {
    let dir = common::scratch("mixed", "all_rigid");
    let text = std::fs::read_to_string(SCENE).unwrap();
    let plain = text
        .replace("elastic = true\n", "")
        .replace("elastic = false\n", "");
    let keyed = plain
        .replace("[simulation]\n", "[simulation]\nbars = \"elastic\"\n")
        .replace("mass = 1.0\n", "mass = 1.0\nelastic = false\n");
    assert_eq!(keyed.matches("elastic = false").count(), 3, "{keyed}");
    let (a, b) = (dir.join("plain.toml"), dir.join("keyed.toml"));
    std::fs::write(&a, plain.replace("integrator = \"newmark\"\n", "")).unwrap();
    std::fs::write(&b, keyed.replace("integrator = \"newmark\"\n", "")).unwrap();
    let (ra, rb) = (
        json(&["simulate", a.to_str().unwrap(), "--json"]),
        json(&["simulate", b.to_str().unwrap(), "--json"]),
    );
    assert_eq!(ra["final_nodes"], rb["final_nodes"]);
    assert_eq!(ra["steps"], rb["steps"]);
}

fn refused(args: &[&str], says: &str) {
    let out = run(args);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(says), "{args:?}: {err}");
}

/// A bad `elastic` (not a boolean), an elastic bar without its axial stiffness, a rigid bar
/// of zero length, a rigid bar with a rest length: errors naming the bar; `statics` and
/// `solve` refuse the key they would ignore.
#[test]
fn bad_bar_models_are_errors_naming_the_bar() {
    let dir = common::scratch("mixed", "bad");
    let text = std::fs::read_to_string(SCENE).unwrap();
    let bar1 = "nodes = [1, 5]\nmass = 1.0\nelastic = false\n";
    assert!(text.contains(bar1));
    for (k, (from, to, says)) in [
        (
            bar1,
            "nodes = [1, 5]\nmass = 1.0\nelastic = \"yes\"\n",
            "bar 1: elastic = \"yes\": give true (an elastic bar) or false (a rigid one)",
        ),
        (
            bar1,
            "nodes = [1, 5]\nmass = 1.0\nelastic = true\n",
            "bar 1: an elastic bar needs a radius",
        ),
        (
            "[-1.8369701987210297e-16, -1.0, 1.0]",
            "[-0.4999999999999998, 0.8660254037844387, 0.0]",
            "bar 1: has zero length",
        ),
        (
            bar1,
            "nodes = [1, 5]\nmass = 1.0\nelastic = false\nrest_length = 1.0\n",
            "bar 1: a rigid bar keeps its length in the scene",
        ),
    ]
    .into_iter()
    .enumerate()
    {
        let scene = dir.join(format!("bad_{k}.toml"));
        std::fs::write(&scene, text.replace(from, to)).unwrap();
        refused(&["simulate", scene.to_str().unwrap()], says);
    }
    refused(
        &["statics", SCENE],
        "bar 0: elastic is read by `simulate` only",
    );
    refused(
        &["solve", SCENE],
        "bar 1: elastic = false is read by `simulate` only",
    );
}
