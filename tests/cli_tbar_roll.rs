//! `tensegrity tbar` issue 11 items 1–5 end to end: `--rim body`, `--loop-study`,
//! `--mass-sweep` and `tbar roll`.

use std::process::Command;

fn json(args: &[&str]) -> serde_json::Value {
    let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .output()
        .expect("binary runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

const BASE: [&str; 7] = [
    "tbar",
    "--beta",
    "pi/6",
    "--phi",
    "pi/8",
    "--cylindrical",
    "0.25",
];

fn with<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut v = BASE.to_vec();
    v.extend_from_slice(extra);
    v
}

#[test]
fn rim_body_json_reports_the_rim_and_the_free_body_counts() {
    let v = json(&with(&["--wheel", "--rim", "body", "--json"]));
    assert_eq!(v["rim"], "body");
    assert_eq!(
        (&v["nodes"], &v["bars"], &v["rim_bars"], &v["strings"]),
        (&34.into(), &89.into(), &81.into(), &32.into())
    );
    assert_eq!(
        (&v["mechanisms"], &v["internal_mechanisms"]),
        (&6.into(), &0.into())
    );
    assert!(v["min_prestress"].is_null());
    // the exported rim-body scene, read back by `tensegrity statics` (the io path)
    let scene = std::env::temp_dir().join(format!("tbar-rim-body-{}.toml", std::process::id()));
    let path = scene.to_str().unwrap();
    json(&with(&[
        "--extended",
        "0.5",
        "--rim",
        "body",
        "--export-scene",
        path,
        "--json",
    ]));
    let st = json(&["statics", path, "--json"]);
    assert_eq!(
        (&st["self_stress_dim"], &st["mechanisms"]),
        (&113.into(), &6.into())
    );
    let f = json(&with(&["--wheel", "--json"]));
    assert_eq!((&f["rim"], &f["rim_bars"]), (&"fixed".into(), &0.into()));
}

#[test]
fn loop_study_shows_the_copy_removing_the_sideways_mechanism() {
    let rows = json(&with(&["--loop-study", "--extended", "0.5", "--json"]));
    let rows = rows.as_array().unwrap();
    let find = |s: &str, st: &str| {
        rows.iter()
            .find(|r| r["structure"] == s && r["stance"] == st)
            .unwrap()
    };
    let loop_edge = find("wheel", "edge");
    assert_eq!(
        (&loop_edge["contacts"], &loop_edge["mechanisms"]),
        (&2.into(), &1.into())
    );
    assert!((loop_edge["out_of_plane"].as_f64().unwrap() - 1.0).abs() < 1e-9);
    let ext_edge = find("extended wheel", "edge");
    assert_eq!(
        (&ext_edge["contacts"], &ext_edge["mechanisms"]),
        (&4.into(), &0.into())
    );
}

#[test]
fn mass_sweep_has_the_q1_envelope_and_none_for_q2() {
    let rows = json(&with(&[
        "--mass-sweep",
        "--sweep-complexities",
        "1,2",
        "--sweep-deltas",
        "0.25",
        "--load",
        "1000",
        "--rim",
        "body",
        "--json",
    ]));
    let rows = rows.as_array().unwrap();
    assert_eq!(rows.len(), 2);
    // the rim-supported q = 1 tread: min_prestress = 3.235768601 w0 (tbar-wheel tests)
    let p = rows[0]["min_prestress"].as_f64().unwrap();
    assert!((p / 1000.0 - 3.235768601).abs() < 1e-8, "{p}");
    assert!(rows[0]["mass"]["mass_ratio"].as_f64().unwrap() > 1.0);
    assert!(rows[1]["min_prestress"].is_null());
}

#[test]
fn roll_compares_with_the_toroid_and_reports_validity() {
    let v = json(&[
        "tbar",
        "roll",
        "--beta",
        "pi/6",
        "--cylindrical",
        "0.25",
        "--extended",
        "0.5",
        "--treads",
        "8,16",
        "--t-end",
        "2",
        "--json",
    ]);
    assert_eq!(v["model"], "rigid");
    assert_eq!(v["full_tensegrity_rolling"], false);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    for r in rows {
        for side in ["tbar", "toroid"] {
            for key in [
                "axle_height_oscillation",
                "valid",
                "warnings",
                "min_normal_force",
                "airborne_fraction",
            ] {
                assert!(r[side].get(key).is_some(), "{side}.{key}");
            }
        }
        assert!(r["tipover"]["critical_lateral_force"].as_f64().unwrap() > 0.0);
    }
    // the polygon's bump shrinks with more treads (≈ 1/n² for the reduced model)
    let osc = |i: usize| rows[i]["tbar"]["axle_height_oscillation"].as_f64().unwrap();
    assert!(osc(1) < 0.5 * osc(0));
}

#[test]
fn roll_out_writes_one_csv_row_per_tread_count_equal_to_the_json() {
    let dir = std::env::temp_dir().join(format!("tbar-roll-out-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("rows.csv");
    let line = [
        "tbar",
        "roll",
        "--treads",
        "8,12",
        "--t-end",
        "0.5",
        "--fidelity",
        "rigid",
        "--json",
    ];
    let v = json(&line);
    let mut with_out = line.to_vec();
    with_out.extend(["--out", csv.to_str().unwrap()]);
    assert_eq!(json(&with_out), v, "the report does not depend on --out");
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 3, "{text}");
    let header: Vec<&str> = lines[0].split(',').collect();
    assert_eq!(header[0], "treads");
    let rows = v["rows"].as_array().unwrap();
    for (line, row) in lines[1..].iter().zip(rows) {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), header.len());
        for (name, field) in header.iter().zip(&fields) {
            let mut value = row;
            for key in name.split('.') {
                value = &value[key];
            }
            match value {
                serde_json::Value::Number(n) => {
                    assert_eq!(field.parse::<f64>().unwrap(), n.as_f64().unwrap(), "{name}")
                }
                serde_json::Value::Bool(b) => assert_eq!(*field, b.to_string(), "{name}"),
                serde_json::Value::Null => assert_eq!(*field, "", "{name}"),
                other => panic!("{name}: not a scalar: {other}"),
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
