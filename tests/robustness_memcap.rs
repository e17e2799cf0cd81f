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

mod common;

use common::scratch;
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
    let mut child = Command::new("sh")
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

/// A planar zig-zag chain of `n` nodes (rank 2n − 3, no self-stress).
fn chain(dir: &Path, n: usize) -> String {
    let mut s = String::from("nodes = [\n");
    for i in 0..n {
        s += &format!("  [{i}.0, {}, 0.0],\n", 0.5 * (i % 2) as f64);
    }
    s += "]\n";
    for i in 0..n - 1 {
        s += &format!("[[bars]]\nnodes = [{i}, {}]\n", i + 1);
    }
    for i in 0..n - 2 {
        s += &format!("[[strings]]\nnodes = [{i}, {}]\n", i + 2);
    }
    let path = dir.join(format!("chain{n}.toml"));
    std::fs::write(&path, s).unwrap();
    path.display().to_string()
}

/// One too-large request per command of the CLI, each refused under the cap naming its
/// parameter and the limit flag.
#[test]
fn every_command_refuses_a_request_too_large_for_the_cap() {
    if !linux() {
        return;
    }
    let dir = scratch("memcap", "commands");
    let out = |name: &str| dir.join(name).display().to_string();
    let (csv, svg, grid, map) = (out("o.csv"), out("o.svg"), out("g.csv"), out("m.csv"));
    let big_chain = chain(&dir, 18000);
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (
            vec!["statics", &big_chain],
            vec!["18000 nodes", "--max-memory"],
        ),
        (
            vec![
                "simulate",
                "examples/dbar.toml",
                "--t-end",
                "5",
                "--out",
                &csv,
                "--output-interval",
                "1e-9",
            ],
            vec!["output interval", "--max-output"],
        ),
        (
            vec!["simulate", "examples/dbar.toml", "--t-end", "1e9"],
            vec!["t_end = 1000000000", "--max-"],
        ),
        (
            vec!["toroid", "--sides", "1000000"],
            vec!["sides = 1000000", "--max-memory"],
        ),
        (
            vec!["roll", "--t-end", "1e9"],
            vec!["t_end = 1000000000", "--max-"],
        ),
        (
            vec!["tipover", "--grid-points", "100000", "--grid", &grid],
            vec!["--grid-points 100000", "--max-"],
        ),
        (
            vec!["tipover", "--dynamic", "--hold", "1e9"],
            vec!["1000000000", "--max-"],
        ),
        (
            vec!["tipover", "--rolling", "--t-end", "1e9"],
            vec!["t_end = 1000000000", "--max-"],
        ),
        (
            vec![
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
                &map,
                "--map-grid",
                "100000x100000",
            ],
            vec!["100000", "--max-"],
        ),
        (
            vec![
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
            vec!["max_complexity = 100", "--max-work"],
        ),
        (
            vec!["michell-table", "--max-complexity", "10000"],
            vec!["--max-complexity", "10000"],
        ),
        (
            vec![
                "tbar",
                "--beta",
                "pi/6",
                "--phi",
                "pi/100000",
                "--cylindrical",
                "0.25",
                "--wheel",
            ],
            vec!["--phi", "--"],
        ),
        (
            vec![
                "tbar",
                "roll",
                "--beta",
                "pi/6",
                "--cylindrical",
                "0.25",
                "--t-end",
                "1e9",
            ],
            vec!["t_end = 1000000000", "--max-"],
        ),
        (
            vec![
                "tbar",
                "roll",
                "--beta",
                "pi/6",
                "--cylindrical",
                "0.25",
                "--treads",
                "100000",
            ],
            vec!["treads = 100000", "--treads"],
        ),
        (
            vec!["fig-rolling", "--t-end", "1e9", "--out", &svg],
            vec!["t_end = 1000000000", "--max-"],
        ),
    ];
    for (args, needles) in &cases {
        refused(args, needles);
    }
    // nothing was written
    assert!(
        common::listing(&dir).iter().all(|f| f.starts_with("chain")),
        "{:?}",
        common::listing(&dir)
    );
}
