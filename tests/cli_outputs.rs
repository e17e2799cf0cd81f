//! Outputs of `tensegrity simulate` that cannot be lost or corrupted: paths checked before
//! the run, every recorded quantity in the CSV, SIGINT keeping the rows so far as a complete
//! file marked incomplete, and kill -9 never leaving a partial file at the requested path.

use crate::common;

use common::{bin, listing, NO_LIMITS};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

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

/// Runs `args` past the resource guard with `--out` at a path under a missing directory;
/// the exit code, stderr and the time it took.
fn unwritable_out(args: &[&str], out: &str) -> (Option<i32>, String, Duration) {
    let start = Instant::now();
    let o = bin()
        .args(args)
        .args(["--out", out])
        .args(NO_LIMITS)
        .output()
        .unwrap();
    let elapsed = start.elapsed();
    eprintln!(
        "{args:?} --out {out}: exit {:?} after {elapsed:.2?}",
        o.status.code()
    );
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        elapsed,
    )
}

#[test]
fn fig_rolling_refuses_an_unwritable_figure_before_rolling() {
    // four wheels rolled for 1000 s each: hours, unless the path is checked first
    let (code, stderr, elapsed) =
        unwritable_out(&["fig-rolling", "--t-end", "1000"], "no/such/dir/x.svg");
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("no/such/dir/x.svg"), "{stderr}");
    assert!(
        stderr.contains("--out"),
        "the message names the flag: {stderr}"
    );
    // no wheel rolled: a refusal (well under 0.2 s when the machine is idle; the bound of
    // the other refusals allows a loaded machine)
    assert!(elapsed < Duration::from_secs(5), "{elapsed:?}");
    assert!(!Path::new("no/such/dir").exists());
}

#[test]
fn bench_work_precision_refuses_an_unwritable_directory_before_measuring() {
    // the full study (every integrator on five scenes, timed) takes minutes
    let (code, stderr, elapsed) = unwritable_out(&["bench", "work-precision"], "no/such/dir/wp");
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("no/such/dir/wp"), "{stderr}");
    assert!(
        stderr.contains("--out"),
        "the message names the flag: {stderr}"
    );
    assert!(elapsed < Duration::from_secs(5), "{elapsed:?}");
    assert!(!Path::new("no/such/dir").exists());
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
    assert!(frame.contains(r#"Name="velocity [m/s]""#) && frame.contains(r#"Name="force [N]""#));
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

/// Every output flag of every command whose outputs are io sinks, with a command line whose
/// work takes minutes to hours (`{}` stands for the output path) and whether the output is a
/// directory.
fn output_flags(dir: &Path) -> Vec<(&'static str, Vec<String>, bool)> {
    let spec = dir.join("big.toml");
    std::fs::write(
        &spec,
        "study = \"toroid\"\n[axes]\nsides = { from = 8, to = 5007, step = 1 }\n",
    )
    .unwrap();
    let spec = spec.to_string_lossy().into_owned();
    let sim = "simulate examples/double_pendulum.toml --t-end 1e6 --dt 1e-4";
    let michell = "michell --complexity 6 --cylindrical 0.25 --beta pi/6 --phi pi/8";
    let tbar = "tbar --complexity 3 --beta pi/6 --phi pi/16 --cylindrical 0.1 --wheel --rim body";
    let roll = "roll --fidelity full --t-end 1e4";
    let rows: Vec<(&str, String, bool)> = vec![
        ("simulate --out", format!("{sim} --out {{}}"), false),
        ("simulate --vtk", format!("{sim} --vtk {{}}"), true),
        ("simulate --animate", format!("{sim} --animate {{}}"), false),
        ("roll --animate", format!("{roll} --animate {{}}"), false),
        (
            "solve --out",
            "solve examples/von_mises.toml --target 2 --out {}".into(),
            false,
        ),
        (
            "solve --svg",
            "solve examples/von_mises.toml --target 2 --svg {}".into(),
            false,
        ),
        (
            "solve --vtk",
            "solve examples/von_mises.toml --target 2 --vtk {}".into(),
            true,
        ),
        (
            "tipover --dynamic --animate",
            "tipover --dynamic --hold 1e4 --animate {}".into(),
            false,
        ),
        (
            "bench work-precision --out",
            "bench work-precision --out {}".into(),
            true,
        ),
        ("sweep --out", format!("sweep {spec} --out {{}}"), false),
        (
            "sweep merge --out",
            format!("sweep merge {spec} --out {{}}"),
            false,
        ),
        (
            "sweep plot --out",
            format!("sweep plot {spec} --x a --y b --out {{}}"),
            false,
        ),
        (
            "michell --sign-map",
            format!("{michell} --map-grid 4000x2000 --sign-map {{}}"),
            false,
        ),
        (
            "michell --gamma-sweep",
            format!("{michell} --extra-strings 100 --gamma-sweep {{}}"),
            false,
        ),
        (
            "michell-table --out",
            "michell-table --max-complexity 60 --out {}".into(),
            false,
        ),
        (
            "michell-table --svg",
            "michell-table --max-complexity 60 --svg {}".into(),
            false,
        ),
        (
            "tipover --grid",
            "tipover --grid-points 3000 --grid {}".into(),
            false,
        ),
        (
            "toroid --export-scene",
            "toroid --sides 4000 --export-scene {}".into(),
            false,
        ),
        (
            "tbar --export-scene",
            format!("{tbar} --export-scene {{}}"),
            false,
        ),
        ("tbar --vtk", format!("{tbar} --vtk {{}}"), false),
        ("tbar --svg", format!("{tbar} --svg {{}}"), false),
        ("figures --out", "figures --out {}".into(), true),
        ("roll --out", format!("{roll} --out {{}}"), false),
        ("roll --vtk", format!("{roll} --vtk {{}}"), true),
        ("roll --svg", format!("{roll} --svg {{}}"), false),
        (
            "tipover --dynamic --out",
            "tipover --dynamic --hold 1e4 --out {}".into(),
            false,
        ),
        (
            "tipover --rolling --out",
            "tipover --rolling --t-end 1e4 --out {}".into(),
            false,
        ),
        (
            "tbar roll --out",
            "tbar roll --fidelity full --t-end 100 --out {}".into(),
            false,
        ),
        // a grid of 560 400 members: seconds of form-finding before the scene or figure
        (
            "formfind --out",
            "formfind --builtin grid:200 --out {}".into(),
            false,
        ),
        (
            "formfind --svg",
            "formfind --builtin grid:200 --svg {}".into(),
            false,
        ),
        // four wheels rolled for 1000 s each: hours, unless the path is checked first
        (
            "fig-rolling --out",
            "fig-rolling --t-end 1000 --out {}".into(),
            false,
        ),
    ];
    rows.into_iter()
        .map(|(name, line, is_dir)| {
            let args = line.split(' ').map(str::to_string).collect();
            (name, args, is_dir)
        })
        .collect()
}

/// Unwritable places: a missing directory, a path through a regular file, and (unless this
/// process can write anywhere, as root can) a read-only directory.
#[cfg(unix)]
fn unwritable_parents(dir: &Path) -> Vec<PathBuf> {
    use std::os::unix::fs::PermissionsExt;
    let blocker = dir.join("blocker");
    std::fs::write(&blocker, "a file, not a directory\n").unwrap();
    let ro = dir.join("read-only");
    std::fs::create_dir(&ro).unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    let mut parents = vec![PathBuf::from("/nonexistent-dir"), blocker];
    if std::fs::write(ro.join("probe"), "").is_err() {
        parents.push(ro);
    } else {
        let _ = std::fs::remove_file(ro.join("probe"));
        eprintln!("note: this process writes into read-only directories (root): case skipped");
    }
    parents
}

#[cfg(unix)]
#[test]
fn every_output_flag_refuses_an_unwritable_path_before_any_work() {
    let dir = scratch("unwritable");
    let flags = output_flags(&dir);
    let parents = unwritable_parents(&dir);
    let before = listing(&dir);
    for (name, args, is_dir) in &flags {
        for parent in &parents {
            let bad = parent.join(if *is_dir { "out-dir" } else { "x.svg" });
            let figure =
                name.ends_with("--svg") || name.contains("plot") || name.starts_with("fig-");
            let bad = if name.ends_with("--animate") {
                bad.with_extension("gif")
            } else if !is_dir && !figure {
                bad.with_extension("csv")
            } else {
                bad
            };
            let bad_text = bad.to_string_lossy().into_owned();
            let args: Vec<&str> = args
                .iter()
                .map(|a| {
                    if a == "{}" {
                        bad_text.as_str()
                    } else {
                        a.as_str()
                    }
                })
                .collect();
            let start = Instant::now();
            let out = bin().args(&args).args(NO_LIMITS).output().unwrap();
            let elapsed = start.elapsed();
            let stderr = String::from_utf8_lossy(&out.stderr);
            // a diagnostic, not the pass condition: the work behind each line takes minutes
            eprintln!(
                "{name} {bad_text}: exit {:?} after {elapsed:.2?}",
                out.status.code()
            );
            assert_eq!(out.status.code(), Some(2), "{name} {bad_text}: {stderr}");
            assert!(
                stderr.contains(&bad_text),
                "{name}: the message names the path: {stderr}"
            );
            assert!(!bad.exists(), "{name}: nothing at {bad_text}");
            assert_eq!(
                listing(&dir),
                before,
                "{name}: no output, temporary or lock file left"
            );
        }
    }
    assert!(!Path::new("/nonexistent-dir").exists());
}

/// `simulate --out CSV --vtk DIR` started on a run of hours; returns once the CSV has rows
/// and the series its first `series.pvd`.
fn long_run_with_vtk(dir: &Path, csv: &Path, vtk: &Path) -> std::process::Child {
    let child = bin()
        .args([
            "simulate",
            "examples/double_pendulum.toml",
            "--t-end",
            "5e4",
            "--integrator",
            "rk4",
            "--dt",
            "1e-3",
            "--output-interval",
            "1e-2",
        ])
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
    let tmp = dir.join(".traj.csv.tmp");
    let start = Instant::now();
    while std::fs::metadata(&tmp).map_or(0, |m| m.len()) < 20_000
        || !vtk.join("series.pvd").exists()
    {
        assert!(start.elapsed() < Duration::from_secs(60), "no progress");
        std::thread::sleep(Duration::from_millis(20));
    }
    child
}

#[cfg(unix)]
#[test]
fn sigint_during_simulate_keeps_a_complete_csv_and_a_readable_series() {
    let dir = scratch("sigint-vtk");
    let (csv, vtk) = (dir.join("traj.csv"), dir.join("vtk"));
    let child = long_run_with_vtk(&dir, &csv, &vtk);
    let pid = child.id().to_string();
    assert!(Command::new("kill")
        .args(["-INT", &pid])
        .status()
        .unwrap()
        .success());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!(lines
        .last()
        .unwrap()
        .starts_with("# incomplete: interrupted at t = "));
    let width = lines[0].split(',').count();
    assert!(lines[1..lines.len() - 1]
        .iter()
        .all(|l| l.split(',').count() == width));
    // the series: every frame named by series.pvd exists and is whole
    let pvd = std::fs::read_to_string(vtk.join("series.pvd")).unwrap();
    assert!(pvd.trim_end().ends_with("</VTKFile>") && pvd.contains("<!-- incomplete: "));
    let frames: Vec<&str> = pvd
        .split("file=\"")
        .skip(1)
        .map(|s| s.split('"').next().unwrap())
        .collect();
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
        ["traj.csv", "vtk"],
        "no temporary or lock file left"
    );
}

#[cfg(unix)]
#[test]
fn a_second_run_writing_the_same_output_is_refused() {
    let dir = scratch("two-writers");
    let (csv, vtk) = (dir.join("traj.csv"), dir.join("vtk"));
    let first = long_run_with_vtk(&dir, &csv, &vtk);
    let pid = first.id().to_string();
    for flag in ["--out", "--vtk"] {
        let path = if flag == "--out" { &csv } else { &vtk };
        let second = bin()
            .args(["simulate", "examples/double_pendulum.toml", "--t-end", "1"])
            .args([flag, path.to_str().unwrap()])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&second.stderr);
        assert_eq!(second.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains("another run") && stderr.contains(&format!("pid {pid}")),
            "{stderr}"
        );
        assert!(
            stderr.contains(flag) && stderr.contains(path.to_str().unwrap()),
            "{stderr}"
        );
    }
    Command::new("kill").args(["-INT", &pid]).status().unwrap();
    let out = first.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(130));
    // the first run's rows, under its own (interrupted) message
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.lines().last().unwrap().starts_with("# incomplete: "));
}

#[cfg(unix)]
#[test]
fn sigint_during_a_command_that_does_not_poll_leaves_no_partial_output() {
    let dir = scratch("sigint-bench");
    let out_dir = dir.join("wp");
    let child = bin()
        .args([
            "bench",
            "work-precision",
            "--out",
            out_dir.to_str().unwrap(),
        ])
        .args(NO_LIMITS)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !out_dir.join(".work_precision.svg.tmp").exists() {
        assert!(start.elapsed() < Duration::from_secs(60), "no progress");
        std::thread::sleep(Duration::from_millis(10));
    }
    Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert_eq!(
        out.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("interrupted"));
    // the directory this run created, its temporary and lock files: all gone
    assert!(listing(&dir).is_empty(), "{:?}", listing(&dir));
}
