//! The prestressability margin LP alone across many sizes (issue 48, item 2): for each free
//! tower of N Snelson prisms and each double-layer grid of K × K prisms, the back-end that
//! `tensegrity statics` picks is built once, then its `prestressability()` is timed (the
//! least wall time of `REPEAT` calls, one thread). Prints CSV rows
//! `family,size,members,path,seconds` and, at the end, every size whose LP cost less than
//! 0.9 × its predecessor's in the same family (a step down: a size anomaly).
//!
//! `cargo run --release -p tensegrity-statics --example lp_scaling [--quick] [--only tower|grid]`
//! (`--quick`: a few sizes of each family; `--only`: one family).
#![allow(missing_docs)]

use std::time::Instant;
use tensegrity_core::test_models;
use tensegrity_statics::{backend, backend_path, StaticsSettings};

const REPEAT: usize = 5;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let quick = args.iter().any(|a| a == "--quick");
    let only = |family: &str| {
        args.iter()
            .position(|a| a == "--only")
            .and_then(|i| args.get(i + 1))
            .is_none_or(|f| f == family)
    };
    let towers: Vec<usize> = if !only("tower") {
        vec![]
    } else if quick {
        vec![2, 5, 10, 11, 20, 50, 100, 200, 400]
    } else {
        let mut v: Vec<usize> = (1..=20).collect();
        v.extend([
            24, 28, 32, 40, 50, 60, 70, 80, 90, 100, 120, 150, 200, 250, 300, 350,
        ]);
        v.extend([
            400, 450, 500, 550, 600, 700, 800, 1000, 1200, 1600, 2400, 3200,
        ]);
        v
    };
    let grids: Vec<usize> = if !only("grid") {
        vec![]
    } else if quick {
        vec![3, 5, 8, 10, 11, 15]
    } else {
        (3..=30).chain([34, 40, 50]).collect()
    };
    println!("family,size,members,path,seconds");
    let mut steps = Vec::new();
    for (family, sizes) in [("tower", &towers), ("grid", &grids)] {
        let mut last: Option<(usize, f64)> = None;
        for &n in sizes {
            let s = match family {
                "tower" => test_models::snelson_tower_free(n),
                _ => test_models::double_layer_grid(n),
            };
            let s = match s {
                Ok(s) => s,
                Err(e) => {
                    eprintln!("{family} {n}: {e}");
                    continue;
                }
            };
            let statics = match backend(&s, StaticsSettings::default()) {
                Ok(b) => b,
                Err(e) => {
                    eprintln!("{family} {n}: {e}");
                    continue;
                }
            };
            let mut best = f64::INFINITY;
            for _ in 0..REPEAT {
                let t = Instant::now();
                let r = statics.prestressability();
                best = best.min(t.elapsed().as_secs_f64());
                if let Err(e) = r {
                    eprintln!("{family} {n}: {e}");
                    break;
                }
            }
            println!(
                "{family},{n},{},{},{best:.6}",
                s.n_members(),
                backend_path(&s, statics.kind())
            );
            if let Some((m, t)) = last {
                if best < 0.9 * t {
                    steps.push(format!("{family} {m} -> {n}: {t:.2e} s -> {best:.2e} s"));
                }
            }
            last = Some((n, best));
        }
    }
    for s in &steps {
        eprintln!("step down: {s}");
    }
}
