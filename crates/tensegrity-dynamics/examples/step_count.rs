//! Runs an anchor scene for a given simulated time, for instruction counting under callgrind
//! (docs/notes/PERFORMANCE.md, "Dynamics per step (issue 25)"): the per-step cost is
//! (Ir(N steps) − Ir(M steps)) / (N − M), so the setup cancels. Prints the final state with
//! all digits (compare two builds with `diff`).
//!
//! `cargo run --release -p tensegrity-core --example step_count -- dbar|prism T_END`

use tensegrity_dynamics::test_models;
use tensegrity_dynamics::{IntegratorKind, Simulation, SimulationSettings};

fn main() {
    let mut args = std::env::args().skip(1);
    let scene = args.next().unwrap_or_else(|| "dbar".into());
    let t_end: f64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(5.0);
    let s = match scene.as_str() {
        "prism" => test_models::motes_anchor_prism(),
        _ => test_models::motes_anchor_dbar(),
    }
    .expect("anchor scene");
    let settings = SimulationSettings {
        t_end,
        dt: 1e-3,
        integrator: IntegratorKind::Rk4,
        ..Default::default()
    };
    let r = Simulation::new(&s, settings)
        .expect("simulation")
        .run()
        .expect("run");
    println!("steps {}", r.steps);
    for (p, v) in r.final_nodes.iter().zip(&r.final_velocities) {
        println!("{:?} {:?}", p.as_slice(), v.as_slice());
    }
}
