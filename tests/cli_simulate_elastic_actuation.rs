//! `[[actuation]]` in the elastic dynamics (`tensegrity_path::actuation`): one actuator
//! reeling a clustered string (examples/cluster_reel.toml) and a node's load table, against
//! the closed form of a mass on a spring whose rest length (or load) ramps from t = 0,
//! w(t) = v t − (v/ω) sin ωt; a cluster with pulley friction is not driven.

mod common;

use common::{json, run, scratch};

/// w(1 s) of examples/cluster_reel.toml: v = 0.1 m/s, ω = 10 rad/s.
fn closed_form() -> f64 {
    0.1 - 0.01 * 10f64.sin()
}

fn rise(r: &serde_json::Value) -> f64 {
    r["final_nodes"][2][2].as_f64().unwrap() + 1.0
}

fn with(dir: &std::path::Path, name: &str, edit: impl Fn(String) -> String) -> String {
    let text = std::fs::read_to_string("examples/cluster_reel.toml").unwrap();
    let path = dir.join(name);
    std::fs::write(&path, edit(text)).unwrap();
    path.display().to_string()
}

#[test]
fn one_actuator_reels_a_cluster_at_the_closed_form() {
    let r = json(&["simulate", "examples/cluster_reel.toml", "--json"]);
    assert_eq!(r["valid"], true, "{r}");
    let w = closed_form();
    // RK4 at ω dt = 10⁻²: 7·10⁻¹¹ measured
    assert!((rise(&r) / w - 1.0).abs() < 1e-9, "{} vs {w}", rise(&r));
    let dir = scratch("elastic_actuation", "integrators");
    for (integrator, tol) in [("rk45", 1e-9), ("newmark", 1e-4)] {
        let scene = with(&dir, &format!("{integrator}.toml"), |t| {
            t.replace(
                "integrator = \"rk4\"",
                &format!("integrator = \"{integrator}\""),
            )
        });
        let r = json(&["simulate", &scene, "--json"]);
        assert_eq!(r["valid"], true, "{r}");
        assert!(
            (rise(&r) / w - 1.0).abs() < tol,
            "{integrator}: {} vs {w}",
            rise(&r)
        );
    }
}

#[test]
fn a_load_table_on_a_node_drives_the_elastic_dynamics() {
    // half the rise from a load ramping to 5 N up over 1 s at a fixed rest length (the
    // string stays taut: its tension falls from 9.81 N to about 4.8 N)
    let dir = scratch("elastic_actuation", "load");
    let scene = with(&dir, "load.toml", |t| {
        t.replace(
            "cluster = 0\ntimes = [0.0, 1.0]\nrest_lengths = [1.9019, 1.8019]",
            "node = 2\ntimes = [0.0, 1.0]\nforces = [[0.0, 0.0, 0.0], [0.0, 0.0, 5.0]]",
        )
    });
    let r = json(&["simulate", &scene, "--json"]);
    assert!(
        (rise(&r) / (0.5 * closed_form()) - 1.0).abs() < 1e-9,
        "{}",
        rise(&r)
    );
}

#[test]
fn a_cluster_with_pulley_friction_is_not_driven() {
    let dir = scratch("elastic_actuation", "friction");
    let scene = with(&dir, "friction.toml", |t| {
        t.replace(
            "rest_length = 1.9019\n",
            "rest_length = 1.9019\nfriction = [0.2]\n",
        )
    });
    let out = run(&["simulate", &scene]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("actuation 0") && err.contains("cluster 0") && err.contains("friction"),
        "{err}"
    );
}
