//! Criterion benches of the symmetry-adapted statics of the toroid wheel (spokes + inner
//! rings) for n = 8 … 10000 prisms: the whole analysis (Fourier blocks, per-block SVD,
//! rigid-body counts, the symmetric margin LP, mass and inertia) against n, and the dense
//! path at the sizes it can reach, for the cost exponents in docs/notes/PERFORMANCE.md.
//!
//! The T-bar wheel (q = 1, β = π/6, δ = 0.25, rigid rim) the same way: the whole
//! `tbar_report` (geometry, descriptor, blocks, symmetric margin LP, the load response by
//! blocks, the symmetric minimum-prestress LP, mass) for 24 … 720 treads, against the dense
//! path (`tbar_report_dense`) at 24 … 96 treads.
//!
//! `cargo bench --bench cyclic` (all sizes); `cargo bench --bench cyclic -- symmetric` for the
//! symmetric toroid path alone, `-- tbar_wheel` for the T-bar groups.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use tensegrity::toroid::{analyse, analyse_dense, build, Stabilize, ToroidParams};

fn wheel(n: usize) -> tensegrity::toroid::Toroid {
    build(
        &ToroidParams::default().sides(n),
        Stabilize::SPOKES_INNER,
        1.0,
    )
    .expect("valid wheel")
}

fn bench_symmetric(c: &mut Criterion) {
    let mut group = c.benchmark_group("toroid_symmetric_analyse");
    group.sample_size(10);
    for n in [8, 32, 100, 316, 1000, 3162, 10000] {
        let t = wheel(n);
        group.bench_with_input(BenchmarkId::from_parameter(n), &t, |b, t| {
            b.iter(|| black_box(analyse(t).unwrap()))
        });
    }
    group.finish();
}

fn bench_dense(c: &mut Criterion) {
    let mut group = c.benchmark_group("toroid_dense_analyse");
    group.sample_size(10);
    for n in [8, 16, 32] {
        let t = wheel(n);
        group.bench_with_input(BenchmarkId::from_parameter(n), &t, |b, t| {
            b.iter(|| black_box(analyse_dense(t).unwrap()))
        });
    }
    group.finish();
}

fn tbar_request(treads: usize) -> tensegrity::tbar_wheel::TbarRequest {
    use tensegrity::tbar_wheel::{Layout, TbarParams, TbarRequest};
    let phi = std::f64::consts::PI / treads as f64;
    let m = tensegrity::michell3d::MichellParams::cylindrical(
        1,
        1.0,
        std::f64::consts::FRAC_PI_6,
        phi,
        0.25,
    );
    TbarRequest::new(TbarParams::tread(m).with_layout(Layout::Wheel))
}

fn bench_tbar(c: &mut Criterion) {
    use tensegrity::tbar_wheel::{tbar_report, tbar_report_dense};
    let mut group = c.benchmark_group("tbar_wheel_cyclic_report");
    group.sample_size(10);
    for n in [24, 48, 96, 180, 360, 720] {
        let req = tbar_request(n);
        group.bench_with_input(BenchmarkId::from_parameter(n), &req, |b, r| {
            b.iter(|| black_box(tbar_report(r).unwrap()))
        });
    }
    group.finish();
    let mut group = c.benchmark_group("tbar_wheel_dense_report");
    group.sample_size(10);
    for n in [24, 48, 96] {
        let req = tbar_request(n);
        group.bench_with_input(BenchmarkId::from_parameter(n), &req, |b, r| {
            b.iter(|| black_box(tbar_report_dense(r).unwrap()))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_symmetric, bench_dense, bench_tbar);
criterion_main!(benches);
