//! `statics` of clustered strings (`[[clusters]]`) end to end:
//!
//! - examples/clustered_prism.toml: the hand counts (10 columns, rank 9, one self-stress,
//!   9 mechanisms of which 3 internal: the twist and two sliding motions of the ring), the
//!   cluster last in every per-member array, its tension the prism's ring tension, named
//!   `cluster 0` in the text report;
//! - a mass over a pulley, sized: t = W, the pulley's reaction t(e₁ − e₂) and the cluster's
//!   mass (ρ/σ_Y) t L over its whole length;
//! - `--method sparse` (the banded sparse QR) models the cluster as the dense SVD does.

use crate::common;

use common::{assert_ok, run, scratch};

fn json(out: &std::process::Output) -> serde_json::Value {
    assert_ok(out);
    serde_json::from_slice(&out.stdout).unwrap()
}

const PRISM: &str = "examples/clustered_prism.toml";

#[test]
fn the_clustered_prism_reports_the_hand_counts_and_the_ring_tension() {
    let r = json(&run(&["statics", PRISM, "--json"]));
    let count = |k: &str| r[k].as_u64().unwrap();
    assert_eq!(
        [
            "bars",
            "strings",
            "clusters",
            "rank",
            "self_stress_dim",
            "mechanisms",
            "internal_mechanisms"
        ]
        .map(count),
        [3, 6, 1, 9, 1, 9, 3]
    );
    assert_eq!(r["prestressable"], true);
    let q: Vec<f64> = (r["prestress"].as_array().unwrap().iter())
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(q.len(), 10);
    // max|q| = 1 on the bars (q_bar = −√3 q_ring in the prism), so q_ring = 1/√3 and the
    // cluster over three ring lengths has q_c = q_ring / 3
    let q_ring = 1.0 / 3f64.sqrt();
    assert!((q[9] - q_ring / 3.0).abs() < 1e-12, "{q:?}");
    assert!((r["prestress_margin"].as_f64().unwrap() - q_ring / 3.0).abs() < 1e-12);
    let text = run(&["statics", PRISM]);
    assert_ok(&text);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("clusters 1"), "{text}");
    assert!(text.contains("cluster 0      0.192450"), "{text}");
}

/// Anchor (0, 0, 0) and pulley (4, 0, 3) pinned, 10 N hanging at (4, 0, 1): segments of 5 m
/// along e₁ = (0.8, 0, 0.6) and 2 m along e₂ = (0, 0, −1); steel.
const PULLEY: &str = r#"
nodes = [[0.0, 0.0, 0.0], [4.0, 0.0, 3.0], [4.0, 0.0, 1.0]]
[materials.rope]
density = 7862.0
youngs_modulus = 210e9
yield_strength = 690e6
[[clusters]]
nodes = [0, 1, 2]
material = "rope"
[[supports]]
node = 0
[[supports]]
node = 1
[[loads]]
node = 2
force = [0.0, 0.0, -10.0]
"#;

#[test]
fn a_mass_over_a_pulley_is_carried_reacted_and_sized_over_the_whole_length() {
    let dir = scratch("clusters", "pulley");
    let scene = dir.join("pulley.toml");
    std::fs::write(&scene, PULLEY).unwrap();
    let r = json(&run(&["statics", scene.to_str().unwrap(), "--json"]));
    let t = r["member_force"][0].as_f64().unwrap();
    assert!((t - 10.0).abs() < 1e-12, "{t}");
    let q = r["force_density"][0].as_f64().unwrap();
    assert!((q - 10.0 / 7.0).abs() < 1e-12, "{q}");
    let pulley: Vec<f64> = (r["reactions"][1]["force"].as_array().unwrap().iter())
        .map(|v| v.as_f64().unwrap())
        .collect();
    for (got, want) in pulley.iter().zip([8.0, 0.0, 16.0]) {
        assert!((got - want).abs() < 1e-12, "{pulley:?}");
    }
    let mass = r["mass_kg"].as_f64().unwrap();
    let expected = 7862.0 / 690e6 * 10.0 * 7.0;
    assert!((mass - expected).abs() < 1e-15, "{mass} vs {expected}");
    assert_eq!(r["governing"][0], "yield");
    let text = run(&["statics", scene.to_str().unwrap()]);
    assert_ok(&text);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("  cluster 0 "), "{text}");
    // its linear response needs the cluster's stiffness, which the scene does not give
    let out = run(&["statics", scene.to_str().unwrap(), "--response"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("cluster 0: the linear response (an axial stiffness) needs its stiffness"),
        "{err}"
    );
}

#[test]
fn the_sparse_back_end_models_a_cluster_as_the_dense_one() {
    let sparse = json(&run(&["statics", PRISM, "--method", "sparse", "--json"]));
    let dense = json(&run(&["statics", PRISM, "--method", "dense", "--json"]));
    assert_eq!(sparse["statics_method"], "sparse_qr");
    for k in [
        "rank",
        "self_stress_dim",
        "internal_mechanisms",
        "prestressable",
        "prestress_stable",
    ] {
        assert_eq!(sparse[k], dense[k], "{k}");
    }
    let (a, b) = (&sparse["prestress"], &dense["prestress"]);
    for (x, y) in a.as_array().unwrap().iter().zip(b.as_array().unwrap()) {
        assert!(
            (x.as_f64().unwrap() - y.as_f64().unwrap()).abs() < 1e-12,
            "{a} vs {b}"
        );
    }
}
