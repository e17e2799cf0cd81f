//! Criterion benches of the dynamics: one right-hand-side evaluation against the member count
//! (class-1 prism chains and class-2 D-bar chains), and full runs (the MOTES comparison:
//! 5000 RK4 steps of the 4-bar class-2 D-bar).
//!
//! Needs in crates/tensegrity-core/Cargo.toml:
//! `[dev-dependencies] criterion.workspace = true` and
//! `[[bench]] name = "dynamics" harness = false`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use tensegrity_core::dynamics::examples::{self, dbar, snelson_prism, PrismParams};
use tensegrity_core::dynamics::{IntegratorKind, Model, Simulation, SimulationSettings};
use tensegrity_core::{Bar, StringMember, Structure};

/// `n` prisms stacked along z, each its own class-1 unit, tied by vertical strings.
fn prism_stack(n: usize) -> Structure {
    let p = snelson_prism(&PrismParams::default()).unwrap();
    let mut b = Structure::builder();
    for k in 0..n {
        let dz = 2.0 * k as f64;
        b = b.nodes(p.nodes().iter().map(|v| [v.x, v.y, v.z + dz]));
        let o = 6 * k;
        for bar in p.bars() {
            b = b.bar(Bar::new(bar.nodes[0] + o, bar.nodes[1] + o).mass(1.0));
        }
        for s in p.strings() {
            let mut s = s.clone();
            s.nodes = [s.nodes[0] + o, s.nodes[1] + o];
            b = b.string(s);
        }
        if k > 0 {
            for i in 0..3 {
                b = b.string(
                    StringMember::new(o - 3 + i, o + i)
                        .stiffness(1000.0)
                        .rest_length(0.5),
                );
            }
        }
    }
    b.build().unwrap()
}

fn dbar_chain(n: usize) -> Structure {
    examples::dbar_chain(n).unwrap()
}

fn rhs(c: &mut Criterion) {
    let mut g = c.benchmark_group("rhs");
    for (name, make) in [
        ("prism-stack", prism_stack as fn(usize) -> Structure),
        ("dbar-chain", dbar_chain),
    ] {
        for n in [1usize, 4, 16, 64] {
            let s = make(n);
            let model = Model::new(&s, None).unwrap();
            let y = model.initial_state(&s).unwrap();
            let mut ws = model.workspace().unwrap();
            let mut dy = vec![0.0; y.len()];
            g.throughput(Throughput::Elements(s.n_members() as u64));
            g.bench_with_input(BenchmarkId::new(name, s.n_members()), &n, |b, _| {
                b.iter(|| {
                    model.rhs(0.0, black_box(&y), &mut dy, &mut ws).unwrap();
                    black_box(dy[0])
                })
            });
        }
    }
    g.finish();
}

fn full_run(c: &mut Criterion) {
    let mut g = c.benchmark_group("run");
    g.sample_size(20);
    let s = dbar(2.0, 0.5, 1.0, 1000.0, 0.05).unwrap();
    for integrator in [IntegratorKind::Rk4, IntegratorKind::Rattle] {
        let sim = Simulation::new(
            &s,
            SimulationSettings {
                t_end: 5.0,
                dt: 1e-3,
                integrator,
                ..Default::default()
            },
        )
        .unwrap();
        g.bench_function(format!("dbar-5000-steps-{integrator}"), |b| {
            b.iter(|| black_box(sim.run().unwrap().steps))
        });
    }
    let sim = Simulation::new(
        &s,
        SimulationSettings {
            t_end: 5.0,
            integrator: IntegratorKind::Rk45,
            rtol: 1e-8,
            atol: 1e-10,
            dt: 1.0,
            ..Default::default()
        },
    )
    .unwrap();
    g.bench_function("dbar-5s-rk45-1e-8", |b| {
        b.iter(|| black_box(sim.run().unwrap().steps))
    });
    g.finish();
}

criterion_group!(benches, rhs, full_run);
criterion_main!(benches);
