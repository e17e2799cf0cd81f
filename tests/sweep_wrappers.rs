//! The grid commands kept as thin wrappers give the sweeps' numbers: `michell-table` against
//! two `michell` sweeps (planar, and δ × q), `tipover --grid` against a `tipover` sweep over
//! σ × ε on real wheels, `bench work-precision` against `integrators` sweeps (steps, RHS
//! evaluations, error), and `michell --sign-map` / `--gamma-sweep` against the single-point
//! `michell --json` at the same load directions (their rows are member forces, which a
//! sweep row of scalars does not hold).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn run(args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .output()
        .expect("binary runs");
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tensegrity-wrap-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The rows of a CSV as maps column → text.
fn rows(path: &Path) -> Vec<HashMap<String, String>> {
    let mut r = csv::ReaderBuilder::new().from_path(path).unwrap();
    let header: Vec<String> = r.headers().unwrap().iter().map(str::to_string).collect();
    r.records()
        .map(|rec| {
            header
                .iter()
                .cloned()
                .zip(rec.unwrap().iter().map(str::to_string))
                .collect()
        })
        .collect()
}

fn num(row: &HashMap<String, String>, key: &str) -> f64 {
    row[key]
        .parse()
        .unwrap_or_else(|_| panic!("{key} = {:?}", row[key]))
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1e-300)
}

/// Runs a sweep of `spec` and returns its rows.
fn sweep(dir: &Path, name: &str, spec: &str) -> Vec<HashMap<String, String>> {
    let (spec_path, out) = (
        dir.join(format!("{name}.toml")),
        dir.join(format!("{name}.csv")),
    );
    std::fs::write(&spec_path, spec).unwrap();
    run(&[
        "sweep",
        spec_path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    rows(&out)
}

#[test]
fn michell_table_is_the_michell_sweep() {
    let dir = scratch("table");
    let table = dir.join("table.csv");
    run(&[
        "michell-table",
        "--max-complexity",
        "6",
        "--out",
        table.to_str().unwrap(),
    ]);
    let table = rows(&table);
    assert_eq!(table.len(), 5 * 4);
    let common = "study = \"michell\"\n[derived]\nphi = \"pi / complexity\"\n";
    let mut swept = sweep(
        &dir,
        "planar",
        &format!("{common}[fixed]\nbeta = \"pi/6\"\nplanar = true\n[axes]\ncomplexity = {{ from = 2, to = 6, step = 1 }}\n"),
    );
    swept.extend(sweep(
        &dir,
        "cyl",
        &format!("{common}[fixed]\nbeta = \"pi/6\"\n[axes]\ncylindrical = [0.1, 0.25, 0.5]\ncomplexity = {{ from = 2, to = 6, step = 1 }}\n"),
    ));
    assert_eq!(swept.len(), table.len());
    for t in &table {
        let (q, delta) = (num(t, "complexity"), num(t, "delta"));
        let s = swept
            .iter()
            .find(|s| {
                num(s, "complexity") == q
                    && s.get("cylindrical").map_or(0.0, |d| d.parse().unwrap()) == delta
            })
            .unwrap_or_else(|| panic!("no sweep row for q {q}, δ {delta}"));
        assert_eq!(s["status"], "ok");
        for (a, b) in [
            ("normalized_yield_mass", "normalized_yield_mass"),
            ("yield_mass_kg", "mass_kg.yield"),
            ("yield_buckling_mass_kg", "mass_kg.yield_buckling"),
        ] {
            assert!(
                close(num(t, a), num(s, b)),
                "q {q} δ {delta} {a}: {} vs {}",
                t[a],
                s[b]
            );
        }
    }
}

#[test]
fn tipover_grid_is_the_tipover_sweep() {
    let dir = scratch("tipover");
    let grid = dir.join("grid.csv");
    run(&[
        "tipover",
        "--grid",
        grid.to_str().unwrap(),
        "--grid-points",
        "4",
    ]);
    let grid = rows(&grid);
    assert_eq!(grid.len(), 16);
    let swept = sweep(
        &dir,
        "tip",
        "study = \"tipover\"\n[axes]\nsigma = [0.2, 0.4, 0.6, 0.8]\nepsilon = [0.25, 0.5, 0.75, 1.0]\n",
    );
    // the grid's rows are σ outer, ε inner: the sweep's case order
    assert_eq!(swept.len(), grid.len());
    let mut compared = 0;
    for (g, s) in grid.iter().zip(&swept) {
        assert!(close(num(g, "sigma"), s["sigma"].parse().unwrap()));
        assert!(close(num(g, "epsilon"), s["epsilon"].parse().unwrap()));
        if s["status"] == "ok" {
            let (a, b) = (num(g, "normalized_friction"), num(s, "normalized_friction"));
            assert!(close(a, b), "{g:?}: {a} vs {b}");
            compared += 1;
        }
    }
    assert!(compared >= 12, "only {compared} wheels built");
}

#[test]
fn sign_map_rows_are_single_point_force_densities() {
    let dir = scratch("signmap");
    let map = dir.join("map.csv");
    let truss = [
        "--complexity",
        "2",
        "--cylindrical",
        "0.25",
        "--beta",
        "pi/6",
        "--phi",
        "pi/8",
    ];
    let mut args = vec!["michell"];
    args.extend(truss);
    args.extend([
        "--sign-map",
        map.to_str().unwrap(),
        "--map-grid",
        "5x3",
        "--json",
    ]);
    run(&args);
    let map = rows(&map);
    assert_eq!(map.len(), 3 * 5 * 3);
    for r in map.iter().step_by(4) {
        let (az, po) = (r["azimuth_rad"].clone(), r["polar_rad"].clone());
        let mut single = vec!["michell"];
        single.extend(truss);
        single.extend(["--azimuth", &az, "--polar", &po, "--json"]);
        let v: serde_json::Value = serde_json::from_slice(&run(&single).stdout).unwrap();
        let j: usize = r["member"].parse().unwrap();
        let want = v["members"][j]["force_density"].as_f64().unwrap();
        let got = num(r, "force_density_N_per_m");
        assert!(
            (got - want).abs() < 1e-9 * want.abs().max(1.0),
            "{r:?}: {want}"
        );
    }
}

#[test]
fn work_precision_points_are_the_integrators_sweep() {
    // the benchmark stays serial (its points are timings); its deterministic fields equal
    // the `integrators` sweep's for the same scene, integrator and parameter
    let dir = scratch("bench");
    let bench_dir = dir.join("wp");
    run(&[
        "bench",
        "work-precision",
        "--quick",
        "--out",
        bench_dir.to_str().unwrap(),
    ]);
    let bench = rows(&bench_dir.join("work_precision.csv"));
    assert!(bench.len() >= 20, "{}", bench.len());
    let scenes = "[\"prism-oscillating\", \"double-pendulum\", \"prism-dropped\", \
                  \"prism-stiff-strings\", \"prism-damped-ground\"]";
    let mut swept = Vec::new();
    for (name, integrators, parameters) in [
        (
            "fixed",
            "[\"rk4\", \"rattle\", \"imex\", \"imex-ark\", \"rk4-flight\"]",
            "[4e-3, 1e-3]",
        ),
        ("rk45", "[\"rk45\"]", "[1e-5, 1e-8]"),
        ("sdirk", "[\"sdirk\"]", "[1e-4, 1e-6]"),
    ] {
        let spec = format!(
            "study = \"integrators\"\n[axes]\nscene = {scenes}\nintegrator = {integrators}\n\
             parameter = {parameters}\n[output]\ncolumns = [\"steps\", \"rhs_evals\", \"error\"]\n"
        );
        swept.extend(sweep(&dir, name, &spec));
    }
    // every bench point is an ok sweep row with the same counts and error; the sweep's other
    // rows are the runs the bench leaves out (explicit methods failing on stiff scenes)
    for b in &bench {
        let p = num(b, "parameter (dt [s] or rtol)");
        let s = swept
            .iter()
            .find(|s| {
                s["scene"] == b["scene"]
                    && s["integrator"] == b["integrator"]
                    && num(s, "parameter") == p
            })
            .unwrap_or_else(|| panic!("no sweep row for {b:?}"));
        assert_eq!(s["status"], "ok", "{s:?}");
        assert_eq!(s["steps"], b["steps"], "{b:?}");
        assert_eq!(s["rhs_evals"], b["rhs_evals"], "{b:?}");
        let (e1, e2) = (num(b, "error [m]"), num(s, "error"));
        assert!((e1 - e2).abs() <= 1e-3 * e1.max(e2), "{b:?}: {e2}");
    }
    let ok = swept.iter().filter(|s| s["status"] == "ok").count();
    assert_eq!(ok, bench.len());
}

#[test]
fn gamma_sweep_rows_are_single_point_forces_with_extra_strings() {
    let dir = scratch("gamma");
    let path = dir.join("gamma.csv");
    let truss = [
        "--complexity",
        "2",
        "--cylindrical",
        "0.25",
        "--beta",
        "pi/6",
        "--phi",
        "pi/8",
        "--extra-strings",
        "500",
    ];
    let mut args = vec!["michell"];
    args.extend(truss);
    args.extend(["--gamma-sweep", path.to_str().unwrap(), "--json"]);
    run(&args);
    let rows = rows(&path);
    assert_eq!(rows.len(), 721 * 15);
    // three load directions of the sweep: every base member and extra string of the row
    for i in [0usize, 200, 500] {
        let gamma = rows[i * 15]["polar_rad"].clone();
        let mut single = vec!["michell"];
        single.extend(truss);
        single.extend(["--polar", &gamma, "--json"]);
        let v: serde_json::Value = serde_json::from_slice(&run(&single).stdout).unwrap();
        for r in &rows[i * 15..(i + 1) * 15] {
            assert_eq!(r["polar_rad"], gamma);
            let j: usize = r["member"].parse().unwrap();
            let list = if r["kind"] == "base" {
                "members"
            } else {
                "extra_strings"
            };
            let want = v[list][j]["force"].as_f64().unwrap();
            let got = num(r, "force_N");
            assert!((got - want).abs() < 1e-9 * 1000.0, "{r:?}: {want}");
        }
    }
}
