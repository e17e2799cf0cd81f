//! Criterion bench of the prestressability margin LP alone, across sizes (issue 48): the
//! back-end that `tensegrity statics` picks (`backend` with the default settings: dense SVD,
//! banded sparse QR or nested dissection) is built once per structure outside the timed
//! loop, and only its `prestressability()` call (bars compressed, strings in tension) is
//! timed: the LP over the self-stress basis, or the interior point on A D⁻¹ Aᵀ where the
//! sparse basis fills in. Structures: free towers of 25, 100, 400 and 1,600 Snelson prisms
//! (`test_models::snelson_tower_free`, 9·N + 3 members) and double-layer grids of K × K
//! four-bar prisms, K = 5, 10, 15, 27 (`test_models::double_layer_grid`, the geometry of
//! formfind's `grid:K` in its exact form, outline held; 14 K² + 2 K members). The
//! benchmark id names the back-end that ran (`svd`, `sparse_qr`, `nested`,
//! `nested_members`) and the structure with its member count.
//!
//! All: `cargo bench -p tensegrity-statics --bench prestressability_lp`; one size, e.g.
//! `cargo bench -p tensegrity-statics --bench prestressability_lp -- grid27_`.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use tensegrity_core::{test_models, Structure};
use tensegrity_statics::{backend, backend_path, StaticsSettings};

fn bench(c: &mut Criterion) {
    let mut cases: Vec<(String, Structure)> = Vec::new();
    for n in [25, 100, 400, 1600] {
        let s = test_models::snelson_tower_free(n).expect("valid tower");
        cases.push((format!("tower{n}"), s));
    }
    for k in [5, 10, 15, 27] {
        let s = test_models::double_layer_grid(k).expect("valid lattice");
        cases.push((format!("grid{k}"), s));
    }
    let mut group = c.benchmark_group("prestressability_lp");
    group.sample_size(10);
    for (name, s) in &cases {
        let statics = backend(s, StaticsSettings::default()).expect("factored");
        assert!(statics.self_stress_dim() > 0, "{name}: no self-stress");
        let id = format!("{name}_{}members", s.n_members());
        let method = backend_path(s, statics.kind());
        group.bench_function(BenchmarkId::new(method, &id), |b| {
            b.iter(|| black_box(statics.prestressability().expect("margin LP")))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
