//! The sweep contract end to end on the library: rows equal the single-point reports,
//! byte-identical files for any thread count, shards merged = one run, interrupted + resumed
//! = one run, and an invalid case is one error row.

use std::path::{Path, PathBuf};
use sweeps::table::{lookup, scalar};
use sweeps::{merge, run, RunOptions, Shard, Silent, Spec};

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

fn sweep(spec: &Spec, out: &Path, opts: RunOptions) -> sweeps::Summary {
    run(spec, out, &opts, &mut Silent).unwrap()
}

fn threads(n: usize) -> RunOptions {
    RunOptions {
        threads: Some(n),
        ..Default::default()
    }
}

/// Rows as field lists (header first).
fn rows(path: &Path) -> Vec<Vec<String>> {
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_path(path)
        .unwrap();
    r.records()
        .map(|rec| rec.unwrap().iter().map(str::to_string).collect())
        .collect()
}

const TOROID: &str = r#"
study = "toroid"
[fixed]
outer_tread = 0.4
[axes]
sides = [8, 12, 2, 16]
stabilize = ["spokes,inner", "spokes,outer", "inner,outer"]
"#;

/// Cheap cases (wheel mass and a closed form), for the exhaustive cut-and-resume test.
const TIPOVER: &str = r#"
study = "tipover"
[fixed]
outer_radius = 1.0
[axes]
sides = [6, 8]
sigma = { from = 0.2, to = 0.8, step = 0.2 }
epsilon = [0.25, 0.5, "x"]
"#;

#[test]
fn every_row_is_the_single_point_report() {
    let dir = tmp();
    let out = dir.path().join("toroid.csv");
    let spec = Spec::parse(TOROID).unwrap();
    let s = sweep(&spec, &out, threads(2));
    assert_eq!((s.total_cases, s.written, s.errors), (12, 12, 3));
    let table = rows(&out);
    let header = &table[0];
    assert_eq!(header[..3], ["case", "sides", "stabilize"]);
    assert_eq!(header[header.len() - 2..], ["status", "message"]);
    for (id, row) in table[1..].iter().enumerate() {
        assert_eq!(row[0], id.to_string());
        // the request built here by hand, independently of the sweep's mapping
        let sides: usize = row[1].parse().unwrap();
        let request = toroid::ToroidRequest {
            wheel: toroid::WheelSpec {
                stabilize: row[2].parse().unwrap(),
                ..toroid::WheelSpec::with_sides(sides)
            },
            ..Default::default()
        };
        match toroid::toroid_report(&request) {
            Ok(report) => {
                let json = serde_json::to_value(&report).unwrap();
                assert_eq!(row[row.len() - 2], "ok");
                for (k, name) in header.iter().enumerate().skip(3).take(header.len() - 5) {
                    let want = lookup(&json, name).unwrap();
                    assert_eq!(row[k], scalar(want).unwrap(), "case {id} {name}");
                    if let Some(x) = want.as_f64() {
                        assert_eq!(row[k].parse::<f64>().unwrap(), x, "round trip");
                    }
                }
            }
            Err(e) => {
                assert_eq!(sides, 2);
                assert_eq!(row[row.len() - 2], "error");
                // refused by the request's check before it runs, naming the parameter as
                // the spec does; the same rule as the run's error
                let rule = e.to_string();
                let rule = rule.trim_start_matches("sides = ");
                assert_eq!(row[row.len() - 1], format!("parameter `sides` = {rule}"));
                assert!(row[3..row.len() - 2].iter().all(String::is_empty));
            }
        }
    }
}

#[test]
fn one_and_two_threads_write_the_same_bytes() {
    let dir = tmp();
    let spec = Spec::parse(TOROID).unwrap();
    let (a, b, c) = (
        dir.path().join("1.csv"),
        dir.path().join("2.csv"),
        dir.path().join("5.csv"),
    );
    sweep(&spec, &a, threads(1));
    sweep(&spec, &b, threads(2));
    sweep(&spec, &c, threads(5));
    let one = std::fs::read(&a).unwrap();
    assert_eq!(one, std::fs::read(&b).unwrap());
    assert_eq!(one, std::fs::read(&c).unwrap());
}

#[test]
fn merged_shards_are_the_single_run() {
    let dir = tmp();
    let spec = Spec::parse(TIPOVER).unwrap();
    let single = dir.path().join("single.csv");
    sweep(&spec, &single, threads(2));
    let want = std::fs::read(&single).unwrap();
    for n in [2, 3, 5] {
        let mut parts: Vec<PathBuf> = (0..n)
            .map(|k| {
                let p = dir.path().join(format!("s{k}of{n}.csv"));
                let opts = RunOptions {
                    shard: Shard { index: k, count: n },
                    ..threads(2)
                };
                let s = sweep(&spec, &p, opts);
                assert_eq!(s.shard_cases, Shard { index: k, count: n }.len(24));
                p
            })
            .collect();
        parts.reverse(); // any input order
        let merged = dir.path().join(format!("merged{n}.csv"));
        merge(&parts, &merged).unwrap();
        assert_eq!(std::fs::read(&merged).unwrap(), want, "{n} shards");
        // a missing shard is a gap
        let e = merge(&parts[1..], &merged).unwrap_err().to_string();
        assert!(e.contains("in none of the files"), "{e}");
    }
}

#[test]
fn a_run_cut_anywhere_and_resumed_is_the_single_run() {
    let dir = tmp();
    let spec = Spec::parse(TIPOVER).unwrap();
    let single = dir.path().join("single.csv");
    sweep(&spec, &single, threads(1));
    let want = std::fs::read(&single).unwrap();
    let cut = dir.path().join("cut.csv");
    // every cut: inside the header, at a row end, in the middle of a row
    for len in 0..=want.len() {
        std::fs::write(&cut, &want[..len]).unwrap();
        let opts = RunOptions {
            resume: true,
            ..threads(2)
        };
        sweep(&spec, &cut, opts);
        assert_eq!(std::fs::read(&cut).unwrap(), want, "cut at byte {len}");
    }
}

#[test]
fn resume_refuses_a_file_of_another_sweep() {
    let dir = tmp();
    let out = dir.path().join("r.csv");
    let spec = Spec::parse(TIPOVER).unwrap();
    sweep(&spec, &out, threads(1));
    let other = Spec::parse(&TIPOVER.replace("sides = [6, 8]", "sides = [6, 10]")).unwrap();
    let opts = RunOptions {
        resume: true,
        ..threads(1)
    };
    let e = run(&other, &out, &opts, &mut Silent)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("cannot resume") && e.contains("axis values"),
        "{e}"
    );
    let e = run(&Spec::parse(TOROID).unwrap(), &out, &opts, &mut Silent).unwrap_err();
    assert!(e.to_string().contains("header"), "{e}");
}

#[test]
fn an_invalid_case_is_one_error_row() {
    let dir = tmp();
    let out = dir.path().join("e.csv");
    let spec = Spec::parse(
        r#"
        study = "michell"
        [fixed]
        planar = true
        beta = "pi/6"
        [axes]
        complexity = [2, 3, 4]
        phi = ["pi/8", "pi/0", "22.5deg"]
        "#,
    )
    .unwrap();
    let s = sweep(&spec, &out, threads(2));
    assert_eq!((s.written, s.errors), (9, 3));
    let table = rows(&out);
    for row in &table[1..] {
        let failed = row[2] == "pi/0";
        assert_eq!(
            row[row.len() - 2],
            if failed { "error" } else { "ok" },
            "{row:?}"
        );
        if failed {
            assert!(
                row[row.len() - 1].contains("`phi`")
                    && row[row.len() - 1].contains("division by zero")
            );
        }
    }
    // the two spellings of π/8 give the same truss
    let mass = table[0].iter().position(|h| h == "mass_kg.yield").unwrap();
    assert_eq!(table[1][mass], table[3][mass]);
    // Skelton's planar closed form (ERRATA 4.4): Σ|q|l²/(w0 r0) = 4.618802153517 at q = 2,
    // β = π/6, φ = π/2 — checked here through a derived rule φ = π/q
    let spec = Spec::parse(
        "study = \"michell\"\n[fixed]\nplanar = true\nbeta = \"pi/6\"\n[axes]\ncomplexity = [2]\n[derived]\nphi = \"pi / complexity\"\n[output]\ncolumns = [\"normalized_yield_mass\"]\n",
    )
    .unwrap();
    sweep(&spec, &out, threads(1));
    let table = rows(&out);
    assert_eq!(
        table[0],
        [
            "case",
            "complexity",
            "normalized_yield_mass",
            "status",
            "message"
        ]
    );
    let m: f64 = table[1][2].parse().unwrap();
    assert!((m - 4.618802153517).abs() < 1e-9, "{m}");
}

#[test]
fn units_go_in_a_leading_comment_line() {
    let dir = tmp();
    let out = dir.path().join("u.csv");
    let spec = Spec::parse("study = \"tipover\"\n[axes]\nouter_radius = [1.0, 2.0]\n[output]\ncolumns = [\"mass_kg\", \"critical_lateral_force\"]").unwrap();
    let opts = RunOptions {
        units: true,
        ..threads(1)
    };
    sweep(&spec, &out, opts);
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), "# units: -,m,kg,N,-,-");
    assert_eq!(
        lines.next().unwrap(),
        "case,outer_radius,mass_kg,critical_lateral_force,status,message"
    );
    // a merge keeps the units line
    let merged = dir.path().join("m.csv");
    merge(std::slice::from_ref(&out), &merged).unwrap();
    assert_eq!(std::fs::read_to_string(&merged).unwrap(), text);
}

#[test]
fn a_case_over_the_limits_is_an_error_row_and_the_others_run() {
    // a hundred million sides used to abort allocating its statics; under the limits it is
    // refused before it runs, naming the parameter and the limit
    let dir = tmp();
    let out = dir.path().join("limits.csv");
    let spec = Spec::parse("study = \"toroid\"\n[axes]\nsides = [6, 100000000, 8]\n").unwrap();
    let limits = tensegrity_core::budget::Limits::default();
    let opts = RunOptions {
        limits: Some(limits),
        ..threads(2)
    };
    let s = sweep(&spec, &out, opts);
    assert_eq!((s.written, s.errors), (3, 1));
    let rows = rows(&out);
    let status = rows[0].iter().position(|h| h == "status").unwrap();
    assert_eq!(rows[1][status], "ok");
    assert_eq!(rows[3][status], "ok");
    assert_eq!(rows[2][status], "error");
    let message = &rows[2][status + 1];
    assert!(
        message.contains("sides = 100000000")
            && message.contains("memory")
            && message.contains("above the limit of 8.000 GiB"),
        "{message}"
    );
    // a tighter work limit refuses every case, by name
    let tight = tensegrity_core::budget::Limits {
        work_s: 1e-12,
        ..limits
    };
    let out = dir.path().join("tight.csv");
    let opts = RunOptions {
        limits: Some(tight),
        ..threads(1)
    };
    let s = sweep(&spec, &out, opts);
    assert_eq!(s.errors, 3);
}
