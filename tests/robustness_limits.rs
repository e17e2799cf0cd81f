//! Issue 26, crashes and hangs: every case of "Measured" that crashed, hung or accepted what
//! its sibling refuses, end to end. Each is refused at once (exit 2, within a few seconds,
//! one line naming the parameter, the limit and the flag that raises it), or answers.

use crate::common;

use common::{chain, scratch};
use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

/// Runs the binary; its output and wall time.
fn run(args: &[&str]) -> (Output, Duration) {
    let t0 = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("binary runs");
    (out, t0.elapsed())
}

/// Asserts a quick refusal (exit 2, < 5 s, nothing on stdout, one line) whose message holds
/// every one of `needles`; the message.
fn assert_refused(args: &[&str], needles: &[&str]) -> String {
    let (out, took) = run(args);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(took < Duration::from_secs(5), "{args:?} took {took:?}");
    assert!(out.stdout.is_empty(), "{args:?} printed a report");
    for n in needles {
        assert!(err.contains(n), "{args:?}: {n:?} missing from {err}");
    }
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    err
}

#[test]
fn a_billion_seconds_of_tbar_rolling_is_refused_before_allocating() {
    // it aborted allocating its samples (exit 134)
    assert_refused(
        &[
            "tbar",
            "roll",
            "--beta",
            "pi/6",
            "--cylindrical",
            "0.25",
            "--t-end",
            "1e9",
        ],
        &["t_end = 1000000000", "--max-", "--t-end 1000000000"],
    );
}

#[test]
fn a_hundred_thousand_treads_are_refused_at_once() {
    // it ran silently for minutes: above the T-bar wheel's 3,600 treads it is refused by
    // the request, below by the estimate of the runs (each step searches every side)
    assert_refused(
        &[
            "tbar",
            "roll",
            "--beta",
            "pi/6",
            "--cylindrical",
            "0.25",
            "--treads",
            "100000",
        ],
        &["--treads", "treads = 100000", "at most 3600"],
    );
    assert_refused(
        &[
            "tbar",
            "roll",
            "--beta",
            "pi/6",
            "--cylindrical",
            "0.25",
            "--treads",
            "3600",
        ],
        &["treads = 3600", "--max-work", "--treads 3600"],
    );
}

#[test]
fn tbar_roll_takes_the_rules_of_roll() {
    let base = ["tbar", "roll", "--beta", "pi/6", "--cylindrical", "0.25"];
    for (flag, value, name) in [
        ("--restitution", "2", "restitution"),
        ("--incline", "90deg", "incline"),
        ("--treads", "0", "treads"),
        ("--treads", "1", "treads"),
        ("--treads", "2", "treads"),
    ] {
        let mut args = base.to_vec();
        args.extend([flag, value]);
        let err = assert_refused(&args, &[flag, name]);
        assert!(!err.contains("panicked"), "{err}");
    }
    // three treads are a polygon: a row with both columns
    let (out, _) = run(&[
        "tbar",
        "roll",
        "--beta",
        "pi/6",
        "--cylindrical",
        "0.25",
        "--treads",
        "3",
        "--t-end",
        "0.2",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["rows"][0]["treads"], 3);
    assert!(j["rows"][0]["tbar"].is_object() && j["rows"][0]["toroid"].is_object());
}

#[test]
fn the_michell_table_checks_its_cap_before_any_row() {
    // it computed for 43 s, then failed at q = 101
    assert_refused(
        &["michell-table", "--max-complexity", "10000"],
        &["--max-complexity", "10000", "100"],
    );
    // and its estimate honours --max-output
    assert_refused(
        &[
            "michell-table",
            "--max-complexity",
            "10",
            "--max-output",
            "100",
        ],
        &[
            "max_complexity = 10",
            "output",
            "--max-output",
            "--max-complexity 10",
        ],
    );
    let (out, _) = run(&["michell-table", "--max-complexity", "3"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // header and (q = 2, 3) × (planar, three δ)
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).lines().count(),
        1 + 2 * 4
    );
}

#[test]
fn a_long_michell_search_is_refused_by_its_estimate() {
    // it ran 215 s without progress: the search up to q = 100, ~10⁹ joint analyses
    assert_refused(
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
        &["max_complexity = 100", "--max-work", "--max-complexity 100"],
    );
    // a heavy joint ends the search early: the default cap answers
    let (out, took) = run(&[
        "michell",
        "optimize",
        "--planar",
        "--radius-ratio",
        "0.3",
        "--joint-mass",
        "0.1",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(took < Duration::from_secs(20), "{took:?}");
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(j["complexity"].as_u64().unwrap() >= 1);
}

/// `statics SCENE --json` succeeds within a minute; its report.
fn statics_answers(scene: &str) -> serde_json::Value {
    let (out, took) = run(&["statics", scene, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(took < Duration::from_secs(60), "{took:?}");
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn long_chains_answer_or_are_refused_by_their_estimate() {
    let dir = scratch("limits", "chains");
    // 3,000 nodes: the sparse path answers in seconds (rank 2n − 3, n + 3 mechanisms)
    let small = chain(&dir, 3000);
    let j = statics_answers(&small);
    assert_eq!(j["rank"], 2 * 3000 - 3);
    assert_eq!(j["self_stress_dim"], 0);
    // 18,000 nodes (35,997 members): the nested dissection of A itself answers in linear
    // time and memory (the banded QR needed ~4 GB, its estimate 7.2 GiB) ...
    let big = chain(&dir, 18000);
    let j = statics_answers(&big);
    assert_eq!(j["rank"], 2 * 18000 - 3);
    assert_eq!(j["mechanisms"], 18000 + 3);
    // ... and its estimate (194 MiB) refuses it under a smaller limit, naming the flag
    assert_refused(
        &["statics", &big, "--max-memory", "50M"],
        &["18000 nodes", "memory", "--max-memory"],
    );
}

/// A tower of `stages` stacked Snelson prisms sharing their triangles (examples/tower200.toml
/// continued): one self-stress and one internal mechanism per prism.
fn tower(dir: &Path, stages: usize) -> String {
    let mut s = String::from("nodes = [\n");
    for ring in 0..=stages {
        for i in 0..3 {
            let a = 2.0 * std::f64::consts::PI * i as f64 / 3.0
                + ring as f64 * std::f64::consts::PI / 6.0;
            s += &format!("  [{}, {}, {ring}.0],\n", a.cos(), a.sin());
        }
    }
    s += "]\n";
    for st in 0..stages {
        for i in 0..3 {
            s += &format!(
                "[[bars]]\nnodes = [{}, {}]\n",
                3 * st + i,
                3 * st + 3 + (i + 1) % 3
            );
            s += &format!(
                "[[strings]]\nnodes = [{}, {}]\n",
                3 * st + i,
                3 * st + 3 + i
            );
        }
    }
    for ring in 0..=stages {
        for i in 0..3 {
            s += &format!(
                "[[strings]]\nnodes = [{}, {}]\n",
                3 * ring + i,
                3 * ring + (i + 1) % 3
            );
        }
    }
    let path = dir.join(format!("tower{stages}.toml"));
    std::fs::write(&path, s).unwrap();
    path.display().to_string()
}

#[test]
#[ignore = "issue 25: the tower of 1500 is now analysed in about a second (sparse statics in near-linear time); a scene of minutes after the QR is still to be chosen"]
fn a_sparse_statics_of_minutes_is_refused_once_its_rank_is_known() {
    // 1,500 prisms: the QR takes a second or two and finds 1,500 self-stresses and 1,506
    // mechanisms, whose bases, LP and stability test would take minutes (the estimate before
    // the QR, at the generic rank, cannot see them): refused over --max-work after the QR
    // (exit 2, one line, no report; its time depends on the QR, so it is not bounded here)
    let dir = scratch("limits", "towers");
    let big = tower(&dir, 1500);
    let (out, _) = run(&["statics", &big]);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(out.stdout.is_empty(), "a report: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    for needle in [
        "1500 self-stresses",
        "1506 mechanisms",
        "after its QR",
        "of work",
        "--max-work",
    ] {
        assert!(err.contains(needle), "{needle:?} missing from {err}");
    }
    // a smaller tower answers: 100 prisms, 100 self-stresses, prestressable
    let small = tower(&dir, 100);
    let (out, _) = run(&["statics", &small, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (j["self_stress_dim"].as_u64(), j["prestressable"].as_bool()),
        (Some(100), Some(true))
    );
}

#[test]
#[ignore = "issue 25: the tower of 1500 is now analysed in about a second (sparse statics in near-linear time); a scene of minutes after the QR is still to be chosen"]
fn a_sweep_case_of_minutes_is_refused_once_its_rank_is_known() {
    // the same check as the command's, in a sweep: the case's estimate before the QR lets the
    // tower of 1500 through, the sparse path's check after the QR refuses it under the sweep's
    // limits (an error row naming the work and the limit), and the small tower's row answers
    let dir = scratch("limits", "sweep_towers");
    let (small, big) = (tower(&dir, 100), tower(&dir, 1500));
    let spec = dir.join("statics.toml");
    std::fs::write(
        &spec,
        format!("study = \"statics\"\n[axes]\nscene = [{small:?}, {big:?}]\n"),
    )
    .unwrap();
    let out = dir.join("statics.csv");
    let (o, _) = run(&[
        "sweep",
        spec.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    let text = std::fs::read_to_string(&out).unwrap_or_default();
    assert!(o.status.code().is_some(), "killed: {o:?}");
    let rows: Vec<&str> = text.lines().collect();
    assert_eq!(rows.len(), 3, "{text}");
    assert!(rows[1].contains(",ok"), "{}", rows[1]);
    assert!(
        rows[2].contains("error") && rows[2].contains("1500 self-stresses"),
        "{}",
        rows[2]
    );
}

#[test]
fn sweeps_refuse_the_big_case_by_name_and_run_the_others() {
    let dir = scratch("limits", "sweeps");
    for (name, spec, needle) in [
        (
            "toroid",
            "study = \"toroid\"\n[axes]\nsides = [6, 100000000]\n",
            "sides = 100000000",
        ),
        (
            "roll",
            "study = \"roll\"\n[fixed]\nfidelity = \"rigid\"\n[axes]\nt_end = [0.2, 1e9]\n",
            "t_end = 1000000000",
        ),
    ] {
        let spec_path = dir.join(format!("{name}.toml"));
        std::fs::write(&spec_path, spec).unwrap();
        let out = dir.join(format!("{name}.csv"));
        let (o, took) = run(&[
            "sweep",
            spec_path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ]);
        assert!(took < Duration::from_secs(60), "{name}: {took:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!err.contains("memory allocation"), "{name}: {err}");
        let text = std::fs::read_to_string(&out).unwrap();
        let rows: Vec<&str> = text.lines().collect();
        assert_eq!(rows.len(), 3, "{name}: {text}");
        assert!(
            rows[1].contains(",ok,") || rows[1].contains(",ok"),
            "{name}: {}",
            rows[1]
        );
        assert!(
            rows[2].contains("error") && rows[2].contains(needle),
            "{name}: {}",
            rows[2]
        );
    }
}
