//! Animations, progress lines in logs and the JSON of every command (issue 22, items 6–8):
//! `--animate` writes exactly round(fps × duration) frames (decoded with the `gif` crate),
//! also for `tbar roll` (rigid and full model);
//! with stderr redirected to a file, `sweep` and `figures` write progress lines with percent
//! and ETA; the JSON of `demo`, `figures`, `michell-table` and `sweep plot` parses and carries
//! its keys; `sweep plot` draws an angle-valued axis (`incline`, written `30deg`) in degrees.

use crate::common;
use common::{assert_ok, bin, run, scratch};

use std::fs::File;
use std::path::Path;
use std::process::{Output, Stdio};

/// The frames of an animated GIF: (width, height, delay) of each.
fn frames(path: &Path) -> Vec<(u16, u16, u16)> {
    common::gif_frames(path).1
}

/// Runs the binary with stderr redirected to a file (as a batch job's log); the log's text.
fn logged(args: &[&str], log: &Path) -> (Output, String) {
    let out = bin()
        .args(args)
        .stderr(Stdio::from(File::create(log).unwrap()))
        .output()
        .unwrap();
    (out, std::fs::read_to_string(log).unwrap())
}

/// Progress lines of `what` in a log: `WHAT: P % (…), elapsed …, ETA …`.
fn progress_lines<'a>(log: &'a str, what: &str) -> Vec<&'a str> {
    let head = format!("{what}: ");
    log.lines()
        .filter(|l| l.starts_with(&head) && l.contains(" % (") && l.contains(", ETA "))
        .collect()
}

fn json(out: &Output) -> serde_json::Value {
    assert_ok(out);
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

#[test]
fn simulate_animates_exactly_fps_times_duration_frames() {
    let dir = scratch("anim", "simulate");
    let gif = dir.join("drop.gif");
    let out = run(&[
        "simulate",
        "examples/prism_drop.toml",
        "--t-end",
        "0.5",
        "--animate",
        gif.to_str().unwrap(),
        "--fps",
        "4",
        "--duration",
        "2",
    ]);
    assert_ok(&out);
    let f = frames(&gif);
    assert_eq!(f.len(), 8, "round(4 × 2) frames");
    // one size for all, shown 1/4 s each
    assert!(f.iter().all(|&x| x == (f[0].0, f[0].1, 25)), "{f:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn roll_animates_the_wheel_with_the_requested_frames() {
    let dir = scratch("anim", "roll");
    let gif = dir.join("roll.gif");
    let out = run(&[
        "roll",
        "--fidelity",
        "rigid",
        "--t-end",
        "0.3",
        "--animate",
        gif.to_str().unwrap(),
        "--fps",
        "10",
        "--duration",
        "0.7",
    ]);
    assert_ok(&out);
    assert_eq!(frames(&gif).len(), 7);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The pixels of the first and the last frame of an animated GIF.
fn first_and_last(path: &Path) -> (Vec<u8>, Vec<u8>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(File::open(path).unwrap()).unwrap();
    let first = decoder.read_next_frame().unwrap().unwrap().buffer.to_vec();
    let mut last = first.clone();
    while let Some(f) = decoder.read_next_frame().unwrap() {
        last = f.buffer.to_vec();
    }
    (first, last)
}

#[test]
fn tbar_roll_animates_the_wheel_with_the_requested_frames() {
    let dir = scratch("anim", "tbar-roll");
    let gif = dir.join("tbar.gif");
    // the default (rigid) model: the T-bar's nodes placed by the rigid pose
    let out = run(&[
        "tbar",
        "roll",
        "--treads",
        "8",
        "--t-end",
        "0.5",
        "--animate",
        gif.to_str().unwrap(),
        "--fps",
        "4",
        "--duration",
        "2",
    ]);
    assert_ok(&out);
    let f = frames(&gif);
    assert_eq!(f.len(), 8, "round(4 × 2) frames");
    assert!(f
        .iter()
        .all(|&(w, h, delay)| (w, h, delay) == (f[0].0, f[0].1, 25)));
    let (first, last) = first_and_last(&gif);
    assert_ne!(first, last, "the wheel turns over the run");
    // the full model: its nodes
    let out = run(&[
        "tbar",
        "roll",
        "--fidelity",
        "full",
        "--t-end",
        "0.02",
        "--animate",
        gif.to_str().unwrap(),
        "--fps",
        "3",
        "--duration",
        "1",
    ]);
    assert_ok(&out);
    assert_eq!(frames(&gif).len(), 3);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_animation_flags_are_refused_before_the_run() {
    let dir = scratch("anim", "bad");
    let mp4 = dir.join("roll.mp4");
    let out = run(&["roll", "--animate", mp4.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("--animate") && e.contains("gif"), "{e}");
    let gif = dir.join("roll.gif");
    let out = run(&["roll", "--animate", gif.to_str().unwrap(), "--fps", "0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--fps"));
    assert!(!gif.exists());
    // only the dynamic tip-over is a run in time
    let out = run(&["tipover", "--animate", gif.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--animate"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_sweep_logs_progress_and_plots_its_incline_axis_in_degrees() {
    let dir = scratch("progress", "sweep");
    let spec = dir.join("incline.toml");
    std::fs::write(
        &spec,
        "study = \"roll\"\n[fixed]\nfidelity = \"rigid\"\nt_end = 0.3\nconvergence_check = false\n\
         [axes]\nincline = [\"20deg\", \"30deg\", \"pi/4\"]\n\
         [output]\ncolumns = [\"mean_speed\", \"mean_axle_height\"]\n",
    )
    .unwrap();
    let csv = dir.join("incline.csv");
    let (out, log) = logged(
        &[
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            csv.to_str().unwrap(),
        ],
        &dir.join("sweep.log"),
    );
    assert_ok(&out);
    let lines = progress_lines(&log, "sweep");
    assert!(!lines.is_empty(), "no progress line in the log:\n{log}");
    assert!(
        lines.last().unwrap().contains("100 % (3/3 cases)"),
        "{lines:?}"
    );
    // the incline axis, written 20deg/30deg/pi/4, plotted in degrees
    let svg = dir.join("speed.svg");
    let args = [
        "sweep",
        "plot",
        csv.to_str().unwrap(),
        "--x",
        "incline",
        "--y",
        "mean_speed",
        "--out",
        svg.to_str().unwrap(),
        "--json",
    ];
    let v = json(&run(&args));
    assert_eq!(v["x_in_degrees"], true);
    assert_eq!(v["y_in_degrees"], false);
    assert_eq!(v["points"], 3);
    assert_eq!(v["curves"][0]["points"], 3);
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("incline [deg]"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn figures_log_progress_and_list_their_files_as_json() {
    let dir = scratch("progress", "figures");
    let (out, log) = logged(
        &[
            "figures",
            "--out",
            dir.join("figs").to_str().unwrap(),
            "--quick",
            "--only",
            "4.2,5.1",
            "--json",
        ],
        &dir.join("figures.log"),
    );
    let v = json(&out);
    let lines = progress_lines(&log, "figures");
    assert!(
        lines
            .last()
            .is_some_and(|l| l.contains("100 % (2/2 figures)")),
        "{log}"
    );
    let figures = v["figures"].as_array().unwrap();
    assert_eq!(figures.len(), 2);
    for f in figures {
        assert!(Path::new(f["file"].as_str().unwrap()).is_file(), "{f}");
        assert!(f["number"].is_string() && f["description"].is_string());
    }
    assert_eq!(v["failed"].as_array().unwrap().len(), 0);
    assert!(v["warnings"].is_array());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn quiet_figures_log_nothing() {
    let dir = scratch("progress", "quiet");
    let (out, log) = logged(
        &[
            "figures",
            "--out",
            dir.join("figs").to_str().unwrap(),
            "--quick",
            "--only",
            "5.1",
            "--quiet",
        ],
        &dir.join("figures.log"),
    );
    assert_ok(&out);
    assert!(progress_lines(&log, "figures").is_empty(), "{log}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_michell_table_json_has_the_csv_columns_as_keys() {
    let v = json(&run(&["michell-table", "--json"]));
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(v["row_count"].as_u64().unwrap() as usize, rows.len());
    assert!(!rows.is_empty());
    for key in [
        "complexity",
        "delta",
        "normalized_yield_mass",
        "yield_mass_kg",
        "yield_buckling_mass_kg",
        "sign_changes_vs_planar",
    ] {
        assert!(rows[0].get(key).is_some(), "{key}: {}", rows[0]);
    }
    // the planar rows: δ = 0, no sign change against themselves
    let planar = rows.iter().find(|r| r["delta"] == 0.0).unwrap();
    assert_eq!(planar["sign_changes_vs_planar"], 0);
}

#[test]

fn the_demo_json_has_its_three_tables() {
    let v = json(&run(&["demo", "--json"]));
    let scenes = v["scenes"].as_array().unwrap();
    assert!(scenes
        .iter()
        .all(|s| s["nodes"].is_u64() && s["scene"].is_string()));
    let wheels = v["wheels"].as_array().unwrap();
    assert_eq!(wheels.len(), 4);
    assert!(wheels
        .iter()
        .all(|w| w["nodes"].is_u64() && w["prestressable"].is_boolean()));
    let rolling = v["rolling"].as_array().unwrap();
    assert!(rolling
        .iter()
        .all(|r| r["mass_kg"].is_f64() && r["valid"].is_boolean()));
}
