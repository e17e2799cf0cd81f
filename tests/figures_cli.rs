//! `tensegrity figures --quick`: every figure of the list is written as a valid SVG with
//! data; the sweep-driven figures' data match closed forms; the structure drawings hold one
//! polyline per member of the library's structure; a figure that cannot be written is
//! reported by name and the others are still written.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const EXPECTED: [&str; 30] = [
    "2_2", "3_1", "3_2", "3_3", "3_8", "3_9", "3_10", "3_11", "3_13", "4_1", "4_2", "4_3", "4_4",
    "4_6", "4_7", "4_8", "4_9", "4_10", "4_11", "4_12", "4_13", "4_14", "4_15", "4_16", "4_18",
    "4_19", "4_20", "5_1", "5_2", "5_3",
];

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .output()
        .expect("binary runs")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tensegrity-figs-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// (header, rows) of a CSV.
fn table(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::ReaderBuilder::new().from_path(path).unwrap();
    let header = r.headers().unwrap().iter().map(str::to_string).collect();
    let rows = r
        .records()
        .map(|rec| rec.unwrap().iter().map(str::to_string).collect())
        .collect();
    (header, rows)
}

fn column(header: &[String], row: &[String], name: &str) -> f64 {
    let i = header.iter().position(|h| h == name).unwrap();
    row[i].parse().unwrap()
}

fn members_of_wheel(sides: &str, stabilize: &str) -> usize {
    let out = run(&[
        "toroid",
        "--sides",
        sides,
        "--stabilize",
        stabilize,
        "--json",
    ]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    (v["bars"].as_u64().unwrap() + v["strings"].as_u64().unwrap()) as usize
}

#[test]
fn quick_figures_are_all_written_with_their_data() {
    let dir = scratch("all");
    let out = run(&["figures", "--out", dir.to_str().unwrap(), "--quick"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for name in EXPECTED {
        let path = dir.join(format!("fig_{name}.svg"));
        assert!(
            stdout.contains(&format!("fig_{name}.svg")),
            "{name} not listed"
        );
        let svg = std::fs::read_to_string(&path).unwrap_or_else(|_| panic!("{name} missing"));
        assert!(
            svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"),
            "{name}"
        );
        let lines = svg.matches("<polyline").count();
        assert!(lines >= 1, "{name} has no data");
        // every polyline has at least two finite points
        for pl in svg.split("<polyline").skip(1) {
            let points = pl
                .split("points=\"")
                .nth(1)
                .unwrap()
                .split('"')
                .next()
                .unwrap();
            let pts: Vec<&str> = points.split_whitespace().collect();
            assert!(pts.len() >= 2, "{name}: {points}");
            assert!(!points.contains("NaN") && !points.contains("inf"), "{name}");
        }
    }
    // Fig. 3.3: one polyline per member of the three wheels (and the legend draws none)
    let fig33 = std::fs::read_to_string(dir.join("fig_3_3.svg")).unwrap();
    let members: usize = ["spokes,inner", "spokes,outer", "inner,outer"]
        .iter()
        .map(|o| members_of_wheel("8", o))
        .sum();
    assert_eq!(fig33.matches("<polyline").count(), members);

    // the rolling figures flag a run outside its model's assumptions exactly when the
    // single-point `roll` says its net normal force goes negative
    let roll = run(&[
        "roll",
        "--fidelity",
        "rigid",
        "--t-end",
        "2",
        "--sides",
        "8",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&roll.stdout).unwrap();
    let lifts = v["min_normal_force"].as_f64().unwrap() < 0.0;
    assert_eq!(
        stdout.contains("warning: Fig. 3.10") && stdout.contains("n = 8 ("),
        lifts
    );
    let fig310 = std::fs::read_to_string(dir.join("fig_3_10.svg")).unwrap();
    assert_eq!(fig310.contains("lifts off"), lifts);
    // and, when none lifts off, a run that is not valid (e.g. not converged) is said so in
    // the title and in a warning naming its wheel, never drawn without a word
    let invalid: Vec<usize> = [8usize, 12, 16, 24]
        .into_iter()
        .filter(|n| {
            let out = run(&[
                "roll",
                "--fidelity",
                "rigid",
                "--t-end",
                "2",
                "--sides",
                &n.to_string(),
                "--json",
            ]);
            let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            !v["valid"].as_bool().unwrap()
        })
        .collect();
    if !lifts {
        assert_eq!(fig310.contains("a run is not valid"), !invalid.is_empty());
        for n in &invalid {
            assert!(stdout.contains(&format!("n = {n}, rigid")), "{n}: {stdout}");
        }
    }

    // Fig. 3.13, a tipover sweep over real wheels: F_f/F_e = −(σ + ε)/(1 − σ) (eq. 3.29)
    let (h, rows) = table(&dir.join("data/fig_3_13.csv"));
    assert_eq!(rows.len(), 4 * 9);
    for r in &rows {
        let (s, e) = (column(&h, r, "sigma"), column(&h, r, "epsilon"));
        let f = column(&h, r, "normalized_friction");
        assert!((f + (s + e) / (1.0 - s)).abs() < 1e-12, "σ {s} ε {e}: {f}");
    }
    // Fig. 4.18, planar: Σ|q|l²/(w0 r0) = q sin φ / (sin β sin(β + φ)) with φ = π/q, and
    // 1.354 kg of steel at q = 2 (ERRATA 4.4)
    let (h, rows) = table(&dir.join("data/fig_4_18_planar.csv"));
    assert_eq!(rows.len(), 7);
    let beta = std::f64::consts::FRAC_PI_6;
    for r in &rows {
        let q = column(&h, r, "complexity");
        let phi = std::f64::consts::PI / q;
        let closed = q * phi.sin() / (beta.sin() * (beta + phi).sin());
        assert!((column(&h, r, "normalized_yield_mass") - closed).abs() < 1e-9 * closed);
    }
    assert!((column(&h, &rows[0], "mass_kg.yield_buckling") - 1.354).abs() < 5e-4);
    let (_, rows) = table(&dir.join("data/fig_4_18.csv"));
    assert_eq!(rows.len(), 3 * 7);
    every_figure_has_its_data_and_an_index_entry(&dir);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Every figure's data beside it (a header with units, rows), and an entry in index.json
/// (and index.md) naming its files, the command that reproduces it and what differs from
/// the thesis; Fig. 3.8's nodes on the slope and Fig. 3.9's n = 100 margin in their data.
fn every_figure_has_its_data_and_an_index_entry(dir: &Path) {
    let index: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("index.json")).unwrap()).unwrap();
    let md = std::fs::read_to_string(dir.join("index.md")).unwrap();
    let entries = index["figures"].as_array().unwrap();
    assert_eq!(entries.len(), EXPECTED.len());
    for (name, e) in EXPECTED.iter().zip(entries) {
        let number = name.replace('_', ".");
        assert_eq!(e["figure"], number.as_str());
        assert_eq!(e["status"], "written");
        let files: Vec<&str> = e["files"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f.as_str().unwrap())
            .collect();
        assert_eq!(
            files,
            [format!("fig_{name}.svg"), format!("fig_{name}.csv")]
        );
        for f in &files {
            assert!(dir.join(f).is_file(), "{f}");
        }
        let (header, rows) = table(&dir.join(files[1]));
        assert!(!rows.is_empty(), "{name}: no data");
        assert!(
            header.iter().any(|h| h.ends_with(']')),
            "{name}: no unit in {header:?}"
        );
        let command = e["command"].as_str().unwrap();
        assert!(
            command.contains(&format!("--only {number} --quick")),
            "{command}"
        );
        assert!(!e["title"].as_str().unwrap().is_empty());
        assert!(!e["differs_from_thesis"].as_str().unwrap().is_empty());
        assert!(
            md.contains(&format!("| {number} | ")),
            "{number} not in index.md"
        );
    }
    // Fig. 3.8 (quick: the rigid model): every node on or above the slope
    let (h, rows) = table(&dir.join("fig_3_8.csv"));
    let item = h.iter().position(|c| c == "item").unwrap();
    for r in rows.iter().filter(|r| r[item] == "node") {
        let pen = column(&h, r, "max_penetration [m]");
        assert!(column(&h, r, "z [m]") >= -pen - 1e-12, "{r:?}");
    }
    // Fig. 3.9: the n = 100 wheel (D = 0.8/n) is prestressable
    let (h, rows) = table(&dir.join("fig_3_9.csv"));
    let n100: Vec<&Vec<String>> = rows
        .iter()
        .filter(|r| column(&h, r, "sides") == 100.0)
        .collect();
    assert!(!n100.is_empty());
    assert!(n100
        .iter()
        .all(|r| column(&h, r, "prestress_margin") > 1e-3));
}

#[test]
fn a_figure_that_cannot_be_written_is_named_and_the_others_are_written() {
    let dir = scratch("fail");
    // a directory where the figure's file should go
    std::fs::create_dir_all(dir.join("fig_4_4.svg")).unwrap();
    let out = run(&[
        "figures",
        "--out",
        dir.to_str().unwrap(),
        "--quick",
        "--only",
        "4.2,4.4,5.1",
    ]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("fig_4_4.svg"), "{stderr}");
    assert!(dir.join("fig_4_2.svg").is_file() && dir.join("fig_5_1.svg").is_file());
    let out = run(&["figures", "--out", dir.to_str().unwrap(), "--only", "9.9"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("no figure 9.9"));
    let _ = std::fs::remove_dir_all(&dir);
}
