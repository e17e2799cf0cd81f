//! Criterion benches: building and analysing the reference toroid (spokes + inner) for
//! n = 8, 24, 100, and one second of rolling down 50° for n = 8 and 24 with the rigid and the
//! full model (RK4 at 0.1 ms, the default, and IMEX at 0.5 ms: docs/notes/ROLLING.md); and 100
//! steps of the full model's rolling (n = 8, 0.01 s at 0.1 ms, with the projection and the
//! monitor of every step: issue 25's "full rolling step", reported per step); `toroid_build_large`: the build alone (structure by indices, issue 25) for
//! n = 1000 and 10000.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use tensegrity_dynamics::IntegratorKind;
use toroid::{analyse, build, Stabilize, ToroidParams, ToroidWheel};
use wheel_rolling::{FullRolling, RigidRolling, RunSpec, Wheel};

fn options() -> Stabilize {
    Stabilize {
        spokes: true,
        inner: true,
        outer: false,
    }
}

fn bench_build_analyse(c: &mut Criterion) {
    let mut group = c.benchmark_group("toroid_build_analyse");
    group.sample_size(10);
    for n in [8usize, 24, 100] {
        let p = ToroidParams::default().sides(n);
        group.bench_with_input(BenchmarkId::new("build", n), &p, |b, p| {
            b.iter(|| black_box(build(p, options(), 1.0).unwrap()))
        });
        let t = build(&p, options(), 1.0).unwrap();
        group.bench_with_input(BenchmarkId::new("analyse", n), &t, |b, t| {
            b.iter(|| black_box(analyse(t).unwrap()))
        });
    }
    group.finish();
}

fn bench_build_large(c: &mut Criterion) {
    let mut group = c.benchmark_group("toroid_build_large");
    group.sample_size(10);
    for n in [1000usize, 10000] {
        let p = ToroidParams::default().sides(n);
        group.bench_with_input(BenchmarkId::new("build", n), &p, |b, p| {
            b.iter(|| black_box(build(p, options(), 1.0).unwrap()))
        });
    }
    group.finish();
}

fn bench_rolling(c: &mut Criterion) {
    let mut group = c.benchmark_group("toroid_rolling_1s");
    group.sample_size(10);
    for n in [8usize, 24] {
        let t = build(&ToroidParams::default().sides(n), options(), 1.0).unwrap();
        let a = analyse(&t).unwrap();
        let wheel = ToroidWheel {
            toroid: &t,
            analysis: &a,
            string_stiffness: 2e4,
            min_tension: 20.0,
        };
        let model = RigidRolling::new(&wheel.polygon(), &RunSpec::default());
        group.bench_with_input(BenchmarkId::new("rigid", n), &model, |b, m| {
            b.iter(|| black_box(m.run(1.0).unwrap()))
        });
        let full = FullRolling::default();
        let scene = wheel.scene().unwrap();
        group.bench_with_input(BenchmarkId::new("full", n), &scene, |b, s| {
            b.iter(|| black_box(full.run_scene(s, 1.0).unwrap()))
        });
        let imex = FullRolling {
            integrator: IntegratorKind::Imex,
            dt: 5e-4,
            ..FullRolling::default()
        };
        group.bench_with_input(BenchmarkId::new("full-imex-5e-4", n), &scene, |b, s| {
            b.iter(|| black_box(imex.run_scene(s, 1.0).unwrap()))
        });
        let ark = FullRolling {
            integrator: IntegratorKind::ImexArk,
            dt: 2.5e-4,
            ..FullRolling::default()
        };
        group.bench_with_input(
            BenchmarkId::new("full-imex-ark-2.5e-4", n),
            &scene,
            |b, s| b.iter(|| black_box(ark.run_scene(s, 1.0).unwrap())),
        );
    }
    group.finish();
}

/// The full model's rolling step (n = 8, defaults): 100 steps (0.01 s) per iteration, with
/// the setup (model, workspace, first monitor sample) in every iteration as well.
fn bench_full_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("toroid_full_step");
    group.sample_size(20);
    group.throughput(criterion::Throughput::Elements(100));
    let t = build(&ToroidParams::default().sides(8), options(), 1.0).unwrap();
    let a = analyse(&t).unwrap();
    let wheel = ToroidWheel {
        toroid: &t,
        analysis: &a,
        string_stiffness: 2e4,
        min_tension: 20.0,
    };
    let scene = wheel.scene().unwrap();
    let full = FullRolling::default();
    group.bench_function("n8-100-steps", |b| {
        b.iter(|| black_box(full.run_scene(&scene, 0.01).unwrap()))
    });
    group.finish();
}

criterion_group!(
    benches,
    bench_build_analyse,
    bench_build_large,
    bench_rolling,
    bench_full_step
);
criterion_main!(benches);
