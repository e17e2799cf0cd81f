//! Criterion benches: form-finding `grid:K` (force density method with the boundary fixed,
//! sparse LU, and the statics of the result) for K = 8, 16, 27 (27: 10 260 members), and the
//! adaptive method on `prism:12` and the expanded octahedron.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use formfind::{builtin, form_find, Method, Settings, Topology};
use std::hint::black_box;

fn bench_grid(c: &mut Criterion) {
    let mut group = c.benchmark_group("formfind_grid");
    group.sample_size(10);
    for k in [8usize, 16, 27] {
        let t = builtin(&format!("grid:{k}")).unwrap();
        group.bench_with_input(BenchmarkId::new("fdm", t.n_members()), &t, |b, t| {
            b.iter(|| black_box(form_find(t, &Settings::default()).unwrap()))
        });
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
