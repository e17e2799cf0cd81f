//! Canonical test structures with known answers, shared by the integration tests.
#![allow(dead_code)]

use std::f64::consts::PI;
use tensegrity_core::{Bar, Material, StringMember, Structure, StructureBuilder, Support};

/// The planar D-bar of thesis §2.2.1 (eq. 2.8): 4 bars, 2 strings.
pub fn dbar(l: f64, h: f64) -> StructureBuilder {
    Structure::builder()
        .nodes([
            [0.0, 0.0, 0.0],
            [l / 2.0, h / 2.0, 0.0],
            [l / 2.0, -h / 2.0, 0.0],
            [l, 0.0, 0.0],
        ])
        .bar(Bar::new(0, 1))
        .bar(Bar::new(0, 2))
        .bar(Bar::new(1, 3))
        .bar(Bar::new(2, 3))
        .string(StringMember::new(0, 3))
        .string(StringMember::new(1, 2))
}

/// Snelson p-bar prism: bottom node i at angle 2πi/p (radius rb, z = 0), top node i at
/// 2πi/p + twist (radius rt, z = h); bars bottom i → top i+1; strings: bottom ring, top ring,
/// verticals bottom i → top i. Members: p bars, then p bottom, p top, p vertical strings.
pub fn snelson(p: usize, twist: f64, rb: f64, rt: f64, h: f64) -> StructureBuilder {
    let mut b = Structure::builder();
    for i in 0..p {
        let a = 2.0 * PI * i as f64 / p as f64;
        b = b.node([rb * a.cos(), rb * a.sin(), 0.0]);
    }
    for i in 0..p {
        let a = 2.0 * PI * i as f64 / p as f64 + twist;
        b = b.node([rt * a.cos(), rt * a.sin(), h]);
    }
    for i in 0..p {
        b = b.bar(Bar::new(i, p + (i + 1) % p));
    }
    for i in 0..p {
        b = b.string(StringMember::new(i, (i + 1) % p));
    }
    for i in 0..p {
        b = b.string(StringMember::new(p + i, p + (i + 1) % p));
    }
    for i in 0..p {
        b = b.string(StringMember::new(i, p + i));
    }
    b
}

/// The benchmark aluminium: ρ 2700 kg/m³, E 60 GPa, σ_Y 110 MPa.
pub fn alu() -> Material {
    Material::new(2700.0, 60e9, 110e6)
}

/// The 45° D-bar spanning `span` with one string, compressed by `load` at node 3, node 0
/// supported; all members of the benchmark aluminium.
pub fn loaded_dbar(span: f64, load: f64) -> Structure {
    let half = span / 2.0;
    Structure::builder()
        .material("alu", alu())
        .nodes([
            [0.0, 0.0, 0.0],
            [half, half, 0.0],
            [half, -half, 0.0],
            [span, 0.0, 0.0],
        ])
        .bar(Bar::new(0, 1).material("alu"))
        .bar(Bar::new(0, 2).material("alu"))
        .bar(Bar::new(1, 3).material("alu"))
        .bar(Bar::new(2, 3).material("alu"))
        .string(StringMember::new(1, 2).material("alu"))
        .support(Support::pinned(0))
        .load(3, [-load, 0.0, 0.0])
        .build()
        .unwrap()
}
