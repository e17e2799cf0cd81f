//! Criterion benches of the statics of a 102-node tower (34 rings of 3 nodes, 33 stacked
//! Snelson stages): the SVD of the 306 × 264 equilibrium matrix, the prestressability LP over
//! its self-stress space, and a load solve.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use tensegrity::core::{test_models, Structure};
use tensegrity::statics::Statics;

fn tower(stages: usize) -> Structure {
    test_models::snelson_tower(stages).expect("valid tower")
}

fn bench_statics(c: &mut Criterion) {
    let s = tower(33);
    assert_eq!(s.n_nodes(), 102);
    let mut group = c.benchmark_group("statics_tower_102_nodes");
    group.sample_size(20);
    group.bench_function("svd_rank_self_stress", |b| {
        b.iter(|| {
            let st = Statics::new(black_box(&s)).unwrap();
            black_box(st.self_stress_basis())
        })
    });
    let st = Statics::new(&s).unwrap();
    group.bench_function("prestressability_lp", |b| {
        b.iter(|| black_box(st.prestressability().unwrap()))
    });
    group.bench_function("load_solve", |b| b.iter(|| black_box(st.solve_loads())));
    group.finish();
}

criterion_group!(benches, bench_statics);
criterion_main!(benches);
