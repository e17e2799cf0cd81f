//! `tensegrity simulate` and `solve` of scenes with clustered strings (`[[clusters]]`, issue
//! 44) against closed forms: the Atwood machine (examples/atwood.toml) falls at
//! a = (m₁ − m₂) g/(m₁ + m₂) with the tension T = 2 m₁ m₂ g/(m₁ + m₂) in its trajectory,
//! and a weight hanging over a pulley on a load path (examples/pulley_load.toml) carries
//! t = W + λP with node 2 sinking by λP/k; the rigid-bar dynamics refuses pulley friction
//! naming the cluster (tests/cli_clusters_friction.rs runs it elastic).

use crate::common;

use common::{json, run, scratch};

/// Runs `simulate SCENE --out CSV` and reads the trajectory back: its header and its rows.
fn trajectory(scene: &str, csv: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let out = run(&[
        "simulate",
        scene,
        "--out",
        csv.to_str().unwrap(),
        "--no-convergence-check",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let table = std::fs::read_to_string(csv).unwrap();
    let mut lines = table.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// The index of the column `name` of a trajectory's header.
fn column(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("{name}: {header:?}"))
}

fn z(v: &serde_json::Value) -> f64 {
    v[2].as_f64().unwrap()
}

#[test]
fn the_atwood_machine_falls_at_the_closed_form_acceleration() {
    let (m1, m2, g, t) = (3.0, 1.0, 9.81, 0.5);
    let a = (m1 - m2) * g / (m1 + m2);
    let fall = 0.5 * a * t * t;
    let r = json(&["simulate", "examples/atwood.toml", "--json"]);
    assert_eq!(r["valid"], true, "{r}");
    let x = &r["final_nodes"];
    assert!((z(&x[1]) - (-1.0 - fall)).abs() < 1e-9 * fall, "{}", x[1]);
    assert!((z(&x[2]) - (-1.5 + fall)).abs() < 1e-9 * fall, "{}", x[2]);
    let v = &r["final_velocities"];
    assert!((z(&v[1]) + a * t).abs() < 1e-9 * a * t, "{}", v[1]);
    assert!(r["energy_drift"].as_f64().unwrap() < 1e-9, "{r}");
    // the trajectory's force column: the cluster's, after the (no) members, at T throughout
    let dir = scratch("clusters", "atwood");
    let csv = dir.join("atwood.csv");
    let scene = dir.join("atwood.toml");
    let text = std::fs::read_to_string("examples/atwood.toml").unwrap();
    std::fs::write(
        &scene,
        text.replace(
            "dt = 1e-3",
            "dt = 1e-3\noutput_interval = 0.1\nrecord = [\"nodes\", \"member_forces\"]",
        ),
    )
    .unwrap();
    let (header, table) = trajectory(scene.to_str().unwrap(), &csv);
    let col = column(&header, "cluster0_force [N]");
    assert!(
        header.iter().any(|h| h == "cluster0_force_density [N/m]"),
        "{header:?}"
    );
    let tension = 2.0 * m1 * m2 * g / (m1 + m2);
    let mut rows = 0;
    for row in &table {
        let f = row[col];
        assert!(
            (f - tension).abs() < 1e-6 * tension,
            "{f} against {tension}"
        );
        assert_eq!(row.len(), header.len());
        rows += 1;
    }
    assert_eq!(rows, 6);
}

#[test]
fn a_weight_over_a_pulley_carries_its_load_along_the_cluster() {
    let (w, p, k) = (10.0 * 9.81, 50.0, 1e4);
    let r = json(&["solve", "examples/pulley_load.toml", "--json"]);
    let points = r["path"]["points"].as_array().unwrap();
    assert!(points.len() > 2);
    for point in points {
        let lambda = point["lambda"].as_f64().unwrap();
        let t = point["tensions"][0].as_f64().unwrap();
        assert_eq!(point["tensions"].as_array().unwrap().len(), 1);
        assert!(
            (t - (w + lambda * p)).abs() < 1e-10 * (w + p),
            "{t} at λ {lambda}"
        );
        let u = &point["displacements"][2];
        assert!((z(u) + lambda * p / k).abs() < 1e-10 * p / k, "{u}");
        // the anchor holds the tension along the horizontal segment
        let anchor = point["reactions"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["node"] == 0 && r["direction"][0] == 1.0)
            .unwrap();
        assert!((anchor["force"].as_f64().unwrap() + t).abs() < 1e-9 * t);
    }
    assert_eq!(points.last().unwrap()["lambda"], 1.0);
}

#[test]
fn the_rigid_bar_dynamics_refuses_pulley_friction_naming_the_elastic_run() {
    let dir = scratch("clusters", "friction");
    let text = std::fs::read_to_string("examples/cluster_deploy.toml").unwrap();
    let scene = dir.join("friction.toml");
    std::fs::write(
        &scene,
        text.replace(
            "rest_length = 5.144190898479565",
            "rest_length = 5.144190898479565\nfriction = [0.2, 0.2]",
        ),
    )
    .unwrap();
    let out = run(&["simulate", scene.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("cluster 0") && err.contains("friction") && err.contains("bars = \"elastic\""),
        "{err}"
    );
}

/// One `[[actuation]]` table naming the cluster drives its whole rest length: at the end of
/// examples/cluster_deploy.toml the cluster's recorded tension is k (L − 4.8 m) with L the
/// loop's length in the same row (a static L₀ would give k (L − 5.144) ≈ 0), the bottom ring
/// has closed and the prism has risen.
#[test]
fn one_clustered_actuator_deploys_the_prism() {
    let dir = scratch("clusters", "deploy");
    let csv = dir.join("deploy.csv");
    let (header, table) = trajectory("examples/cluster_deploy.toml", &csv);
    let col = |name: &str| column(&header, name);
    let last = table.last().unwrap();
    let node = |i: usize| {
        let c = col(&format!("n{i}_x [m]"));
        [last[c], last[c + 1], last[c + 2]]
    };
    let dist = |a: [f64; 3], b: [f64; 3]| -> f64 {
        (0..3).map(|d| (a[d] - b[d]).powi(2)).sum::<f64>().sqrt()
    };
    let loop_length = dist(node(0), node(1)) + dist(node(1), node(2)) + dist(node(2), node(0));
    let k = 1000.0 / 3.0;
    let tension = last[col("cluster0_force [N]")];
    // the dashpot's c L̇ is small once settled
    let expected = k * (loop_length - 4.8);
    assert!(expected > 10.0, "{expected}");
    assert!(
        (tension - expected).abs() < 1e-2 * expected,
        "{tension} vs {expected}"
    );
    assert!(loop_length < 5.0, "the ring did not close: {loop_length}");
    let height = node(3)[2] - node(0)[2];
    assert!(height > 1.02, "the prism did not rise: {height}");
}

/// A cluster's `rest_length_change` drives its whole rest length along the load path (EA
/// kept): the weight over the pulley (examples/pulley_load.toml without its load) keeps its
/// tension W at every point and rises by −ΔL₀ (1 + W/EA) at λ = 1, to 10⁻¹².
#[test]
fn a_clusters_rest_length_change_reels_a_weight_along_the_load_path() {
    let dir = scratch("clusters", "reel_path");
    let text = std::fs::read_to_string("examples/pulley_load.toml").unwrap();
    let scene = dir.join("reel.toml");
    let unloaded = &text[..text.find("[[loads]]").unwrap()];
    std::fs::write(
        &scene,
        unloaded.replace(
            "rest_length = 1.99019",
            "rest_length = 1.99019\nrest_length_change = -0.1",
        ),
    )
    .unwrap();
    let r = json(&["solve", scene.to_str().unwrap(), "--json"]);
    assert_eq!(r["stop"], "reached_target", "{r}");
    let (w, ea) = (98.1, 1e4 * 1.99019);
    for p in r["path"]["points"].as_array().unwrap() {
        let t = p["tensions"][0].as_f64().unwrap();
        assert!((t - w).abs() < 1e-10 * w, "{p}");
        let lambda = p["lambda"].as_f64().unwrap();
        let rise = p["displacements"][2][2].as_f64().unwrap();
        let expected = 0.1 * lambda * (1.0 + w / ea);
        assert!(
            (rise - expected).abs() < 1e-12,
            "{rise} vs {expected} at {lambda}"
        );
    }
    // `simulate` and `statics` would ignore it: refused naming it
    let out = run(&["statics", scene.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("cluster 0: rest_length_change"), "{err}");
}

/// Ground contact with a cluster in the rigid-bar dynamics: the Snelson prism of
/// examples/prism_drop.toml dropped on a frictionless penalty ground, once with its bottom
/// ring as three strings and once as one cluster 0 → 1 → 2 → 0 (k/3, 3 L₀, damping c/3):
/// the drop keeps the prism's three-fold symmetry, so the segments stay equal and the
/// cluster pulls as the three strings do; the two runs land and bounce alike to 10⁻¹⁰ m.
#[test]
fn a_clustered_ring_lands_on_the_ground_as_its_three_strings() {
    let dir = scratch("clusters", "drop");
    let text = std::fs::read_to_string("examples/prism_drop.toml")
        .unwrap()
        .replace("integrator = \"rk45\"", "integrator = \"rk4\"\ndt = 2e-4")
        .replace("rtol = 1e-8\n", "")
        .replace("atol = 1e-10\n", "")
        .replace("t_end = 3.0", "t_end = 1.5")
        .replace("mu_static = 0.8\n", "")
        .replace("mu_kinetic = 0.6\n", "");
    let ring = [
        "[[strings]]\nnodes = [0, 1]\nstiffness = 1000.0\nrest_length = 1.7147302994931883\ndamping = 2.0\n\n",
        "[[strings]]\nnodes = [1, 2]\nstiffness = 1000.0\nrest_length = 1.7147302994931883\ndamping = 2.0\n\n",
        "[[strings]]\nnodes = [2, 0]\nstiffness = 1000.0\nrest_length = 1.7147302994931888\ndamping = 2.0\n\n",
    ];
    let mut clustered = text.clone();
    for r in ring {
        assert!(clustered.contains(r), "{r}");
        clustered = clustered.replace(r, "");
    }
    clustered = clustered.replace(
        "[gravity]",
        "[[clusters]]\nnodes = [0, 1, 2, 0]\nstiffness = 333.3333333333333\nrest_length = 5.144190898479565\ndamping = 0.6666666666666666\n\n[gravity]",
    );
    let run_scene = |name: &str, body: &str| {
        let path = dir.join(name);
        std::fs::write(&path, body).unwrap();
        json(&[
            "simulate",
            path.to_str().unwrap(),
            "--json",
            "--no-convergence-check",
        ])
    };
    let (strings, cluster) = (
        run_scene("strings.toml", &text),
        run_scene("cluster.toml", &clustered),
    );
    assert_eq!(cluster["valid"], true, "{cluster}");
    let (a, b) = (
        common::points(&strings["final_nodes"]),
        common::points(&cluster["final_nodes"]),
    );
    // it landed: the bottom nodes on the ground (penalty: sunk by about 1 mm)
    assert!(b[..3].iter().all(|p| p[2].abs() < 2e-3), "{b:?}");
    for (p, q) in a.iter().zip(&b) {
        for d in 0..3 {
            assert!((p[d] - q[d]).abs() < 1e-10, "{p:?} vs {q:?}");
        }
    }
}
