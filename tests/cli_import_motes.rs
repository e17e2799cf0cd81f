//! `tensegrity import motes` (`tensegrity_io::matrices`): the MOTES D-bar and the TsgFEM
//! T-bar anchor scenes (examples/anchors/) written as their codes' matrices — N (3 × n, a
//! node per column), C_b and C_s (−1 at a member's first node, +1 at its second), the bar
//! masses, string stiffnesses and rest lengths as lists — imported back give the same
//! structure, the same `statics` report and the same trajectory (the anchors' tables beside
//! the structure, the T-bar's roller and load and both `[simulation]` tables, appended to
//! the imported scene), to the last digit; bad matrices are refused naming the row.

use crate::common;

use common::{assert_refused, json, run, scratch};
use std::path::Path;

/// One model in matrix form (the anchor scene's numbers).
struct Model {
    anchor: &'static str,
    nodes: &'static [[f64; 3]],
    bars: &'static [[usize; 2]],
    strings: &'static [[usize; 2]],
    bar_mass: f64,
    stiffness: f64,
    rest_lengths: &'static [f64],
    /// What the anchor scene has beside the structure and its pinned node 0.
    tables: &'static str,
}

const DBAR: Model = Model {
    anchor: "examples/anchors/motes_dbar.toml",
    nodes: &[
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
    ],
    bars: &[[3, 0], [0, 1], [1, 2], [2, 3]],
    strings: &[[1, 3], [0, 2]],
    bar_mass: 1.0,
    stiffness: 100.0,
    rest_lengths: &[1.0, 0.5],
    tables: "\n[simulation]\nt_end = 5.0\nintegrator = \"rk4\"\ndt = 1e-3\n",
};

const TBAR: Model = Model {
    anchor: "examples/anchors/tsgfem_tbar.toml",
    nodes: &[
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 0.5, 0.0],
        [1.0, -0.5, 0.0],
    ],
    bars: &[[0, 2], [2, 1], [2, 3], [2, 4]],
    strings: &[[0, 3], [3, 1], [0, 4], [4, 1]],
    bar_mass: 1.0,
    stiffness: 1000.0,
    rest_lengths: &[1.095673308974897; 4],
    tables: "\n[[supports]]\nnode = 1\nfixed = [false, true, true]\n\n[[loads]]\nnode = 3\nforce = [0.0, -20.0, 0.0]\n\n[simulation]\nt_end = 2.0\nintegrator = \"rk4\"\ndt = 1e-3\n",
};

/// A connectivity matrix, one member per row, in MATLAB's bracket form.
fn connectivity(members: &[[usize; 2]], n: usize) -> String {
    let rows: Vec<String> = (members.iter())
        .map(|&[i, j]| {
            let row: Vec<&str> = (0..n)
                .map(|k| match k {
                    _ if k == i => "-1",
                    _ if k == j => "1",
                    _ => "0",
                })
                .collect();
            row.join(" ")
        })
        .collect();
    format!("[{}]\n", rows.join(";\n"))
}

/// Writes the model's matrices into `dir` and imports them; the imported scene's path.
fn import(m: &Model, dir: &Path) -> String {
    let n = m.nodes.len();
    let axis = |a: usize| -> String {
        let v: Vec<String> = m.nodes.iter().map(|p| format!("{:?}", p[a])).collect();
        v.join(", ")
    };
    let list = |v: Vec<f64>| -> String {
        v.iter()
            .map(|x| format!("{x:?}"))
            .collect::<Vec<_>>()
            .join("\n")
    };
    let files = [
        (
            "N.csv",
            format!(
                "% N: a node per column\n{}\n{}\n{}\n",
                axis(0),
                axis(1),
                axis(2)
            ),
        ),
        ("C_b.txt", connectivity(m.bars, n)),
        ("C_s.txt", connectivity(m.strings, n)),
        ("masses.txt", list(vec![m.bar_mass; m.bars.len()])),
        ("k.txt", list(vec![m.stiffness; m.strings.len()])),
        ("l0.txt", list(m.rest_lengths.to_vec())),
    ];
    for (name, text) in &files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let path = |name: &str| dir.join(name).display().to_string();
    let out = path("imported.toml");
    let o = run(&[
        "import",
        "motes",
        &path("N.csv"),
        &path("C_b.txt"),
        &path("C_s.txt"),
        "--bar-mass",
        &path("masses.txt"),
        "--stiffness",
        &path("k.txt"),
        "--rest-length",
        &path("l0.txt"),
        "--pinned",
        "0",
        "--out",
        &out,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let scene = std::fs::read_to_string(&out).unwrap() + m.tables;
    std::fs::write(&out, scene).unwrap();
    out
}

#[test]
fn the_anchor_models_from_their_matrices_are_the_anchor_scenes() {
    for (name, m) in [("dbar", &DBAR), ("tbar", &TBAR)] {
        let dir = scratch("import", name);
        let imported = import(m, &dir);
        for command in [
            &["statics", "--json"][..],
            &["simulate", "--json", "--no-convergence-check"][..],
        ] {
            let ours = json(&[&[command[0], &imported][..], &command[1..]].concat());
            let anchor = json(&[&[command[0], m.anchor][..], &command[1..]].concat());
            for key in [
                "final_nodes",
                "final_velocities",
                "prestress",
                "rank",
                "mechanisms",
            ] {
                assert_eq!(ours[key], anchor[key], "{name} {}: {key}", command[0]);
            }
        }
    }
}

#[test]
fn bad_matrices_are_refused_naming_the_row() {
    let dir = scratch("import", "bad");
    let n = dir.join("N.txt");
    std::fs::write(&n, "0 1 2\n0 0 0\n0 0 1\n").unwrap();
    for (text, says) in [
        ("-1 1 0\n0 1 1\n", "C_b: row 2 (member 1): 1 at node 2"),
        ("-1 1 0\n0 1\n", "C_b: row 2 has 2 number(s), row 1 has 3"),
        (
            "-1 0 0 1\n",
            "C_b: row 1 (member 0): 4 column(s) for 3 node(s)",
        ),
        ("-1 x 1\n", "C_b: row 1: 'x' is not a number"),
        ("-1 1 0\n-1 1 0\n", "bar 1"),
    ] {
        let c = dir.join("C_b.txt");
        std::fs::write(&c, text).unwrap();
        let o = run(&["import", "motes", n.to_str().unwrap(), c.to_str().unwrap()]);
        assert_refused(&o, text, says);
    }
}

/// The bundled matrix files (examples/motes_dbar/, MATLAB's bracket form and CSV) are the
/// D-bar anchor: the same statics report.
#[test]
fn the_bundled_dbar_matrices_are_the_anchor() {
    let dir = scratch("import", "bundled");
    let out = dir.join("dbar.toml");
    let f = |name: &str| format!("examples/motes_dbar/{name}");
    let o = run(&[
        "import",
        "motes",
        &f("nodes.csv"),
        &f("bars.txt"),
        &f("strings.txt"),
        "--bar-mass",
        &f("bar_mass.txt"),
        "--stiffness",
        &f("stiffness.txt"),
        "--rest-length",
        &f("rest_length.txt"),
        "--pinned",
        "0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let ours = json(&["statics", out.to_str().unwrap(), "--json"]);
    let anchor = json(&["statics", DBAR.anchor, "--json"]);
    assert_eq!(ours, anchor);
}
