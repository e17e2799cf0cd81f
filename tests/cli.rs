//! The `tensegrity` binary end to end: `statics --json` on the bundled scenes and on bad input.

use crate::common;
use common::{assert_ok, run};

use std::process::Command;

fn json(scene: &str) -> serde_json::Value {
    let out = run(&["statics", scene, "--json"]);
    assert_ok(&out);
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

#[test]
fn loaded_dbar_json_has_forces_reactions_and_the_benchmark_mass() {
    let v = json("examples/dbar_loaded.toml");
    assert_eq!(v["rank"], 5);
    assert_eq!(v["self_stress_dim"], 0);
    assert_eq!(v["prestressable"], false);
    let mass = v["mass_kg"].as_f64().unwrap();
    assert!((mass - 8.858023).abs() < 5e-7, "{mass}");
    let per_member: f64 = v["member_mass_kg"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_f64().unwrap())
        .sum();
    assert!((per_member - mass).abs() < 1e-12);
    assert_eq!(v["governing"][0], "buckling");
    assert_eq!(v["governing"][4], "yield");
    let f = v["member_force"].as_array().unwrap();
    assert!((f[4].as_f64().unwrap() - 1e4).abs() < 1e-6);
    assert!((f[0].as_f64().unwrap() + 1e4 / 2f64.sqrt()).abs() < 1e-6);
    let r = &v["reactions"][0];
    assert_eq!(r["node"], 0);
    assert!((r["force"][0].as_f64().unwrap() - 1e4).abs() < 1e-6);
    assert!(v["residual"].as_f64().unwrap() < 1e-8);
}

#[test]
fn prism_json_reports_the_self_stress_and_margin() {
    let v = json("examples/prism.toml");
    assert_eq!(v["rank"], 11);
    assert_eq!(v["self_stress_dim"], 1);
    assert_eq!(v["mechanisms"], 7);
    assert_eq!(v["prestressable"], true);
    let margin = v["prestress_margin"].as_f64().unwrap();
    assert!((margin - 1.0 / 3f64.sqrt()).abs() < 1e-9, "{margin}");
    let basis = v["self_stress"].as_array().unwrap();
    assert_eq!(basis.len(), 1);
    let q: Vec<f64> = basis[0]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(q.len(), 12);
    // bars first: −√3 : 1 (rings) : √3 (verticals)
    assert!((q[0] / q[3] + 3f64.sqrt()).abs() < 1e-12);
    assert!((q[9] / q[3] - 3f64.sqrt()).abs() < 1e-12);
    assert!(v.get("force_density").is_none(), "no loads, no load solve");
}

#[test]
fn tower_has_two_self_stresses() {
    let v = json("examples/tower.toml");
    assert_eq!(v["self_stress_dim"], 2);
    assert_eq!(v["self_stress"].as_array().unwrap().len(), 2);
    assert_eq!(v["prestressable"], true);
}

#[test]
fn demo_runs_on_built_in_scenes() {
    let out = run(&["demo"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    let line = text
        .lines()
        .find(|l| l.starts_with("dbar_loaded.toml"))
        .unwrap();
    assert!(line.contains("8.858023"), "{line}");
}

#[test]
fn bad_scene_fails_with_a_clear_message_and_exit_code() {
    let dir = common::scratch("cli", "cli-test");
    let path = dir.join("bad.toml");
    std::fs::write(
        &path,
        "nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]\n[[bars]]\nnodes = [0, 4]\n",
    )
    .unwrap();
    let out = run(&["statics", path.to_str().unwrap(), "--json"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("bar 0") && err.contains("line 2") && err.contains("out of range"),
        "{err}"
    );
    let out = run(&["statics", "no/such/file.toml"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("no/such/file.toml"));
}

#[test]
fn toroid_json_reports_counts_flexes_and_inertia() {
    let out = run(&["toroid", "--stabilize", "spokes", "--json"]);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (
            v["nodes"].as_u64(),
            v["bars"].as_u64(),
            v["strings"].as_u64()
        ),
        (Some(42), Some(25), Some(112))
    );
    assert_eq!(v["internal_mechanisms"], 8);
    let i = &v["inertia"];
    let i1 = v["I1"].as_f64().unwrap();
    assert_eq!(i[0][0].as_f64().unwrap(), i1);
    assert!((i[1][1].as_f64().unwrap() - i[2][2].as_f64().unwrap()).abs() < 1e-9);
}

#[test]
fn roll_and_tipover_run_from_the_command_line() {
    let out = run(&[
        "roll",
        "--sides",
        "12",
        "--incline",
        "50deg",
        "--t-end",
        "2",
        "--fidelity",
        "rigid",
        "--json",
    ]);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["fidelity"], "rigid");
    assert!(
        v["axle_height_oscillation"].as_f64().unwrap() < 1.0 - (std::f64::consts::PI / 12.0).cos()
    );
    assert!(v["mean_speed"].as_f64().unwrap() > 0.0);
    // the full model, briefly: the wheel starts at rest and the hub moves downhill
    let out = run(&[
        "roll",
        "--t-end",
        "0.3",
        "--fidelity",
        "full",
        "--contact",
        "penalty",
        "--json",
    ]);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["fidelity"], "full");
    assert!(v["mean_speed"].as_f64().unwrap() > 0.0);
    assert!(v["max_reaction"].as_f64().unwrap() > 0.0);
    let out = run(&["tipover", "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // ρ = 0.4, ε = 0.75, σ = 0.6: F_f/F_e = −(σ + ε)/(1 − σ) = −3.375
    assert!((v["normalized_friction"].as_f64().unwrap() + 3.375).abs() < 1e-12);
    let out = run(&["toroid", "--inner-radius", "1.5"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("inner_radius"));
    let out = run(&["roll", "--incline", "fifty"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("fifty"));
}

#[test]
fn an_exported_toroid_scene_gives_the_same_statics() {
    let dir = common::scratch("cli", "export");
    let path = dir.join("toroid.toml");
    let p = path.to_str().unwrap();
    let out = run(&[
        "toroid",
        "--sides",
        "6",
        "--stabilize",
        "spokes,inner",
        "--export-scene",
        p,
        "--string-stiffness",
        "5e4",
        "--json",
    ]);
    assert_ok(&out);
    let toroid: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let statics = json(p);
    for key in [
        "rank",
        "self_stress_dim",
        "prestressable",
        "internal_mechanisms",
    ] {
        assert_eq!(toroid[key], statics[key], "{key}");
    }
    let (a, b) = (
        toroid["prestress_margin"].as_f64().unwrap(),
        statics["prestress_margin"].as_f64().unwrap(),
    );
    // the toroid's margin comes from the symmetric LP, the scene's from the dense LP: the
    // same optimum, each solved to the LP tolerance (1e-10)
    assert!((a - b).abs() < 1e-9, "{a} vs {b}");
}

#[test]
fn simulate_reproduces_the_published_double_pendulum() {
    let out = run(&["simulate", "examples/double_pendulum.toml", "--json"]);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["t_end"], 5.0);
    let tip = &v["final_nodes"][2];
    let (x, y) = (tip[0].as_f64().unwrap(), tip[1].as_f64().unwrap());
    assert!(
        (x - 1.3403149308).abs() < 1e-6 && (y + 1.4793519015).abs() < 1e-6,
        "({x}, {y})"
    );
    // the pin holds and the rods keep their length
    assert!(v["final_nodes"][0][0].as_f64().unwrap().abs() < 1e-9);
    assert!(v["bar_length_drift"].as_f64().unwrap() < 1e-8);
    assert!(v["energy_drift"].as_f64().unwrap() < 1e-8);
    // a file flag overrides the scene: a shorter run ends earlier
    let out = run(&[
        "simulate",
        "examples/double_pendulum.toml",
        "--t-end",
        "0.5",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["t_end"], 0.5);
}

/// `--integrator sdirk` (and the scene value `integrator = "sdirk"`) run the implicit method:
/// the double pendulum's published tip at t = 5 s to 1e-6 with the default rtol 1e-8.
#[test]
fn simulate_with_sdirk_reproduces_the_double_pendulum() {
    let out = run(&[
        "simulate",
        "examples/double_pendulum.toml",
        "--integrator",
        "sdirk",
        "--json",
    ]);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let tip = &v["final_nodes"][2];
    let (x, y) = (tip[0].as_f64().unwrap(), tip[1].as_f64().unwrap());
    assert!(
        (x - 1.3403149308).abs() < 1e-6 && (y + 1.4793519015).abs() < 1e-6,
        "({x}, {y})"
    );
    assert!(v["bar_length_drift"].as_f64().unwrap() < 1e-10);
    let scene = std::fs::read_to_string("examples/double_pendulum.toml").unwrap();
    assert!(
        scene.contains("integrator = \""),
        "the example names its integrator"
    );
    let path = common::scratch("cli", "sdirk").join("double_pendulum.toml");
    let mut patched = String::new();
    for line in scene.lines() {
        if line.trim_start().starts_with("integrator =") {
            patched.push_str("integrator = \"sdirk\"\n");
        } else {
            patched.push_str(line);
            patched.push('\n');
        }
    }
    std::fs::write(&path, patched).unwrap();
    let out = run(&["simulate", path.to_str().unwrap(), "--json"]);
    assert_ok(&out);
    let w: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(w["final_nodes"], v["final_nodes"]);
}

#[test]
fn output_piped_into_a_closed_reader_does_not_panic() {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(["statics", "examples/prism.toml"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take()); // close the pipe before the report is written
    let status = child.wait().unwrap();
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    assert!(status.success(), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn a_compressed_string_is_sized_with_a_warning() {
    // the thesis D-bar (two strings, one self-stress) under end compression: the minimal-norm
    // solution compresses the long string (q = −4166.67 N/m, from the normal equations)
    let dir = common::scratch("cli", "warn");
    let path = dir.join("dbar2.toml");
    let mut text = String::from(
        "nodes = [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, -1.0, 0.0], [2.0, 0.0, 0.0]]\n",
    );
    for (kind, [a, b]) in [
        ("bars", [0, 1]),
        ("bars", [0, 2]),
        ("bars", [1, 3]),
        ("bars", [2, 3]),
        ("strings", [0, 3]),
        ("strings", [1, 2]),
    ] {
        text += &format!("[[{kind}]]\nnodes = [{a}, {b}]\nmaterial = \"aluminium\"\n");
    }
    text += "[[supports]]\nnode = 0\n[[loads]]\nnode = 3\nforce = [-1.0e4, 0.0, 0.0]\n";
    std::fs::write(&path, text).unwrap();
    let v = json(path.to_str().unwrap());
    let q: Vec<f64> = v["force_density"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!((q[4] + 12500.0 / 3.0).abs() < 1e-6, "{q:?}");
    assert!((q[0] + 2500.0 / 3.0).abs() < 1e-6, "{q:?}");
    assert!(v["sizing_warning"].as_str().unwrap().contains("string 0"));
    let per_member: f64 = v["member_mass_kg"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_f64().unwrap())
        .sum();
    assert!((per_member - v["mass_kg"].as_f64().unwrap()).abs() < 1e-12);
}

#[test]
fn michell_writes_sign_maps_gamma_sweeps_and_the_mass_table() {
    let dir = common::scratch("cli", "michell");
    let (map, sweep) = (dir.join("map.csv"), dir.join("sweep.csv"));
    let out = run(&[
        "michell",
        "--complexity",
        "2",
        "--cylindrical",
        "0.25",
        "--beta",
        "pi/6",
        "--phi",
        "pi/8",
        "--extra-strings",
        "5000",
        "--gamma-sweep",
        sweep.to_str().unwrap(),
        "--sign-map",
        map.to_str().unwrap(),
        "--map-members",
        "0,2",
        "--map-grid",
        "37x19",
        "--json",
    ]);
    assert_ok(&out);
    let map_text = std::fs::read_to_string(&map).unwrap();
    assert_eq!(map_text.lines().count(), 1 + 2 * 37 * 19);
    // the load along −ι̂₃ (γ = π) compresses the tip member m₀₁₀₀ (member 2), eq. 4.20
    let row = map_text
        .lines()
        .find(|l| {
            l.starts_with("2,") && l.contains(",0.00000000000000000e0,3.14159265358979312e0,")
        })
        .expect("member 2 at azimuth 0, polar π");
    assert!(row.ends_with(",-1"), "{row}");
    let sweep_text = std::fs::read_to_string(&sweep).unwrap();
    assert!(sweep_text.starts_with("polar_rad,member,kind,force_N"));
    // 721 angles × (12 members + 3 extra strings)
    assert_eq!(sweep_text.lines().count(), 1 + 721 * 15);

    let out = run(&["michell-table", "--max-complexity", "3"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    let planar_q2: Vec<f64> = text
        .lines()
        .find(|l| l.starts_with("2,0,"))
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    // closed form q sin φ / (sin β sin(β + φ)) at q = 2, φ = π/2, β = π/6: 8/√3
    assert!((planar_q2[2] - 8.0 / 3f64.sqrt()).abs() < 1e-9);
    // ERRATA 4.4: 1.354 kg of steel at w₀ = 1 kN
    assert!((planar_q2[4] - 1.354).abs() < 5e-4);
    assert_eq!(text.lines().count(), 1 + 2 * 4);
}

#[test]
fn statics_reports_natural_frequencies_with_six_rigid_body_modes() {
    let out = run(&[
        "statics",
        "examples/prism.toml",
        "--modes",
        "8",
        "--mass",
        "consistent",
        "--json",
    ]);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let f: Vec<f64> = v["natural_frequencies_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    // the six rigid-body modes are skipped (and counted): the 8 lowest of nonzero frequency
    assert_eq!(v["zero_modes_skipped"], 6);
    assert_eq!(f.len(), 8);
    assert!(f.windows(2).all(|w| w[0] <= w[1]) && f[0] > 1.0, "{f:?}");
    // the prestress-stiffened mechanism: 1/T of the free oscillation (tests/modes_vs_dynamics)
    assert!((f[0] - 1.0 / 0.584605).abs() < 1e-5, "{f:?}");
    let v = json("examples/dbar.toml");
    assert!(v.get("natural_frequencies_hz").is_none());
}

#[test]
fn figures_are_written_as_svg() {
    let dir = common::scratch("cli", "fig");
    let roll = dir.join("rolling.svg");
    let out = run(&[
        "fig-rolling",
        "--fidelity",
        "rigid",
        "--t-end",
        "2",
        "--out",
        roll.to_str().unwrap(),
    ]);
    assert_ok(&out);
    let svg = std::fs::read_to_string(&roll).unwrap();
    // four wheels in Fig. 3.10, two in Fig. 3.11
    assert_eq!(svg.matches("<polyline").count(), 6);
    let table = dir.join("fig418.svg");
    let out = run(&[
        "michell-table",
        "--max-complexity",
        "4",
        "--out",
        dir.join("t.csv").to_str().unwrap(),
        "--svg",
        table.to_str().unwrap(),
    ]);
    assert_ok(&out);
    let svg = std::fs::read_to_string(&table).unwrap();
    assert_eq!(svg.matches("<polyline").count(), 4);
    assert!(svg.contains("δ = 0.25"));
}

#[test]
fn simulate_writes_a_vtk_series() {
    let dir = common::scratch("cli", "vtk");
    let out = run(&[
        "simulate",
        "examples/double_pendulum.toml",
        "--t-end",
        "0.2",
        "--output-interval",
        "0.05",
        "--vtk",
        dir.to_str().unwrap(),
    ]);
    assert_ok(&out);
    let pvd = std::fs::read_to_string(dir.join("series.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), 5); // t = 0, 0.05, …, 0.2
    let frame = std::fs::read_to_string(dir.join("frame_00000.vtu")).unwrap();
    assert!(frame.contains(r#"NumberOfPoints="3" NumberOfCells="2""#));
    // the first frame holds the initial nodes: the tip at (√2, −√2)
    assert!(
        frame.contains(&format!(
            "{:e} {:e} 0e0",
            2.0 * 0.5f64.sqrt(),
            -2.0 * 0.5f64.sqrt()
        )),
        "{frame}"
    );
}

/// A three-bar linkage between two pins, pushed sideways at a knee: a mechanism for that load.
const PUSHED_LINKAGE: &str = r#"
nodes = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 0.0, 0.0]]
[materials.alu]
density = 2700.0
youngs_modulus = 60e9
yield_strength = 110e6
[[bars]]
nodes = [0, 1]
material = "alu"
[[bars]]
nodes = [1, 2]
material = "alu"
[[bars]]
nodes = [2, 3]
material = "alu"
[[supports]]
node = 0
[[supports]]
node = 3
[[loads]]
node = 1
force = [1000.0, 0.0, 0.0]
"#;

#[test]
fn a_load_a_mechanism_cannot_carry_fails_unless_least_squares_is_asked_for() {
    let dir = common::scratch("cli", "linkage");
    let scene = dir.join("linkage.toml");
    std::fs::write(&scene, PUSHED_LINKAGE).unwrap();
    let scene = scene.to_str().unwrap();
    let out = run(&["statics", scene]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("cannot be carried") && err.contains("7.071068e2") && err.contains("[1, 2]"),
        "{err}"
    );
    assert!(
        out.stdout.is_empty(),
        "no mass printed for a load that is not carried"
    );
    let out = run(&["statics", scene, "--least-squares", "--json"]);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["load_carried"], false);
    assert_eq!(v["unbalanced_nodes"], serde_json::json!([1, 2]));
    assert!(v.get("mass_kg").is_none());
    assert!((v["residual"].as_f64().unwrap() - 500.0 * 2f64.sqrt()).abs() < 1e-6);
}

#[test]
fn bad_flags_are_usage_errors_naming_the_flag() {
    for (args, flag) in [
        (
            &["roll", "--ground-stiffness", "0"][..],
            "--ground-stiffness",
        ),
        (&["roll", "--mu=-1"][..], "--mu"),
        (&["roll", "--ground-damping=-5"][..], "--ground-damping"),
        (
            &["tipover", "--grid", "never.csv", "--grid-points", "0"][..],
            "--grid-points",
        ),
        (&["toroid", "--outer-radius", "-1"][..], "--outer-radius"),
        (
            &["simulate", "examples/prism.toml", "--dt", "nan"][..],
            "--dt",
        ),
    ] {
        let out = run(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(flag) && err.contains("must be"),
            "{args:?}: {err}"
        );
        assert!(out.stdout.is_empty(), "{args:?}");
    }
    assert!(!std::path::Path::new("never.csv").exists());
    // a value the flag parser cannot judge alone is named by the library, still exit 2
    let out = run(&["toroid", "--inner-radius", "1.5"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("inner_radius = 1.5"));
    // the same for the T-bar: a wheel needs π/φ integer
    let out = run(&[
        "tbar",
        "--beta",
        "pi/6",
        "--phi",
        "0.7",
        "--cylindrical",
        "0.25",
        "--wheel",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("phi = 0.7"));
}

#[test]
fn a_drifted_simulation_warns_and_fails_under_strict() {
    let args = [
        "simulate",
        "examples/prism_drop.toml",
        "--integrator",
        "rk4",
        "--dt",
        "0.01",
        "--json",
    ];
    let out = run(&args);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let warnings = v["warnings"].as_array().expect("warnings in the JSON");
    // a warning is an object: its kind, its text and its numbers
    assert_eq!(warnings[0]["kind"], "drift");
    assert_eq!(warnings[0]["invariant"], "bar_length");
    assert!(warnings[0]["value"].as_f64().unwrap() > warnings[0]["limit"].as_f64().unwrap());
    assert!(warnings[0]["message"]
        .as_str()
        .unwrap()
        .contains("bar lengths drifted"));
    assert!(String::from_utf8_lossy(&out.stderr).contains("warning: bar lengths drifted"));
    let mut strict = args.to_vec();
    strict.push("--strict");
    assert_eq!(run(&strict).status.code(), Some(1));
    // the scene's own settings (rk45) stay within the limits: no warnings key at all
    let out = run(&["simulate", "examples/prism_drop.toml", "--json", "--strict"]);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v.get("warnings").is_none());
}

#[test]
fn a_run_away_step_is_reported_as_divergence_with_the_remedy_not_as_singular_constraints() {
    let out = run(&[
        "simulate",
        "examples/prism.toml",
        "--integrator",
        "rattle",
        "--dt",
        "0.05",
        "--t-end",
        "5",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("error: simulating examples/prism.toml: the RATTLE step from t = ")
            && err.contains(" s (step 0.05 s) failed: its constraint ")
            && err
                .contains("use a smaller --dt, --integrator rk45 (adaptive) or --integrator sdirk")
            && !err.contains("singular")
            && !err.contains("fixed at both ends"),
        "{err}"
    );
}

#[test]
fn an_explicit_blow_up_names_the_step_and_the_remedy() {
    let out = run(&[
        "simulate",
        "examples/prism.toml",
        "--integrator",
        "rk4",
        "--dt",
        "0.2",
        "--t-end",
        "5",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.trim_end().ends_with(
            "; the step (0.2 s) is likely too large for the stiffness of the strings or the \
             ground: use a smaller --dt, or --integrator sdirk (implicit, for stiff strings and \
             contact) or --integrator rk45 (adaptive)"
        ),
        "{err}"
    );
}

#[test]
fn a_large_wheel_is_analysed_through_its_symmetry() {
    // n = 2000: A is 30006 × 38001; its dense SVD would need ~52 GiB and was refused. The
    // symmetry-adapted path (2000 blocks of 17 × 20) analyses it in milliseconds: rank
    // 15n = 30000, self-stress 4n + 1 = 8001, no internal mechanism.
    let out = run(&["toroid", "--sides", "2000", "--json"]);
    assert_ok(&out);
    let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (&r["rank"], &r["self_stress_dim"], &r["internal_mechanisms"]),
        (&30000.into(), &8001.into(), &0.into())
    );
    let by_rep = r["symmetry"]["self_stress_by_representation"]
        .as_array()
        .unwrap();
    assert_eq!(by_rep.len(), 2000);
    let total: u64 = by_rep.iter().map(|v| v.as_u64().unwrap()).sum();
    assert_eq!(total, 8001);
}

#[test]
fn a_fixed_step_run_that_cannot_finish_is_refused_before_it_starts() {
    let out = run(&[
        "simulate",
        "examples/prism.toml",
        "--t-end",
        "1e300",
        "--dt",
        "1e-300",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("dt = 1e-300") && err.contains("max_steps"),
        "{err}"
    );
}
