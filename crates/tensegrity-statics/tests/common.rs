//! The shared test structures, from `tensegrity_core::test_models` (one copy for the tests,
//! the benches and the work–precision study).
#![allow(dead_code, unused_imports)]

use nalgebra::DVector;
use tensegrity_core::test_models::snelson_twist;
pub use tensegrity_core::test_models::{alu, dbar_frame as dbar, snelson};
use tensegrity_core::{Bar, Material, StringMember, Structure, Support};

/// The 45° D-bar spanning `span` with one string, compressed by `load` at node 3, node 0
/// supported; all members of the benchmark aluminium.
pub fn loaded_dbar(span: f64, load: f64) -> Structure {
    tensegrity_core::test_models::loaded_dbar(span, load).unwrap()
}

/// The p-bar Snelson prism with steel bars of 1 kg and `radius`, strings of 2 kN/m whose rest
/// lengths carry its self-stress at 50 N/m (k (l − s0) = q l), optionally pinned at its base:
/// the structure and its force densities.
pub fn prestressed_snelson(p: usize, radius: f64, pinned: bool) -> (Structure, DVector<f64>) {
    let base = snelson(p, snelson_twist(p), 1.0, 1.0, 1.0).build().unwrap();
    let q = tensegrity_statics::Statics::new(&base)
        .unwrap()
        .prestressability()
        .unwrap()
        .stress
        * 50.0;
    let lengths = base.member_lengths();
    let mut b = Structure::builder()
        .material("rod", Material::new(7800.0, 200e9, 500e6))
        .nodes(base.nodes().iter().map(|x| [x.x, x.y, x.z]));
    for bar in base.bars() {
        b = b.bar(
            Bar::new(bar.nodes[0], bar.nodes[1])
                .mass(1.0)
                .material("rod")
                .radius(radius),
        );
    }
    let k = 2000.0;
    for (i, st) in base.strings().iter().enumerate() {
        let m = p + i;
        b = b.string(
            StringMember::new(st.nodes[0], st.nodes[1])
                .stiffness(k)
                .rest_length(lengths[m] * (1.0 - q[m] / k)),
        );
    }
    if pinned {
        for i in 0..p {
            b = b.support(Support::pinned(i));
        }
    }
    (b.build().unwrap(), q)
}

/// The derivatives of `f` with respect to every coordinate of every node of `s`, by central
/// differences of step `h` extrapolated ((4 D(h/2) − D(h)) / 3, error O(h⁴)).
pub fn node_central_differences(
    s: &Structure,
    h: f64,
    f: impl Fn(&Structure) -> f64,
) -> Vec<nalgebra::Vector3<f64>> {
    let nodes = s.nodes().to_vec();
    (0..nodes.len())
        .map(|i| {
            nalgebra::Vector3::from_fn(|axis, _| {
                let at = |h: f64| {
                    let moved = |sign: f64| {
                        let mut x = nodes.clone();
                        x[i][axis] += sign * h;
                        f(&s.with_nodes(x).unwrap())
                    };
                    (moved(1.0) - moved(-1.0)) / (2.0 * h)
                };
                (4.0 * at(0.5 * h) - at(h)) / 3.0
            })
        })
        .collect()
}

/// The worst difference of `exact` from `fd` (node gradients) relative to `largest`,
/// asserted below 10⁻⁶ at every coordinate (the message names `name`, the node and axis).
pub fn worst_node_error(
    name: &str,
    exact: &[nalgebra::Vector3<f64>],
    fd: &[nalgebra::Vector3<f64>],
    largest: f64,
) -> f64 {
    let mut worst = 0.0f64;
    for (i, (e, d)) in exact.iter().zip(fd).enumerate() {
        for axis in 0..3 {
            let r = (e[axis] - d[axis]).abs() / largest;
            assert!(
                r < 1e-6,
                "{name} node {i} axis {axis}: exact {} fd {}",
                e[axis],
                d[axis]
            );
            worst = worst.max(r);
        }
    }
    worst
}

/// `lattice` with, beside it (x shifted by −2), a generic affine image of the default Snelson
/// prism (self-stresses are affinely invariant) with its coordinates rounded to multiples of
/// 1/`scale`: its one self-stress holds only to about that precision. Bars and strings are
/// plain members; the lattice keeps its supports.
pub fn lattice_beside_rounded_prism(lattice: &Structure, scale: f64) -> Structure {
    use tensegrity_core::test_models::{snelson_prism, PrismParams};
    let prism = snelson_prism(&PrismParams::default()).unwrap();
    let offset = lattice.nodes().len();
    let round = |x: f64| (x * scale).round() / scale;
    let mut b = Structure::builder()
        .nodes(lattice.nodes().iter().map(|p| [p.x, p.y, p.z]))
        .nodes(prism.nodes().iter().map(|p| {
            [
                round(0.93 * p.x + 0.21 * p.y + 0.17 * p.z - 2.0),
                round(-0.12 * p.x + 1.07 * p.y + 0.29 * p.z),
                round(0.08 * p.x - 0.19 * p.y + 0.89 * p.z),
            ]
        }));
    for bar in lattice.bars() {
        b = b.bar(Bar::new(bar.nodes[0], bar.nodes[1]));
    }
    for bar in prism.bars() {
        b = b.bar(Bar::new(offset + bar.nodes[0], offset + bar.nodes[1]));
    }
    for st in lattice.strings() {
        b = b.string(StringMember::new(st.nodes[0], st.nodes[1]));
    }
    for st in prism.strings() {
        b = b.string(StringMember::new(
            offset + st.nodes[0],
            offset + st.nodes[1],
        ));
    }
    for sup in lattice.supports() {
        b = b.support(sup.clone());
    }
    b.build().unwrap()
}
