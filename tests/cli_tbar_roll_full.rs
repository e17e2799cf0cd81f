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

/// `tbar roll --fidelity full` with its defaults (n = 8 loop, 1 s on 30°, light rim body)
/// keeps every assumption of its models — no tip sinks more than 1 % of r₀, the ground never
/// pulls, the energy budget closes — for the T-bar and the toroid column alike, and fits the
/// default `--max-work` with the refined run counted (the guard admits it). The convergence
/// check is skipped here (it triples the cost); `the_default_full_roll_is_valid` (ignored,
/// release) runs the command exactly as a user does.
#[test]
fn the_default_full_roll_keeps_its_models_assumptions() {
    let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args([
            "tbar",
            "roll",
            "--fidelity",
            "full",
            "--no-convergence-check",
            "--json",
        ])
        .output()
        .expect("binary runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (&v["model"], &v["fidelity"]),
        (&"full".into(), &"full".into())
    );
    assert_eq!(v["valid"], true, "{}", v["warnings"]);
    let row = &v["rows"][0];
    let m = &row["mass_properties"];
    // the rim body is not most of the mass
    let (mass, rim) = (
        m["mass"].as_f64().unwrap(),
        m["rim_mass"].as_f64().unwrap_or(0.0),
    );
    assert!(rim < 0.5 * mass, "rim {rim} of {mass} kg");
    for side in ["tbar", "toroid"] {
        let r = &row[side];
        assert!(r["max_penetration"].as_f64().unwrap() < 0.01, "{side}");
        assert!(r["min_normal_force"].as_f64().unwrap() >= 0.0, "{side}");
        assert!(r["energy_balance_error"].as_f64().unwrap() < 1e-2, "{side}");
        assert_eq!(r["model"], "full");
        assert_eq!(r["fidelity_reason"], "requested");
    }
    // the guard admitted it under the default --max-work (no flag given) with the check on
    let estimate = tensegrity_engine::tbar_roll::estimate(&tbar_wheel::TbarRollRequest {
        fidelity: wheel_rolling::FidelityChoice::Full,
        ..Default::default()
    })
    .unwrap()
    .unwrap();
    let limits = tensegrity_core::budget::Limits::default();
    assert!(limits.check(&estimate).is_ok(), "{}", estimate.work_s);
}

/// The T-bar column of a short default full roll (0.3 s: the first half-pivot) with its
/// convergence check: with the default contact (`stick`, friction that holds a stick) every
/// headline quantity moves by at most half its tolerance at half the step and twice the
/// ground stiffness, and the run keeps its model's assumptions. With the regularised Coulomb
/// law (`--contact penalty`) the tip creeps at v_s artanh(tan 30° / μ_s) = 0.91 v_s, just
/// below the slip threshold v_s, and whether it counts as slipping depends on the step:
/// `slip_fraction` moves from 0.083 to 0.0007, so that run is not valid and `--strict`
/// exits 1 after writing its JSON. (The toroid column of so short a run is still in its
/// start transient: its `final_speed` moves 3.7 %; the 1 s default is converged, see
/// `the_default_full_roll_is_valid`.)
#[test]
fn the_stick_contact_converges_where_the_regularised_friction_does_not() {
    let full = |extra: &[&str]| {
        let mut args = vec![
            "tbar",
            "roll",
            "--fidelity",
            "full",
            "--t-end",
            "0.3",
            "--json",
        ];
        args.extend_from_slice(extra);
        let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
            .args(&args)
            .output()
            .expect("binary runs");
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON written");
        (out.status.code(), v)
    };
    let (_, stick) = full(&[]);
    assert_eq!(stick["contact"], "stick");
    let t = &stick["rows"][0]["tbar"];
    assert_eq!(t["valid"], true, "{}", t["warnings"]);
    assert_eq!(t["convergence"]["converged"], true);
    for q in t["convergence"]["quantities"].as_array().unwrap() {
        if let Some(change) = q["relative_change"].as_f64() {
            let tolerance = q["tolerance"].as_f64().unwrap();
            assert!(change <= 0.5 * tolerance, "{q}");
        }
    }
    assert!(t["max_penetration"].as_f64().unwrap() < 1e-3);
    assert!(t["energy_balance_error"].as_f64().unwrap() < 1e-6);

    let (code, penalty) = full(&["--contact", "penalty", "--strict"]);
    assert_eq!(code, Some(1));
    assert_eq!(penalty["valid"], false);
    assert_eq!(penalty["contact"], "penalty");
    let quantities = penalty["rows"][0]["tbar"]["convergence"]["quantities"]
        .as_array()
        .unwrap()
        .clone();
    let slip = quantities
        .iter()
        .find(|q| q["name"] == "slip_fraction")
        .unwrap();
    assert_eq!(slip["converged"], false, "{slip}");
    assert!(slip["relative_change"].as_f64().unwrap() > 0.05, "{slip}");
}

/// Issue 21, must show: `tbar roll --fidelity full` with its defaults is valid — its model's
/// assumptions kept and every headline quantity converged at half the step and twice the
/// ground stiffness, for the T-bar and the toroid column (stick contact; the slip counted on
/// the contact's load-weighted slip speed), and `--strict` exits 0. Release, about 25 s of
/// CPU (33 s wall on a shared 2-core machine), too slow for the default run:
/// `cargo test --release --test integration cli_tbar_roll_full:: -- --ignored`. Its fast counterpart on
/// 0.3 s is `the_stick_contact_converges_where_the_regularised_friction_does_not`.
#[test]
#[ignore = "release, ~33 s: the default full T-bar roll with its convergence check"]
fn the_default_full_roll_is_valid() {
    let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(["tbar", "roll", "--fidelity", "full", "--json", "--strict"])
        .output()
        .expect("binary runs");
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["valid"], true, "{}", v["warnings"]);
    assert_eq!(out.status.code(), Some(0));
    for side in ["tbar", "toroid"] {
        let c = &v["rows"][0][side]["convergence"];
        assert_eq!(c["converged"], true, "{side}: {c}");
        for q in c["quantities"].as_array().unwrap() {
            if let Some(change) = q["relative_change"].as_f64() {
                assert!(
                    change <= 0.5 * q["tolerance"].as_f64().unwrap(),
                    "{side}: {q}"
                );
            }
        }
    }
}
