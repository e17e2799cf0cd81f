//! `tensegrity import ntrt` (`tensegrity_io::ntrt`): NTRT's SUPERball and 3-prism models
//! (examples/ntrt/, NTRT's own YAML files) imported as scenes: their nodes in the file's
//! order at the YAML's coordinates, a bar per rod pair with the mass ρ π r² L of its builder,
//! a string per actuator pair with its stiffness, damping and the rest length L − t₀/k that
//! carries its pretension; `statics` then says what the drawn geometry is (the SUPERball's,
//! rounded to 0.01, has no self-stress); bad models are refused naming the item.

mod common;

use common::{json, run, scratch};

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
            "pair group vertical_string: no builder of this tag",
        ),
        (
            "pretension",
            good.replace("pretension: 3000", "pretension: 1e6"),
            "builder horizontal_string: pretension 1000000 stretches pair [bottom1, bottom2]",
        ),
        (
            "sub",
            format!("{good}\nsubstructures:\n  a:\n    path: x.yaml\n"),
            "substructures: substructures (offsets, rotations, bonds) are not imported",
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
        assert_eq!(o.status.code(), Some(2), "{name}: {o:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(says), "{name}: {err}");
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
