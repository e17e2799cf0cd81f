//! Counts at the edges (issue 42): every count a user gives — a wheel's sides, a truss's
//! complexity, a built-in form's size — is refused by name before anything of its size is
//! allocated, or estimated and refused over the limits; never an abort. Each command runs
//! under a 4 GB address-space limit, so an allocation of the count's size would fail the test.

use crate::common;
use std::process::Command;

/// Runs `tensegrity ARGS` under `ulimit -v 4000000`; (exit code, stderr).
fn run_capped(args: &str) -> (Option<i32>, String) {
    let bin = env!("CARGO_BIN_EXE_tensegrity");
    let out = Command::new("bash")
        .arg("-c")
        .arg(format!("ulimit -v 4000000; exec {bin} {args}"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("bash runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

#[test]
fn a_count_beyond_its_type_says_so_instead_of_calling_it_no_integer() {
    // 2³² sides is an integer: the message says what bound it passes
    let (code, err) = run_capped("toroid --sides 4294967296");
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("--sides") && err.contains("must be at most 4294967295"),
        "{err}"
    );
    let (code, err) = run_capped("michell --complexity 1e12 --beta 0.5 --phi 0.3");
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("--complexity") && err.contains("at most"),
        "{err}"
    );
    // a fraction is still no count
    let (code, err) = run_capped("toroid --sides 2.5");
    assert_eq!(code, Some(2));
    assert!(err.contains("expected a non-negative integer"), "{err}");
}

#[test]
fn huge_counts_are_estimated_and_refused_before_allocation() {
    for (args, flag) in [
        ("toroid --sides 4294967295", "--max-memory"),
        ("roll --sides 100000000", "--max-memory"),
        (
            "formfind --builtin prism:1000000000000",
            "prism:1000000000000",
        ),
        ("formfind --builtin grid:1000000000", "grid:1000000000"),
    ] {
        let (code, err) = run_capped(args);
        assert_eq!(code, Some(2), "{args}: {err}");
        assert!(err.contains(flag), "{args}: {err}");
    }
}

/// Found by a catalogue of every flag of eight commands given `nan`, `-1`, `0`, `1e308`,
/// `1e-320`, `abc`, `4294967296`, `-0`, `inf`, `1e12` (1,430 runs, 2026-12-06): one panic, one
/// NaN in a report and two hangs; each is now refused before work.
#[test]
fn the_catalogue_s_panic_nan_and_hangs_are_refused_before_work() {
    let tbar = "tbar --beta 0.5 --phi 0.3 --complexity 1";
    // a huge cylindrical offset overflowed the node merger's grid (a panic)
    let (code, err) = run_capped(&format!("{tbar} --cylindrical 1e308"));
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("delta = 1e308") && err.contains("at most 1e8"),
        "{err}"
    );
    // a subnormal load sized every member to 0 kg and the mass ratio to NaN
    let (code, err) = run_capped(&format!("{tbar} --cylindrical 0.25 --load 1e-320"));
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("load = 1e-320"), "{err}");
    // an adaptive run of 10¹² s was estimated at one step: 10¹⁴ samples now count
    for t_end in ["1e12", "4294967296"] {
        let start = std::time::Instant::now();
        let (code, err) = run_capped(&format!(
            "simulate examples/prism_drop.toml --t-end {t_end} --json"
        ));
        assert_eq!(code, Some(2), "{err}");
        assert!(
            err.contains("output samples") && err.contains("--max-work"),
            "{err}"
        );
        assert!(start.elapsed() < std::time::Duration::from_secs(5));
    }
}

/// `tbar roll --gravity 1e12`: the n = 24 row's speeds were NaN and marked valid. A run whose
/// headline numbers are not finite is not valid, with a `non_finite` warning per quantity.
#[test]
fn a_run_that_leaves_double_precision_is_not_valid() {
    let out = common::run(&[
        "tbar",
        "roll",
        "--t-end",
        "0.2",
        "--no-convergence-check",
        "--gravity",
        "1e12",
        "--json",
    ]);
    common::assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["valid"], false);
    let mut non_finite_rows = 0;
    for row in v["rows"].as_array().unwrap() {
        let t = &row["tbar"];
        let finite = ["mean_speed", "final_speed", "mean_axle_height"]
            .iter()
            .all(|k| t[k].as_f64().is_some_and(f64::is_finite));
        if !finite {
            non_finite_rows += 1;
            assert_eq!(t["valid"], false, "{t}");
            let kinds: Vec<&str> = t["warnings"]
                .as_array()
                .unwrap()
                .iter()
                .filter_map(|w| w["kind"].as_str())
                .collect();
            assert!(kinds.contains(&"non_finite"), "{kinds:?}");
        }
    }
    // the n = 24 row (and n = 8) leave double precision today
    assert!(non_finite_rows >= 1);
}

/// A scene catalogue (every number of examples/prism_drop.toml set to `nan`, `-1`, `0`,
/// `1e308`, `1e-320`, `1e12`, `-1e308`; 532 runs of `simulate` and `statics`): a string
/// damping, stiffness or bar mass of 10¹² made the adaptive RK45 run crawl at its stability
/// limit for hours (estimated at one step). The estimate now bounds its steps from below by
/// t_end · λ / 3 for the model's fastest rate λ: refused at once.
#[test]
fn a_stiff_scene_under_an_adaptive_explicit_method_is_estimated_by_its_fastest_rate() {
    let dir = common::scratch("counts", "stiff");
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/prism_drop.toml"),
    )
    .unwrap();
    let stiff = dir.join("stiff.toml");
    std::fs::write(&stiff, text.replace("damping = 2.0", "damping = 1e12")).unwrap();
    let start = std::time::Instant::now();
    let (code, err) = run_capped(&format!("simulate {} --json", stiff.display()));
    assert_eq!(code, Some(2), "{err}");
    // λ = 2c/m = 2·10¹² / 0.25 = 8·10¹² 1/s over 3 s: 8·10¹² steps
    assert!(
        err.contains("8.000e12 time steps") && err.contains("--max-work"),
        "{err}"
    );
    assert!(start.elapsed() < std::time::Duration::from_secs(5));
    // the bundled scene itself is unaffected
    let (code, err) = run_capped("simulate examples/prism_drop.toml --json");
    assert_eq!(code, Some(0), "{err}");
}
