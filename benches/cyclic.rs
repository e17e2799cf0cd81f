//! Criterion benches of the symmetry-adapted statics of the toroid wheel (spokes + inner
//! rings) for n = 8 … 10000 prisms: the whole analysis (Fourier blocks, per-block SVD,
//! rigid-body counts, the symmetric margin LP, mass and inertia) against n, and the dense
//! path at the sizes it can reach, for the cost exponents in docs/PERFORMANCE.md.
//!
//! `cargo bench --bench cyclic` (all sizes); `cargo bench --bench cyclic -- symmetric` for the
//! symmetric path alone.

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

criterion_group!(benches, bench_symmetric, bench_dense);
criterion_main!(benches);
