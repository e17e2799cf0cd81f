//! The resource guard end to end: every oversized request is refused up front — quickly,
//! with exit code 2, before any output file is created — with an error naming the parameter,
//! the estimate and the flag that raises the limit; normal runs are unaffected and the flags
//! move the limits both ways.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

/// Runs the binary; returns its output and wall time.
fn run(args: &[&str]) -> (Output, Duration) {
    let t0 = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("binary runs");
    (out, t0.elapsed())
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tensegrity-guard-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Asserts a quick refusal (exit 2, < 5 s) whose message contains every one of `needles`;
/// returns the message.
fn assert_refused(args: &[&str], needles: &[&str]) -> String {
    let (out, took) = run(args);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(took < Duration::from_secs(5), "{args:?} took {took:?}");
    assert!(out.stdout.is_empty(), "{args:?} printed a report");
    for n in needles {
        assert!(err.contains(n), "{args:?}: {n:?} missing from {err}");
    }
    assert_eq!(err.lines().count(), 1, "one line, no backtrace: {err}");
    err
}

#[test]
fn a_hundred_thousand_sided_toroid_is_refused_naming_sides_memory_and_the_flag() {
    // dense path: 127 TiB; a symmetry-adapted path: a few GiB, still above 1 GiB
    assert_refused(
        &["toroid", "--sides", "100000", "--max-memory", "1Gi"],
        &[
            "sides = 100000",
            "memory",
            "above the limit of 1.000 GiB",
            "--max-memory",
        ],
    );
    // a hundred million sides is refused under the default limits whatever the path
    assert_refused(
        &["toroid", "--sides", "100000000"],
        &["sides = 100000000", "raise the limit with --max-"],
    );
}

#[test]
fn a_billion_seconds_of_rolling_is_refused() {
    assert_refused(
        &["roll", "--t-end", "1e9"],
        &["t_end = 1000000000", "raise the limit with --max-"],
    );
    assert_refused(
        &[
            "fig-rolling",
            "--t-end",
            "1e9",
            "--out",
            "/nonexistent/x.svg",
        ],
        &["t_end = 1000000000"],
    );
}

#[test]
fn a_ten_billion_point_sign_map_is_refused_before_the_file_is_created() {
    let dir = scratch("signmap");
    let csv = dir.join("map.csv");
    let csv_s = csv.to_str().unwrap();
    let args = [
        "michell",
        "--complexity",
        "4",
        "--cylindrical",
        "0.25",
        "--beta",
        "pi/6",
        "--phi",
        "pi/8",
        "--sign-map",
        csv_s,
        "--map-grid",
        "100000x100000",
    ];
    assert_refused(&args, &["--map-grid 100000x100000", "--max-"]);
    assert!(!csv.exists());
    // without --sign-map the grid is not computed, so it is not refused
    let (out, _) = run(&args[..9]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_nanosecond_output_interval_is_refused_before_the_outputs_are_opened() {
    let dir = scratch("interval");
    let csv = dir.join("traj.csv");
    let vtk = dir.join("vtk");
    for out_flag in [
        ["--out", csv.to_str().unwrap()],
        ["--vtk", vtk.to_str().unwrap()],
    ] {
        let mut args = vec!["simulate", "examples/dbar.toml", "--t-end", "5"];
        args.extend(out_flag);
        args.extend(["--output-interval", "1e-9"]);
        // 5e9 samples of 13 numbers: 1.6 TB of CSV
        assert_refused(
            &args,
            &["output interval 0.000000001 s", "output", "--max-output"],
        );
    }
    assert!(!csv.exists() && !vtk.exists());
}

#[test]
fn a_ten_billion_point_friction_map_is_refused() {
    // used to abort allocating 10¹⁰ rows
    assert_refused(
        &[
            "tipover",
            "--grid-points",
            "100000",
            "--grid",
            "/nonexistent/f.csv",
        ],
        &["--grid-points 100000", "--max-"],
    );
}

#[test]
fn a_ten_million_case_sweep_is_refused_for_its_output() {
    let dir = scratch("sweep");
    let spec = dir.join("huge.toml");
    std::fs::write(
        &spec,
        "study = \"toroid\"\n[axes]\nsides = { from = 3, to = 10002, step = 1 }\nouter_radius = { from = 1.0, to = 2.0, steps = 1000 }\n",
    )
    .unwrap();
    let out = dir.join("out.csv");
    assert_refused(
        &[
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        &[
            "10000000 sweep cases",
            "1.863 GiB of output",
            "--max-output",
        ],
    );
    assert!(!out.exists());
}

#[test]
fn the_flags_move_the_limits_both_ways() {
    let dir = scratch("flags");
    let csv = dir.join("traj.csv");
    let base = [
        "simulate",
        "examples/dbar.toml",
        "--t-end",
        "0.01",
        "--out",
        csv.to_str().unwrap(),
        "--output-interval",
        "1e-4",
    ];
    // 101 rows of 13 numbers ≈ 33 kB: refused under 1Ki, accepted by default
    let mut small = base.to_vec();
    small.extend(["--max-output", "1Ki"]);
    assert_refused(&small, &["--max-output", "above the limit of 1.000 KiB"]);
    let (out, _) = run(&base);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rows = std::fs::read_to_string(&csv).unwrap().lines().count();
    assert_eq!(rows, 102, "header + 101 samples");
    // work: the default toroid is a few ms of estimated work
    assert_refused(
        &["toroid", "--max-work", "1e-9"],
        &["sides = 8", "work", "--max-work"],
    );
}

#[test]
fn normal_runs_are_unaffected() {
    let (out, _) = run(&["simulate", "examples/anchors/motes_dbar.toml", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["steps"], 5000);
    let (out, _) = run(&["toroid", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (out, _) = run(&["roll", "--t-end", "0.5", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Under an address-space limit (`ulimit -v`, 2 GB) the default memory limit follows it: a
/// 2000-sided wheel that used to grow to 24 GB and be killed is refused with a clear error
/// (dense statics), or completes within the guard (a symmetry-adapted path): never an abort.
#[test]
fn under_an_address_space_limit_the_default_memory_limit_follows_it() {
    if !Path::new("/proc/self/limits").exists() {
        return;
    }
    let exe = env!("CARGO_BIN_EXE_tensegrity");
    let t0 = Instant::now();
    let out = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v 2000000 && exec {exe} toroid --sides 2000"
        ))
        .output()
        .expect("sh runs");
    let err = String::from_utf8_lossy(&out.stderr);
    match out.status.code() {
        Some(0) => assert!(t0.elapsed() < Duration::from_secs(60)),
        Some(2) => {
            assert!(t0.elapsed() < Duration::from_secs(5));
            assert!(
                err.contains("sides = 2000") && err.contains("--max-"),
                "{err}"
            );
        }
        other => panic!("exit {other:?}: {err}"),
    }
}

/// `figures` used to accept `--max-work` and ignore it (42 s of rolling runs under
/// `--max-work 10`): its figures' measured work is summed before any directory is made, and
/// the refusal names the figures and `--only`; a cheap selection runs under the same limit.
#[test]
fn figures_are_refused_above_max_work_before_the_directory_is_made() {
    let dir = scratch("figures").join("out");
    let out = dir.to_str().unwrap();
    let err = assert_refused(
        &["figures", "--out", out, "--max-work", "10"],
        &[
            "30 figure(s)",
            "Figs. 3.10 and 3.11",
            "49.600 s",
            "--max-work",
            "--only",
        ],
    );
    assert!(err.contains("only = 2.2,3.1"), "{err}");
    assert!(!dir.exists(), "nothing made before the refusal");
    let (ok, _) = run(&[
        "figures",
        "--out",
        out,
        "--only",
        "4.1",
        "--max-work",
        "10",
        "--quiet",
    ]);
    assert!(
        ok.status.success(),
        "{}",
        String::from_utf8_lossy(&ok.stderr)
    );
    assert!(dir.join("fig_4_1.svg").exists());
}
