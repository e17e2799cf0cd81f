//! A bistable unit traced through both of its limit points by `solve`, each point tagged
//! stable or unstable, and its stable states confirmed by the dynamics: `simulate` (rigid
//! bars, damped strings, the load applied at once) settles where the path says, near the
//! start below the fold and on the inverted branch above it (examples/bistable.toml).

use serde_json::Value;
use std::process::Command;

fn json(args: &[&str]) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("binary runs");
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The scene with the apex load `load` (N, down).
fn scene(load: f64) -> String {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/bistable.toml"
    ))
    .unwrap();
    text.replace(
        "force = [0.0, -10.0, 0.0]",
        &format!("force = [0.0, {:?}, 0.0]", -load),
    )
}

fn apex(v: &Value) -> (f64, f64) {
    (v[2][0].as_f64().unwrap(), v[2][1].as_f64().unwrap())
}

#[test]
fn the_dynamics_settles_where_the_load_path_says() {
    // the path through both folds, stable outside them, unstable between
    let path = json(&["solve", "examples/bistable.toml", "--target", "3", "--json"]);
    assert_eq!(path["limit_points"], 2);
    let fold = path["first_limit_load_factor"].as_f64().unwrap();
    assert!((fold - 1.716561).abs() < 1e-5, "{fold}");
    for p in path["path"]["points"].as_array().unwrap() {
        let (lambda, y) = (
            p["lambda"].as_f64().unwrap(),
            p["nodes"][2][1].as_f64().unwrap(),
        );
        let stable = p["stability"] == "stable";
        // between the folds' apex heights (±0.29 m) the truss is unstable
        if y.abs() > 0.31 {
            assert!(stable, "λ {lambda}, apex {y}");
        } else if y.abs() < 0.27 {
            assert!(!stable, "λ {lambda}, apex {y}");
        }
    }
    // below the fold (10 N, λ = 1 of it): near the start; above it (25 N): inverted
    for (load, inverted) in [(10.0, false), (25.0, true)] {
        let text = scene(load);
        let settled = json(&[
            "simulate",
            &text,
            "--t-end",
            "20",
            "--no-convergence-check",
            "--json",
        ]);
        assert_eq!(settled["valid"], true);
        let at_rest = apex(&settled["final_nodes"]);
        let velocity = settled["final_velocities"][2][1].as_f64().unwrap();
        assert!(velocity.abs() < 1e-4, "settled: {velocity}");
        let statics = json(&["solve", &text, "--json"]);
        let last = &statics["path"]["points"]
            .as_array()
            .unwrap()
            .last()
            .unwrap()
            .clone();
        assert_eq!(last["stability"], "stable");
        let predicted = apex(&last["nodes"]);
        assert_eq!(predicted.1 < 0.0, inverted, "{predicted:?}");
        // rigid bars in the dynamics, elastic ones (EA = 64.7 MN) in the path: 10⁻⁶ m
        assert!(
            (at_rest.0 - predicted.0).abs() < 1e-5 && (at_rest.1 - predicted.1).abs() < 1e-5,
            "{at_rest:?} against {predicted:?}"
        );
    }
}
