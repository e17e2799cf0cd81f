//! Outputs of `tensegrity simulate` that cannot be lost or corrupted: paths checked before
//! the run, every recorded quantity in the CSV, SIGINT keeping the rows so far as a complete
//! file marked incomplete, and kill -9 never leaving a partial file at the requested path.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_tensegrity"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tensegrity-out-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A 2 m, 1 kg bar falling freely from rest under g = 10 m/s² for 0.5 s.
const FALLING_BAR: &str = r#"
nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]
[[bars]]
nodes = [0, 1]
mass = 1.0
[gravity]
acceleration = [0.0, 0.0, -10.0]
[simulation]
t_end = 0.5
integrator = "rk4"
dt = 1e-3
output_interval = 0.25
record = ["nodes", "velocities", "member_forces", "energy"]
"#;

#[test]
fn an_unwritable_output_fails_before_the_run() {
    let start = Instant::now();
    let out = bin()
        .args([
            "simulate",
            "examples/double_pendulum.toml",
            "--t-end",
            "1e6",
        ])
        .args(["--out", "no/such/dir/traj.csv"])
        // past the resource guard: the point is that the path is checked before the work
        .args([
            "--max-work",
            "1e12",
            "--max-output",
            "1000Ti",
            "--max-memory",
            "1000Ti",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no/such/dir/traj.csv"));
    // 10⁹ steps would take minutes: the path was checked first
    assert!(start.elapsed() < Duration::from_secs(20));
}

#[test]
fn every_recorded_quantity_is_in_the_csv_with_its_closed_form() {
    let dir = scratch("record");
    let scene = dir.join("bar.toml");
    std::fs::write(&scene, FALLING_BAR).unwrap();
    let csv = dir.join("traj.csv");
    let vtk = dir.join("vtk");
    let out = bin()
        .args([
            "simulate",
            scene.to_str().unwrap(),
            "--out",
            csv.to_str().unwrap(),
            "--vtk",
            vtk.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("{name} in {header:?}"))
    };
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 3); // t = 0, 0.25, 0.5
    let last = &rows[2];
    let t = last[col("t [s]")];
    assert_eq!(t, 0.5);
    // free fall: z = −g t²/2, v_z = −g t, no force in the bar, energy conserved
    assert!((last[col("n1_z [m]")] + 5.0 * t * t).abs() < 1e-9);
    assert!((last[col("v1_z [m/s]")] + 10.0 * t).abs() < 1e-9);
    assert!(last[col("bar0_force [N]")].abs() < 1e-9);
    assert!(last[col("bar0_force_density [N/m]")].abs() < 1e-9);
    assert!((last[col("kinetic_energy [J]")] - 0.5 * 1.0 * (10.0 * t).powi(2)).abs() < 1e-8);
    assert!((last[col("total_energy [J]")] - rows[0][col("total_energy [J]")]).abs() < 1e-8);
    // the VTK frames carry the recorded velocities (point data) and forces (cell data)
    let frame = std::fs::read_to_string(vtk.join("frame_00002.vtu")).unwrap();
    assert!(frame.contains(r#"Name="velocity""#) && frame.contains(r#"Name="force""#));
}

/// Starts a run that would take hours and waits until its CSV has rows.
fn long_run(dir: &Path) -> (std::process::Child, PathBuf) {
    let csv = dir.join("traj.csv");
    let child = bin()
        .args([
            "simulate",
            "examples/double_pendulum.toml",
            "--t-end",
            "5e4",
        ])
        .args([
            "--integrator",
            "rk4",
            "--dt",
            "1e-3",
            "--output-interval",
            "1e-3",
        ])
        .args(["--out", csv.to_str().unwrap()])
        // hours of work and 10 GB of CSV on purpose: past the resource guard
        .args(["--max-work", "1e12", "--max-output", "1000Ti"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let tmp = dir.join(".traj.csv.tmp");
    let start = Instant::now();
    while std::fs::metadata(&tmp).map_or(0, |m| m.len()) < 100_000 {
        assert!(start.elapsed() < Duration::from_secs(60), "no progress");
        std::thread::sleep(Duration::from_millis(20));
    }
    (child, csv)
}

#[cfg(unix)]
#[test]
fn sigint_keeps_the_rows_so_far_as_a_complete_file_marked_incomplete() {
    let dir = scratch("sigint");
    let (child, csv) = long_run(&dir);
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    assert_eq!(
        out.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines
        .last()
        .unwrap()
        .starts_with("# incomplete: interrupted at t = "));
    let width = lines[0].split(',').count();
    for l in &lines[1..lines.len() - 1] {
        assert_eq!(l.split(',').count(), width, "every row whole");
    }
    assert!(lines.len() > 10);
    assert!(!dir.join(".traj.csv.tmp").exists());
}

#[cfg(unix)]
#[test]
fn kill_9_never_leaves_a_partial_file_at_the_requested_path() {
    let dir = scratch("kill9");
    let (mut child, csv) = long_run(&dir);
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    assert!(!csv.exists(), "the requested path holds no partial file");
}

#[cfg(unix)]
#[test]
fn sigint_stops_a_run_between_samples_too() {
    let child = bin()
        .args([
            "simulate",
            "examples/double_pendulum.toml",
            "--t-end",
            "5e4",
        ])
        .args(["--integrator", "rk4", "--dt", "1e-3"])
        // minutes of work on purpose: past the resource guard
        .args(["--max-work", "1e12"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_millis(500));
    let start = Instant::now();
    Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130));
    assert!(String::from_utf8_lossy(&out.stderr).contains("interrupted at t = "));
    assert!(start.elapsed() < Duration::from_secs(10), "stopped at once");
}
