//! `tensegrity formfind` end to end (issue 23): the JSON keys of a built-in prism, the scene
//! `--out` writes read back by `statics` (prestressable, the same self-stress dimension) and
//! by `simulate` (one second without loads or gravity moves no node by more than 10⁻⁹ of the
//! structure's size), the figure `--svg` draws, bad topology files (exit 2, the file, the
//! line and the item named) and the refusal of a form too large for the limits.

use crate::common;

use serde_json::Value;
use std::path::Path;

fn json(out: &std::process::Output) -> Value {
    common::assert_ok(out);
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn a_builtin_prism_reports_the_issue_keys() {
    let r = json(&common::run(&[
        "formfind",
        "--builtin",
        "prism:3",
        "--analyse",
        "--json",
    ]));
    for key in [
        "method",
        "nodes",
        "force_density",
        "self_stress_dim",
        "prestressable",
        "prestress_stable",
        "residual",
        "iterations",
    ] {
        assert!(r.get(key).is_some(), "{key} missing in {r}");
    }
    // every force density given: the force density method, one direct solve
    assert_eq!(r["method"], "fdm");
    assert_eq!(r["iterations"], 1);
    let nodes = r["nodes"].as_array().unwrap();
    assert_eq!(nodes.len(), 6);
    assert!(nodes.iter().all(|p| p.as_array().unwrap().len() == 3));
    let q: Vec<f64> = r["force_density"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(q.len(), 12);
    // bars compressed, strings in tension; the ring/vertical ratio of the closed form
    assert!(q[..3].iter().all(|&x| x < 0.0) && q[3..].iter().all(|&x| x > 0.0));
    let ring = 1.0 / (2.0 * (std::f64::consts::PI / 3.0).sin());
    assert!((q[3] / q[9] - ring).abs() < 1e-10, "{q:?}");
    assert!((q[0] / q[9] + 1.0).abs() < 1e-10, "{q:?}");
    assert_eq!(r["self_stress_dim"], 1);
    assert_eq!(r["prestressable"], true);
    assert_eq!(r["prestress_stable"], true);
    assert!(r["residual"].as_f64().unwrap() < 1e-12, "{r}");
}

/// `--analyse` (issue 48): the form, its force densities, residual and synthesis are the same
/// to the bit with and without it (the JSON numbers print the shortest round-trip form, so
/// equal text is equal bits); with it the statics are the values reported before the flag
/// existed (always computed then), without it they are null and the text says how to get
/// them.
/// The arguments of a `formfind` run and its statics: self-stress dimension, prestressable,
/// prestress stable.
type AnalysedCase<'a> = (&'a [&'a str], (u64, bool, bool));

#[test]
fn the_statics_of_the_form_come_with_analyse_only_and_change_nothing_else() {
    let cases: [AnalysedCase; 6] = [
        (&["--builtin", "prism:3"], (1, true, true)),
        (&["--builtin", "octahedron"], (1, true, true)),
        (&["--builtin", "grid:4"], (121, true, true)),
        (&["--builtin", "tower:3:2"], (2, true, true)),
        (&["examples/formfind/loaded_net.toml"], (0, false, true)),
        (&["examples/formfind/prism3_dr.toml"], (1, true, true)),
    ];
    let statics = ["self_stress_dim", "prestressable", "prestress_stable"];
    for (source, (dim, prestressable, stable)) in cases {
        let run = |extra: &[&str]| {
            let mut args = vec!["formfind"];
            args.extend_from_slice(source);
            args.extend_from_slice(extra);
            json(&common::run(&args))
        };
        let (plain, analysed) = (run(&["--json"]), run(&["--analyse", "--json"]));
        let (mut a, mut b) = (plain.clone(), analysed.clone());
        for key in statics.iter().chain(&["wall_time_s"]) {
            a.as_object_mut().unwrap().remove(*key);
            b.as_object_mut().unwrap().remove(*key);
        }
        assert_eq!(a, b, "{source:?}: the form differs with --analyse");
        for key in [
            "nodes",
            "force_density",
            "residual",
            "member_force",
            "rest_length",
        ] {
            assert!(!plain[key].is_null(), "{source:?}: {key}");
        }
        for key in statics {
            assert!(
                plain[key].is_null(),
                "{source:?}: {key} without --analyse: {plain}"
            );
        }
        assert_eq!(analysed["self_stress_dim"], dim, "{source:?}");
        assert_eq!(analysed["prestressable"], prestressable, "{source:?}");
        assert_eq!(analysed["prestress_stable"], stable, "{source:?}");
    }
    let text = common::run(&["formfind", "--builtin", "prism:3"]);
    common::assert_ok(&text);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("not analysed (--analyse)"), "{text}");
    let text = common::run(&["formfind", "--builtin", "prism:3", "--analyse"]);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains("self-stress states 1  prestressable true  prestress stable true"),
        "{text}"
    );
}

/// The scene of `formfind --builtin NAME --out`, and the form's report.
fn export(name: &str, dir: &Path) -> (std::path::PathBuf, Value) {
    let scene = dir.join(format!("{}.toml", name.replace(':', "_")));
    let args = [
        "formfind",
        "--builtin",
        name,
        "--prestress",
        "50",
        "--stiffness",
        "2e4",
        "--out",
        scene.to_str().unwrap(),
        "--analyse",
        "--json",
    ];
    let report = json(&common::run(&args));
    assert!(scene.exists(), "{}", scene.display());
    (scene, report)
}

#[test]
fn the_exported_scene_is_prestressable_with_the_same_self_stress() {
    let dir = common::scratch("formfind", "statics");
    for name in ["prism:3", "prism:5", "octahedron", "tower:3:2"] {
        let (scene, found) = export(name, &dir);
        let statics = json(&common::run(&[
            "statics",
            scene.to_str().unwrap(),
            "--json",
        ]));
        assert_eq!(statics["prestressable"], true, "{name}: {statics}");
        assert_eq!(
            statics["self_stress_dim"], found["self_stress_dim"],
            "{name}: {statics}"
        );
        assert_eq!(statics["nodes"], found["n_nodes"]);
        // the largest string tension of the exported structure is the prestress level
        let f: Vec<f64> = found["member_force"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let bars = found["n_bars"].as_u64().unwrap() as usize;
        let largest = f[bars..].iter().copied().fold(0.0, f64::max);
        assert!((largest - 50.0).abs() < 1e-9, "{name}: {largest}");
        assert!(f[..bars].iter().all(|&x| x < 0.0), "{name}: {f:?}");
    }
}

#[test]
fn the_exported_scene_rests_in_equilibrium_for_one_second() {
    let dir = common::scratch("formfind", "simulate");
    for name in ["prism:3", "octahedron"] {
        let (scene, found) = export(name, &dir);
        let args = [
            "simulate",
            scene.to_str().unwrap(),
            "--t-end",
            "1",
            "--integrator",
            "rk45",
            "--json",
        ];
        let run = json(&common::run(&args));
        let start: Vec<[f64; 3]> = serde_json::from_value(found["nodes"].clone()).unwrap();
        let end: Vec<[f64; 3]> = serde_json::from_value(run["final_nodes"].clone()).unwrap();
        assert_eq!(start.len(), end.len());
        let size = diameter(&start);
        let moved = start
            .iter()
            .zip(&end)
            .map(|(a, b)| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        assert!(moved <= 1e-9 * size, "{name}: moved {moved:e} of {size}");
        assert_eq!(run["t_end"], 1.0);
    }
}

fn diameter(p: &[[f64; 3]]) -> f64 {
    let mut d: f64 = 0.0;
    for a in p {
        for b in p {
            d = d.max((0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt());
        }
    }
    d
}

#[test]
fn a_topology_file_is_found_and_drawn() {
    let dir = common::scratch("formfind", "svg");
    let svg = dir.join("octahedron.svg");
    let out = common::run(&[
        "formfind",
        "examples/formfind/octahedron.toml",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    common::assert_ok(&out);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("<svg"), "{text}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("12 nodes, 6 bars, 24 strings") && stdout.contains("wrote figure"),
        "{stdout}"
    );
}

#[test]
fn bad_topologies_exit_2_naming_the_file_line_and_item() {
    let dir = common::scratch("formfind", "bad");
    let good = std::fs::read_to_string("examples/formfind/x_module.toml").unwrap();
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "nodes = [1, 3]",
            "nodes = [1, 3, 2]",
            &["bars[1]", "exactly two"],
        ),
        (
            "nodes = [2, 3]",
            "nodes = [2, 9]",
            &["strings[2]", "node 9 makes the topology 10 nodes"],
        ),
        (
            "nodes = [3, 0]",
            "nodes = [2, 1]",
            &["strings[3]", "as strings[1] does"],
        ),
        ("node = 2", "node = 1", &["fixed[2]", "fixed already"]),
        ("[[fixed]]", "[[fixes]]", &["unknown field `fixes`"]),
    ];
    for (i, (from, to, wants)) in cases.iter().enumerate() {
        assert!(good.contains(from), "{from}");
        let path = dir.join(format!("bad{i}.toml"));
        std::fs::write(&path, good.replacen(from, to, 1)).unwrap();
        let out = common::run(&["formfind", path.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{to}: {}", stderr(&out));
        let e = stderr(&out);
        assert!(
            e.contains(&format!("bad{i}.toml")) && e.contains("line "),
            "{e}"
        );
        for w in *wants {
            assert!(e.contains(w), "{to}: {e}");
        }
    }
    // a missing file, an unknown built-in, both sources, neither
    let out = common::run(&["formfind", "no/such/topology.toml"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("no/such/topology.toml"));
    let out = common::run(&["formfind", "--builtin", "dodecahedron"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("dodecahedron"), "{}", stderr(&out));
    let both = [
        "formfind",
        "examples/formfind/prism3.toml",
        "--builtin",
        "prism:3",
    ];
    assert_eq!(common::run(&both).status.code(), Some(2));
    let out = common::run(&["formfind"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--builtin"), "{}", stderr(&out));
}

#[test]
fn an_output_path_is_checked_before_the_form_is_found() {
    let out = common::run(&[
        "formfind",
        "--builtin",
        "prism:3",
        "--out",
        "no/such/dir/scene.toml",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let e = stderr(&out);
    assert!(e.contains("--out") && e.contains("no/such/dir"), "{e}");
}

#[test]
fn a_form_over_the_limits_is_refused_before_it_is_found() {
    let out = common::run(&["formfind", "--builtin", "grid:300", "--max-work", "0.001"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let e = stderr(&out);
    assert!(
        e.contains("builtin = grid:300") && e.contains("--max-work"),
        "{e}"
    );
}

#[test]
fn a_free_standing_form_held_at_three_nodes_is_a_singular_system() {
    // the simplex held at four nodes is determined; at three, its affine freedom is not:
    // D_ff is singular, the computation fails (exit 1) saying so
    let text = std::fs::read_to_string("examples/formfind/simplex_fixed.toml").unwrap();
    let three = &text[..text.rfind("[[fixed]]").unwrap()];
    let path = common::scratch("formfind", "singular").join("three.toml");
    std::fs::write(&path, three).unwrap();
    let out = common::run(&["formfind", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("singular"), "{}", stderr(&out));
}
