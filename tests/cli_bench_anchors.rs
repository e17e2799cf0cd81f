//! `tensegrity bench anchors` end to end (issue 25, item 4): `--quick --repeats 1
//! --no-instructions` (no callgrind in the default tests) with `--json` and `--csv`; the
//! anchors' final nodes are those of `tensegrity simulate SCENE --json`, the same run; the
//! CSV has one row per anchor and per series point; `bench work-precision` keeps its form.
//! With valgrind installed, the quick run with instructions: the toroid's instructions, whose
//! cost is linear in its sides (the cyclic path), fit an exponent within [0.8, 1.2] (skipped,
//! with a message, without valgrind).

use crate::common;

use common::{assert_ok, run, scratch};
use serde_json::Value;

fn simulate_final_nodes(scene: &str) -> Vec<Vec<f64>> {
    let out = run(&["simulate", scene, "--json"]);
    assert_ok(&out);
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    serde_json::from_value(v["final_nodes"].clone()).unwrap()
}

#[test]
fn quick_json_and_csv() {
    let dir = scratch("bench", "anchors");
    let csv = dir.join("bench.csv");
    let out = run(&[
        "bench",
        "anchors",
        "--quick",
        "--repeats",
        "1",
        "--no-instructions",
        "--json",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert_ok(&out);
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let anchors = v["anchors"].as_array().unwrap();
    let names: Vec<&str> = anchors
        .iter()
        .map(|a| a["anchor"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "motes_dbar",
            "motes_prism",
            "tsgfem_tbar",
            "double_pendulum_rk4"
        ]
    );
    for a in anchors {
        let ours: Vec<Vec<f64>> = serde_json::from_value(a["final_nodes"].clone()).unwrap();
        let sim = simulate_final_nodes(a["scene"].as_str().unwrap());
        for (p, q) in ours.iter().zip(&sim) {
            for d in 0..3 {
                assert!((p[d] - q[d]).abs() <= 1e-12, "{}: {p:?} {q:?}", a["anchor"]);
            }
        }
        assert!(a["final_error_m"].as_f64().unwrap() < a["final_tolerance_m"].as_f64().unwrap());
        assert!(a["instructions_per_step"].is_null());
        // a stored reference time: its date and machine, and no ratio formed from it
        assert!(a["ratio"].is_null());
        assert!(a["reference"]["measured"]
            .as_str()
            .unwrap()
            .starts_with("2026-11-28"));
    }
    assert_eq!(v["request"]["quick"], true);
    assert!(v["instructions_note"].is_null());
    let series: Vec<&str> = v["series"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["series"].as_str().unwrap())
        .collect();
    assert_eq!(series, ["toroid", "towers", "michell", "rolling"]);
    assert!(v["series"][0]["fit"]["exponent"].as_f64().is_some());
    for s in v["series"].as_array().unwrap() {
        assert_eq!(s["instructions_note"], "instructions not requested");
        assert!(s["instructions_fit"].is_null());
        for p in s["points"].as_array().unwrap() {
            assert!(p["instructions"].is_null() && p["instructions_per_step"].is_null());
        }
    }

    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "group,name,size,members,steps,best_s,per_step_s,instructions_per_step,reference_code,reference_s,ratio,exponent,instructions,instructions_exponent"
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 4 + 3 + 3 + 3 + 2);
    assert!(rows[0].starts_with("anchor,motes_dbar,,,5000,"));
    // the ratio cell of a stored reference is empty
    assert!(rows[0].contains(",MOTES,54.3,,"));
    assert!(rows[4].starts_with("series,toroid,100,1901,,"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_values_and_the_hidden_run() {
    let out = run(&["bench", "anchors", "--repeats", "0", "--quick"]);
    assert_eq!(
        out.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("--repeats"));
    let out = run(&["bench", "anchor-run", "tsgfem_tbar", "--steps", "3"]);
    assert_ok(&out);
    assert!(out.stdout.is_empty());
    let out = run(&["bench", "series-run", "towers", "3", "--reps", "2"]);
    assert_ok(&out);
    assert!(out.stdout.is_empty());
    let out = run(&["bench", "series-run", "no_such", "3"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("toroid, towers, michell, rolling"));
    let out = run(&["bench", "anchor-run", "no_such"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("motes_dbar"));
    // the existing form is unchanged, and the hidden mode is not listed
    let help = run(&["bench", "--help"]);
    let help = String::from_utf8_lossy(&help.stdout);
    assert!(help.contains("work-precision") && help.contains("anchors"));
    assert!(!help.contains("anchor-run") && !help.contains("series-run"));
}

fn valgrind_present() -> bool {
    std::process::Command::new("valgrind")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

#[test]
fn the_toroids_instructions_grow_linearly() {
    if !valgrind_present() {
        eprintln!("skipped: valgrind is not installed (the instruction counts need callgrind)");
        return;
    }
    let out = run(&["bench", "anchors", "--quick", "--repeats", "1", "--json"]);
    assert_ok(&out);
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(
        v["instructions_note"].is_null(),
        "{}",
        v["instructions_note"]
    );
    // every anchor's step costs instructions, fewer than a whole process start
    for a in v["anchors"].as_array().unwrap() {
        let i = a["instructions_per_step"].as_f64().unwrap();
        assert!(i > 1e3 && i < 1e7, "{}: {i}", a["anchor"]);
    }
    for s in v["series"].as_array().unwrap() {
        assert!(
            s["instructions_note"].is_null(),
            "{}",
            s["instructions_note"]
        );
        for p in s["points"].as_array().unwrap() {
            assert!(
                p["instructions"].as_f64().unwrap() > 0.0,
                "{}: {p}",
                s["series"]
            );
        }
    }
    // the toroid by its cyclic path: linear in the sides
    let toroid = &v["series"][0];
    assert_eq!(toroid["series"], "toroid");
    let exponent = toroid["instructions_fit"]["exponent"].as_f64().unwrap();
    assert!((0.8..=1.2).contains(&exponent), "{exponent}: {toroid}");
    // the rolling series counts per step: steps · per step
    for p in v["series"][3]["points"].as_array().unwrap() {
        let per_step = p["instructions_per_step"].as_f64().unwrap();
        let whole = p["instructions"].as_f64().unwrap();
        assert!((whole - 20.0 * per_step).abs() <= 1e-6 * whole, "{p}");
    }
}
