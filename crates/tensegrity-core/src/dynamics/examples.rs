//! Ready-made structures for tests, benches and the work–precision report.

use crate::error::Result;
use crate::structure::{Bar, StringMember, Structure, Support};
use std::f64::consts::PI;

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
    let string = |b: crate::structure::StructureBuilder, i: usize, j: usize, q: f64| {
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

/// The compound double pendulum: two uniform 1 kg, 1 m rods sharing a joint, the first end
/// pinned at the origin, both at `angle` from the downward vertical −y, g = 9.8 m/s² along
/// −y, from rest. Node 2 is the tip.
pub fn double_pendulum(angle: f64) -> Result<Structure> {
    let (s, c) = angle.sin_cos();
    Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [s, -c, 0.0], [2.0 * s, -2.0 * c, 0.0]])
        .bar(Bar::new(0, 1).mass(1.0))
        .bar(Bar::new(1, 2).mass(1.0))
        .support(Support::pinned(0))
        .gravity([0.0, -9.8, 0.0])
        .build()
}

/// The planar class-2 D-bar of thesis §2.2.1 (in the z = 0 plane): nodes (0,0), (L/2, h/2),
/// (L/2, −h/2), (L, 0); bars 0–1, 0–2, 1–3, 2–3; strings 0–3 and 1–2 with stiffness `k`,
/// shortened by `stretch` (horizontal string) and `2·stretch` (vertical string) relative to
/// their lengths, so that they are in tension and the D-bar is *not* in equilibrium (equal
/// stretches would balance exactly for any L, h); bars of mass `m`.
pub fn dbar(l: f64, h: f64, m: f64, k: f64, stretch: f64) -> Result<Structure> {
    Structure::builder()
        .nodes([
            [0.0, 0.0, 0.0],
            [l / 2.0, h / 2.0, 0.0],
            [l / 2.0, -h / 2.0, 0.0],
            [l, 0.0, 0.0],
        ])
        .bar(Bar::new(0, 1).mass(m))
        .bar(Bar::new(0, 2).mass(m))
        .bar(Bar::new(1, 3).mass(m))
        .bar(Bar::new(2, 3).mass(m))
        .string(
            StringMember::new(0, 3)
                .stiffness(k)
                .rest_length(l * (1.0 - stretch)),
        )
        .string(
            StringMember::new(1, 2)
                .stiffness(k)
                .rest_length(h * (1.0 - 2.0 * stretch)),
        )
        .build()
}

/// A free bar of length `l` and mass 1 kg along x, centred at the origin, spinning at `omega`
/// rad/s about z.
pub fn spinning_bar(l: f64, omega: f64) -> Result<Structure> {
    let v = omega * l / 2.0;
    Structure::builder()
        .nodes([[-l / 2.0, 0.0, 0.0], [l / 2.0, 0.0, 0.0]])
        .velocities([[0.0, -v, 0.0], [0.0, v, 0.0]])
        .bar(Bar::new(0, 1).mass(1.0))
        .build()
}

/// `n` D-bars (L = 2, h = 0.5, 1 kg bars, k = 1000 N/m) in a row along x, sharing their end
/// joints: interior joints are class-4, the ends class-2. Strings are 5 % (span) and 10 %
/// (height) short. With n ≥ 2 the Ω system has more than 48 rows and uses the sparse path.
pub fn dbar_chain(n: usize) -> Result<Structure> {
    let (l, h) = (2.0, 0.5);
    let mut b = Structure::builder();
    for k in 0..=n {
        b = b.node([k as f64 * l, 0.0, 0.0]);
    }
    for k in 0..n {
        let x = k as f64 * l;
        b = b.node([x + l / 2.0, h / 2.0, 0.0]);
        b = b.node([x + l / 2.0, -h / 2.0, 0.0]);
    }
    for k in 0..n {
        let (a, d) = (k, k + 1);
        let (up, dn) = (n + 1 + 2 * k, n + 2 + 2 * k);
        b = b
            .bar(Bar::new(a, up).mass(1.0))
            .bar(Bar::new(a, dn).mass(1.0))
            .bar(Bar::new(up, d).mass(1.0))
            .bar(Bar::new(dn, d).mass(1.0))
            .string(
                StringMember::new(a, d)
                    .stiffness(1000.0)
                    .rest_length(0.95 * l),
            )
            .string(
                StringMember::new(up, dn)
                    .stiffness(1000.0)
                    .rest_length(0.9 * h),
            );
    }
    b.build()
}
