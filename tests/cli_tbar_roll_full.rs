//! `tensegrity tbar roll --fidelity full` end to end: the JSON of a short full run (the
//! contract keys of the toroid's full run, `full_tensegrity_rolling: true`, the rigid
//! reference of the same polygon) and the refusal of a fixed rim.

use std::process::Command;

const BASE: [&str; 8] = [
    "tbar",
    "roll",
    "--beta",
    "pi/6",
    "--cylindrical",
    "0.25",
    "--treads",
    "4",
];

fn run(extra: &[&str]) -> std::process::Output {
    let mut args = BASE.to_vec();
    args.extend_from_slice(extra);
    Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .output()
        .expect("binary runs")
}

#[test]
fn a_short_full_run_reports_the_full_models_figures() {
    let out = run(&[
        "--fidelity",
        "full",
        "--extended",
        "0.5",
        "--t-end",
        "0.05",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (&v["model"], &v["full_tensegrity_rolling"]),
        (&"full".into(), &true.into())
    );
    assert_eq!((&v["rim"], &v["t_end"]), (&"body".into(), &0.05.into()));
    let row = &v["rows"][0];
    assert!(
        row["errors"].as_array().unwrap().is_empty(),
        "{}",
        row["errors"]
    );
    for side in ["tbar", "tbar_rigid_reference", "toroid"] {
        for key in [
            "min_normal_force",
            "airborne_fraction",
            "slip_fraction",
            "max_penetration",
            "energy_balance_error",
            "valid",
            "warnings",
            "mean_speed",
            "axle_height_oscillation",
            "impacts",
            "first_impact",
        ] {
            assert!(row[side].get(key).is_some(), "{side}.{key}");
        }
    }
    assert_eq!(
        (&row["tbar"]["model"], &row["toroid"]["model"]),
        (&"full".into(), &"full".into())
    );
    assert_eq!(row["tbar_rigid_reference"]["model"], "rigid");
    // the extended q = 1 wheel of 4 treads: 2·(3·4) rim points + 2 hubs + 8 tips, 8 tread
    // bars + 3·24 isostatic rim bars, 32 strings; the rigid reference has its mass and I₁
    let f = &row["full"];
    assert_eq!(
        (&f["nodes"], &f["bars"], &f["strings"]),
        (&34.into(), &80.into(), &32.into())
    );
    assert_eq!(
        (&f["rim_bars"], &f["redundant_rim_bars"]),
        (&72.into(), &41.into())
    );
    assert_eq!(
        row["tbar"]["mass_kg"],
        row["tbar_rigid_reference"]["mass_kg"]
    );
    assert_eq!(row["tbar"]["mass_kg"], row["mass_properties"]["mass"]);
    // at rest on the side 0–1 the four tips carry the weight: no flight, no pull
    assert!(row["tbar"]["airborne_fraction"].as_f64().unwrap() == 0.0);
    assert!(row["tbar"]["min_normal_force"].as_f64().unwrap() >= 0.0);
}

#[test]
fn the_full_model_refuses_the_fixed_rim() {
    let out = run(&["--fidelity", "full", "--rim", "fixed", "--t-end", "0.01"]);
    // a bad value (exit 2), named by the request's parameter
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("rim = \"fixed\"") && err.contains("rim body"),
        "{err}"
    );
}
