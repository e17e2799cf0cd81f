//! `tensegrity import ntrt` (`tensegrity_io::ntrt`): NTRT's SUPERball and 3-prism models
//! (examples/ntrt/, NTRT's own YAML files) imported as scenes: their nodes in the file's
//! order at the YAML's coordinates, a bar per rod pair with the mass ρ π r² L of its builder,
//! a string per actuator pair with its stiffness, damping and the rest length L − t₀/k that
//! carries its pretension; `statics` then says what the drawn geometry is (the SUPERball's,
//! rounded to 0.01, has no self-stress); NTRT's combined models (the tetrahedral spine,
//! BigPuppy, the 3-prism spine, and a parent written here) with their substructures placed
//! as NTRT places them, named by dot path, bonded node to node or node to edge, the parent's
//! builders winning; bad models are refused naming the item.

use crate::common;

use common::{assert_refused, json, run, scratch};

/// A member of a written scene: its kind, its nodes, the numbers of its other keys by name.
type Member = (String, [usize; 2], Vec<(String, f64)>);

/// The members of a written scene.
fn members(scene: &str) -> Vec<Member> {
    let mut out = Vec::new();
    for block in scene.split("\n[[").skip(1) {
        let kind = block.split("]]").next().unwrap().to_string();
        if kind != "bars" && kind != "strings" {
            continue;
        }
        let mut nodes = [0, 0];
        let mut keys = Vec::new();
        for line in block.lines().skip(1) {
            let Some((k, v)) = line.split_once(" = ") else {
                break;
            };
            if k == "nodes" {
                let v: Vec<usize> = (v.trim_matches(['[', ']']).split(", "))
                    .map(|x| x.parse().unwrap())
                    .collect();
                nodes = [v[0], v[1]];
            } else if let Ok(x) = v.parse::<f64>() {
                keys.push((k.to_string(), x));
            }
        }
        out.push((kind, nodes, keys));
    }
    out
}

fn key(keys: &[(String, f64)], name: &str) -> f64 {
    keys.iter()
        .find(|(k, _)| k == name)
        .unwrap_or_else(|| panic!("{name}"))
        .1
}

fn import(model: &str, dir: &std::path::Path) -> String {
    let out = dir.join("scene.toml");
    let o = run(&["import", "ntrt", model, "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    std::fs::read_to_string(&out).unwrap()
}

#[test]
fn the_superball_imports_with_the_yamls_nodes_members_and_parameters() {
    let dir = scratch("ntrt", "superball");
    let scene = import("examples/ntrt/superball.yaml", &dir);
    // the nodes in the file's order, named in the header
    assert!(scene.contains("#   0: left_vert_bottom\n#   1: left_vert_top\n"));
    assert!(scene.contains("#   11: dist_horiz_right\n"));
    assert!(scene.contains("  [-7.5, 16.84, 0.0],\n  [7.5, 0.0, 0.0],\n"));
    let m = members(&scene);
    let bars: Vec<_> = m.iter().filter(|x| x.0 == "bars").collect();
    let strings: Vec<_> = m.iter().filter(|x| x.0 == "strings").collect();
    assert_eq!((bars.len(), strings.len()), (6, 24));
    assert_eq!(bars[0].1, [0, 1]);
    // every rod 16.84 long: ρ π r² L with ρ = 0.688, r = 0.31
    let mass = 0.688 * std::f64::consts::PI * 0.31 * 0.31 * 16.84;
    for b in &bars {
        assert!((key(&b.2, "mass") - mass).abs() < 1e-12 * mass, "{b:?}");
    }
    // k = 613, c = 200, pretension 2452 N: L₀ = L − 4 (the first string: left_vert_bottom to
    // bottom_horiz_prox, L = √(7.5² + 0.92² + 8.42²))
    let l = (7.5f64 * 7.5 + 0.92 * 0.92 + 8.42 * 8.42).sqrt();
    assert_eq!(strings[0].1, [0, 4]);
    assert_eq!(key(&strings[0].2, "stiffness"), 613.0);
    assert_eq!(key(&strings[0].2, "damping"), 200.0);
    assert!((key(&strings[0].2, "rest_length") - (l - 4.0)).abs() < 1e-12);
    // the drawn geometry, rounded to 0.01, carries no self-stress: statics says so
    let r = json(&[
        "statics",
        dir.join("scene.toml").to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(
        (r["rank"].as_u64(), r["self_stress_dim"].as_u64()),
        (Some(30), Some(0))
    );
    assert_eq!(r["prestressable"], false);
}

#[test]
fn the_three_prism_takes_each_builders_pretension() {
    let dir = scratch("ntrt", "prism");
    let scene = import("examples/ntrt/3prism.yaml", &dir);
    let m = members(&scene);
    assert_eq!(m.iter().filter(|x| x.0 == "bars").count(), 3);
    let strings: Vec<_> = m.iter().filter(|x| x.0 == "strings").collect();
    assert_eq!(strings.len(), 9);
    // horizontal: k = 1000, t₀ = 3000 → L − 3 (bottom1–bottom2: L = 10); vertical: t₀ =
    // 1000 → L − 1 (bottom1–top1: L = 5)
    assert_eq!(strings[0].1, [0, 1]);
    assert!((key(&strings[0].2, "rest_length") - 7.0).abs() < 1e-12);
    assert_eq!(strings[6].1, [0, 3]);
    assert!((key(&strings[6].2, "rest_length") - 4.0).abs() < 1e-12);
    assert_eq!(key(&strings[6].2, "damping"), 10.0);
}

#[test]
fn bad_models_are_refused_naming_the_item() {
    let dir = scratch("ntrt", "bad");
    let good = std::fs::read_to_string("examples/ntrt/3prism.yaml").unwrap();
    for (name, text, says) in [
        (
            "node",
            good.replace("- [bottom1, top2]", "- [bottom1, top9]"),
            "pair group prism_rod: node top9 is not among the nodes",
        ),
        (
            "class",
            good.replacen("class: tgRodInfo", "class: tgSphereInfo", 1),
            "builder prism_rod: class `tgSphereInfo` is not imported",
        ),
        (
            "builder",
            good.replace(
                "  vertical_string:\n    class",
                "  vertical_strings:\n    class",
            ),
            "pair group vertical_string: no builder matches its tags (vertical_string)",
        ),
        (
            "pretension",
            good.replace("pretension: 3000", "pretension: 1e6"),
            "builder horizontal_string: pretension 1000000 stretches pair [bottom1, bottom2]",
        ),
        (
            "key",
            format!("{good}\nsubstructure:\n  a:\n    path: x.yaml\n"),
            "substructure: not an NTRT model key",
        ),
        (
            "syntax",
            good.replace("bottom2: [5, 0, 0]", "bottom2: [5, 0, 0"),
            "line",
        ),
    ] {
        let path = dir.join(format!("{name}.yaml"));
        std::fs::write(&path, text).unwrap();
        let o = run(&["import", "ntrt", path.to_str().unwrap()]);
        assert_refused(&o, name, says);
    }
}

/// The SUPERball's connectivity as a topology (`--topology`), form-found by the adaptive
/// force density method from its drawn nodes: the expanded octahedron — one self-stress,
/// prestressable and stable, bars and strings at force densities −1 : 2/3 (−3/2 : 1), six
/// equal bars and twenty-four equal strings of √6/4 the bar's length, the bars in three
/// parallel pairs half a bar length apart.
#[test]
fn form_finding_the_superballs_connectivity_gives_the_expanded_octahedron() {
    let dir = scratch("ntrt", "formfind");
    let topo = dir.join("superball_topology.toml");
    let o = run(&[
        "import",
        "ntrt",
        "examples/ntrt/superball.yaml",
        "--topology",
        "--out",
        topo.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = json(&[
        "formfind",
        topo.to_str().unwrap(),
        "--method",
        "adaptive",
        "--analyse",
        "--json",
    ]);
    assert_eq!(r["self_stress_dim"], 1);
    assert_eq!(
        (&r["prestressable"], &r["prestress_stable"]),
        (&true.into(), &true.into())
    );
    let q: Vec<f64> = common::numbers(&r["force_density"]);
    assert!((q[6] / q[0] + 2.0 / 3.0).abs() < 1e-9, "{q:?}");
    let x = common::points(&r["nodes"]);
    let dist = |a: usize, b: usize| -> f64 {
        (0..3)
            .map(|d| (x[a][d] - x[b][d]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let text = std::fs::read_to_string(&topo).unwrap();
    let m = members(&text);
    let bar = dist(m[0].1[0], m[0].1[1]);
    for (kind, [a, b], _) in &m {
        let expected = if kind == "bars" {
            bar
        } else {
            bar * 6f64.sqrt() / 4.0
        };
        assert!(
            (dist(*a, *b) - expected).abs() < 1e-9 * bar,
            "{kind} {a}-{b}"
        );
    }
    // the two vertical rods (nodes 0-1 and 2-3) are parallel, half a bar length apart
    assert!((dist(0, 2) - 0.5 * bar).abs() < 1e-9 * bar);
}

/// The node names listed in a written scene's header, in order.
fn names(scene: &str) -> Vec<String> {
    (scene.lines())
        .filter_map(|l| l.strip_prefix("#   ")?.split_once(": "))
        .map(|(_, n)| n.to_string())
        .collect()
}

/// The node positions of a written scene.
fn positions(scene: &str) -> Vec<[f64; 3]> {
    let block = scene.split("nodes = [\n").nth(1).unwrap();
    (block.lines())
        .take_while(|l| l.starts_with("  ["))
        .map(|l| {
            let v: Vec<f64> = (l
                .trim()
                .trim_end_matches(',')
                .trim_matches(['[', ']'])
                .split(", "))
            .map(|x| x.parse().unwrap())
            .collect();
            [v[0], v[1], v[2]]
        })
        .collect()
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|d| (a[d] - b[d]).abs() < 1e-12 * (1.0 + b[d].abs()))
}

fn length(x: &[[f64; 3]], [a, b]: [usize; 2]) -> f64 {
    (0..3)
        .map(|d| (x[a][d] - x[b][d]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// NTRT's tetrahedral spine (examples/ntrt/Spines/, its vertebra in ../BaseStructures/): six
/// copies t1…t6 of the 5-node tetrahedron, the k-th (from 0) offset by k · (0, 0, −12); four
/// rods each (the child's builder: 0.014 π 0.5² √300); eight node_node strings between each
/// two adjacent copies only (5 × 8 = 40, the parent's `string`: k = 1000, c = 10, t₀ = 0 so
/// L₀ = L).
#[test]
fn the_tetrahedral_spine_is_six_offset_copies_bonded_pairwise() {
    let dir = scratch("ntrt", "spine");
    let scene = import("examples/ntrt/Spines/TetrahedralSpine.yaml", &dir);
    let base = [
        ("center", [0.0, 10.0, 0.0]),
        ("front", [10.0, 20.0, 10.0]),
        ("right", [10.0, 0.0, -10.0]),
        ("back", [-10.0, 20.0, -10.0]),
        ("left", [-10.0, 0.0, 10.0]),
    ];
    let (n, x) = (names(&scene), positions(&scene));
    assert_eq!((n.len(), x.len()), (30, 30));
    for k in 0..6 {
        for (i, (name, p)) in base.iter().enumerate() {
            assert_eq!(n[5 * k + i], format!("t{}.{name}", k + 1));
            let expected = [p[0], p[1], p[2] - 12.0 * k as f64];
            assert!(
                close(x[5 * k + i], expected),
                "{}: {:?}",
                n[5 * k + i],
                x[5 * k + i]
            );
        }
    }
    let m = members(&scene);
    let bars: Vec<_> = m.iter().filter(|x| x.0 == "bars").collect();
    let strings: Vec<_> = m.iter().filter(|x| x.0 == "strings").collect();
    assert_eq!((bars.len(), strings.len()), (24, 40));
    let mass = 0.014 * std::f64::consts::PI * 0.25 * 300f64.sqrt();
    for b in &bars {
        assert!((key(&b.2, "mass") - mass).abs() < 1e-12 * mass, "{b:?}");
    }
    let at = |name: &str| base.iter().position(|b| b.0 == name).unwrap();
    let bonds = [
        ("front", "front"),
        ("right", "right"),
        ("back", "back"),
        ("left", "left"),
        ("right", "front"),
        ("right", "left"),
        ("back", "front"),
        ("back", "left"),
    ];
    let mut expected = Vec::new();
    for k in 0..5 {
        for (a, b) in bonds {
            expected.push([5 * k + at(a), 5 * (k + 1) + at(b)]);
        }
    }
    let got: Vec<[usize; 2]> = strings.iter().map(|s| s.1).collect();
    assert_eq!(got, expected);
    for s in &strings {
        assert_eq!(
            (key(&s.2, "stiffness"), key(&s.2, "damping")),
            (1000.0, 10.0)
        );
        assert!((key(&s.2, "rest_length") - length(&x, s.1)).abs() < 1e-12);
    }
}

/// NTRT's BigPuppy (examples/ntrt/BigPuppy.yaml, PuppySpine/, PuppyLimb/): a spine of seven
/// 5-node vertebrae (every odd one turned 90° about x about its own centre) and four
/// 18-node legs (two turned 180° about y about the origin), 35 + 4 · 18 = 107 nodes,
/// 28 + 4 · 12 = 76 rods, 42 + 4 · 27 + 46 = 196 strings; the top file's builders override
/// the defaults the vertebrae and feet would take.
#[test]
fn the_puppy_places_nested_rotated_substructures_and_takes_the_parents_builders() {
    let dir = scratch("ntrt", "puppy");
    let scene = import("examples/ntrt/BigPuppy.yaml", &dir);
    let (n, x) = (names(&scene), positions(&scene));
    assert_eq!(n.len(), 107);
    let node = |name: &str| {
        n.iter()
            .position(|m| m == name)
            .unwrap_or_else(|| panic!("{name}"))
    };
    // vertebra back1 (10, 26, 10), centre (0, 26, 0): turned +90° about x about the centre,
    // (x, y, z) − c → (x, −z, y), then translated by (11, 0, 0) (offset 0 for the first)
    let v1 = node("spine.vertebra1.back1");
    assert!(close(x[v1], [21.0, 16.0, 0.0]), "{:?}", x[v1]);
    // the second is not turned: translated (11, 0, 0) and offset once by (11, 0, 0)
    assert!(close(x[node("spine.vertebra2.back1")], [32.0, 26.0, 10.0]));
    // the seventh: turned, offset six times
    assert!(close(x[node("spine.vertebra7.front1")], [67.0, 36.0, 0.0]));
    // hip centre (0, 0, 0) + (0, 26, −11) in the leg; the right legs turned 180° about y
    // about the origin, (x, y, z) → (−x, y, −z); then translated
    assert!(close(
        x[node("front_right_leg.hip.center")],
        [22.0, 26.0, 11.0]
    ));
    assert!(close(
        x[node("back_left_leg.hip.center")],
        [66.0, 26.0, -11.0]
    ));
    assert!(close(
        x[node("back_right_leg.foot.bottom1")],
        [58.0, 0.0, 3.0]
    ));
    let m = members(&scene);
    let bars: Vec<_> = m.iter().filter(|x| x.0 == "bars").collect();
    let strings: Vec<_> = m.iter().filter(|x| x.0 == "strings").collect();
    assert_eq!((bars.len(), strings.len()), (76, 196));
    // a vertebra's rod (no builder in Vertebra.yaml: NTRT's default density 1 would give
    // π 0.5² √200) takes the top file's density 0.014
    let rod = bars
        .iter()
        .find(|b| b.1 == [node("spine.vertebra1.center"), v1])
        .unwrap();
    let mass = 0.014 * std::f64::consts::PI * 0.25 * 200f64.sqrt();
    assert!((key(&rod.2, "mass") - mass).abs() < 1e-12 * mass);
    // every string the top file's `string`: k = 2000, c = 20, t₀ = 1000 → L₀ = L − 0.5
    for s in &strings {
        assert_eq!(
            (key(&s.2, "stiffness"), key(&s.2, "damping")),
            (2000.0, 20.0)
        );
        assert!((key(&s.2, "rest_length") - (length(&x, s.1) - 0.5)).abs() < 1e-12);
    }
    // a bond by dot paths: front_right_leg's hip.inner_top to spine's vertebra1.back2
    let ends = [
        node("front_right_leg.hip.inner_top"),
        node("spine.vertebra1.back2"),
    ];
    assert!(strings.iter().any(|s| s.1 == ends));
}

/// A parent file (absolute child paths) with two copies a/b of the 3-prism: b turned 90°
/// about z about its centre, scaled 2 about it, offset once and translated; a node_node bond
/// a.top1–b.bottom1 and a dot-path pair a.top2–b.bottom2 of the parent's `tie`; the
/// parent's horizontal_string (k = 500) overriding the child's (k = 1000) while the child's
/// vertical_string (k = 1000) stays.
#[test]
fn a_parent_places_its_children_and_overrides_their_builders() {
    let dir = scratch("ntrt", "parent");
    let prism = std::fs::canonicalize("examples/ntrt/3prism.yaml").unwrap();
    let parent = format!(
        "substructures:\n  a/b:\n    path: {p}\n    offset: [0, 10, 0]\n  b:\n    rotation: {{axis: [0, 0, 1], angle: 90}}\n    scale: 2\n    translation: [1, 2, 3]\n\
         bond_groups:\n  tie:\n    a/b/node_node:\n      - [top1, bottom1]\n\
         pair_groups:\n  tie:\n    - [a.top2, b.bottom2]\n\
         builders:\n  horizontal_string:\n    class: tgBasicActuatorInfo\n    parameters: {{stiffness: 500, damping: 1, pretension: 0}}\n  tie:\n    class: tgBasicActuatorInfo\n    parameters: {{stiffness: 7}}\n",
        p = prism.display()
    );
    let path = dir.join("parent.yaml");
    std::fs::write(&path, &parent).unwrap();
    let scene = import(path.to_str().unwrap(), &dir);
    let (n, x) = (names(&scene), positions(&scene));
    let base = [
        [-5.0, 0.0, 0.0],
        [5.0, 0.0, 0.0],
        [0.0, 0.0, 8.66],
        [-5.0, 5.0, 0.0],
        [5.0, 5.0, 0.0],
        [0.0, 5.0, 8.66],
    ];
    assert_eq!(n[0], "a.bottom1");
    assert_eq!(n[6], "b.bottom1");
    let c = [0.0, 2.5, 2.0 * 8.66 / 6.0];
    for (i, p) in base.iter().enumerate() {
        assert!(close(x[i], *p), "{}", n[i]);
        // +90° about z: (x, y) − c → (−(y − c_y), x − c_x); then 2×, then (0, 10, 0) + (1, 2, 3)
        let q = [
            c[0] - 2.0 * (p[1] - c[1]) + 1.0,
            c[1] + 2.0 * (p[0] - c[0]) + 12.0,
            c[2] + 2.0 * (p[2] - c[2]) + 3.0,
        ];
        assert!(close(x[6 + i], q), "{}: {:?} vs {q:?}", n[6 + i], x[6 + i]);
    }
    let strings: Vec<_> = members(&scene)
        .into_iter()
        .filter(|m| m.0 == "strings")
        .collect();
    assert_eq!(strings.len(), 9 + 9 + 2);
    let k = |s: &Member| key(&s.2, "stiffness");
    // each copy: 6 horizontal (the parent's k = 500) then 3 vertical (the child's k = 1000)
    for copy in [0, 9] {
        assert!(strings[copy..copy + 6].iter().all(|s| k(s) == 500.0));
        assert!(strings[copy + 6..copy + 9].iter().all(|s| k(s) == 1000.0));
    }
    // the pair group (read before the bonds), then the bond: a.top1 (3) – b.bottom1 (6)
    assert_eq!((strings[18].1, k(&strings[18])), ([4, 7], 7.0));
    assert_eq!((strings[19].1, k(&strings[19])), ([3, 6], 7.0));
}

#[test]
fn bad_combined_models_are_refused_naming_the_item() {
    let dir = scratch("ntrt", "badsub");
    let prism = std::fs::canonicalize("examples/ntrt/3prism.yaml").unwrap();
    let two = format!("substructures:\n  a/b:\n    path: {}\n", prism.display());
    for (name, text, says) in [
        (
            "missing",
            "substructures:\n  leg:\n    path: nowhere/leg.yaml\n".to_string(),
            "missing.yaml: substructure leg: ",
        ),
        (
            "cycle",
            "substructures:\n  me:\n    path: cycle.yaml\n".to_string(),
            "substructure me: ",
        ),
        (
            "unknown",
            format!("{two}pair_groups:\n  rod:\n    - [a.top1, b.top9]\n"),
            "pair group rod: node b.top9 is not among the nodes",
        ),
        (
            "ambiguous",
            format!("{two}pair_groups:\n  rod:\n    - [top1, b.top2]\n"),
            "pair group rod: node top1 is ambiguous: 2 nodes at the same depth have this name (a.top1, b.top1)",
        ),
        (
            "structure",
            format!("{two}bond_groups:\n  rod:\n    a/c/node_node:\n      - [top1, top2]\n"),
            "bond group rod: a/c/node_node: no substructure `c`",
        ),
    ] {
        let path = dir.join(format!("{name}.yaml"));
        std::fs::write(&path, text).unwrap();
        let o = run(&["import", "ntrt", path.to_str().unwrap()]);
        let err = assert_refused(&o, name, says);
        if name == "missing" {
            assert!(err.contains("nowhere/leg.yaml: cannot read"), "{err}");
        }
        if name == "cycle" {
            assert!(err.contains("cycle.yaml includes itself"), "{err}");
        }
    }
    // node_edge bonds: an edge that is a rod, too few pairs
    for (name, pairs, says) in [
        (
            "rodedge",
            "[top1, bottom1/top2], [top2, bottom2/top3], [top3, bottom3/top1]",
            "bond group s: a/b/node_edge: the edge b.bottom1/b.top2 is a rod",
        ),
        (
            "twopairs",
            "[top1, bottom1/bottom2], [top2, bottom2/bottom3]",
            "bond group s: a/b/node_edge: a node_edge bond needs three or more",
        ),
    ] {
        let path = dir.join(format!("{name}.yaml"));
        std::fs::write(
            &path,
            format!("{two}bond_groups:\n  s:\n    a/b/node_edge: [{pairs}]\n"),
        )
        .unwrap();
        let o = run(&["import", "ntrt", path.to_str().unwrap()]);
        assert_refused(&o, name, says);
    }
}

/// NTRT's 3-prism spine (examples/ntrt/Spines/3PrismSpine.yaml): six 3-prisms, each bonded
/// node to edge to the next: prism k+1's bottom-string middles are fitted to prism k's top
/// nodes, which puts prism k+1 on prism k turned about the vertical line through the
/// triangles' centre (x = 0, z = 8.66/3) by θ = atan(5 / (8.66/3)) (≈ 60°, from the first
/// middle's direction (0, 0, −1) onto top1's (−5, 0, −8.66/3)): prism k is the base prism
/// turned kθ and raised 5k. Each bond takes out prism k's three top strings and prism k+1's
/// three bottom strings and joins each top node to both ends of its edge (6 strings, the
/// bond's horizontal_string: L₀ = L − 3): 6 × 9 − 5 × 6 + 5 × 6 = 54 strings.
#[test]
fn the_three_prism_spine_fits_each_prism_node_to_edge() {
    let dir = scratch("ntrt", "prismspine");
    let scene = import("examples/ntrt/Spines/3PrismSpine.yaml", &dir);
    let (n, x) = (names(&scene), positions(&scene));
    let base = [
        ("bottom1", [-5.0, 0.0, 0.0]),
        ("bottom2", [5.0, 0.0, 0.0]),
        ("bottom3", [0.0, 0.0, 8.66]),
        ("top1", [-5.0, 5.0, 0.0]),
        ("top2", [5.0, 5.0, 0.0]),
        ("top3", [0.0, 5.0, 8.66]),
    ];
    assert_eq!(n.len(), 36);
    let cz: f64 = 8.66 / 3.0;
    let theta = (5.0 / cz).atan();
    for k in 0..6 {
        let (s, c) = (k as f64 * theta).sin_cos();
        for (i, (name, p)) in base.iter().enumerate() {
            let at = 6 * k + i;
            assert_eq!(n[at], format!("3prism{}.{name}", k + 1));
            let q = [
                p[0] * c + (p[2] - cz) * s,
                p[1] + 5.0 * k as f64,
                -p[0] * s + (p[2] - cz) * c + cz,
            ];
            assert!(
                (0..3).all(|d| (x[at][d] - q[d]).abs() < 1e-9),
                "{}: {:?} vs {q:?}",
                n[at],
                x[at]
            );
        }
    }
    let m = members(&scene);
    let strings: Vec<_> = m.iter().filter(|x| x.0 == "strings").collect();
    assert_eq!((m.len() - strings.len(), strings.len()), (18, 54));
    let sorted = |mut v: Vec<[usize; 2]>| {
        v.iter_mut().for_each(|p| p.sort());
        v.sort();
        v
    };
    let (b, t) = (
        |k: usize, i: usize| 6 * k + i,
        |k: usize, i: usize| 6 * k + 3 + i,
    );
    let mut expected = Vec::new();
    let mut bonds = Vec::new();
    for k in 0..6 {
        for i in 0..3 {
            expected.push([b(k, i), t(k, i)]);
            if k == 0 {
                expected.push([b(k, i), b(k, (i + 1) % 3)]);
            }
            if k == 5 {
                expected.push([t(k, i), t(k, (i + 1) % 3)]);
            }
            if k < 5 {
                bonds.push([b(k + 1, i), t(k, i)]);
                bonds.push([t(k, i), b(k + 1, (i + 1) % 3)]);
            }
        }
    }
    expected.extend(&bonds);
    assert_eq!(
        sorted(strings.iter().map(|s| s.1).collect()),
        sorted(expected)
    );
    for s in strings.iter().filter(|s| bonds.contains(&s.1)) {
        assert!((key(&s.2, "rest_length") - (length(&x, s.1) - 3.0)).abs() < 1e-9);
    }
    // the bars keep their lengths (the base prism's rods: √(10² + 5²), √(5² + 5² + 8.66²))
    for bar in m.iter().filter(|x| x.0 == "bars") {
        let l = length(&x, bar.1);
        assert!(
            (l - 125f64.sqrt()).abs() < 1e-9 || (l - (50.0 + 8.66f64 * 8.66).sqrt()).abs() < 1e-9,
            "{l}"
        );
    }
}

/// NTRT's Double3Prism (examples/ntrt/Double3Prism.yaml): four node_edge pairs attach
/// prism 1's top1, top2, bottom2, bottom1 to prism 2's edges bottom1/top1, bottom2/bottom1,
/// top2/bottom2, top1/top2. Prism 1 stays; prism 2's four edge strings and the four strings
/// among prism 1's attached nodes (b1–b2, t1–t2, b1–t1, b2–t2; its rod b1–t2 stays) are
/// taken out, eight strings join each node to both ends of its edge: 18 − 8 + 8 = 18.
#[test]
fn the_double_three_prism_joins_node_to_edge() {
    let dir = scratch("ntrt", "double");
    let scene = import("examples/ntrt/Double3Prism.yaml", &dir);
    let (n, x) = (names(&scene), positions(&scene));
    assert_eq!(n.len(), 12);
    for (i, p) in [[-5.0, 0.0, 0.0], [5.0, 0.0, 0.0], [0.0, 0.0, 8.66]]
        .iter()
        .enumerate()
    {
        assert!(close(x[i], *p), "{}", n[i]);
    }
    // nodes: prism k's bottom1..3 at 6k + 0..2, top1..3 at 6k + 3..5
    let (b, t) = (
        |k: usize, i: usize| 6 * k + i - 1,
        |k: usize, i: usize| 6 * k + 2 + i,
    );
    let mut expected = Vec::new();
    for k in 0..2 {
        expected.extend([[b(k, 2), b(k, 3)], [b(k, 1), b(k, 3)], [t(k, 2), t(k, 3)]]);
        expected.extend([[t(k, 1), t(k, 3)], [b(k, 3), t(k, 3)]]);
    }
    let joins = [
        (t(0, 1), [b(1, 1), t(1, 1)]),
        (t(0, 2), [b(1, 2), b(1, 1)]),
        (b(0, 2), [t(1, 2), b(1, 2)]),
        (b(0, 1), [t(1, 1), t(1, 2)]),
    ];
    for (node, [e0, e1]) in joins {
        expected.extend([[e0, node], [node, e1]]);
    }
    let mut got: Vec<[usize; 2]> = (members(&scene).into_iter())
        .filter(|m| m.0 == "strings")
        .map(|m| {
            let mut e = m.1;
            e.sort();
            e
        })
        .collect();
    expected.iter_mut().for_each(|e| e.sort());
    got.sort();
    expected.sort();
    assert_eq!(got, expected);
}
