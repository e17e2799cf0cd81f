//! Load steps of a triangulated truss tower (the scenes of `scripts/truss-tower`, built here):
//! three nodes a layer, nine steel bars a stage, a force across and down on the top nodes
//! that bends it by about 5 % of its height. Cost against size: docs/notes/PERFORMANCE.md,
//! "Load paths".

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::Vector3;
use tensegrity_path::{load_steps, ElasticMember, ElasticModel, MemberKind, Support};

fn tower(stages: usize) -> ElasticModel {
    let mut nodes = Vec::new();
    for l in 0..=stages {
        for i in 0..3 {
            let a = ((120 * i + 60 * l) as f64).to_radians();
            nodes.push(Vector3::new(a.cos(), a.sin(), l as f64));
        }
    }
    let ea = 206e9 * std::f64::consts::PI * 1e-4;
    let bar = |i: usize, j: usize| ElasticMember {
        nodes: [i, j],
        kind: MemberKind::Bar,
        ea,
        rest_length: (nodes[j] - nodes[i]).norm(),
    };
    let mut members = Vec::new();
    for l in 1..=stages {
        let (base, below) = (3 * l, 3 * (l - 1));
        for i in 0..3 {
            members.push(bar(base + i, base + (i + 1) % 3));
            members.push(bar(below + i, base + i));
            members.push(bar(below + i, base + (i + 2) % 3));
        }
    }
    let force = 1e6 / (stages * stages) as f64;
    let mut load = vec![Vector3::zeros(); nodes.len()];
    for i in 0..3 {
        load[3 * stages + i] = Vector3::new(force, 0.0, -force);
    }
    ElasticModel {
        clusters: Vec::new(),
        supports: (0..3).map(Support::pinned).collect(),
        nodes,
        members,
        load,
        drivers: Default::default(),
    }
}

fn steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("load_steps_truss_tower");
    group.sample_size(10);
    for stages in [20, 111, 333] {
        let model = tower(stages);
        group.bench_with_input(BenchmarkId::from_parameter(9 * stages), &model, |b, m| {
            b.iter(|| load_steps(m, 10, 1.0).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, steps);
criterion_main!(benches);
