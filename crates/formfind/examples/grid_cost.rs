//! Measures form-finding of `grid:K` (release: `cargo run --release -p formfind --example
//! grid_cost -- 8 16 27 40`): members, nodes and seconds, split into the form and its
//! statics.
use formfind::{builtin, form_find, Settings};
use std::time::Instant;

fn main() {
    let ks: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    println!("K,nodes,members,seconds,self_stress_dim,prestress_stable,residual");
    for k in ks {
        let t = builtin(&format!("grid:{k}")).unwrap();
        let start = Instant::now();
        let f = form_find(&t, &Settings::default()).unwrap();
        let s = start.elapsed().as_secs_f64();
        println!(
            "{k},{},{},{s:.4},{},{},{:.2e}",
            t.n_nodes,
            t.n_members(),
            f.self_stress_dim,
            f.prestress_stable,
            f.residual
        );
    }
}
