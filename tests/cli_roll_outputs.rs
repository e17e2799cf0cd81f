//! Outputs of the rolling commands (`roll`, `tipover --dynamic`, `tipover --rolling`) as io
//! sinks: every output path is checked before the run (a bad one: exit 2 at once, naming the
//! flag and the path), and SIGINT during `roll --out CSV --vtk DIR` keeps the rows so far as a
//! complete CSV with its `# incomplete` trailer and a `series.pvd` listing only frames that
//! exist (exit 130). `tbar roll --out` (one row per tread count) is opened before its runs.

use crate::common;

use common::{bin, listing, NO_LIMITS};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tensegrity-roll-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every output flag of the rolling commands, with a command line of a long run.
fn output_flags() -> Vec<(&'static str, Vec<&'static str>)> {
    let roll = ["roll", "--fidelity", "full", "--t-end", "100"];
    let mut rows: Vec<(&str, Vec<&str>)> = ["--out", "--vtk", "--svg"]
        .into_iter()
        .map(|flag| (flag, roll.to_vec()))
        .collect();
    rows.push(("--out", vec!["tipover", "--dynamic"]));
    rows.push(("--out", vec!["tipover", "--rolling", "--t-end", "100"]));
    rows.push((
        "--out",
        vec!["tbar", "roll", "--fidelity", "full", "--t-end", "100"],
    ));
    rows
}

#[test]
fn every_output_flag_of_the_rolling_commands_refuses_a_bad_path_at_once() {
    let bad = "no/such/dir/x";
    assert!(!Path::new(env!("CARGO_MANIFEST_DIR")).join("no").exists());
    for (flag, line) in output_flags() {
        let start = Instant::now();
        let out = bin()
            .args(&line)
            .args([flag, bad])
            .args(NO_LIMITS)
            .output()
            .unwrap();
        let elapsed = start.elapsed();
        let stderr = String::from_utf8_lossy(&out.stderr);
        let name = format!("{} {flag}", line.join(" "));
        assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
        assert!(
            stderr.contains(flag) && stderr.contains(bad),
            "{name}: {stderr}"
        );
        assert!(
            elapsed < Duration::from_millis(200),
            "{name}: refused after {elapsed:?}, not before the run"
        );
    }
    assert!(!Path::new(env!("CARGO_MANIFEST_DIR")).join("no").exists());
}

/// The files a `series.pvd` lists, checked to be a VTK collection.
fn pvd_files(pvd: &str) -> Vec<String> {
    let doc = roxmltree::Document::parse(pvd).expect("series.pvd parses");
    assert_eq!(doc.root_element().tag_name().name(), "VTKFile");
    doc.descendants()
        .filter(|n| n.has_tag_name("DataSet"))
        .map(|n| n.attribute("file").expect("a file").to_string())
        .collect()
}

#[cfg(unix)]
#[test]
fn sigint_during_roll_keeps_a_complete_csv_and_a_readable_series() {
    let dir = scratch("sigint");
    let (csv, vtk) = (dir.join("r.csv"), dir.join("vtk"));
    let child = bin()
        .args(["roll", "--fidelity", "rigid", "--t-end", "1e4"])
        .args([
            "--out",
            csv.to_str().unwrap(),
            "--vtk",
            vtk.to_str().unwrap(),
        ])
        .args(NO_LIMITS)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    std::thread::sleep(Duration::from_millis(1500));
    while !vtk.join("series.pvd").exists() || !dir.join(".r.csv.tmp").exists() {
        assert!(start.elapsed() < Duration::from_secs(60), "no progress");
        std::thread::sleep(Duration::from_millis(20));
    }
    let pid = child.id().to_string();
    assert!(Command::new("kill")
        .args(["-INT", &pid])
        .status()
        .unwrap()
        .success());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    // the CSV: its header, whole rows, and the trailer last
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        "t,axle_s,axle_h,omega,pivot_m,normal_N,tangential_N,energy_J,slip_m_s"
    );
    assert!(
        lines
            .last()
            .unwrap()
            .starts_with("# incomplete: interrupted at t = "),
        "{:?}",
        lines.last()
    );
    let rows = &lines[1..lines.len() - 1];
    assert!(rows.len() > 10, "{} rows", rows.len());
    for row in rows {
        let fields: Vec<&str> = row.split(',').collect();
        assert_eq!(fields.len(), 9, "{row}");
        assert!(fields.iter().all(|f| f.parse::<f64>().is_ok()), "{row}");
    }
    // the series: series.pvd parses and lists only (and all) the frames that exist, each whole
    let pvd = std::fs::read_to_string(vtk.join("series.pvd")).unwrap();
    assert!(pvd.contains("<!-- incomplete: "));
    let frames = pvd_files(&pvd);
    assert!(frames.len() > 1);
    for f in &frames {
        let frame = std::fs::read_to_string(vtk.join(f)).unwrap();
        assert!(frame.trim_end().ends_with("</VTKFile>"), "{f} is whole");
    }
    assert_eq!(
        listing(&vtk).len(),
        frames.len() + 1,
        "series.pvd and its frames only"
    );
    assert_eq!(
        listing(&dir),
        ["r.csv", "vtk"],
        "no temporary or lock file left"
    );
}
