//! Criterion benches: form-finding `grid:K` (force density method with the boundary fixed:
//! the sparse Cholesky of D_ff) for K = 8, 16, 27, 85 (14 K² + 2 K members: 27 → 10 260,
//! 85 → 101 320), the form alone (`fdm`, the default) and with its statics (`fdm+analyse`,
//! K ≤ 27), and the adaptive method on `prism:12` and the expanded octahedron. One size:
//! `cargo bench -p formfind --bench formfind -- formfind_grid/fdm/101320`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use formfind::{builtin, form_find, Method, Settings, Topology};
use std::hint::black_box;

fn bench_grid(c: &mut Criterion) {
    let mut group = c.benchmark_group("formfind_grid");
    group.sample_size(10);
    let analysed = Settings {
        analyse: true,
        ..Settings::default()
    };
    for k in [8usize, 16, 27, 85] {
        let t = builtin(&format!("grid:{k}")).unwrap();
        group.bench_with_input(BenchmarkId::new("fdm", t.n_members()), &t, |b, t| {
            b.iter(|| black_box(form_find(t, &Settings::default()).unwrap()))
        });
        if k <= 27 {
            let id = BenchmarkId::new("fdm+analyse", t.n_members());
            group.bench_with_input(id, &t, |b, t| {
                b.iter(|| black_box(form_find(t, &analysed).unwrap()))
            });
        }
    }
    group.finish();
}

fn without_force_densities(mut t: Topology) -> Topology {
    for g in t.groups.values_mut() {
        g.force_density = None;
    }
    t
}

fn bench_adaptive(c: &mut Criterion) {
    let mut group = c.benchmark_group("formfind_adaptive");
    group.sample_size(10);
    let settings = Settings {
        method: Method::Adaptive,
        ..Settings::default()
    };
    for name in ["prism:12", "octahedron"] {
        let t = without_force_densities(builtin(name).unwrap());
        group.bench_with_input(BenchmarkId::new("adaptive", name), &t, |b, t| {
            b.iter(|| black_box(form_find(t, &settings).unwrap()))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_grid, bench_adaptive);
criterion_main!(benches);
