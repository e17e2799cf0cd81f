//! Runs honest at their edges (issue 42, docs/ROBUSTNESS.md): each case the catalogue found
//! cut, dropped or computed before refusing is now a clear error before any work (exit code
//! 2, naming the flag) or a valid result.

use crate::common;
use common::{assert_ok, bin, run, scratch};
use std::path::Path;
use std::process::Output;
use std::time::{Duration, Instant};

/// Asserts exit code 2 and returns stderr.
fn refused(out: &Output) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{err}");
    err
}

fn json(out: &Output) -> serde_json::Value {
    assert_ok(out);
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Runs `tensegrity ARGS`, killed (and the test failed) after `limit`; its output and time.
fn run_within(args: &[&str], limit: Duration) -> (Output, Duration) {
    let t0 = Instant::now();
    let mut child = bin()
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    while child.try_wait().unwrap().is_none() {
        if t0.elapsed() > limit {
            let _ = child.kill();
            panic!("`tensegrity {}` ran past {limit:?}", args.join(" "));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    (child.wait_with_output().unwrap(), t0.elapsed())
}

/// examples/prism_drop.toml with `from` replaced by `to` everywhere, written to `dir`.
fn drop_scene(dir: &Path, name: &str, edits: &[(&str, &str)]) -> String {
    let mut text = std::fs::read_to_string("examples/prism_drop.toml").unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{from}");
        text = text.replace(from, to);
    }
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn a_simulate_step_longer_than_the_output_interval_is_refused() {
    // the flag: the scene samples every 10 ms
    let err = refused(&run(&[
        "simulate",
        "examples/prism_drop.toml",
        "--integrator",
        "rk4",
        "--dt",
        "0.02",
    ]));
    assert!(
        err.contains("invalid value for --dt: dt = 0.02: must not exceed the output interval 0.01 s (the scene's `[simulation] output_interval`)"),
        "{err}"
    );
    // the scene's own step
    let dir = scratch("runs", "dt");
    let scene = drop_scene(
        &dir,
        "dt.toml",
        &[("integrator = \"rk45\"", "integrator = \"rk4\"\ndt = 0.02")],
    );
    let err = refused(&run(&["simulate", &scene]));
    assert!(
        err.contains(
            "dt = 0.02: (the scene's `[simulation] dt`) must not exceed the output interval 0.01 s"
        ),
        "{err}"
    );
    // the flag's interval, with a trajectory: refused before it is opened
    let csv = dir.join("t.csv");
    let args = [
        "simulate",
        "examples/double_pendulum.toml",
        "--integrator",
        "rk4",
    ];
    let mut args = args.to_vec();
    args.extend(["--dt", "2e-3", "--output-interval", "1e-3", "--out"]);
    args.push(csv.to_str().unwrap());
    let err = refused(&run(&args));
    assert!(err.contains("0.001 s (--output-interval)"), "{err}");
    assert!(!csv.exists());
}

#[test]
fn imex_ark_takes_its_documented_step_and_is_valid_on_the_ground_example() {
    let r = json(&run(&[
        "simulate",
        "examples/prism_drop.toml",
        "--integrator",
        "imex-ark",
        "--json",
    ]));
    // 3 s at 2.5e-4 s (it stepped at the 10 ms output interval: 300 steps, invalid)
    assert_eq!(r["steps"], 12000, "{r}");
    assert!(r["warnings"].as_array().is_none_or(Vec::is_empty), "{r}");
    assert_eq!(r["convergence"]["converged"], true, "{r}");
    let help = String::from_utf8_lossy(&run(&["simulate", "--help"]).stdout).into_owned();
    assert!(help.contains("imex 5e-4, imex-ark 2.5e-4"), "{help}");
}

#[test]
fn final_speeds_near_zero_are_judged_on_the_problems_scale() {
    // the prism set down on the ground, damped: it comes to rest (final speeds ~1 cm/s)
    let dir = scratch("runs", "rest");
    let scene = drop_scene(
        &dir,
        "rest.toml",
        &[
            (", 0.5],", ", 0.001],"),
            (", 1.5],", ", 1.001],"),
            ("damping = 2.0", "damping = 50.0"),
            ("damping = 100.0", "damping = 300.0"),
        ],
    );
    let args = [
        "simulate",
        &scene,
        "--integrator",
        "rattle",
        "--dt",
        "2.5e-4",
    ];
    let r = json(&run(&[&args[..], &["--json"]].concat()));
    let c = &r["convergence"];
    assert_eq!(c["converged"], true, "{r}");
    // its speeds moved by 134 % of themselves: 4.5e-3 of √(g L) ≈ 3.3 m/s
    let v = c["quantities"][1]["relative_change"].as_f64().unwrap();
    assert!(v > 1e-3 && v < 1e-2, "{v}");
    // the README's ground example is valid on its defaults
    let gif = dir.join("drop.gif");
    let out = run(&[
        "simulate",
        "examples/prism_drop.toml",
        "--t-end",
        "1",
        "--animate",
        gif.to_str().unwrap(),
        "--fps",
        "10",
        "--duration",
        "2",
    ]);
    assert_ok(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("warning"), "{err}");
}

#[test]
fn simulate_takes_rk4_flight_and_samples_it_at_the_output_times() {
    let dir = scratch("runs", "flight");
    let csv = dir.join("f.csv");
    let r = json(&run(&[
        "simulate",
        "examples/prism_drop.toml",
        "--integrator",
        "rk4-flight",
        "--output-interval",
        "0.007",
        "--out",
        csv.to_str().unwrap(),
        "--json",
    ]));
    assert!(r["warnings"].as_array().is_none_or(Vec::is_empty), "{r}");
    assert_eq!(r["convergence"]["converged"], true, "{r}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let times: Vec<f64> = text
        .lines()
        .skip(1)
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    // every 7 ms from 0 to 2.996 s, each at its time (flight steps of 5 ms used to end late)
    assert_eq!(times.len(), 429);
    for (k, t) in times.iter().enumerate() {
        assert!((t - 0.007 * k as f64).abs() < 1e-9, "row {k}: t = {t}");
    }
}

#[test]
fn roll_refuses_the_full_models_flags_under_the_rigid_model() {
    // each flag at another value and, since 2026-12-06, at its default value (given on the
    // command line is enough: the rigid model ignores it either way)
    for (flag, value) in [
        ("--contact", "stick"),
        ("--integrator", "rk4"),
        ("--string-stiffness", "5e4"),
        ("--ground-stiffness", "1e6"),
        ("--ground-damping", "5"),
        ("--min-tension", "30"),
        ("--contact", "penalty"),
        ("--integrator", "imex-ark"),
        ("--string-stiffness", "2e4"),
        ("--ground-stiffness", "1e5"),
        ("--min-tension", "20"),
    ] {
        let err = refused(&run(&[
            "roll",
            "--fidelity",
            "rigid",
            "--t-end",
            "0.1",
            flag,
            value,
        ]));
        assert!(
            err.contains(&format!("invalid value for {flag}"))
                && err.contains("only the full model reads it, and --fidelity rigid runs the rigid polygon model"),
            "{err}"
        );
    }
    // what the rigid model reads is taken
    assert_ok(&run(&[
        "roll",
        "--fidelity",
        "rigid",
        "--t-end",
        "0.1",
        "--mu",
        "1.0",
        "--json",
    ]));
    // fig-rolling refuses the same, before it rolls anything or opens its figure
    let dir = scratch("runs", "fig_rigid");
    let svg = dir.join("r.svg");
    let err = refused(&run(&[
        "fig-rolling",
        "--fidelity",
        "rigid",
        "--contact",
        "stick",
        "--out",
        svg.to_str().unwrap(),
    ]));
    assert!(
        err.contains("invalid value for --contact") && err.contains("only the full model reads it"),
        "{err}"
    );
    assert!(!svg.exists());
}

#[test]
fn bench_anchors_honours_the_limits_before_it_runs() {
    let quick = [
        "bench",
        "anchors",
        "--quick",
        "--repeats",
        "1",
        "--no-instructions",
    ];
    let with = |extra: &[&str]| run(&[&quick[..], extra].concat());
    let err = refused(&with(&["--max-work", "0.01"]));
    assert!(
        err.contains("15 benchmark measurements, best of 1 needs an estimated")
            && err.contains("raise the limit with --max-work"),
        "{err}"
    );
    let err = refused(&with(&["--max-memory", "1M"]));
    assert!(err.contains("raise the limit with --max-memory"), "{err}");
    let dir = scratch("runs", "bench");
    let csv = dir.join("bench.csv");
    let err = refused(&with(&[
        "--max-output",
        "100",
        "--csv",
        csv.to_str().unwrap(),
    ]));
    assert!(err.contains("raise the limit with --max-output"), "{err}");
    assert!(!csv.exists());
    // the full sizes, 5 repeats: about 15 s estimated, refused under 1 s at once
    let (out, took) = run_within(
        &["bench", "anchors", "--no-instructions", "--max-work", "1"],
        Duration::from_secs(20),
    );
    let err = refused(&out);
    assert!(
        err.contains("23 benchmark measurements, best of 5"),
        "{err}"
    );
    assert!(took < Duration::from_secs(10), "{took:?}");
    assert_ok(&with(&["--json"]));
}

/// A tower of `stages` twisted triangles (3 (stages + 1) nodes), bars across each stage,
/// strings around each triangle and up each side; its path in `dir`.
fn tower(dir: &Path, stages: usize) -> String {
    let mut s = String::from("nodes = [\n");
    for i in 0..=stages {
        for j in 0..3 {
            let a = (j as f64) * 2.0 * std::f64::consts::PI / 3.0 + 0.5 * i as f64;
            s += &format!("  [{}, {}, {}],\n", a.cos(), a.sin(), i as f64);
        }
    }
    s += "]\n";
    for i in 0..stages {
        for j in 0..3 {
            let (a, b) = (3 * i + j, 3 * (i + 1) + (j + 1) % 3);
            s += &format!("[[bars]]\nnodes = [{a}, {b}]\nmass = 1.0\n");
            s += &format!(
                "[[strings]]\nnodes = [{a}, {}]\nstiffness = 1e3\n",
                3 * (i + 1) + j
            );
        }
    }
    for i in 0..=stages {
        for j in 0..3 {
            let (a, b) = (3 * i + j, 3 * i + (j + 1) % 3);
            s += &format!("[[strings]]\nnodes = [{a}, {b}]\nstiffness = 1e3\n");
        }
    }
    let path = dir.join(format!("tower{stages}.toml"));
    std::fs::write(&path, s).unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn the_modes_figure_is_bounded_before_any_work() {
    let dir = scratch("runs", "modes");
    let svg = dir.join("modes.svg");
    let svg = svg.to_str().unwrap();
    // 603 nodes, 200 mechanisms: the 12 lowest drawn, said on stderr
    let (out, _) = run_within(
        &[
            "statics",
            "examples/tower200.toml",
            "--modes",
            "1000",
            "--svg",
            svg,
        ],
        Duration::from_secs(120),
    );
    assert_ok(&out);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("note: --svg draws the 12 lowest of the 1000 modes of --modes"),
        "{err}"
    );
    let drawn = std::fs::read_to_string(svg).unwrap();
    assert_eq!(drawn.matches("<g class=\"panel\"").count(), 12);
    // 3003 nodes: the dense modes figure is refused at once, naming --modes
    let big = tower(&dir, 1000);
    let (out, took) = run_within(
        &["statics", &big, "--modes", "1000", "--svg", svg],
        Duration::from_secs(60),
    );
    let err = refused(&out);
    assert!(
        err.contains("modes = 1000: ")
            && err.contains("the mode-shape figure (the mechanisms of the 9009 × 9003 equilibrium matrix, 12 panels) needs an estimated")
            && err.contains("--modes 1000"),
        "{err}"
    );
    assert!(took < Duration::from_secs(15), "{took:?}");
}

#[test]
fn a_figure_size_is_checked_before_any_figure_is_computed() {
    let dir = scratch("runs", "figures");
    let out_dir = dir.join("figs");
    let o = out_dir.to_str().unwrap();
    let (out, took) = run_within(
        &["figures", "--out", o, "--size", "1x1"],
        Duration::from_secs(60),
    );
    let err = refused(&out);
    assert!(
        err.contains(
            "invalid value for --size: size = \"1x1\": each panel must be at least 72 × 72 px"
        ),
        "{err}"
    );
    assert!(took < Duration::from_secs(5), "{took:?}");
    assert!(!out_dir.exists(), "nothing written");
    // wide enough for one panel, not for Fig. 3.3's three
    let err = refused(&run(&["figures", "--out", o, "--size", "200x300"]));
    assert!(
        err.contains("(Fig. 3.3 has 3 panel(s) side by side)"),
        "{err}"
    );
    assert!(!out_dir.exists());
    let args = ["figures", "--out", o, "--only", "2.2", "--png"];
    let err = refused(&run(&[
        &args[..],
        &["--size", "10000x10000", "--dpi", "2400"],
    ]
    .concat()));
    assert!(
        err.contains("invalid value for --dpi: dpi = 2400: a PNG of 10000x10000"),
        "{err}"
    );
    // a size every chosen figure takes
    assert_ok(&run(&[&args[..], &["--size", "200x300"]].concat()));
    assert!(out_dir.join("fig_2_2.png").exists());
}
