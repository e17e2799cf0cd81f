//! Measures form-finding of `grid:K` (release: `cargo run --release -p formfind --example
//! grid_cost -- 8 16 27 40`): members, nodes and seconds, split into the form alone (the
//! default, no statics) and the form with its statics (`analyse`).
use formfind::{builtin, form_find, Settings};
use std::time::Instant;

fn main() {
    let ks: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    println!("K,nodes,members,form_s,analysed_s,self_stress_dim,prestress_stable,residual");
    let analysed = Settings {
        analyse: true,
        ..Settings::default()
    };
    for k in ks {
        let t = builtin(&format!("grid:{k}")).unwrap();
        let start = Instant::now();
        let form = form_find(&t, &Settings::default()).unwrap();
        let s = start.elapsed().as_secs_f64();
        let start = Instant::now();
        let f = form_find(&t, &analysed).unwrap();
        let a = start.elapsed().as_secs_f64();
        assert_eq!(form.nodes, f.nodes);
        println!(
            "{k},{},{},{s:.4},{a:.4},{},{},{:.2e}",
            t.n_nodes,
            t.n_members(),
            f.self_stress_dim.unwrap_or_default(),
            f.prestress_stable.unwrap_or_default(),
            f.residual
        );
    }
}
