//! Counts at the edges (issue 42): every count a user gives — a wheel's sides, a truss's
//! complexity, a built-in form's size — is refused by name before anything of its size is
//! allocated, or estimated and refused over the limits; never an abort. Each command runs
//! under a 4 GB address-space limit, so an allocation of the count's size would fail the test.

mod common;
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
