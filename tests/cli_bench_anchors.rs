//! `tensegrity bench anchors` end to end (issue 25, item 4): `--quick --repeats 1
//! --no-instructions` (no callgrind in the default tests) with `--json` and `--csv`; the
//! anchors' final nodes are those of `tensegrity simulate SCENE --json`, the same run; the
//! CSV has one row per anchor and per series point; `bench work-precision` keeps its form.

mod common;

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
        assert!(a["ratio"].as_f64().unwrap() > 0.0);
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

    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "group,name,size,members,steps,best_s,per_step_s,instructions_per_step,reference_code,reference_s,ratio,exponent"
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 4 + 3 + 3 + 3 + 2);
    assert!(rows[0].starts_with("anchor,motes_dbar,,,5000,"));
    assert!(rows[0].contains(",MOTES,54.3,"));
    assert!(rows[4].starts_with("series,toroid,8,153,,"));
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
    let out = run(&["bench", "anchor-run", "no_such"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("motes_dbar"));
    // the existing form is unchanged, and the hidden mode is not listed
    let help = run(&["bench", "--help"]);
    let help = String::from_utf8_lossy(&help.stdout);
    assert!(help.contains("work-precision") && help.contains("anchors"));
    assert!(!help.contains("anchor-run"));
}
