//! Criterion benches of the sparse statics against the dense SVD path: the full statics
//! report (rank, self-stress basis, margin LP, flexes, prestress stability) of towers of
//! stacked Snelson prisms sharing their triangles (banded; up to 3,200 prisms, issue 25), of a
//! small double-layer lattice and of random banded structures; and the nested-dissection
//! path (`statics_nested`: the automatic choice for a wide structure) on double-layer
//! lattices of K × K cells up to K = 80 (89,760 members), and in its members orientation
//! (the automatic choice for a long unloaded structure above 5,000 members) on towers of
//! 800, 3,200 and 12,800 prisms.
//!
//! `cargo bench -p tensegrity-core --bench sparse_statics`
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use tensegrity_core::{test_models, Bar, StringMember, Structure};
use tensegrity_statics::report::{statics_report, StaticsRequest};
use tensegrity_statics::{StaticsMethod, StaticsSettings};

/// The free Snelson tower of [`test_models::snelson_tower_free`]: 9·stages + 3 members.
fn tower(stages: usize) -> Structure {
    test_models::snelson_tower_free(stages).expect("valid tower")
}

/// A deterministic value in [0, 1).
fn hash(i: usize, salt: usize) -> f64 {
    let x = ((i * 7919 + salt * 104_729 + 13) as f64 * 0.618_033_988_7).sin() * 43_758.545_3;
    x - x.floor()
}

/// `n` random nodes along a box, each joined to its 5 next neighbours: about 4n members.
fn random_banded(n: usize) -> Structure {
    let mut b = Structure::builder();
    for i in 0..n {
        b = b.node([hash(i, 1), hash(i, 2), i as f64 * 0.3 + hash(i, 3)]);
    }
    let mut k = 0;
    for i in 0..n {
        for j in i + 1..(i + 6).min(n) {
            if hash(k, 4) < 0.8 {
                b = if k % 3 == 0 {
                    b.bar(Bar::new(i, j))
                } else {
                    b.string(StringMember::new(i, j))
                };
            }
            k += 1;
        }
    }
    b.build().expect("valid structure")
}

fn request(method: StaticsMethod) -> StaticsRequest {
    StaticsRequest {
        settings: StaticsSettings::default().method(method),
        ..Default::default()
    }
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("statics_report");
    group.sample_size(10);
    let cases = [
        ("tower", 25, tower(25)),
        ("tower", 50, tower(50)),
        ("tower", 100, tower(100)),
        ("tower", 200, tower(200)),
        ("tower", 400, tower(400)),
        ("tower", 800, tower(800)),
        ("tower", 1600, tower(1600)),
        ("tower", 3200, tower(3200)),
        (
            "lattice",
            6,
            test_models::double_layer_grid(6).expect("valid lattice"),
        ),
        ("random", 150, random_banded(150)),
        ("random", 500, random_banded(500)),
    ];
    for (name, size, s) in &cases {
        let members = s.n_members();
        let id = format!("{name}{size}_{members}members");
        group.bench_function(BenchmarkId::new("sparse_qr", &id), |b| {
            b.iter(|| statics_report(black_box(s), &request(StaticsMethod::Sparse)).unwrap())
        });
        if members <= 1000 {
            group.bench_function(BenchmarkId::new("dense_svd", &id), |b| {
                b.iter(|| statics_report(black_box(s), &request(StaticsMethod::Dense)).unwrap())
            });
        }
    }
    group.finish();
    let mut group = c.benchmark_group("statics_nested");
    group.sample_size(10);
    for k in [10, 20, 40, 80] {
        let s = test_models::double_layer_grid(k).expect("valid lattice");
        let id = format!("lattice{k}_{}members", s.n_members());
        group.bench_function(BenchmarkId::new("auto", &id), |b| {
            b.iter(|| statics_report(black_box(&s), &request(StaticsMethod::Auto)).unwrap())
        });
    }
    // towers above 5000 members: the nested dissection of A itself (the automatic choice),
    // against the banded QR of the `statics_report` group above (`sparse_qr`, forced)
    for stages in [800, 3200, 12800] {
        let s = tower(stages);
        let id = format!("tower{stages}_{}members", s.n_members());
        group.bench_function(BenchmarkId::new("auto", &id), |b| {
            b.iter(|| statics_report(black_box(&s), &request(StaticsMethod::Auto)).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
