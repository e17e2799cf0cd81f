//! Scalable structures for benches: rows of D-bars, stacks of prisms, a Snelson tower.
//!
//! Reference answers are the invariants (N P = D to round-off, equilibrium of the initial
//! prisms) and the sizes (a 4-D-bar chain has 57 constraint rows, a 33-stage tower 102 nodes).

use super::snelson::{snelson_prism, PrismParams};
use crate::error::Result;
use crate::structure::{Bar, StringMember, Structure, Support};
use std::f64::consts::PI;

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

/// `n` default prisms ([`snelson_prism`]) stacked along z (2 m apart), each its own class-1
/// unit, tied by vertical strings (k = 1000 N/m, rest length 0.5 m) from the top of one to the
/// bottom of the next.
pub fn prism_stack(n: usize) -> Result<Structure> {
    let p = snelson_prism(&PrismParams::default())?;
    let mut b = Structure::builder();
    for k in 0..n {
        let dz = 2.0 * k as f64;
        b = b.nodes(p.nodes().iter().map(|v| [v.x, v.y, v.z + dz]));
        let o = 6 * k;
        for bar in p.bars() {
            b = b.bar(Bar::new(bar.nodes[0] + o, bar.nodes[1] + o).mass(1.0));
        }
        for s in p.strings() {
            let mut s = s.clone();
            s.nodes = [s.nodes[0] + o, s.nodes[1] + o];
            b = b.string(s);
        }
        if k > 0 {
            for i in 0..3 {
                b = b.string(
                    StringMember::new(o - 3 + i, o + i)
                        .stiffness(1000.0)
                        .rest_length(0.5),
                );
            }
        }
    }
    b.build()
}

/// The free tower of [`snelson_tower`] (no supports, no load), as `examples/tower.toml`:
/// 3(N+1) nodes, 3N bars, 6N + 3 strings.
pub fn snelson_tower_free(stages: usize) -> Result<Structure> {
    tower_builder(stages).build()
}

/// A statics tower of `stages` stacked Snelson stages: `stages + 1` rings of 3 nodes (each
/// twisted π/6 from the one below, 1 m apart), per stage 3 bars and 3 vertical strings, a ring
/// of strings at every level; the bottom ring pinned and a load (100, 0, −50) N on the first
/// top node. With 33 stages: 102 nodes, a 306 × 264 equilibrium matrix.
pub fn snelson_tower(stages: usize) -> Result<Structure> {
    tower_builder(stages)
        .support(Support::pinned(0))
        .support(Support::pinned(1))
        .support(Support::pinned(2))
        .load(3 * stages, [100.0, 0.0, -50.0])
        .build()
}

fn tower_builder(stages: usize) -> crate::structure::StructureBuilder {
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
    b
}
