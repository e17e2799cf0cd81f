//! `tensegrity statics` on stacked-prism towers: the 200-prism tower of
//! `examples/tower200.toml` goes through the sparse rank-revealing QR and gives one self-stress
//! and one internal mechanism per prism and the margin 1/√3 of the dense path (measured in
//! release: docs/notes/PERFORMANCE.md); the two-prism `examples/tower.toml` gives the same answer
//! through both factorisations.
use serde_json::Value;
use std::process::Command;

fn statics(scene: &str, method: &str) -> Value {
    let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(["statics", scene, "--json", "--method", method])
        .output()
        .expect("the binary runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON report")
}

#[test]
fn the_200_prism_tower_is_analysed_by_the_sparse_path() {
    let r = statics("examples/tower200.toml", "auto");
    assert_eq!(r["statics_method"], "sparse_qr");
    assert!(
        r.get("statics_warning").is_none(),
        "{}",
        r["statics_warning"]
    );
    assert_eq!(r["nodes"], 603);
    assert_eq!(
        (r["bars"].as_u64(), r["strings"].as_u64()),
        (Some(600), Some(1203))
    );
    // the dense SVD path (release, 8 s): rank 1603, 200 self-stresses, 206 mechanisms, margin
    // 0.5773502691896059 = 1/√3 to 1e-14
    assert_eq!(r["rank"], 1603);
    assert_eq!(r["self_stress_dim"], 200);
    assert_eq!(r["mechanisms"], 206);
    assert_eq!(r["internal_mechanisms"], 200);
    assert_eq!(r["prestressable"], true);
    assert_eq!(r["prestress_stable"], true);
    let margin = r["prestress_margin"].as_f64().unwrap();
    assert!((margin - 1.0 / 3f64.sqrt()).abs() < 1e-9, "{margin}");
    // 1,803 × 200 numbers: above SELF_STRESS_LIST_MAX, the basis is not listed, and says so
    assert_eq!(r["self_stress"].as_array().unwrap().len(), 0);
    let why = r["self_stress_omitted"].as_str().unwrap();
    assert!(why.contains("200-dimensional"), "{why}");
}

#[test]
fn the_two_prism_tower_gives_the_same_report_through_both_paths() {
    let dense = statics("examples/tower.toml", "dense");
    let sparse = statics("examples/tower.toml", "sparse");
    assert!(dense.get("statics_method").is_none());
    assert_eq!(sparse["statics_method"], "sparse_qr");
    for key in [
        "rank",
        "self_stress_dim",
        "mechanisms",
        "internal_mechanisms",
        "prestressable",
    ] {
        assert_eq!(dense[key], sparse[key], "{key}");
    }
    assert_eq!(dense["self_stress_dim"], 2);
    let (a, b) = (
        dense["prestress_margin"].as_f64().unwrap(),
        sparse["prestress_margin"].as_f64().unwrap(),
    );
    assert!((a - b).abs() < 1e-9, "{a} vs {b}");
}
