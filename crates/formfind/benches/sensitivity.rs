//! Criterion benches of the force density method's derivatives (`formfind::sensitivity`) on
//! square cable nets of k × k cells (2 k (k + 1) strings, the boundary held on a saddle, every
//! inner node loaded): the plain solve (assembling and factoring D_ff and solving for the
//! form), the adjoint gradient of one objective (one solve with those factors, whatever the
//! parameter count), the forward-mode gradient of that objective by the first 50 force
//! densities (or all, below 50: one solve each, [`FdmSensitivity::forward_gradient`]) and the
//! forward derivatives of the whole form with respect to every force density (one solve
//! each), for k = 2, 4, 7, 22 (12, 40, 112, 1 012 force densities). One size:
//! `cargo bench -p formfind --bench sensitivity -- sensitivity/adjoint/1012`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use formfind::sensitivity::{Cotangent, FdmSensitivity, Parameter};
use formfind::{FixedNode, Member, NodeLoad, Topology};
use std::hint::black_box;

/// The k × k cable net and its force densities (2 for every string).
fn net(k: usize) -> (Topology, Vec<f64>) {
    let id = |u: usize, v: usize| v * (k + 1) + u;
    let mut strings = Vec::new();
    let (mut fixed, mut loads) = (Vec::new(), Vec::new());
    for v in 0..=k {
        for u in 0..=k {
            if u < k {
                strings.push(Member::new(id(u, v), id(u + 1, v)));
            }
            if v < k {
                strings.push(Member::new(id(u, v), id(u, v + 1)));
            }
            let (x, y) = (u as f64 / k as f64 - 0.5, v as f64 / k as f64 - 0.5);
            if u == 0 || v == 0 || u == k || v == k {
                fixed.push(FixedNode {
                    node: id(u, v),
                    position: [x, y, x * x - y * y],
                });
            } else {
                loads.push(NodeLoad {
                    node: id(u, v),
                    force: [0.0, 0.0, -0.3],
                });
            }
        }
    }
    let q = vec![2.0; strings.len()];
    let t = Topology {
        n_nodes: (k + 1) * (k + 1),
        strings,
        fixed,
        loads,
        ..Topology::default()
    };
    (t, q)
}

fn bench_sensitivity(c: &mut Criterion) {
    let mut group = c.benchmark_group("sensitivity");
    group.sample_size(20);
    for k in [2usize, 4, 7, 22] {
        let (t, q) = net(k);
        let m = t.n_members();
        group.bench_with_input(BenchmarkId::new("solve", m), &(), |b, _| {
            b.iter(|| black_box(FdmSensitivity::new(&t, &q).unwrap()))
        });
        let mut s = FdmSensitivity::new(&t, &q).unwrap();
        // f = Σ z_i (the sag): ∂f/∂z_i = 1
        let mut df = Cotangent::zeros(t.n_nodes, m);
        for d in df.nodes.iter_mut() {
            d.z = 1.0;
        }
        group.bench_with_input(BenchmarkId::new("adjoint", m), &(), |b, _| {
            b.iter(|| black_box(s.adjoint(&df).unwrap()))
        });
        // the forward-mode gradient of the one objective by (at most) 50 force densities
        let fifty: Vec<Parameter> = (0..m.min(50)).map(Parameter::ForceDensity).collect();
        group.bench_with_input(BenchmarkId::new("forward_gradient_50", m), &(), |b, _| {
            b.iter(|| black_box(s.forward_gradient(&df, &fifty).unwrap()))
        });
        group.bench_with_input(BenchmarkId::new("forward_all", m), &(), |b, _| {
            b.iter(|| {
                for k in 0..m {
                    black_box(s.forward(Parameter::ForceDensity(k)).unwrap());
                }
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_sensitivity);
criterion_main!(benches);
