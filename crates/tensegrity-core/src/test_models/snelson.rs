//! The Snelson prism: p bars between two p-gons, ring and vertical strings.
//!
//! Reference answers (ERRATA P.1): with equal radii a self-stress exists only at the twist
//! π/2 − π/p ([`snelson_twist`]); for p = 3 the force densities are q_ring = 1, q_vertical = √3,
//! q_bar = −√3 (times the prestress level). [`snelson_prism`] realises that self-stress with
//! rest lengths, so it is at rest in equilibrium (|N̈| ≈ 1e-13, ERRATA conservation checks).

use crate::error::Result;
use crate::structure::{Bar, StringMember, Structure, StructureBuilder};
use std::f64::consts::PI;

/// The twist π/2 − π/p of the top p-gon at which an equal-radius Snelson prism has its
/// self-stress (ERRATA P.1; 30° for p = 3).
pub fn snelson_twist(p: usize) -> f64 {
    PI / 2.0 - PI / p as f64
}

/// A bare Snelson p-bar prism (no masses or stiffnesses): bottom node i at angle 2πi/p (radius
/// `rb`, z = 0), top node i at 2πi/p + `twist` (radius `rt`, z = `h`); bars bottom i → top
/// i+1; strings: bottom ring, top ring, verticals bottom i → top i. Members: p bars, then p
/// bottom, p top, p vertical strings.
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

/// Parameters of [`snelson_prism`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrismParams {
    /// Radius of both triangles (m).
    pub radius: f64,
    /// Height (m).
    pub height: f64,
    /// Mass of each bar (kg).
    pub bar_mass: f64,
    /// Stiffness of every string (N/m).
    pub stiffness: f64,
    /// Prestress level p (N/m): force densities q_ring = p, q_vertical = √3 p, q_bar = −√3 p.
    pub prestress: f64,
    /// Damping of every string (N·s/m).
    pub damping: f64,
    /// Height of the bottom triangle (m).
    pub z0: f64,
}

impl Default for PrismParams {
    fn default() -> Self {
        Self {
            radius: 1.0,
            height: 1.5,
            bar_mass: 1.0,
            stiffness: 1000.0,
            prestress: 10.0,
            damping: 0.0,
            z0: 0.0,
        }
    }
}

/// The 3-bar Snelson prism in its self-equilibrium (ERRATA P.1): bottom nodes 0..3 at angles
/// 2πi/3, top nodes 3..6 at 2πi/3 + π/6; bars bottom i → top i+1, vertical strings bottom i →
/// top i, ring strings i → i+1 (strings 0..3 bottom, 3..6 top, 6..9 vertical). Rest lengths
/// s0 = l(1 − q/k) realise the prestress, so the prism is at rest in equilibrium.
pub fn snelson_prism(p: &PrismParams) -> Result<Structure> {
    let alpha = PI / 6.0;
    let mut nodes = Vec::new();
    for i in 0..3 {
        let th = 2.0 * PI * i as f64 / 3.0;
        nodes.push([p.radius * th.cos(), p.radius * th.sin(), p.z0]);
    }
    for i in 0..3 {
        let th = 2.0 * PI * i as f64 / 3.0 + alpha;
        nodes.push([p.radius * th.cos(), p.radius * th.sin(), p.z0 + p.height]);
    }
    let len = |a: usize, b: usize| {
        let (x, y) = (nodes[a], nodes[b]);
        ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
    };
    let mut b = Structure::builder().nodes(nodes.clone());
    for i in 0..3 {
        b = b.bar(Bar::new(i, 3 + (i + 1) % 3).mass(p.bar_mass));
    }
    let q_ring = p.prestress;
    let q_vert = 3f64.sqrt() * p.prestress;
    let string = |b: StructureBuilder, i: usize, j: usize, q: f64| {
        b.string(
            StringMember::new(i, j)
                .stiffness(p.stiffness)
                .rest_length(len(i, j) * (1.0 - q / p.stiffness))
                .damping(p.damping),
        )
    };
    for i in 0..3 {
        b = string(b, i, (i + 1) % 3, q_ring);
    }
    for i in 0..3 {
        b = string(b, 3 + i, 3 + (i + 1) % 3, q_ring);
    }
    for i in 0..3 {
        b = string(b, i, 3 + i, q_vert);
    }
    b.build()
}

/// The default prism with vertical string 6 shortened by 1 %: it oscillates without any
/// string going slack (with 5 % one does, and RK4 loses its order at the kink). Reference:
/// energy and bar lengths are conserved (relative energy drift ≤ 1e-6 over 1 s of RK4 at
/// dt = 1e-3).
pub fn oscillating_prism() -> Result<Structure> {
    let s = snelson_prism(&PrismParams::default())?;
    let mut strings = s.strings().to_vec();
    strings[6].rest_length = strings[6].rest_length.map(|l| 0.99 * l);
    let mut b = Structure::builder().nodes(s.nodes().iter().map(|n| [n.x, n.y, n.z]));
    for bar in s.bars() {
        b = b.bar(bar.clone());
    }
    for st in strings {
        b = b.string(st);
    }
    b.build()
}
