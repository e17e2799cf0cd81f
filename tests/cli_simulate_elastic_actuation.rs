//! `[[actuation]]` in the elastic dynamics (`tensegrity_path::actuation`): one actuator
//! reeling a clustered string (examples/cluster_reel.toml: its EA kept, the dashpot settling
//! the mass at the static equilibrium of the new rest length, L₀' (1 + m g/EA), under RK4,
//! RK45 and Newmark alike), a node's load table against the closed form of an undamped mass
//! on a spring under a ramp, w(t) = (F/k)(t − sin(ωt)/ω), and a cluster with pulley friction
//! that is not driven.

use crate::common;

use common::{json, run, scratch};

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
fn one_actuator_reels_a_cluster_to_its_new_equilibrium() {
    // EA = k L₀ = 100 × 1.9019 N; reeled to L₀' = 1.8019 m the string holding m g is
    // L₀' (1 + m g/EA) long: the mass rises by 2 − that
    let ea = 100.0 * 1.9019;
    let w = 2.0 - 1.8019 * (1.0 + 9.81 / ea);
    let r = json(&["simulate", "examples/cluster_reel.toml", "--json"]);
    assert_eq!(r["valid"], true, "{r}");
    // 2.4·10⁻⁸ measured: the dashpot's decay over the 3 s hold
    assert!((rise(&r) / w - 1.0).abs() < 1e-6, "{} vs {w}", rise(&r));
    let dir = scratch("elastic_actuation", "integrators");
    for integrator in ["rk45", "newmark"] {
        let scene = with(&dir, &format!("{integrator}.toml"), |t| {
            t.replace(
                "integrator = \"rk4\"",
                &format!("integrator = \"{integrator}\""),
            )
        });
        let other = json(&["simulate", &scene, "--json"]);
        assert_eq!(other["valid"], true, "{other}");
        // the three integrators on the same driven motion (6·10⁻¹² measured)
        assert!(
            (rise(&other) - rise(&r)).abs() < 1e-9,
            "{integrator}: {} vs {}",
            rise(&other),
            rise(&r)
        );
    }
}

#[test]
fn a_load_table_on_a_node_drives_the_elastic_dynamics() {
    // undamped, the rest length fixed, a load ramping to 5 N up over 1 s: the mass rises by
    // w(1 s) = (F/k)(1 − sin(ω)/ω), ω = √(k/m) = 10 rad/s (the string stays taut: its
    // tension falls from 9.81 N to about 4.8 N)
    let dir = scratch("elastic_actuation", "load");
    let scene = with(&dir, "load.toml", |t| {
        t.replace("damping = 10.0\n", "")
            .replace("t_end = 4.0", "t_end = 1.0")
            .replace(
                "cluster = 0\ntimes = [0.0, 1.0]\nrest_lengths = [1.9019, 1.8019]",
                "node = 2\ntimes = [0.0, 1.0]\nforces = [[0.0, 0.0, 0.0], [0.0, 0.0, 5.0]]",
            )
    });
    let r = json(&["simulate", &scene, "--json"]);
    let w = 0.05 * (1.0 - 10f64.sin() / 10.0);
    // RK4 at ω dt = 10⁻²
    assert!((rise(&r) / w - 1.0).abs() < 1e-9, "{} vs {w}", rise(&r));
}

#[test]
fn a_cluster_with_pulley_friction_is_not_driven() {
    let dir = scratch("elastic_actuation", "friction");
    let scene = with(&dir, "friction.toml", |t| {
        t.replace("damping = 10.0\n", "damping = 10.0\nfriction = [0.2]\n")
    });
    let out = run(&["simulate", &scene]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("actuation 0") && err.contains("cluster 0") && err.contains("friction"),
        "{err}"
    );
}
