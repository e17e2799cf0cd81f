//! `tensegrity tbar` end to end: the JSON contract of issue 11, the exports and a bad φ.

use std::process::Command;

fn run(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .output()
        .expect("binary runs")
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = run(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

#[test]
fn wheel_json_contract() {
    let base = [
        "tbar",
        "--beta",
        "pi/6",
        "--phi",
        "pi/8",
        "--cylindrical",
        "0.25",
    ];
    let mut args = base.to_vec();
    args.extend([
        "--wheel",
        "--prestress",
        "4",
        "--directions",
        "200",
        "--json",
    ]);
    let v = json(&args);
    assert_eq!(
        (&v["nodes"], &v["bars"], &v["strings"], &v["treads"]),
        (&32.into(), &8.into(), &32.into(), &8.into())
    );
    let labels = v["node_labels"].as_array().unwrap();
    assert_eq!(labels[0], "tip");
    assert_eq!(labels[1], "bar_base");
    assert_eq!(labels[2], "1010");
    assert_eq!(v["node_coordinates"].as_array().unwrap().len(), 32);
    assert_eq!(v["self_stress_dim"], 16);
    assert_eq!(v["prestressable"], true);
    assert_eq!(v["internal_mechanisms"], 0);
    assert!(v["prestress_margin"].as_f64().unwrap() > 0.0);
    assert!(v["min_prestress"].as_f64().unwrap() > 3.0);
    assert_eq!(v["critical_member"]["kind"], "string");
    assert_eq!(v["slack_fraction"], 0.0);
    assert!(v["mass_kg"].as_f64().unwrap() > 0.0);
    let mut ext = base.to_vec();
    ext.extend(["--extended", "0.5", "--json"]);
    let e = json(&ext);
    assert_eq!(
        (&e["nodes"], &e["bars"], &e["strings"]),
        (&64.into(), &16.into(), &64.into())
    );
}

#[test]
fn a_wheel_of_360_treads_goes_through_the_cyclic_blocks() {
    let v = json(&[
        "tbar",
        "--beta",
        "pi/6",
        "--phi",
        "pi/360",
        "--cylindrical",
        "0.25",
        "--wheel",
        "--json",
    ]);
    assert_eq!(v["statics_method"], "cyclic");
    assert_eq!(
        (&v["treads"], &v["self_stress_dim"]),
        (&360.into(), &720.into())
    );
    assert_eq!(
        (&v["mechanisms"], &v["internal_mechanisms"]),
        (&0.into(), &0.into())
    );
    assert!(v["min_prestress"].as_f64().unwrap() > 0.0);
    assert!(v["mass_kg"].as_f64().unwrap() > 0.0);
    assert!(
        v["warnings"].as_array().unwrap().is_empty(),
        "{}",
        v["warnings"]
    );
}

#[test]
fn exports_and_errors() {
    let dir = std::env::temp_dir().join(format!("tensegrity-tbar-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (scene, vtu, svg) = (dir.join("t.toml"), dir.join("t.vtu"), dir.join("t.svg"));
    let out = run(&[
        "tbar",
        "--beta",
        "pi/6",
        "--phi",
        "pi/8",
        "--spherical",
        "pi/12",
        "--wheel",
        "--export-scene",
        scene.to_str().unwrap(),
        "--vtk",
        vtu.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let st = json(&["statics", scene.to_str().unwrap(), "--json"]);
    assert_eq!(st["self_stress_dim"], 16);
    assert!(std::fs::read_to_string(&vtu)
        .unwrap()
        .contains(r#"NumberOfPoints="32""#));
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<polyline"));
    let bad = run(&[
        "tbar",
        "--beta",
        "pi/6",
        "--phi",
        "0.3",
        "--cylindrical",
        "0.25",
        "--wheel",
    ]);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("π/φ must be an integer"));
}
