//! `tensegrity export mjcf` (`tensegrity_io::mjcf`): a scene written as a MuJoCo model, read
//! back as XML here: every bar a free body at its midpoint, turned so that its end sites fall
//! on its nodes, with the rod inertia m l²/12; shared and pinned nodes tied by `<connect>`;
//! every string a spatial tendon whose dead band ends at the rest length (the drawn length
//! where none is given); what MJCF cannot say refused naming the item. MuJoCo itself loads
//! and settles the model in crates/tensegrity-py/tests/test_mjcf.py.

use crate::common;

use common::{assert_refused, run, scratch};
use roxmltree::{Document, Node};

/// Two bars sharing node 1 (a class-2 joint), one with a mass and one with a material's
/// ρ π r² l; node 0 pinned; node 3 on no bar, pinned (a world site); a prestressed string, a
/// string without a rest length and a cluster over a pulley at node 3.
const SCENE: &str = r#"
nodes = [[0.1, -0.2, 0.3], [0.4, 0.5, 1.9], [1.7, 0.2, 1.1], [2.0, -1.0, 0.0]]
[materials.al]
density = 2700.0
youngs_modulus = 70e9
yield_strength = 2e8
[[bars]]
nodes = [0, 1]
mass = 1.25
radius = 0.03
[[bars]]
nodes = [1, 2]
material = "al"
radius = 0.02
[[strings]]
nodes = [2, 3]
stiffness = 800.0
rest_length = 1.4
damping = 3.0
[[strings]]
nodes = [0, 2]
stiffness = 50.0
[[clusters]]
nodes = [0, 3, 1]
stiffness = 120.0
rest_length = 3.5
[[supports]]
node = 0
[[supports]]
node = 3
[gravity]
acceleration = [0.0, 0.0, -9.81]
"#;

const NODES: [[f64; 3]; 4] = [
    [0.1, -0.2, 0.3],
    [0.4, 0.5, 1.9],
    [1.7, 0.2, 1.1],
    [2.0, -1.0, 0.0],
];

fn numbers(text: &str) -> Vec<f64> {
    text.split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect()
}

fn named<'a, 'i>(doc: &'a Document<'i>, tag: &str, name: &str) -> Node<'a, 'i> {
    doc.descendants()
        .find(|n| n.has_tag_name(tag) && n.attribute("name") == Some(name))
        .unwrap_or_else(|| panic!("no <{tag} name=\"{name}\">"))
}

fn child<'a, 'i>(node: Node<'a, 'i>, tag: &str) -> Node<'a, 'i> {
    node.children().find(|n| n.has_tag_name(tag)).unwrap()
}

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

/// `v` turned by the unit quaternion `q` = (w, x, y, z).
fn rotate(q: &[f64], v: [f64; 3]) -> [f64; 3] {
    let (w, u) = (q[0], [q[1], q[2], q[3]]);
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let t = cross(u, v).map(|c| 2.0 * c);
    let ut = cross(u, t);
    [0, 1, 2].map(|i| v[i] + w * t[i] + ut[i])
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

fn export(dir: &std::path::Path, scene: &str, extra: &[&str]) -> std::process::Output {
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene).unwrap();
    let mut args = vec!["export", "mjcf", path.to_str().unwrap()];
    args.extend_from_slice(extra);
    run(&args)
}

fn exported(dir: &std::path::Path) -> String {
    let o = export(dir, SCENE, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout).unwrap()
}

#[test]
fn bars_are_bodies_at_their_midpoints_with_the_rod_inertia_and_sites_on_their_nodes() {
    let dir = scratch("mjcf", "bars");
    let xml = exported(&dir);
    let doc = Document::parse(&xml).unwrap();
    let al_mass = 2700.0 * std::f64::consts::PI * 0.02 * 0.02 * dist(NODES[1], NODES[2]);
    for (k, [a, b], mass) in [(0, [0, 1], 1.25), (1, [1, 2], al_mass)] {
        let body = named(&doc, "body", &format!("bar{k}"));
        let centre: Vec<f64> = (0..3).map(|i| 0.5 * (NODES[a][i] + NODES[b][i])).collect();
        let pos = numbers(body.attribute("pos").unwrap());
        assert!(close(&pos, &centre, 1e-15), "bar {k}: {pos:?}");
        let inertial = child(body, "inertial");
        let m = numbers(inertial.attribute("mass").unwrap())[0];
        assert!((m - mass).abs() < 1e-12 * mass, "bar {k}: mass {m}");
        let i = numbers(inertial.attribute("diaginertia").unwrap());
        let l = dist(NODES[a], NODES[b]);
        assert!((i[0] - mass * l * l / 12.0).abs() < 1e-12, "bar {k}: {i:?}");
        assert_eq!(i[0], i[1]);
        // about the axis: a solid rod of the capsule's radius, ½ m r² (MuJoCo needs it > 0)
        let r = numbers(
            named(&doc, "geom", &format!("bar{k}"))
                .attribute("size")
                .unwrap(),
        )[0];
        assert!(
            (i[2] - 0.5 * mass * r * r).abs() < 1e-15,
            "bar {k}: axial {}",
            i[2]
        );
        assert!(i[2] < 1e-2 * i[0], "bar {k}: axial {}", i[2]);
        // each end site, turned and moved with the body, falls on its node
        let q = numbers(body.attribute("quat").unwrap());
        for (end, node) in [(0, a), (1, b)] {
            let name = if (k, end) == (1, 0) {
                "n1_bar1".to_string()
            } else {
                format!("n{node}")
            };
            let local = numbers(named(&doc, "site", &name).attribute("pos").unwrap());
            let turned = rotate(&q, [local[0], local[1], local[2]]);
            let world: Vec<f64> = (0..3).map(|i| pos[i] + turned[i]).collect();
            assert!(close(&world, &NODES[node], 1e-14), "{name}: {world:?}");
        }
        let geom = named(&doc, "geom", &format!("bar{k}"));
        assert_eq!(geom.attribute("mass"), Some("0"));
    }
    // node 3 is on no bar: a site of the world body
    let site = named(&doc, "site", "n3");
    assert_eq!(site.parent().unwrap().tag_name().name(), "worldbody");
    assert!(close(
        &numbers(site.attribute("pos").unwrap()),
        &NODES[3],
        0.0
    ));
    let option = doc
        .descendants()
        .find(|n| n.has_tag_name("option"))
        .unwrap();
    assert_eq!(option.attribute("gravity"), Some("0 0 -9.81"));
    assert_eq!(option.attribute("timestep"), Some("0.001"));
}

#[test]
fn strings_and_clusters_are_tendons_slack_below_their_rest_length() {
    let dir = scratch("mjcf", "tendons");
    let xml = exported(&dir);
    let doc = Document::parse(&xml).unwrap();
    let sites = |t: Node| -> Vec<String> {
        t.children()
            .filter_map(|n| n.attribute("site").map(str::to_string))
            .collect()
    };
    let s0 = named(&doc, "spatial", "s0");
    assert_eq!(numbers(s0.attribute("springlength").unwrap()), [0.0, 1.4]);
    assert_eq!(s0.attribute("stiffness"), Some("800"));
    assert_eq!(s0.attribute("damping"), Some("3"));
    assert_eq!(sites(s0), ["n2", "n3"]);
    // no rest length: the drawn length (no prestress)
    let s1 = named(&doc, "spatial", "s1");
    let upper = numbers(s1.attribute("springlength").unwrap())[1];
    assert!((upper - dist(NODES[0], NODES[2])).abs() < 1e-15, "{upper}");
    let c0 = named(&doc, "spatial", "c0");
    assert_eq!(sites(c0), ["n0", "n3", "n1"]);
    assert_eq!(numbers(c0.attribute("springlength").unwrap()), [0.0, 3.5]);
    assert_eq!(c0.attribute("stiffness"), Some("120"));
}

#[test]
fn shared_and_pinned_nodes_are_connects_at_the_node() {
    let dir = scratch("mjcf", "connects");
    let doc_text = exported(&dir);
    let doc = Document::parse(&doc_text).unwrap();
    let pin = named(&doc, "connect", "n0_world");
    assert_eq!(pin.attribute("body1"), Some("bar0"));
    assert_eq!(pin.attribute("body2"), None);
    let half = 0.5 * dist(NODES[0], NODES[1]);
    assert!(close(
        &numbers(pin.attribute("anchor").unwrap()),
        &[0.0, 0.0, -half],
        1e-15
    ));
    let joint = named(&doc, "connect", "n1_bar0_bar1");
    assert_eq!(
        (joint.attribute("body1"), joint.attribute("body2")),
        (Some("bar1"), Some("bar0"))
    );
    let half = 0.5 * dist(NODES[1], NODES[2]);
    assert!(close(
        &numbers(joint.attribute("anchor").unwrap()),
        &[0.0, 0.0, -half],
        1e-15
    ));
    assert_eq!(
        doc.descendants()
            .filter(|n| n.has_tag_name("connect"))
            .count(),
        2
    );
    assert_eq!(
        doc.descendants()
            .filter(|n| n.has_tag_name("freejoint"))
            .count(),
        2
    );
}

#[test]
fn out_timestep_and_ground_height_are_written() {
    let dir = scratch("mjcf", "out");
    let model = dir.join("model.xml");
    let o = export(
        &dir,
        SCENE,
        &[
            "--out",
            model.to_str().unwrap(),
            "--timestep",
            "0.0005",
            "--ground-height",
            "-0.25",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(o.stdout.is_empty());
    let xml = std::fs::read_to_string(&model).unwrap();
    let doc = Document::parse(&xml).unwrap();
    let option = doc
        .descendants()
        .find(|n| n.has_tag_name("option"))
        .unwrap();
    assert_eq!(option.attribute("timestep"), Some("0.0005"));
    let ground = named(&doc, "geom", "ground");
    assert_eq!(numbers(ground.attribute("pos").unwrap()), [0.0, 0.0, -0.25]);
    assert_eq!(ground.attribute("conaffinity"), Some("1"));
    // only the capsules touch the plane
    assert_eq!(named(&doc, "geom", "bar0").attribute("contype"), Some("1"));
    assert_eq!(
        named(&doc, "geom", "bar0").attribute("conaffinity"),
        Some("0")
    );
}

#[test]
fn what_mjcf_cannot_say_is_refused_naming_the_item() {
    let dir = scratch("mjcf", "refused");
    let cases = [
        // a free node on no bar: no mass for MuJoCo to move
        (
            SCENE.replace("[[supports]]\nnode = 3\n", ""),
            "node 3: is free and on no bar",
        ),
        // a node held in z only
        (
            SCENE.replace(
                "[[supports]]\nnode = 3\n",
                "[[supports]]\nnode = 3\n[[supports]]\nnode = 2\ndirections = [\"z\"]\n",
            ),
            "support 2 (node 2): holds the node in some directions only",
        ),
        (
            format!("{SCENE}[[loads]]\nnode = 2\nforce = [0.0, 0.0, -5.0]\n"),
            "load 0 (node 2): MJCF has no constant nodal force",
        ),
        (SCENE.replace("mass = 1.25\n", ""), "bar 0: has no mass"),
        (
            SCENE.replace(
                "rest_length = 3.5\n",
                "rest_length = 3.5\nfriction = [0.3]\n",
            ),
            "cluster 0: has pulley friction",
        ),
    ];
    for (scene, message) in cases {
        let o = export(&dir, &scene, &[]);
        assert_refused(&o, message, message);
        assert!(o.stdout.is_empty());
    }
}
