//! `[[clusters]]` in scene files and scene data: read into the structure's clusters, written
//! back exactly (TOML and data), every bad cluster named with its line.

use tensegrity_io::scene::{to_toml, Scene, SceneArrays};

/// A string from an anchor (node 0) over two pulleys (nodes 1, 2) to a hanging node 3.
const TWO_PULLEYS: &str =
    "nodes = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [2.0, 0.0, 1.0], [2.0, 0.0, 0.0]]

[[clusters]]
nodes = [0, 1, 2, 3]
stiffness = 1e4
rest_length = 2.9
damping = 0.5
friction = [0.1, 0.0]
material = \"uhmwpe\"

[[supports]]
node = 0

[[supports]]
node = 1

[[supports]]
node = 2
";

#[test]
fn a_cluster_is_read_and_written_back_exactly() {
    let scene = Scene::from_str_named(TWO_PULLEYS, "pulleys.toml").unwrap();
    let c = &scene.structure.clusters()[0];
    assert_eq!(c.nodes, vec![0, 1, 2, 3]);
    assert_eq!(
        (c.stiffness, c.rest_length, c.damping),
        (Some(1e4), Some(2.9), 0.5)
    );
    assert_eq!(c.friction, Some(vec![0.1, 0.0]));
    assert!(!c.is_frictionless());
    assert_eq!(c.inner_nodes(), &[1, 2]);
    assert_eq!(c.length(scene.structure.nodes()), 3.0);
    let again = Scene::from_str_named(&to_toml(&scene.structure), "again").unwrap();
    assert_eq!(again.structure, scene.structure);
    let data = Scene::from_arrays(SceneArrays::of(&scene), "data").unwrap();
    assert_eq!(data.structure, scene.structure);
}

#[test]
fn bad_clusters_are_named_with_their_line() {
    let cases = [
        (
            "nodes = [0, 1, 2, 3]",
            "nodes = [0, 1]",
            "passes through 2 node(s)",
        ),
        (
            "nodes = [0, 1, 2, 3]",
            "nodes = [0, 1, 2, 9]",
            "node index 9",
        ),
        (
            "nodes = [0, 1, 2, 3]",
            "nodes = [0, 1, 1, 3]",
            "segment 1 (nodes 1 and 1) has zero length",
        ),
        (
            "stiffness = 1e4",
            "stiffness = -1.0",
            "stiffness must be positive and finite",
        ),
        (
            "rest_length = 2.9",
            "rest_length = nan",
            "rest_length must be positive and finite",
        ),
        (
            "damping = 0.5",
            "damping = -0.5",
            "damping must be non-negative",
        ),
        (
            "friction = [0.1, 0.0]",
            "friction = [0.1]",
            "1 friction coefficient(s) for 2 inner node(s)",
        ),
        (
            "friction = [0.1, 0.0]",
            "friction = [0.1, -2.0]",
            "friction must be non-negative",
        ),
        (
            "material = \"uhmwpe\"",
            "material = \"unobtainium\"",
            "unknown material",
        ),
    ];
    for (from, to, says) in cases {
        assert!(TWO_PULLEYS.contains(from), "{from}");
        let e = Scene::from_str_named(&TWO_PULLEYS.replacen(from, to, 1), "bad.toml")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("bad.toml (line 3): cluster 0: ") && e.contains(says),
            "{to}: {e}"
        );
    }
    // a segment on a string's nodes, and an unknown key
    let with_string = format!("{TWO_PULLEYS}\n[[strings]]\nnodes = [2, 1]\n");
    let e = Scene::from_str_named(&with_string, "dup.toml")
        .unwrap_err()
        .to_string();
    assert!(
        e.ends_with("cluster 0: segment 1 (nodes 1 and 2) duplicates string 0"),
        "{e}"
    );
    let e = Scene::from_str_named(&TWO_PULLEYS.replacen("damping", "dampin", 1), "key.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("unknown field `dampin`"), "{e}");
    // a node on a cluster only is not isolated; a node on nothing is
    let lonely = TWO_PULLEYS.replacen("[2.0, 0.0, 0.0]]", "[2.0, 0.0, 0.0], [5.0, 5.0, 5.0]]", 1);
    let e = Scene::from_str_named(&lonely, "lonely.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("node 4 is isolated"), "{e}");
}
