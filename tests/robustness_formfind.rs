//! `formfind` at its edges (issue 42, docs/ROBUSTNESS.md "Form-finding"): each input the
//! catalogue found aborting, silently switching method, ignoring data, overflowing or
//! misread is now refused before the work with a message naming the item, the file or the
//! flag (exit 2 for bad input), or found correctly with its warning.

use crate::common;

use common::numbers;
use common::{assert_ok, run, scratch};
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Output;

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Asserts exit code 2 and returns stderr.
fn refused(out: &Output) -> String {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    err
}

fn json(out: &Output) -> Value {
    assert_ok(out);
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

/// The 3-bar prism's members (bars, bottom ring, top ring, verticals), as prism3.toml.
#[rustfmt::skip]
const PRISM_MEMBERS: [[usize; 2]; 12] = [
    [0, 3], [1, 4], [2, 5], [0, 1], [1, 2], [2, 0], [3, 4], [4, 5], [5, 3], [0, 5], [1, 3], [2, 4],
];

/// The 3-bar prism by groups: bars, rings and verticals at force densities `q`.
fn prism(q: [f64; 3]) -> String {
    let mut s = format!(
        "[groups.bars]\nforce_density = {:e}\n[groups.ring]\nforce_density = {:e}\n\
         [groups.vertical]\nforce_density = {:e}\n",
        q[0], q[1], q[2]
    );
    for i in 0..3 {
        s += &format!("[[bars]]\nnodes = [{i}, {}]\ngroup = \"bars\"\n", 3 + i);
    }
    for i in 0..3 {
        s += &format!(
            "[[strings]]\nnodes = [{i}, {}]\ngroup = \"ring\"\n",
            (i + 1) % 3
        );
        s += &format!(
            "[[strings]]\nnodes = [{}, {}]\ngroup = \"ring\"\n",
            3 + i,
            3 + (i + 1) % 3
        );
    }
    for i in 0..3 {
        s += &format!(
            "[[strings]]\nnodes = [{i}, {}]\ngroup = \"vertical\"\n",
            3 + (i + 2) % 3
        );
    }
    s
}

#[test]
fn a_node_count_beyond_the_members_is_refused_before_anything_is_allocated() {
    let dir = scratch("robust-formfind", "nodes");
    let big = "n_nodes = 1000000000000\n[[bars]]\nnodes = [0, 1]\n";
    let p = write(&dir, "big.toml", big);
    let err = refused(&run(&["formfind", p.to_str().unwrap()]));
    assert!(
        err.contains(p.to_str().unwrap())
            && err.contains("line 1")
            && err.contains("n_nodes: 1000000000000 nodes, but every node must be on a member or fixed, and 1 member(s) and 0 fixed node(s) reach at most 2"),
        "{err}"
    );
    // the same in a sweep of it: each case an error row naming the item, no abort
    let spec = format!(
        "study = \"formfind\"\n[fixed]\ntopology = \"{}\"\n[axes]\nprestress = [1.0, 2.0]\n",
        p.display()
    );
    let spec = write(&dir, "sweep.toml", &spec);
    let out = dir.join("out.csv");
    let (spec, csv) = (spec.to_str().unwrap(), out.to_str().unwrap());
    assert_ok(&run(&["sweep", spec, "--out", csv, "--quiet"]));
    let table = std::fs::read_to_string(&out).unwrap();
    let rows: Vec<&str> = table.lines().skip(1).collect();
    assert_eq!(rows.len(), 2, "{table}");
    for row in rows {
        assert!(
            row.contains(",error,") && row.contains("(line 1): n_nodes: 1000000000000 nodes"),
            "{row}"
        );
    }
}

#[test]
fn force_densities_that_admit_no_form_are_an_error_unless_auto_is_asked_for() {
    let dir = scratch("robust-formfind", "fallback");
    let p = write(&dir, "prism_q2.toml", &prism([-1.0, 1.0, 2.0]));
    let p = p.to_str().unwrap();
    // every member has a force density: the force density method, and its failure the error
    let out = run(&["formfind", p]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("the force density matrix has rank deficiency")
            && err.contains("(--method adaptive, started from these"),
        "{err}"
    );
    // `auto` falls back to the adaptive method, and says so
    let out = run(&["formfind", p, "--method", "auto", "--json"]);
    let r = json(&out);
    assert_eq!(r["method"], "adaptive");
    let err = stderr(&out);
    assert!(
        err.contains("warning: method auto chose adaptive: the force density method found no form")
            && err.contains("replaced the given force densities"),
        "{err}"
    );
    // the adaptive form replaced q_vertical = 2: bars at -1, verticals at 1 (the prism's)
    let q = numbers(&r["force_density"]);
    assert!(
        (q[9] - 1.0).abs() < 1e-9 && (q[0] + 1.0).abs() < 1e-9,
        "{q:?}"
    );
    // a prism whose force densities admit the form: the force density method, no warning
    let ring = 1.0 / 3f64.sqrt();
    let p = write(&dir, "prism.toml", &prism([-1.0, ring, 1.0]));
    let out = run(&[
        "formfind",
        p.to_str().unwrap(),
        "--method",
        "auto",
        "--json",
    ]);
    assert_eq!(json(&out)["method"], "fdm");
    assert!(stderr(&out).contains("method auto chose fdm: every member has a force density"));
}

#[test]
fn the_adaptive_method_is_estimated_over_its_iteration_cap_before_it_starts() {
    let dir = scratch("robust-formfind", "adaptive");
    // 1000 nodes, no force density: the adaptive method, 10 000 dense eigensolves at most
    let chain = common::chain(&dir, 1000);
    let err = refused(&run(&["formfind", &chain]));
    assert!(
        err.contains(&format!("topology = {chain}"))
            && err.contains("--max-iterations 10000")
            && err.contains("the adaptive force density iteration")
            && err.contains("of work, above the limit of 1.000 min"),
        "{err}"
    );
    // 300 nodes under a limit of 20 s: refused too, naming the cap to lower
    let chain = common::chain(&dir, 300);
    let err = refused(&run(&["formfind", &chain, "--max-work", "20"]));
    assert!(err.contains("--max-iterations 10000"), "{err}");
    // the gallery's adaptive sphere (60 nodes) stays inside the default limit
    let out = run(&[
        "formfind",
        "examples/formfind/icosidodecahedron30.toml",
        "--json",
    ]);
    assert_eq!(json(&out)["method"], "adaptive");
}

#[test]
fn given_lengths_are_used_by_dynamic_relaxation_or_refused_by_member() {
    let dir = scratch("robust-formfind", "lengths");
    let text = std::fs::read_to_string("examples/formfind/prism3_dr.toml").unwrap();
    // lengths without the nodes dynamic relaxation starts from
    let bare = text
        .split("[[bars]]")
        .skip(1)
        .collect::<Vec<_>>()
        .join("[[bars]]");
    let p = write(&dir, "no_nodes.toml", &format!("[[bars]]{bare}"));
    let err = refused(&run(&["formfind", p.to_str().unwrap()]));
    assert!(
        err.contains("nodes: dynamic relaxation, the method that uses the members' lengths (bars[0].length, …)"),
        "{err}"
    );
    // lengths on only some members: the first without one
    let some = text.replacen("length = 1.1249075930174168\n", "", 1);
    let p = write(&dir, "some.toml", &some);
    let err = refused(&run(&["formfind", p.to_str().unwrap()]));
    assert!(
        err.contains("strings[6].length: none given, while bars[0] has one: dynamic relaxation"),
        "{err}"
    );
    // a method that ignores lengths, asked for by name
    let p = "examples/formfind/prism3_dr.toml";
    let err = refused(&run(&["formfind", p, "--method", "adaptive"]));
    assert!(
        err.contains(
            "bars[0].length: the adaptive method ignores lengths; dynamic relaxation (--method dr)"
        ),
        "{err}"
    );
    // and the lengths used: dynamic relaxation, bars of the length given
    let r = json(&run(&["formfind", p, "--json"]));
    assert_eq!(r["method"], "dr");
    let x: Vec<Vec<f64>> = r["nodes"].as_array().unwrap().iter().map(numbers).collect();
    let bar = (0..3)
        .map(|k| (x[0][k] - x[3][k]).powi(2))
        .sum::<f64>()
        .sqrt();
    // a rod of EA = 1e5 N shortened by its compression from 2.1795… m
    assert!((bar - 2.179538291811533).abs() < 1e-2, "{bar}");
}

#[test]
fn overflowing_stiffness_or_force_densities_never_reach_a_report_or_a_scene() {
    let dir = scratch("robust-formfind", "overflow");
    let scene = dir.join("x.toml");
    let s = scene.to_str().unwrap();
    let args = [
        "formfind",
        "--builtin",
        "prism:3",
        "--stiffness",
        "1e308",
        "--out",
        s,
    ];
    let err = refused(&run(&args));
    assert!(
        err.contains("--stiffness") && err.contains("strings[0] would stretch by T/EA ="),
        "{err}"
    );
    assert!(!scene.exists());
    // force densities times 1e300: the same form and forces as at scale 1, all finite
    let ring = 1.0 / 3f64.sqrt();
    let at = |scale: f64, name: &str| {
        let p = write(&dir, name, &prism([-scale, ring * scale, scale]));
        json(&run(&[
            "formfind",
            p.to_str().unwrap(),
            "--analyse",
            "--json",
        ]))
    };
    let (one, huge) = (at(1.0, "one.toml"), at(1e300, "huge.toml"));
    assert_eq!(huge["prestress_stable"], true);
    let residual = huge["residual"].as_f64().unwrap();
    assert!(residual.is_finite() && residual < 1e-12, "{huge}");
    let (f1, f2) = (
        numbers(&one["member_force"]),
        numbers(&huge["member_force"]),
    );
    for (a, b) in f1.iter().zip(&f2) {
        assert!((a - b).abs() < 1e-9 * a.abs().max(1.0), "{f1:?} vs {f2:?}");
    }
}

#[test]
fn a_single_line_ending_in_toml_is_a_path_and_an_existing_file_is_read() {
    let dir = scratch("robust-formfind", "source");
    let missing = dir.join("a=b.toml");
    let err = refused(&run(&["formfind", missing.to_str().unwrap()]));
    assert!(
        err.contains("a=b.toml") && !err.contains("topology text"),
        "{err}"
    );
    // an existing file whose name holds `=` and does not end in .toml
    let text = std::fs::read_to_string("examples/formfind/prism3.toml").unwrap();
    let named = write(&dir, "q=1.topology", &text);
    let r = json(&run(&["formfind", named.to_str().unwrap(), "--json"]));
    assert_eq!(r["source"], named.to_str().unwrap());
}

#[test]
fn stiff_rods_relax_to_the_precision_floor_on_the_defaults() {
    let dir = scratch("robust-formfind", "rods");
    // the prism's rest lengths at 100 N with every member at EA = 2e8 N (2e6 times the
    // prestress: rods), in prism3_dr.toml's members and rough start
    let args = [
        "formfind",
        "examples/formfind/prism3.toml",
        "--stiffness",
        "2e8",
        "--json",
    ];
    let rest = numbers(&json(&run(&args))["rest_length"]);
    let text = std::fs::read_to_string("examples/formfind/prism3_dr.toml").unwrap();
    let mut lengths = rest.iter();
    let stiff: Vec<String> = text
        .lines()
        .map(|line| match line {
            l if l.starts_with("length = ") => format!("length = {:e}", lengths.next().unwrap()),
            l if l.starts_with("stiffness = ") => "stiffness = 2e8".to_string(),
            l => l.to_string(),
        })
        .collect();
    assert!(lengths.next().is_none());
    let p = write(&dir, "rods.toml", &stiff.join("\n"));
    let out = run(&["formfind", p.to_str().unwrap()]);
    assert_ok(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    // the floor 8 ε EA / max |T| ≈ 1.8e-9 (max |T| ≈ 193 N, the bars'), far above 1e-12
    let head = stdout.lines().next().unwrap();
    assert!(
        head.contains("method dr") && head.contains("(tolerance 1.8e-9)"),
        "{head}"
    );
    // the relaxed tensions T = q L are the prism's at 100 N
    let r = json(&run(&["formfind", p.to_str().unwrap(), "--json"]));
    let (q, x) = (numbers(&r["force_density"]), &r["nodes"]);
    let point = |i: usize| numbers(&x[i]);
    let pairs = PRISM_MEMBERS.iter();
    let tension: Vec<f64> = pairs
        .zip(&q)
        .map(|(&[i, j], qk)| {
            let (a, b) = (point(i), point(j));
            qk * (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
        })
        .collect();
    let largest = tension.iter().fold(0.0f64, |a, &t| a.max(t));
    assert!((largest - 100.0).abs() < 1e-6, "{tension:?}");
}
