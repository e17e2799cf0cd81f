//! Criterion benches of the dynamics: one right-hand-side evaluation against the member count
//! (class-1 prism chains and class-2 D-bar chains), and full runs (5000 RK4 steps of the
//! 4-bar class-2 D-bar; the MOTES anchor `examples/anchors/motes_dbar.toml`: its right-hand
//! side and its 5000 RK4 steps, `anchor/…`), and one RK4 step of the D-bar and of the class-1
//! MOTES prism alone (`step/…`, issue 25; their instruction counts are in docs/notes/PERFORMANCE.md).
//! The structures come from `tensegrity_dynamics::test_models`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use tensegrity_core::Structure;
use tensegrity_dynamics::test_models::{self, dbar};
use tensegrity_dynamics::{Integrator, IntegratorKind, Model, Rk4, Simulation, SimulationSettings};

fn prism_stack(n: usize) -> Structure {
    test_models::prism_stack(n).unwrap()
}

fn dbar_chain(n: usize) -> Structure {
    test_models::dbar_chain(n).unwrap()
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

/// The MOTES anchor D-bar (square, k = 100, node 0 pinned; 15 Ω rows, Woodbury path).
fn anchor(c: &mut Criterion) {
    let mut g = c.benchmark_group("anchor");
    let s = test_models::motes_anchor_dbar().unwrap();
    let model = Model::new(&s, None).unwrap();
    let y = model.initial_state(&s).unwrap();
    let mut ws = model.workspace().unwrap();
    let mut dy = vec![0.0; y.len()];
    g.bench_function("motes-dbar-rhs", |b| {
        b.iter(|| {
            model.rhs(0.0, black_box(&y), &mut dy, &mut ws).unwrap();
            black_box(dy[0])
        })
    });
    g.sample_size(20);
    let sim = Simulation::new(
        &s,
        SimulationSettings {
            t_end: 5.0,
            dt: 1e-3,
            integrator: IntegratorKind::Rk4,
            ..Default::default()
        },
    )
    .unwrap();
    g.bench_function("motes-dbar-5000-steps-rk4", |b| {
        b.iter(|| black_box(sim.run().unwrap().steps))
    });
    g.finish();
}

/// One RK4 step (four right-hand sides) of the MOTES anchor D-bar (Ω by Woodbury) and of the
/// class-1 MOTES prism, stepping on from the last state (both oscillate, bounded).
fn step(c: &mut Criterion) {
    let mut g = c.benchmark_group("step");
    for (name, s) in [
        ("motes-dbar-rk4", test_models::motes_anchor_dbar().unwrap()),
        (
            "motes-prism-rk4",
            test_models::motes_anchor_prism().unwrap(),
        ),
    ] {
        let model = Model::new(&s, None).unwrap();
        let mut y = model.initial_state(&s).unwrap();
        let mut ws = model.workspace().unwrap();
        let mut rk = Rk4::new(y.len());
        let mut t = 0.0;
        g.bench_function(name, |b| {
            b.iter(|| {
                rk.step(&model, &mut ws, t, black_box(&mut y), 1e-3)
                    .unwrap();
                t += 1e-3;
                black_box(y[0])
            })
        });
    }
    g.finish();
}

criterion_group!(benches, rhs, full_run, anchor, step);
criterion_main!(benches);
