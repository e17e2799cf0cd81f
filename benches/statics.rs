//! Criterion benches of the statics of a 102-node tower (34 rings of 3 nodes, 33 stacked
//! Snelson stages): the SVD of the 306 × 264 equilibrium matrix, the prestressability LP over
//! its self-stress space, and a load solve.

use criterion::{criterion_group, criterion_main, Criterion};
use std::f64::consts::PI;
use std::hint::black_box;
use tensegrity::core::{Bar, Statics, StringMember, Structure, Support};

fn tower(stages: usize) -> Structure {
    let mut b = Structure::builder();
    for ring in 0..=stages {
        for i in 0..3 {
            let a = 2.0 * PI * i as f64 / 3.0 + ring as f64 * PI / 6.0;
            b = b.node([a.cos(), a.sin(), ring as f64]);
        }
    }
    for stage in 0..stages {
        for i in 0..3 {
            b = b.bar(Bar::new(3 * stage + i, 3 * stage + 3 + (i + 1) % 3));
            b = b.string(StringMember::new(3 * stage + i, 3 * stage + 3 + i));
        }
    }
    for ring in 0..=stages {
        for i in 0..3 {
            b = b.string(StringMember::new(3 * ring + i, 3 * ring + (i + 1) % 3));
        }
    }
    let top = 3 * stages;
    b.support(Support::pinned(0))
        .support(Support::pinned(1))
        .support(Support::pinned(2))
        .load(top, [100.0, 0.0, -50.0])
        .build()
        .expect("valid tower")
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
