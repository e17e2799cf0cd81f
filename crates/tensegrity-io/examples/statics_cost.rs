//! The statics of a scene in-process, for side-by-side timings against a peer's rank
//! computation (`scripts/peers-side-by-side`): reads each scene, then times (the least wall
//! time of five runs, one thread) the rank decision alone — the back-end the automatic
//! method builds: the factorisation of A and its rank, hence the self-stress and mechanism
//! counts — and the whole report (`statics_report`: the rank, the margin LP, prestress
//! stability, the self-stress basis where listed). Prints one JSON object a scene on its own
//! line.
//!
//! `cargo run --release -p tensegrity-io --example statics_cost -- SCENE.toml ...`
#![allow(missing_docs)]

use std::path::Path;
use std::time::Instant;
use tensegrity_io::scene::Scene;
use tensegrity_statics::report::{statics_report, StaticsRequest};
use tensegrity_statics::{backend, StaticsSettings};

const REPEAT: usize = 5;

fn best<T>(mut f: impl FnMut() -> T) -> (f64, T) {
    let mut out = None;
    let mut best = f64::INFINITY;
    for _ in 0..REPEAT {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    (best, out.expect("REPEAT > 0"))
}

fn main() {
    for arg in std::env::args().skip(1) {
        let scene = match Scene::from_path(Path::new(&arg)) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{arg}: {e}");
                std::process::exit(2);
            }
        };
        let s = &scene.structure;
        let (rank_s, b) = best(|| backend(s, StaticsSettings::default()));
        let b = match b {
            Ok(b) => b,
            Err(e) => {
                eprintln!("{arg}: {e}");
                std::process::exit(1);
            }
        };
        let request = StaticsRequest::default();
        let (report_s, r) = best(|| statics_report(s, &request));
        // the margin, or null (with the reason on stderr) where the report failed
        let margin = match r {
            Ok(r) => r.prestress_margin.to_string(),
            Err(e) => {
                eprintln!("{arg}: the report: {e}");
                "null".to_string()
            }
        };
        println!(
            "{{\"scene\": {:?}, \"members\": {}, \"rank\": {}, \"self_stress_dim\": {}, \"method\": \"{:?}\", \"rank_s\": {rank_s:e}, \"report_s\": {report_s:e}, \"prestress_margin\": {margin}}}",
            arg,
            s.n_members(),
            b.rank(),
            b.self_stress_dim(),
            b.kind()
        );
    }
}
