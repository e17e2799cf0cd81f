//! `michell optimize`, `michell --extra-strings auto|P` and `tipover --dynamic` from the
//! command line: the JSON keys of the contract and their values against closed forms and each other.

use std::process::Command;

fn json(args: &[&str]) -> serde_json::Value {
    let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn optimize_reports_the_planar_closed_form() {
    let v = json(&[
        "michell",
        "optimize",
        "--planar",
        "--radius-ratio",
        "0.25",
        "--complexity",
        "4",
        "--json",
    ]);
    let a = 0.25f64.powf(0.25);
    let f = |k: &str| v[k].as_f64().unwrap();
    assert!((f("beta") - a.atan()).abs() < 1e-12);
    assert!((f("phi").cos() - 2.0 * a / (1.0 + a * a)).abs() < 1e-12);
    assert!((f("normalized_yield_mass") - 4.0 * (1.0 / a - a)).abs() < 1e-9);
    assert_eq!(v["complexity"], 4);
    assert!(f("mass_kg") > 0.0);
}

#[test]
fn optimize_finds_a_complexity_with_a_joint_mass_and_refuses_without() {
    let v = json(&[
        "michell",
        "optimize",
        "--planar",
        "--radius-ratio",
        "0.05",
        "--joint-mass",
        "1e-4",
        "--json",
    ]);
    let q = v["complexity"].as_u64().unwrap() as usize;
    assert!(q > 1);
    let joints = (q + 1) * (q + 2) / 2;
    let m = v["mass_kg"].as_f64().unwrap();
    assert!((v["joint_mass_kg"].as_f64().unwrap() - 1e-4 * joints as f64).abs() < 1e-15);
    assert!(m > v["member_mass_kg"].as_f64().unwrap());
    let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(["michell", "optimize", "--planar", "--radius-ratio", "0.05"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("joint_mass"));
}

#[test]
fn auto_extra_strings_hold_every_sign_and_less_prestress_does_not() {
    let base = [
        "michell",
        "--complexity",
        "3",
        "--cylindrical",
        "0.25",
        "--beta",
        "pi/6",
        "--phi",
        "pi/8",
        "--json",
        "--extra-strings",
    ];
    let auto = json(&[&base[..], &["auto"]].concat());
    let t = auto["min_extra_prestress"].as_f64().unwrap();
    assert_eq!(auto["prestress"].as_f64().unwrap(), t);
    assert_eq!(auto["sign_changes"], serde_json::json!([]));
    let critical = auto["critical_member"].clone();
    let below = format!("{}", 0.99 * t);
    let v = json(&[&base[..], &[below.as_str()]].concat());
    assert_eq!(v["min_extra_prestress"].as_f64().unwrap(), t);
    let changes = v["sign_changes"].as_array().unwrap();
    assert!(changes.contains(&critical), "{changes:?} lacks {critical}");
}

#[test]
fn dynamic_tipover_reports_both_thresholds() {
    let v = json(&["tipover", "--dynamic", "--json"]);
    let s = v["static_threshold"].as_f64().unwrap();
    let d = v["dynamic_threshold"].as_f64().unwrap();
    // (m g/2)(T/h) with h = R_o cos(π/8) for the reference wheel resting on a side
    let m = v["mass_kg"].as_f64().unwrap();
    let h = (std::f64::consts::PI / 8.0).cos();
    assert!((s - 0.5 * m * 9.81 * 0.4 / h).abs() < 1e-9 * s);
    assert!((d / s - 1.0).abs() < 0.05, "{d} vs {s}");
    assert_eq!(v["tipped"], true);
}

#[test]
fn a_history_file_without_a_timed_tipover_run_is_a_usage_error() {
    let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(["tipover", "--out", "lean.csv"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--dynamic") && err.contains("--rolling"),
        "{err}"
    );
}
