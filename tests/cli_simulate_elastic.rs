//! `tensegrity simulate` of elastic scenes: TsgFEM's T-bar dynamics example as a scene file
//! lands on TsgFEM's final state (its run under GNU Octave, `scripts/tsgfem-export`); a
//! string net with point masses and dashpots settles, under the implicit Newmark method,
//! where `solve` puts the same net under the masses' weights; the keys of elastic scenes are
//! refused where they would be ignored.

use crate::common;

use common::{json, points, run};

fn gap(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(a, b)| (0..3).map(move |d| (a[d] - b[d]).abs()))
        .fold(0.0, f64::max)
}

#[test]
fn the_tsgfem_tbar_scene_lands_on_tsgfems_final_state() {
    let r = json(&[
        "simulate",
        "examples/anchors/tsgfem_tbar_elastic.toml",
        "--json",
    ]);
    let data: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(
            "crates/tensegrity-path/tests/data/tsgfem_tbar_dynamics_slack.json",
        )
        .unwrap(),
    )
    .unwrap();
    let state: Vec<f64> = data["state_end"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let n = state.len() / 6;
    let at = |k: usize| -> Vec<[f64; 3]> {
        (0..n)
            .map(|i| {
                let o = k * 3 * n + 3 * i;
                [state[o], state[o + 1], state[o + 2]]
            })
            .collect()
    };
    let g = gap(&points(&r["final_nodes"]), &at(0));
    // the issue asks for 1e-7 m; the same RK4 at the same step gives round-off
    assert!(g < 1e-10, "final nodes {g:e} m from TsgFEM's");
    let gv = gap(&points(&r["final_velocities"]), &at(1));
    assert!(gv < 1e-8, "final velocities {gv:e} m/s from TsgFEM's");
    assert_eq!(r["steps"], 8013);
    assert_eq!(r["valid"], true, "{r}");
    // the convergence check's refined run (dt/2) moves the final nodes by 2e-5 of the size
    let change = r["convergence"]["quantities"][0]["relative_change"]
        .as_f64()
        .unwrap();
    assert!(change < 1e-4, "{change}");
}

/// A node of 20 kg hung below three anchors by damped strings (k = 2000 N/m, rest length
/// 1.35 m against 1.414 m, dashpots 50 N s/m), under gravity and 1 N sideways: 40 s of
/// Newmark at 2 ms settle it (to 10⁻⁸ m) where the static path of the same net ends, the
/// weight its dead load (a hanging net has no unloaded equilibrium).
#[test]
fn a_damped_string_net_settles_where_solve_puts_it() {
    let dir = common::scratch("elastic", "net");
    let net = |extra: &str| {
        let mut s = String::from("nodes = [");
        for k in 0..3 {
            let a = std::f64::consts::TAU * k as f64 / 3.0;
            s.push_str(&format!("[{}, {}, 0.0], ", a.cos(), a.sin()));
        }
        s.push_str("[0.0, 0.0, -1.0]]\n");
        for a in 0..3 {
            s.push_str(&format!(
                "[[strings]]\nnodes = [{a}, 3]\nstiffness = 2000.0\nrest_length = 1.35\ndamping = 50.0\n"
            ));
            s.push_str(&format!("[[supports]]\nnode = {a}\n"));
        }
        s + extra
    };
    // the weight: a dead load from λ = 0 in `solve` (a net that hangs has no unloaded
    // equilibrium); the path adds a small load on top
    let weight = "[[masses]]\nnode = 3\nmass = 20.0\n[gravity]\nacceleration = [0.0, 0.0, -9.81]\n";
    let dynamic = dir.join("net_dynamic.toml");
    std::fs::write(
        &dynamic,
        net(&format!("{weight}[[loads]]\nnode = 3\nforce = [1.0, 0.0, 0.0]\n[simulation]\nt_end = 40.0\nintegrator = \"newmark\"\ndt = 2e-3\n")),
    )
    .unwrap();
    let fixed = dir.join("net_static.toml");
    std::fs::write(
        &fixed,
        net(&format!(
            "{weight}[[loads]]\nnode = 3\nforce = [1.0, 0.0, 0.0]\n"
        )),
    )
    .unwrap();
    let settled = json(&["simulate", dynamic.to_str().unwrap(), "--json"]);
    assert_eq!(settled["valid"], true, "{settled}");
    let path = json(&["solve", fixed.to_str().unwrap(), "--json"]);
    let last = path["path"]["points"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()
        .clone();
    assert_eq!(last["lambda"], 1.0);
    let (z_static, z_dynamic) = (&last["nodes"][3], &settled["final_nodes"][3]);
    // the strings stretch until 3 k (L − L₀) z/L = W
    assert!(z_static[2].as_f64().unwrap() < -0.9, "hangs at {z_static}");
    for d in 0..3 {
        let (s, y) = (
            z_static[d].as_f64().unwrap(),
            z_dynamic[d].as_f64().unwrap(),
        );
        assert!(
            (s - y).abs() < 1e-8,
            "settled at {z_dynamic} m, static {z_static} m"
        );
    }
    let v = settled["final_velocities"][3][2].as_f64().unwrap();
    assert!(v.abs() < 1e-8, "still moving: {v}");
}

/// Asserts that `simulate ARGS` is refused (exit 2) with `says` on stderr.
fn refused(args: &[&str], says: &str) {
    let out = run(args);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(says), "{args:?}: {err}");
}

#[test]
fn elastic_keys_are_refused_where_they_would_be_ignored() {
    let dir = common::scratch("elastic", "keys");
    let scene = dir.join("rigid_with_string_mass.toml");
    std::fs::write(
        &scene,
        "nodes = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n[[bars]]\nnodes = [0, 1]\nmass = 1.0\n[[strings]]\nnodes = [1, 2]\nstiffness = 100.0\nmass = 0.1\n[simulation]\nt_end = 0.1\n",
    )
    .unwrap();
    refused(
        &["simulate", scene.to_str().unwrap()],
        "string 0: mass is read by the elastic dynamics only",
    );
    // a point mass on a node past the last; a ground under elastic members
    for (k, (extra, says)) in [
        (
            "[[masses]]\nnode = 9\nmass = 1.0\n",
            "(line 12): point mass 0: node 9 does not exist (the structure has 3)",
        ),
        (
            "[[masses]]\nnode = 2\nmass = 1.0\n[ground]\nstiffness = 1e4\n",
            "[ground] is not modelled for elastic members",
        ),
    ]
    .into_iter()
    .enumerate()
    {
        let scene = dir.join(format!("net_{k}.toml"));
        std::fs::write(
            &scene,
            format!("nodes = [[0, 0, 0], [1, 0, 0], [0, 1, 1]]\n[[strings]]\nnodes = [1, 2]\nstiffness = 100.0\n[[strings]]\nnodes = [0, 2]\nstiffness = 100.0\n[[supports]]\nnode = 0\n[[supports]]\nnode = 1\n{extra}[simulation]\nt_end = 0.1\n"),
        )
        .unwrap();
        refused(&["simulate", scene.to_str().unwrap()], says);
    }
    let tbar = "examples/anchors/tsgfem_tbar_elastic.toml";
    // an elastic scene under an integrator of rigid bars
    refused(
        &["simulate", tbar, "--integrator", "rattle"],
        "an elastic model is integrated by rk4, rk45 or newmark",
    );
    // the estimate (8013 RK4 steps of 6 members, the refined companion beside) against
    // --max-work
    refused(
        &["simulate", tbar, "--max-work", "0.001"],
        "the elastic dynamics (6 members, 12 free coordinates, 8013 steps of rk4)",
    );
    // --animate draws rigid-bar runs only
    refused(
        &["simulate", tbar, "--animate", "x.gif"],
        "draws rigid-bar runs only",
    );
    // RK4 above the stability limit of the stiff bars: refused with the limit
    refused(
        &["simulate", tbar, "--dt", "2e-3"],
        "exceeds its stability limit 1.132e-3 s",
    );
}

/// What the user is told to change names what an elastic scene can run: a Newmark step too
/// long for the T-bar drifts its energy and the warning asks for a smaller step (not for
/// RATTLE, which elastic scenes refuse); a `[[masses]]` entry without its `mass` is the
/// scene file's key, not the flag `--mass` of `statics`; a bar whose rest length puts its
/// EA/L₀ 10²⁹⁶ below the strings' is refused naming both, before any step.
#[test]
fn elastic_runs_name_remedies_and_keys_they_can_use() {
    let tbar = "examples/anchors/tsgfem_tbar_elastic.toml";
    let out = run(&["simulate", tbar, "--integrator", "newmark", "--dt", "10"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success()
            && err.contains("energy of this conservative model drifted")
            && err.contains("use a smaller --dt (the trapezoidal rule")
            && !err.contains("rattle"),
        "{err}"
    );
    let text = std::fs::read_to_string(tbar).unwrap();
    let dir = common::scratch("elastic", "remedies");
    let no_mass = dir.join("no_mass.toml");
    std::fs::write(&no_mass, format!("{text}\n[[masses]]\nnode = 0\n")).unwrap();
    refused(
        &["simulate", no_mass.to_str().unwrap()],
        "missing field `mass`",
    );
    let long = dir.join("long_rest.toml");
    let bad = text.replacen("rest_length = 2.000139266823317", "rest_length = 1e300", 1);
    std::fs::write(&long, bad).unwrap();
    refused(
        &["simulate", long.to_str().unwrap()],
        "times member 0 (bar): EA/L0",
    );
    // a run-away elastic run (a cluster's dashpot of 1e300 N s/m) names a smaller step and
    // Newmark, not the rigid-bar integrators (sdirk, rk45) it cannot take
    let atwood = std::fs::read_to_string("examples/atwood.toml").unwrap();
    let damped = dir.join("damped.toml");
    let text = atwood.replacen("stiffness = 1e4", "stiffness = 1e4\ndamping = 1e300", 1);
    std::fs::write(&damped, text).unwrap();
    let out = run(&["simulate", damped.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.code() == Some(1)
            && err.contains("the elastic dynamics diverged at t = ")
            && err.contains("use a smaller --dt, or --integrator newmark")
            && !err.contains("sdirk"),
        "{err}"
    );
}
