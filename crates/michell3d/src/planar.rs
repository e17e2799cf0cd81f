//! Closed forms of Skelton's planar truss (§4.1, ERRATA 4.2–4.4).
//!
//! - Force regions (Fig. 4.4, exact for every q): for an in-plane tip load at angle θ
//!   (w = w₀[0, cos θ, sin θ]), θ ∈ [π+β, 2π−β] puts every U-spiral member (n_ik → n_(i+1)k) in
//!   tension and every D-spiral member in compression; θ ∈ [β, π−β] the reverse.
//! - Yield mass for a tip load perpendicular to the radius (θ = 3π/2): the tip members carry
//!   t₀ = w₀/(2 sin β) and each level carries Σ|t|·l = 2 t₀ c r₀, so
//!   M_yield = (ρ/σ) w₀ r₀ q sin φ / (sin β sin(β+φ)) (ERRATA 4.3), i.e. a normalised yield mass
//!   q sin φ / (sin β sin(β+φ)) (4.62 at q = 2 … 10.90 at q = 35 with φ = π/q, β = π/6;
//!   ERRATA 4.4).
//! - Michell's continuum truss: 2 w₀ r₀ ln(r₀/r_q)/σ, normalised 2 ln(r₀/r_q) = −2q ln a, the
//!   limit of the discrete mass for β = π/4 as q → ∞ with qφ fixed.

use crate::params::MichellParams;
use std::f64::consts::PI;

/// The two in-plane load-angle intervals of Fig. 4.4: `[π+β, 2π−β]` (U tension, D compression)
/// and `[β, π−β]` (U compression, D tension).
pub fn force_regions(beta: f64) -> [(f64, f64); 2] {
    [(PI + beta, 2.0 * PI - beta), (beta, PI - beta)]
}

/// Normalised planar yield mass q sin φ / (sin β sin(β+φ)) (ERRATA 4.3) for a tip load
/// perpendicular to the tip radius; multiply by (ρ/σ) w₀ r₀ for kilograms.
pub fn yield_mass_normalized(params: &MichellParams) -> f64 {
    let (b, p) = (params.beta, params.phi);
    params.complexity as f64 * p.sin() / (b.sin() * (b + p).sin())
}

/// Tip member force magnitude t₀ = w₀ / (2 sin β) under a perpendicular tip load.
pub fn tip_member_force(w0: f64, beta: f64) -> f64 {
    w0 / (2.0 * beta.sin())
}

/// Normalised Michell continuum mass 2 ln(r₀/r_q) = −2 q ln a.
pub fn michell_continuum_normalized(params: &MichellParams) -> f64 {
    -2.0 * params.complexity as f64 * params.a().ln()
}
