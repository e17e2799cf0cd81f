//! `tensegrity formfind` with `[[clusters]]` (issue 44, item 3) end to end: the ring on a
//! clothesline against its closed form, the cluster's keys in the JSON, the scene `--out`
//! writes (its `[[clusters]]`) read back by `statics`, whose load solve finds the cluster's
//! tension again to 10⁻⁹, and by `solve`, which does not move it; a prestressed (unloaded)
//! form whose written cluster carries the scaled tension k (L − L₀) = α t; bad clusters
//! refused with exit 2 naming the file, the line and the item.

use crate::common;

use serde_json::Value;

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The `stiffness` and `rest_length` of the first `[[clusters]]` of a written scene.
fn written_cluster(scene: &str) -> (f64, f64) {
    let text = std::fs::read_to_string(scene).unwrap();
    let table = text
        .split("[[clusters]]")
        .nth(1)
        .expect("a [[clusters]] table");
    let value = |key: &str| -> f64 {
        let line = table.lines().find(|l| l.starts_with(key)).unwrap();
        line.split('=').nth(1).unwrap().trim().parse().unwrap()
    };
    (value("stiffness"), value("rest_length"))
}

#[test]
fn the_clothesline_ring_matches_its_closed_form_and_statics_finds_its_tension() {
    let dir = common::scratch("ffcl", "line");
    let scene = dir.join("line.toml").display().to_string();
    let example = "examples/formfind_cluster_clothesline.toml";
    let r = common::json(&["formfind", example, "--json", "--out", &scene]);
    // sin φ = W / 2t = 1/2: x = (D − H √3) / 2, z = −x / √3 (D = 4, H = 1)
    let x = (4.0 - 3f64.sqrt()) / 2.0;
    let z = -x / 3f64.sqrt();
    let ring = &r["nodes"][1];
    assert!(
        (f(&ring[0]) - x).abs() < 1e-11 && (f(&ring[2]) - z).abs() < 1e-11,
        "{ring}"
    );
    assert_eq!(r["method"], "fdm");
    assert!(r["iterations"].as_u64().unwrap() > 1, "{}", r["iterations"]);
    assert_eq!(f(&r["tolerance"]), 1e-12);
    assert!(
        f(&r["equilibrium_residual"]) < 1e-12,
        "{}",
        r["equilibrium_residual"]
    );
    let c = &r["clusters"][0];
    assert_eq!(f(&c["force"]), 10.0);
    assert_eq!(f(&c["tension"]), 10.0); // a loaded form is not scaled
    let (big_l, l0, k) = (f(&c["length"]), f(&c["rest_length"]), f(&c["stiffness"]));
    assert!((l0 - (big_l - 10.0 / k)).abs() < 1e-12 * big_l);
    assert!((l0 - big_l / (1.0 + 10.0 / 2e4)).abs() < 1e-12 * big_l);
    // the written scene carries the cluster; statics' own load solve finds t again
    let (k_scene, l0_scene) = written_cluster(&scene);
    assert_eq!((k_scene, l0_scene), (k, l0));
    let s = common::json(&["statics", &scene, "--json"]);
    assert_eq!(s["clusters"], 1);
    let force = s["member_force"].as_array().unwrap();
    assert_eq!(force.len(), 1);
    assert!((f(&force[0]) - 10.0).abs() < 1e-9, "{}", force[0]);
    // and the same reactions
    for (a, b) in r["reactions"]
        .as_array()
        .unwrap()
        .iter()
        .zip(s["reactions"].as_array().unwrap())
    {
        assert_eq!(a["node"], b["node"]);
        for axis in 0..3 {
            let (ra, rb) = (f(&a["force"][axis]), f(&b["force"][axis]));
            assert!((ra - rb).abs() < 1e-9, "{a} against {b}");
        }
    }
}

#[test]
fn a_cluster_through_two_loaded_nodes_keeps_its_tension_in_the_written_scene() {
    let dir = common::scratch("ffcl", "net");
    let scene = dir.join("net.toml").display().to_string();
    let example = "examples/formfind_cluster_net.toml";
    let r = common::json(&["formfind", example, "--json", "--out", &scene]);
    let c = &r["clusters"][0];
    // steel, 1 mm²: EA = 2.06·10⁵ N
    assert!((f(&c["axial_stiffness"]) - 2.06e5).abs() < 1e-6);
    let q: Vec<f64> = common::numbers(&c["segment_force_density"]);
    let l: Vec<f64> = common::numbers(&c["segment_length"]);
    for (q, l) in q.iter().zip(&l) {
        assert!((q * l - 7.0).abs() < 1e-12, "{q} · {l}");
    }
    assert!((q[0] - q[1]).abs() > 1.0, "{q:?}");
    let s = common::json(&["statics", &scene, "--json"]);
    let force: Vec<f64> = common::numbers(&s["member_force"]);
    let members: Vec<f64> = common::numbers(&r["member_force"]);
    assert_eq!(force.len(), 3, "{force:?}");
    assert!((force[2] - 7.0).abs() < 1e-9, "{force:?}");
    for (a, b) in force.iter().zip(&members) {
        assert!((a - b).abs() < 1e-9, "{force:?} against {members:?}");
    }
    // the load path from the written scene stays where it is: the form is its equilibrium
    let p = common::json(&["solve", &scene, "--json"]);
    assert!(
        f(&p["max_displacement"]) < 1e-9,
        "{}",
        p["max_displacement"]
    );
}

/// A centre held by two strings along y and a cluster 0 → 4 → 1 along x: unloaded, so the
/// synthesis scales the tensions to the prestress level (the cluster's t = 5 N is the
/// largest: α = 100 / 5).
const CROSS: &str = "nodes = [[-2.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, -2.0, 0.0], [0.0, 2.0, 0.0], [0.3, 0.1, 0.0]]
[[strings]]
nodes = [4, 2]
force_density = 1.0
[[strings]]
nodes = [4, 3]
force_density = 1.0
[[clusters]]
nodes = [0, 4, 1]
force = 5.0
[[fixed]]
node = 0
position = [-2.0, 0.0, 0.0]
[[fixed]]
node = 1
position = [2.0, 0.0, 0.0]
[[fixed]]
node = 2
position = [0.0, -2.0, 0.0]
[[fixed]]
node = 3
position = [0.0, 2.0, 0.0]
";

#[test]
fn an_unloaded_form_scales_the_cluster_with_the_prestress() {
    let dir = common::scratch("ffcl", "cross");
    let scene = dir.join("cross.toml").display().to_string();
    let r = common::json(&[
        "formfind",
        CROSS,
        "--json",
        "--out",
        &scene,
        "--stiffness",
        "1e4",
    ]);
    let centre = &r["nodes"][4];
    assert!(
        centre
            .as_array()
            .unwrap()
            .iter()
            .all(|x| f(x).abs() < 1e-11),
        "{centre}"
    );
    let c = &r["clusters"][0];
    assert!((f(&c["tension"]) - 100.0).abs() < 1e-12);
    let members: Vec<f64> = common::numbers(&r["member_force"]);
    assert!(
        members.iter().all(|t| (t - 40.0).abs() < 1e-12),
        "{members:?}"
    );
    let (k, l0) = written_cluster(&scene);
    assert!((k * (4.0 - l0) - 100.0).abs() < 1e-9, "{k} (4 − {l0})");
    assert!((l0 - 4.0 / (1.0 + 100.0 / 1e4)).abs() < 1e-12);
    let s = common::json(&["statics", &scene, "--json"]);
    assert_eq!(s["prestressable"], true);
    // the figure draws the cluster's segments as strings, coloured by force as well
    let svg = dir.join("cross.svg").display().to_string();
    common::assert_ok(&common::run(&[
        "formfind",
        CROSS,
        "--svg",
        &svg,
        "--color-by",
        "force",
    ]));
    let drawn = std::fs::read_to_string(&svg).unwrap();
    assert!(
        drawn.matches("<line").count() + drawn.matches("<path").count() >= 4,
        "{drawn}"
    );
    assert_eq!(s["clusters"], 1);
    // the text report lists the cluster
    let out = common::run(&["formfind", CROSS]);
    common::assert_ok(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("2 strings, 1 clusters; method fdm"), "{text}");
    assert!(
        text.contains("cluster 0    t 100.000000000  L 4.000000000"),
        "{text}"
    );
}

#[test]
fn bad_clusters_exit_2_naming_the_file_line_and_item() {
    let dir = common::scratch("ffcl", "bad");
    let base = std::fs::read_to_string("examples/formfind_cluster_clothesline.toml").unwrap();
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "force = 10.0",
            "force_density = 2.0",
            &[
                "line 22",
                "clusters[0].force_density",
                "not a force density",
            ],
        ),
        (
            "force = 10.0",
            "force = 10.0\nfriction = [0.1]",
            &["line 22", "clusters[0].friction", "frictionless"],
        ),
        (
            "nodes = [0, 1, 2]",
            "nodes = [0, 2]",
            &["line 22", "clusters[0]", "at least three"],
        ),
        (
            "nodes = [0, 1, 2]",
            "nodes = [0, 1, 7]",
            &["line 22", "clusters[0]: node 7 makes the topology 8 nodes"],
        ),
        (
            "nodes = [0, 1, 2]",
            "nodes = [0, 1, 1]",
            &["line 22", "clusters[0]: segment 1 has both ends on node 1"],
        ),
        (
            "force = 10.0",
            "force = -1.0",
            &["line 22", "clusters[0].force", "positive"],
        ),
        (
            "force = 10.0 ",
            "",
            &["line 22", "clusters[0].force: no tension given"],
        ),
        (
            "stiffness = 2e4",
            "pulleys = 2",
            &["unknown field `pulleys`"],
        ),
    ];
    for (from, to, wants) in cases {
        assert!(base.contains(from), "{from}");
        let path = dir.join("bad.toml");
        std::fs::write(&path, base.replacen(from, to, 1)).unwrap();
        let out = common::run(&["formfind", path.to_str().unwrap()]);
        let e = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{to}: {e}");
        assert!(e.contains("bad.toml"), "{e}");
        for w in *wants {
            assert!(e.contains(w), "{from} → {to}: {e}");
        }
    }
    // the adaptive method takes no clusters (exit 2, naming it)
    let out = common::run(&[
        "formfind",
        "examples/formfind_cluster_clothesline.toml",
        "--method",
        "adaptive",
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("clusters[0]: the adaptive method"),
        "{}",
        stderr(&out)
    );
}
