//! `tensegrity formfind` with loads end to end (issue 43, item 4): the loaded cable net of
//! `examples/formfind/loaded_net.toml` — its reactions carry the 9 N of loads, its JSON keys
//! and text; the scene `--out` writes keeps the supports and the loads, and `statics` on it
//! finds the same force densities and reactions by its own load solve; jax_fdm's loaded arch
//! as topology text; bad loads refused with exit 2, the file, the line and the item named.

use crate::common;

use common::numbers;

use serde_json::Value;

fn json(out: &std::process::Output) -> Value {
    common::assert_ok(out);
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

/// The node and force of each entry of a `loads` or `reactions` list.
fn forces(v: &Value) -> Vec<(u64, [f64; 3])> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|f| {
            let x = numbers(&f["force"]);
            (f["node"].as_u64().unwrap(), [x[0], x[1], x[2]])
        })
        .collect()
}

const NET: &str = "examples/formfind/loaded_net.toml";

#[test]
fn the_loaded_net_balances_its_loads_and_its_scene_is_read_back_by_statics() {
    let dir = common::scratch("formfind-loads", "net");
    let scene = dir.join("net.toml");
    let r = json(&common::run(&[
        "formfind",
        NET,
        "--json",
        "--out",
        scene.to_str().unwrap(),
    ]));
    assert_eq!(r["method"], "fdm");
    let loads = forces(&r["loads"]);
    assert_eq!(loads.len(), 9);
    assert!(loads.iter().all(|(_, f)| *f == [0.0, 0.0, -1.0]));
    let reactions = forces(&r["reactions"]);
    assert_eq!(reactions.len(), 12);
    // Σ r + Σ p = 0: the 12 held nodes carry the 9 N, and nothing in x or y overall
    let mut sum = [0.0; 3];
    for (_, f) in &reactions {
        for a in 0..3 {
            sum[a] += f[a];
        }
    }
    assert!(
        sum[0].abs() < 1e-12 && sum[1].abs() < 1e-12 && (sum[2] - 9.0).abs() < 1e-12,
        "{sum:?}"
    );
    // the mid-edge node 1 at (2, 0, 0) holds a y string of q = 2 to node 5 at
    // (2, 1, z5): r_1 = q (x_1 − x_5) = (0, −2, −2 z5)
    let z5 = numbers(&r["nodes"][5])[2];
    let (node, r1) = reactions[1];
    assert_eq!(node, 1);
    assert!(r1[0].abs() < 1e-15 && (r1[1] + 2.0).abs() < 1e-12 && (r1[2] + 2.0 * z5).abs() < 1e-12);
    assert!(r["equilibrium_residual"].as_f64().unwrap() < 1e-14);
    assert!(r["residual"].as_f64().unwrap() < 1e-14);
    // the loads fix the forces: the report's prestress is the largest q L, not 100 N
    let q = numbers(&r["force_density"]);
    let force = numbers(&r["member_force"]);
    let largest = force.iter().fold(0.0f64, |m, &f| m.max(f));
    assert_eq!(r["prestress"].as_f64().unwrap(), largest);
    assert!(largest < 3.0, "{largest}");

    // the written scene keeps the supports and the loads
    let text = std::fs::read_to_string(&scene).unwrap();
    assert_eq!(text.matches("[[supports]]").count(), 12);
    assert_eq!(text.matches("[[loads]]").count(), 9);
    // `statics` solves the scene's loads on its own: the same q and reactions
    let s = json(&common::run(&[
        "statics",
        scene.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(s["load_carried"], true);
    let sq = numbers(&s["force_density"]);
    for (k, (a, b)) in q.iter().zip(&sq).enumerate() {
        assert!((a - b).abs() < 1e-9 * a.abs(), "string {k}: {a} vs {b}");
    }
    for ((n, a), (m, b)) in reactions.iter().zip(forces(&s["reactions"])) {
        assert_eq!(*n, m);
        for i in 0..3 {
            assert!((a[i] - b[i]).abs() < 1e-9, "node {n}: {a:?} vs {b:?}");
        }
    }

    // the text names the loads, the reactions and the residual
    let out = common::run(&["formfind", NET]);
    common::assert_ok(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    for want in [
        "force q·L under the loads",
        "loads (N):",
        "reactions at the fixed nodes (N):",
        "     1  +0.000000000 -2.000000000 +1.137254902",
        "equilibrium residual at the free nodes",
    ] {
        assert!(text.contains(want), "{want} missing in\n{text}");
    }
}

#[test]
fn jax_fdm_s_arch_as_topology_text() {
    let mut text = String::new();
    for k in 0..10 {
        text += &format!("[[bars]]\nnodes = [{k}, {}]\nforce_density = -1.0\n", k + 1);
    }
    text += "[[fixed]]\nnode = 0\nposition = [-2.5, 0.0, 0.0]\n";
    text += "[[fixed]]\nnode = 10\nposition = [2.5, 0.0, 0.0]\n";
    for k in 1..10 {
        text += &format!("[[loads]]\nnode = {k}\nforce = [0.0, 0.0, -0.2]\n");
    }
    let r = json(&common::run(&["formfind", &text, "--json"]));
    // z_i = 0.1 i (10 − i), jax_fdm's baseline; the supports take (±0.5, 0, 0.9)
    for i in 0..=10 {
        let p = numbers(&r["nodes"][i]);
        assert!(
            (p[2] - 0.1 * (i * (10 - i)) as f64).abs() < 1e-12,
            "node {i}: {p:?}"
        );
    }
    let reactions = forces(&r["reactions"]);
    let want = [(0, [0.5, 0.0, 0.9]), (10, [-0.5, 0.0, 0.9])];
    for ((n, f), (m, g)) in reactions.iter().zip(want) {
        assert_eq!(*n, m);
        assert!((0..3).all(|a| (f[a] - g[a]).abs() < 1e-12), "{f:?}");
    }
}

#[test]
fn bad_loads_exit_2_naming_the_file_the_line_and_the_item() {
    let net = std::fs::read_to_string(NET).unwrap();
    let dir = common::scratch("formfind-loads", "bad");
    let first = "[[loads]]\nnode = 4\nforce = [0.0, 0.0, -1.0]";
    assert!(net.contains(first));
    let line = net[..net.find(first).unwrap()].lines().count() + 1;
    let fixed_free = {
        // every [[fixed]] table dropped: a free-standing net under loads
        let mut t = String::new();
        let mut skip = 0;
        for l in net.lines() {
            if l == "[[fixed]]" {
                skip = 3;
            }
            if skip > 0 {
                skip -= 1;
                continue;
            }
            t += l;
            t += "\n";
        }
        t
    };
    let cases: [(&str, String, Vec<String>); 4] = [
        (
            "range",
            net.replacen(first, "[[loads]]\nnode = 40\nforce = [0.0, 0.0, -1.0]", 1),
            vec![
                format!("(line {line})"),
                "loads[0]: node 40 out of range".into(),
            ],
        ),
        (
            "nan",
            net.replacen(first, "[[loads]]\nnode = 4\nforce = [0.0, nan, -1.0]", 1),
            vec![
                format!("(line {line})"),
                "loads[0].force".into(),
                "finite".into(),
            ],
        ),
        (
            "free",
            fixed_free,
            vec![
                "loads: 9 load(s) on a free-standing topology".into(),
                "sum to [0.0, 0.0, -9.0] N".into(),
                "`fixed`".into(),
            ],
        ),
        (
            "adaptive",
            net.clone(),
            vec!["loads[0]: the adaptive method takes no loads".into()],
        ),
    ];
    for (name, text, wants) in cases {
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, text).unwrap();
        let mut args = vec!["formfind", path.to_str().unwrap()];
        if name == "adaptive" {
            args.extend(["--method", "adaptive"]);
        }
        let out = common::run(&args);
        assert_eq!(out.status.code(), Some(2), "{name}: {out:?}");
        let e = String::from_utf8_lossy(&out.stderr);
        // the reader's refusals name the file; the method's choice is the library's
        if name != "adaptive" {
            assert!(e.contains(path.to_str().unwrap()), "{name}: {e}");
        }
        for w in &wants {
            assert!(e.contains(w.as_str()), "{name}: {w} missing in {e}");
        }
    }
}
