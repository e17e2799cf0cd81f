//! Criterion benches of the anchor scenes (`examples/anchors/`, issue 25): each scene's
//! whole run as `bench anchors` times it (the simulation built once; the integration with
//! its monitors, 2000–5000 RK4 steps), `anchors/<name>`; and one quick pass of the scaling
//! series' smallest sizes, `anchors_series/<name>`.
//!
//! `cargo bench -p tensegrity-engine --bench anchors`

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use tensegrity_bench::series::{measure, SeriesKind};
use tensegrity_bench::Anchor;

fn anchors(c: &mut Criterion) {
    let mut g = c.benchmark_group("anchors");
    g.sample_size(20);
    for anchor in Anchor::ALL {
        let sim = anchor.scene().unwrap().simulation().unwrap();
        g.bench_function(anchor.name(), |b| b.iter(|| black_box(sim.run().unwrap())));
    }
    g.finish();
}

fn series(c: &mut Criterion) {
    let mut g = c.benchmark_group("anchors_series");
    g.sample_size(10);
    for kind in SeriesKind::ALL {
        g.bench_function(kind.name(), |b| {
            b.iter(|| black_box(measure(kind, true, 1).unwrap()))
        });
    }
    g.finish();
}

criterion_group!(benches, anchors, series);
criterion_main!(benches);
