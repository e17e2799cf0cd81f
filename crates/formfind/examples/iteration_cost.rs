//! Measures the cost of the iterative methods against their estimate (release: `cargo run
//! --release -p formfind --example iteration_cost -- 100 200 400`): for a zig-zag chain of n
//! nodes without force densities, the adaptive method's start (the bisection of the bars'
//! scale) and its seconds per iteration; for the same chain with lengths, dynamic relaxation's
//! seconds per step; each beside [`formfind::estimate`] of the run.
use formfind::{estimate, form_find, Member, Method, Settings, Topology};
use std::time::Instant;

/// A planar zig-zag chain of `n` nodes: bars between neighbours, strings every other node.
fn chain(n: usize, lengths: bool) -> Topology {
    let nodes: Vec<[f64; 3]> = (0..n)
        .map(|i| [i as f64, 0.5 * (i % 2) as f64, 0.1 * ((i * 7) % 5) as f64])
        .collect();
    let member = |a: usize, b: usize, l: f64| Member {
        length: lengths.then_some(l),
        ..Member::new(a, b)
    };
    Topology {
        n_nodes: n,
        bars: (0..n - 1).map(|i| member(i, i + 1, 1.2)).collect(),
        strings: (0..n - 2).map(|i| member(i, i + 2, 1.0)).collect(),
        nodes: Some(nodes),
        ..Topology::default()
    }
}

/// Seconds of `form_find` with `iterations` as the cap (the run fails to converge: the
/// cost of the cap is the point).
fn seconds(t: &Topology, method: Method, iterations: usize) -> (f64, f64) {
    let settings = Settings {
        method,
        max_iterations: iterations,
        ..Settings::default()
    };
    let start = Instant::now();
    let result = form_find(t, &settings);
    let seconds = start.elapsed().as_secs_f64();
    if let Err(e) = result {
        eprintln!(
            "{method}, {} nodes, {iterations} iterations: {e}",
            t.n_nodes
        );
    }
    (seconds, estimate(t, &settings).work_s)
}

fn main() {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    println!("method,nodes,members,iterations,seconds,per_iteration,estimate_s");
    for n in sizes {
        let t = chain(n, false);
        let (one, _) = seconds(&t, Method::Adaptive, 1);
        let k = 20;
        let (many, est) = seconds(&t, Method::Adaptive, k + 1);
        let per = (many - one) / k as f64;
        let m = t.n_members();
        println!("adaptive,{n},{m},1,{one:.4},,");
        println!("adaptive,{n},{m},{},{many:.4},{per:.3e},{est:.4}", k + 1);
        let t = chain(n, true);
        let steps = 2000;
        let (s, est) = seconds(&t, Method::Dr, steps);
        let per = s / steps as f64;
        println!("dr,{n},{m},{steps},{s:.4},{per:.3e},{est:.4}");
    }
}
