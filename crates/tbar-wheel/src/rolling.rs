//! Mass properties, out-of-plane tip-over and the rolling polygon of the T-bar wheel (issue
//! item 5). The rolling itself is wheel-rolling's reduced rigid model on this polygon
//! ([`MassProperties::polygon`]); [`crate::roll`] is the T-bar side of `tbar roll`.
//!
//! **Mass properties.** Bars are uniform rods of linear density ρ_b (kg/m), strings are
//! massless (the toroid crate's convention, so the two wheels compare at equal density).
//! With the rigid rim only the treads' bars count (the rim is not modelled); with the rim
//! body its bars count too. A rod from a to b of mass m has, about the axle ι̂₁ (through the
//! origin), I = (m/3)(|a⊥|² + a⊥·b⊥ + |b⊥|²), a⊥ = (a_y, a_z): the exact integral of
//! |r⊥(s)|² over the rod. For a rigid-rim q = 1 wheel of n treads this is n ρ_b (r₀ − r_q)
//! (r_q² + r_q r₀ + r₀²)/3 (rim base) — every bar radial.
//!
//! **Rolling polygon.** Standing on its tips, the wheel is a regular polygon of n = π/φ
//! sides and circumradius r₀ (the tips): the reduced rigid model's `sides` and
//! `outer_radius` ([`MassProperties::polygon`]). A plastic pivot-to-pivot impact keeps ω⁺/ω⁻ = (I₁ + m r₀² cos(2π/n)) /
//! (I₁ + m r₀²) ([`impact_ratio`]).
//!
//! **Tip-over** (thesis §3.3.2, eq. 3.25–3.26 with ERRATA 3.12–3.15). A lateral force F_e on
//! the axle of a wheel of weight m g standing on contacts a track T apart (across ι̂₁) tips
//! it about the far contact when F_e h > m g T/2, h the axle height. The thesis takes
//! h = R_o: F_e > (m g/2)(T/R_o) = (m g/2) ρ. For the extended wheel the track is the offset
//! of the copy, T = |offset| (its tips lie in the planes x = 0 and x = offset), and
//! R_o = r₀; standing on an edge the axle is lower, h = r₀ cos φ, and the threshold rises to
//! (m g/2) T/(r₀ cos φ). The wheel tips before it slides when μ_s > F_e/(m g) = ρ/2. A single
//! loop has T = 0: it tips under any lateral force (the thesis's instability), flagged.

use crate::error::{invalid, Result};
use crate::geometry::TbarGeometry;
use crate::params::Layout;
use serde::Serialize;
use std::f64::consts::PI;
use tensegrity_core::Warning;
use tensegrity_derive::Columns;

/// Default bar density (kg/m): the toroid crate's.
pub const DEFAULT_BAR_DENSITY: f64 = 1.0;

/// Mass properties of a built T-bar structure.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MassProperties {
    /// Bar density ρ_b (kg/m).
    pub bar_density: f64,
    /// Density of the rim body's bars ρ_r (kg/m; ρ_b unless set apart for the full model).
    pub rim_density: f64,
    /// Mass of the treads' bars (kg).
    pub tread_mass: f64,
    /// Mass of the rim body's bars (kg), 0 with the rigid rim.
    pub rim_mass: f64,
    /// Total mass m (kg).
    pub mass: f64,
    /// Moment of inertia about the axle ι̂₁, I₁ (kg m²).
    pub i1: f64,
    /// Treads per wheel n = π/φ: the sides of the rolling polygon.
    pub sides: usize,
    /// Tip radius r₀ (m): the polygon's circumradius.
    pub outer_radius: f64,
}

impl MassProperties {
    /// The rolling polygon: n = π/φ sides on the tip radius r₀, with this mass and I₁.
    pub fn polygon(&self) -> wheel_rolling::Polygon {
        wheel_rolling::Polygon {
            sides: self.sides,
            outer_radius: self.outer_radius,
            mass: self.mass,
            i1: self.i1,
        }
    }
}

/// I about ι̂₁ of a uniform rod of mass `m` from `a` to `b`.
pub fn rod_i1(m: f64, a: &nalgebra::Vector3<f64>, b: &nalgebra::Vector3<f64>) -> f64 {
    let (ay, az, by, bz) = (a.y, a.z, b.y, b.z);
    m / 3.0 * (ay * ay + az * az + ay * by + az * bz + by * by + bz * bz)
}

/// Mass and I₁ of `g` with bars of density `bar_density` (strings massless).
pub fn mass_properties(g: &TbarGeometry, bar_density: f64) -> Result<MassProperties> {
    mass_properties_with(g, bar_density, bar_density)
}

/// Mass and I₁ of `g` with treads' bars of density `bar_density` and rim-body bars of
/// density `rim_density` (strings massless).
pub fn mass_properties_with(
    g: &TbarGeometry,
    bar_density: f64,
    rim_density: f64,
) -> Result<MassProperties> {
    for (name, v) in [("bar_density", bar_density), ("rim_density", rim_density)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(invalid(name, v, "must be finite and > 0"));
        }
    }
    let rod = |[s, e]: [usize; 2], density: f64| {
        let (a, b) = (g.nodes[s], g.nodes[e]);
        let m = density * (b - a).norm();
        (m, rod_i1(m, &a, &b))
    };
    let sum = |bars: &[[usize; 2]], density: f64| {
        bars.iter()
            .map(|&b| rod(b, density))
            .fold((0.0, 0.0), |acc, x| (acc.0 + x.0, acc.1 + x.1))
    };
    let (tread_mass, tread_i1) = sum(&g.bars, bar_density);
    let (rim_mass, rim_i1) = g
        .rim
        .as_ref()
        .map_or((0.0, 0.0), |r| sum(&r.bars, rim_density));
    Ok(MassProperties {
        bar_density,
        rim_density,
        tread_mass,
        rim_mass,
        mass: tread_mass + rim_mass,
        i1: tread_i1 + rim_i1,
        sides: g.params.treads_per_wheel()?,
        outer_radius: g.params.michell.r0,
    })
}

/// ω⁺/ω⁻ of a plastic pivot-to-pivot impact of the polygon: (I₁ + m r₀² cos(2π/n)) /
/// (I₁ + m r₀²).
pub fn impact_ratio(p: &MassProperties) -> f64 {
    let mr2 = p.mass * p.outer_radius * p.outer_radius;
    (p.i1 + mr2 * (2.0 * PI / p.sides as f64).cos()) / (p.i1 + mr2)
}

/// Out-of-plane tip-over figures of a T-bar wheel.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct TipOver {
    /// Track T (m): the offset of the copy (0 for a single loop).
    #[column(unit = "m")]
    pub track: f64,
    /// R_o = r₀ (m).
    #[column(unit = "m")]
    pub outer_radius: f64,
    /// ρ = T/R_o.
    pub rho: f64,
    /// Wheel mass m (kg).
    #[column(unit = "kg")]
    pub mass: f64,
    /// Lateral axle force above which the wheel tips, thesis form (m g/2) ρ (N).
    #[column(unit = "N")]
    pub critical_lateral_force: f64,
    /// The same standing on an edge (axle height r₀ cos φ): (m g/2) T/(r₀ cos φ) (N).
    #[column(unit = "N")]
    pub critical_lateral_force_edge: f64,
    /// Smallest static friction coefficient for which it tips before sliding, ρ/2.
    pub min_friction_to_tip: f64,
    /// What the figures assume and where they do not hold.
    pub warnings: Vec<Warning>,
}

/// Tip-over of the structure `g` (a wheel or an extended wheel) of mass `mass` (kg).
pub fn tipover(g: &TbarGeometry, mass: f64, gravity: f64) -> Result<TipOver> {
    for (name, v) in [("mass", mass), ("gravity", gravity)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(invalid(name, v, "must be finite and > 0"));
        }
    }
    let r0 = g.params.michell.r0;
    let phi = g.params.michell.phi;
    let mut warnings = Vec::new();
    let track = match g.params.layout {
        Layout::Extended { offset } => offset.abs(),
        Layout::Tread | Layout::Wheel => {
            warnings.push(Warning::SingleLoopTrack);
            0.0
        }
    };
    let rho = track / r0;
    let weight = mass * gravity;
    Ok(TipOver {
        track,
        outer_radius: r0,
        rho,
        mass,
        critical_lateral_force: 0.5 * weight * rho,
        critical_lateral_force_edge: 0.5 * weight * track / (r0 * phi.cos()),
        min_friction_to_tip: 0.5 * rho,
        warnings,
    })
}
