//! Force propagation (recursive and global) for q = 5, 10, 20, 35, and a 360×180 sign map.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use michell3d::complexity::fig_4_18_params;
use michell3d::*;
use std::f64::consts::PI;
use std::hint::black_box;

fn propagation(c: &mut Criterion) {
    let w = tip_load(1000.0, 0.3, 2.0).unwrap();
    let loads = NodalLoads::tip(w);
    let mut group = c.benchmark_group("propagation");
    for q in [5, 10, 20, 35] {
        let truss = MichellTruss::new(fig_4_18_params(q, Some(0.25))).unwrap();
        group.bench_function(format!("recursive/q{q}"), |b| {
            b.iter(|| propagate(black_box(&truss), &loads, Method::Recursive).unwrap())
        });
        group.bench_function(format!("global/q{q}"), |b| {
            b.iter(|| propagate(black_box(&truss), &loads, Method::Global).unwrap())
        });
    }
    group.finish();
}

fn sign_map(c: &mut Criterion) {
    let truss = MichellTruss::new(fig_4_18_params(10, Some(0.25))).unwrap();
    let az = AngleGrid::new(0.0, 2.0 * PI, 360);
    let po = AngleGrid::new(0.0, PI, 180);
    let mut group = c.benchmark_group("sign_map");
    group.bench_function("q10/360x180/one_member", |b| {
        b.iter(|| sign_maps(black_box(&truss), &[100], 1000.0, az, po, Method::Recursive).unwrap())
    });
    let all: Vec<usize> = (0..truss.members().len()).step_by(10).collect();
    group.bench_function("q10/360x180/66_members", |b| {
        b.iter(|| sign_maps(black_box(&truss), &all, 1000.0, az, po, Method::Recursive).unwrap())
    });
    group.finish();
}

criterion_group!(benches, propagation, sign_map);
criterion_main!(benches);
