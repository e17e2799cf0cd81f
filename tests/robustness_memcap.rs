//! Every command under a memory cap (issue 26, item 1): run through
//! `sh -c 'ulimit -v CAP; exec tensegrity …'`, a request too large for the cap is refused
//! before it allocates — exit 2, one line naming the parameter and the flag that raises the
//! limit — never an allocation failure (exit 134, "memory allocation … failed"), a signal
//! death or a hang; and each case of the "Measured" list that allocated runs under a
//! cap with its expected clear error or correct completion.
//!
//! Under `ulimit -v` the default `--max-memory` is ¾ of the cap (the guard reads the
//! address-space limit), so a request that fits the machine but not the cap is refused
//! naming the limit too (`toroid --sides 100000` under 2 GB).
//!
//! Linux only (`ulimit -v` and /proc); each test returns at once elsewhere.

use crate::common;

use common::{chain, scratch};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The address-space cap of every run here (KiB): 2 GB, room for the binary, its threads'
/// stacks and allocator arenas, far below what the refused requests would need.
const CAP_KIB: u64 = 2_000_000;

/// The longest any run here may take before it counts as a hang.
const HANG: Duration = Duration::from_secs(120);

fn linux() -> bool {
    Path::new("/proc/self/limits").exists()
}

/// Runs `tensegrity ARGS` under `ulimit -v cap_kib` from the repository root, killed after
/// [`HANG`]; its output and wall time.
fn capped(cap_kib: u64, args: &[&str]) -> (Output, Duration) {
    let t0 = Instant::now();
    let child = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {cap_kib} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("sh runs");
    let id = child.id();
    let watchdog = std::thread::spawn(move || {
        let t = Instant::now();
        while t.elapsed() < HANG {
            std::thread::sleep(Duration::from_millis(200));
            if !Path::new(&format!("/proc/{id}")).exists() {
                return;
            }
        }
        let _ = Command::new("kill")
            .args(["-KILL", &id.to_string()])
            .status();
    });
    let out = child.wait_with_output().expect("waits");
    let took = t0.elapsed();
    let _ = watchdog.join();
    (out, took)
}

/// Exit code, stderr; panics on a signal death, an allocation failure or a panic.
fn no_abort(args: &[&str], out: &Output, took: Duration) -> (i32, String) {
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    let code = out.status.code().unwrap_or_else(|| {
        panic!("{args:?} died of a signal after {took:?} (a hang killed, or an abort): {err}")
    });
    assert_ne!(code, 134, "{args:?} aborted: {err}");
    for bad in ["memory allocation", "panicked", "RUST_BACKTRACE"] {
        assert!(!err.contains(bad), "{args:?}: {bad:?} in {err}");
    }
    (code, err)
}

/// Asserts a clean refusal under the cap: exit 2, nothing on stdout, one line holding every
/// one of `needles` (the parameter, the flag).
fn refused(args: &[&str], needles: &[&str]) {
    let (out, took) = capped(CAP_KIB, args);
    let (code, err) = no_abort(args, &out, took);
    assert_eq!(code, 2, "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?} printed a report");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "{args:?}: one line: {err}"
    );
    for n in needles {
        assert!(err.contains(n), "{args:?}: {n:?} missing from {err}");
    }
}

/// Asserts a completion under the cap; its stdout.
fn completes(args: &[&str]) -> String {
    let (out, took) = capped(CAP_KIB, args);
    let (code, err) = no_abort(args, &out, took);
    assert_eq!(code, 0, "{args:?}: {err}");
    String::from_utf8_lossy(&out.stdout).to_string()
}

/// One too-large request per command of the CLI, each refused under the cap naming its
/// parameter and the flag that raises the limit (or, for a hard limit, the parameter's flag).
#[test]
fn every_command_refuses_a_request_too_large_for_the_cap() {
    if !linux() {
        return;
    }
    let dir = scratch("memcap", "commands");
    let out = |name: &str| dir.join(name).display().to_string();
    let (csv, svg, grid, map) = (out("o.csv"), out("o.svg"), out("g.csv"), out("m.csv"));
    let big_chain = chain(&dir, 18000);
    let michell = [
        "michell",
        "--complexity",
        "4",
        "--cylindrical",
        "0.25",
        "--beta",
        "pi/6",
    ];
    let tbar = ["tbar", "--beta", "pi/6", "--cylindrical", "0.25"];
    let tbar_roll = ["tbar", "roll", "--beta", "pi/6", "--cylindrical", "0.25"];
    let with = |base: &[&'static str], more: &[&'static str]| -> Vec<String> {
        base.iter().chain(more).map(|s| s.to_string()).collect()
    };
    let cases: Vec<(Vec<String>, Vec<&str>)> = vec![
        // the 18,000-node chain on the banded QR: 29 GiB estimated (the automatic
        // choice answers it in ~100 MB by the nested dissection of A)
        (
            with(&["statics", "--method", "sparse"], &[])
                .into_iter()
                .chain([big_chain.clone()])
                .collect(),
            vec!["18000 nodes", "--max-memory"],
        ),
        (
            with(
                &[
                    "simulate",
                    "examples/dbar.toml",
                    "--t-end",
                    "5",
                    "--output-interval",
                    "1e-9",
                    "--out",
                ],
                &[],
            )
            .into_iter()
            .chain([csv.clone()])
            .collect(),
            vec!["output interval", "--max-output"],
        ),
        (
            with(&["simulate", "examples/dbar.toml", "--t-end", "1e9"], &[]),
            vec!["t_end / dt", "--dt", "--t-end"],
        ),
        (
            with(&["toroid", "--sides", "1000000"], &[]),
            vec!["sides = 1000000", "--max-memory"],
        ),
        // fits the machine (0.5 GB measured, 5.2 GiB estimated), not ¾ of the 2 GB cap
        (
            with(&["toroid", "--sides", "100000"], &[]),
            vec!["sides = 100000", "above the limit of 1.", "--max-memory"],
        ),
        (
            with(&["roll", "--t-end", "1e9"], &[]),
            vec!["t_end = 1000000000", "--max-"],
        ),
        (
            with(&["tipover", "--grid-points", "100000", "--grid"], &[])
                .into_iter()
                .chain([grid.clone()])
                .collect(),
            vec!["--grid-points 100000", "--max-"],
        ),
        (
            with(&["tipover", "--dynamic", "--hold", "1e9"], &[]),
            vec!["hold = 1000000000", "--hold 1000000000", "--max-"],
        ),
        (
            with(&["tipover", "--rolling", "--t-end", "1e9"], &[]),
            vec!["t_end = 1000000000", "--t-end 1000000000", "--max-"],
        ),
        (
            with(
                &michell,
                &["--phi", "pi/8", "--map-grid", "100000x100000", "--sign-map"],
            )
            .into_iter()
            .chain([map.clone()])
            .collect(),
            vec!["100000x100000", "--max-"],
        ),
        (
            with(
                &michell[..1],
                &[
                    "--complexity",
                    "10000",
                    "--cylindrical",
                    "0.25",
                    "--beta",
                    "pi/6",
                    "--phi",
                    "pi/8",
                ],
            ),
            vec!["complexity = 10000", "at most 100"],
        ),
        (
            with(
                &[
                    "michell",
                    "optimize",
                    "--cylindrical",
                    "0.25",
                    "--radius-ratio",
                    "0.01",
                    "--joint-mass",
                    "1e-6",
                    "--max-complexity",
                    "100",
                ],
                &[],
            ),
            vec!["max_complexity = 100", "--max-work"],
        ),
        (
            with(&["michell-table", "--max-complexity", "10000"], &[]),
            vec!["--max-complexity", "10000"],
        ),
        (
            with(&tbar, &["--complexity", "1000", "--phi", "pi/8"]),
            vec!["complexity = 1000", "must be at most"],
        ),
        (
            with(&tbar, &["--complexity", "20", "--phi", "pi/360", "--wheel"]),
            vec!["complexity = 20", "--max-"],
        ),
        (
            with(&tbar, &["--phi", "pi/100000", "--wheel"]),
            vec!["100000", "3600"],
        ),
        (
            with(&tbar_roll, &["--t-end", "1e9"]),
            vec!["t_end = 1000000000", "--max-"],
        ),
        (
            with(&tbar_roll, &["--treads", "100000"]),
            vec!["treads = 100000", "--treads"],
        ),
        (
            with(&["fig-rolling", "--t-end", "1e9", "--out"], &[])
                .into_iter()
                .chain([svg.clone()])
                .collect(),
            vec!["t_end = 1000000000", "--max-"],
        ),
    ];
    for (args, needles) in &cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        refused(&args, needles);
    }
    // nothing was written
    let left: Vec<String> = common::listing(&dir)
        .into_iter()
        .filter(|f| !f.starts_with("chain"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

/// The sweeps whose cases were too large (`sides = 1e8` in a toroid spec,
/// `t_end = 1e9` in a roll spec: they aborted, the cases skipping the guard), under the cap:
/// the big case is an error row naming its parameter, the small one runs.
#[test]
fn sweeps_of_too_large_cases_finish_under_the_cap() {
    if !linux() {
        return;
    }
    let dir = scratch("memcap", "sweeps");
    for (name, spec, needle) in [
        ("toroid", "study = \"toroid\"\n[axes]\nsides = [6, 100000000]\n", "sides = 100000000"),
        (
            "roll",
            "study = \"roll\"\n[fixed]\nfidelity = \"rigid\"\n[axes]\nt_end = [0.2, 1e9]\n",
            "t_end = 1000000000",
        ),
        (
            "lean",
            "study = \"lean\"\n[axes]\nt_end = [0.01, 1e9]\n",
            "t_end = 1000000000",
        ),
        (
            "tbar",
            "study = \"tbar\"\n[fixed]\nbeta = \"pi/6\"\ncylindrical = 0.25\nwheel = true\n[axes]\nphi = [\"pi/8\", \"pi/360\"]\ncomplexity = [1, 20]\n",
            "complexity = 20",
        ),
    ] {
        let spec_path = dir.join(format!("{name}.toml"));
        std::fs::write(&spec_path, spec).unwrap();
        let csv = dir.join(format!("{name}.csv"));
        let args = ["sweep", spec_path.to_str().unwrap(), "--out", csv.to_str().unwrap(), "--quiet"];
        let (out, took) = capped(CAP_KIB, &args);
        let (code, err) = no_abort(&args, &out, took);
        assert!(code == 0 || code == 1, "{name}: exit {code}: {err}");
        let text = std::fs::read_to_string(&csv).unwrap();
        let rows: Vec<&str> = text.lines().skip(1).collect();
        assert!(rows[0].contains(",ok,") || rows[0].ends_with(",ok"), "{name}: {}", rows[0]);
        assert!(
            rows.iter().any(|r| r.contains("error") && r.contains(needle)),
            "{name}: {text}"
        );
    }
}

/// The other cases of "Measured" that allocated, under the cap: the 3,000-node chain
/// answers (it took 68–114 s), `statics /dev/zero` is refused at once (it grew to 4.2 GB),
/// and a second `simulate --out` to the same file is refused while the first writes (the
/// first reported rows it did not leave).
#[test]
fn the_measured_cases_that_allocated_behave_under_the_cap() {
    if !linux() {
        return;
    }
    let dir = scratch("memcap", "measured");
    let small = chain(&dir, 3000);
    let json = completes(&["statics", &small, "--json"]);
    let j: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(j["rank"], 2 * 3000 - 3);
    assert_eq!(j["self_stress_dim"], 0);
    refused(&["statics", "/dev/zero"], &["/dev/zero", "67108864 bytes"]);
    // two writers of one file: the second is refused at open, the first keeps its rows
    let csv = dir.join("same.csv");
    let csv = csv.to_str().unwrap();
    let first = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {CAP_KIB} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_tensegrity"))
        .args([
            "simulate",
            "examples/prism_drop.toml",
            "--t-end",
            "30",
            "--output-interval",
            "1e-3",
            "--out",
            csv,
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // the first run holds the lock once its temporary file exists
    let tmp = dir.join(".same.csv.tmp");
    let t0 = Instant::now();
    while !tmp.exists() && t0.elapsed() < HANG {
        std::thread::sleep(Duration::from_millis(10));
    }
    let second = [
        "simulate",
        "examples/prism_drop.toml",
        "--t-end",
        "1",
        "--out",
        csv,
    ];
    refused(&second, &["another run", "--out"]);
    let out = first.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let said = String::from_utf8_lossy(&out.stdout).to_string() + &err;
    let rows = std::fs::read_to_string(dir.join("same.csv"))
        .unwrap()
        .lines()
        .count()
        - 1;
    assert!(
        said.contains(&format!("{rows} rows")),
        "{rows} rows, but: {said}"
    );
}

/// Commands without a size parameter complete under the cap: `figures --quick` and
/// `bench work-precision --quick`.
#[test]
fn the_quick_figures_and_bench_complete_under_the_cap() {
    if !linux() {
        return;
    }
    let dir = scratch("memcap", "quick");
    let figs = dir.join("figs");
    completes(&["figures", "--quick", "--out", figs.to_str().unwrap()]);
    assert!(figs.join("fig_4_18.svg").exists());
    let bench = dir.join("bench");
    completes(&[
        "bench",
        "work-precision",
        "--quick",
        "--out",
        bench.to_str().unwrap(),
    ]);
    assert!(bench.join("work_precision.csv").exists());
}

/// The rank case under a cap: `toroid --sides 30000` is refused cleanly under 2 GB
/// (1.55 GiB estimated) and under 3 GB gives 4n + 1 self-stresses and no internal mechanism,
/// certified (seconds in release, longer in the test build:
/// `cargo test --release --test integration robustness_memcap:: -- --ignored`).
#[test]
#[ignore = "seconds in release: cargo test --release --test integration robustness_memcap:: -- --ignored"]
fn thirty_thousand_sides_are_certified_under_the_cap() {
    if !linux() {
        return;
    }
    // its estimate (1.55 GiB) is above ¾ of the 2 GB cap, where it is refused cleanly
    // (exit 2, `--max-memory`); under 3 GB it runs
    refused(
        &["toroid", "--sides", "30000"],
        &["sides = 30000", "--max-memory"],
    );
    let args = ["toroid", "--sides", "30000", "--json"];
    let (out, took) = capped(3_000_000, &args);
    let (code, err) = no_abort(&args, &out, took);
    assert_eq!(code, 0, "{err}");
    let json = String::from_utf8_lossy(&out.stdout).to_string();
    let j: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(j["self_stress_dim"], 4 * 30000 + 1);
    assert_eq!(j["internal_mechanisms"], 0);
    assert!(j["statics_warning"].is_null(), "{}", j["statics_warning"]);
}
