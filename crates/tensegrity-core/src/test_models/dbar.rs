//! The planar D-bar of thesis §2.2.1 (eq. 2.8–2.10): nodes (0, 0), (L/2, h/2), (L/2, −h/2),
//! (L, 0); bars 0–1, 0–2, 1–3, 2–3 (class-2 joints at the ends); strings 0–3 and 1–2.
//!
//! Reference answers: its connectivity is eq. 2.8–2.10 (with erratum 2.1), it has exactly one
//! self-stress (bars compressed, strings tensioned), and the loaded 45° D-bar's member forces
//! follow from the joint equilibrium by hand (tests `statics.rs` and `sizing.rs`).

use crate::error::Result;
use crate::material::Material;
use crate::structure::{Bar, StringMember, Structure, StructureBuilder, Support};

/// The bare D-bar geometry (no masses, stiffnesses or materials): 4 bars, 2 strings.
pub fn dbar_frame(l: f64, h: f64) -> StructureBuilder {
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

/// The dynamic D-bar (in the z = 0 plane): bars of mass `m`, strings 0–3 and 1–2 of stiffness
/// `k`, shortened by `stretch` (horizontal string) and `2·stretch` (vertical string) relative
/// to their lengths, so that they are in tension and the D-bar is *not* in equilibrium (equal
/// stretches would balance exactly for any L, h). The MOTES comparison uses
/// `dbar(2.0, 0.5, 1.0, 1000.0, 0.05)`.
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

/// The dynamic D-bar `dbar(2.0, 0.5, 1.5, 1000.0, 0.05)` held in some directions only: node 0
/// in x and z, node 3 in y. Its constraint rows mix joints with partial supports, the case the
/// joint-space and Woodbury solves must agree with the direct one on.
pub fn partly_supported_dbar() -> Result<Structure> {
    dbar(2.0, 0.5, 1.5, 1000.0, 0.05)?
        .to_builder()
        .support(Support::directions(0, [true, false, true]))
        .support(Support::directions(3, [false, true, false]))
        .build()
}

/// Two bars (masses 1 and 2 kg) in an L, the first pinned at both ends: a constraint set whose
/// joint system is singular (its Schur complement m/3 − m/3 vanishes), which every solve of the
/// constraint forces must report rather than divide by.
pub fn bar_pinned_at_both_ends() -> Result<Structure> {
    Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]])
        .bar(Bar::new(0, 1).mass(1.0))
        .bar(Bar::new(1, 2).mass(2.0))
        .support(Support::pinned(0))
        .support(Support::pinned(1))
        .build()
}

/// The benchmark aluminium: ρ 2700 kg/m³, E 60 GPa, σ_Y 110 MPa.
pub fn alu() -> Material {
    Material::new(2700.0, 60e9, 110e6)
}

/// The 45° D-bar spanning `span` with one string (1–2), compressed by `load` (N) at node 3,
/// node 0 pinned; all members of the benchmark aluminium ([`alu`]). Hand calculation: every
/// bar carries −load/√2, the string load.
pub fn loaded_dbar(span: f64, load: f64) -> Result<Structure> {
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
}
