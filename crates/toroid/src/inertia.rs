//! Mass and inertia of the wheel about its centre (thesis §3.2.3 with ERRATA 3.10–3.11).
//!
//! Bars are slender rods of mass m and length l (strings are massless). About its centre r a
//! bar has I_c = (m l²/12)(I₃ − b̂b̂ᵀ) (no inertia about its own axis), and about the wheel
//! centre I_w = I_c + m(|r|² I₃ − r rᵀ) (eq. 3.17). The wheel's inertia is the sum over bars
//! (eq. 3.18) and I₁ = I(1,1), about the rolling axis ι₁ = x (eq. 3.19).
//!
//! The thesis builds I_c from a bar frame whose b̂₂ = n_j × n_i / ‖n_j × n_i‖ (eq. 3.14), which is
//! 0/0 for any bar whose line passes through the centre (the axle); the robust form above needs
//! no frame and equals the thesis recipe wherever that is defined ([`bar_inertia_thesis`]).

use nalgebra::{Matrix3, Vector3};
use tensegrity_core::Structure;

/// Inertia of a slender bar (ends `ni`, `nj`, mass `m`) about the origin, robust form.
///
/// ```
/// use nalgebra::Vector3;
/// use toroid::bar_inertia;
/// // an axle of length 2 through the centre: m l²/12 about the transverse axes, 0 about itself
/// let i = bar_inertia(&Vector3::new(-1.0, 0.0, 0.0), &Vector3::new(1.0, 0.0, 0.0), 3.0);
/// assert!((i[(1, 1)] - 1.0).abs() < 1e-15 && i[(0, 0)].abs() < 1e-15);
/// ```
pub fn bar_inertia(ni: &Vector3<f64>, nj: &Vector3<f64>, m: f64) -> Matrix3<f64> {
    let b = nj - ni;
    let l2 = b.norm_squared();
    let e = b / l2.sqrt();
    let r = 0.5 * (ni + nj);
    let centroidal = (Matrix3::identity() - e * e.transpose()) * (m * l2 / 12.0);
    centroidal + (Matrix3::identity() * r.norm_squared() - r * r.transpose()) * m
}

/// The thesis recipe (eq. 3.13–3.17): rotate diag(I_t, I_t, 0) from the bar frame
/// b̂₃ = b/‖b‖, b̂₂ = n_j × n_i/‖n_j × n_i‖, b̂₁ = b̂₂ × b̂₃, then add the parallel-axis term.
/// `None` when n_j × n_i vanishes (the bar's line passes through the centre).
pub fn bar_inertia_thesis(ni: &Vector3<f64>, nj: &Vector3<f64>, m: f64) -> Option<Matrix3<f64>> {
    let b = nj - ni;
    let l = b.norm();
    let b3 = b / l;
    let cross = nj.cross(ni);
    let norm = cross.norm();
    if norm <= 1e-12 * ni.norm().max(nj.norm()).powi(2) || norm.is_nan() {
        return None;
    }
    let b2 = cross / norm;
    let b1 = b2.cross(&b3);
    let rot = Matrix3::from_columns(&[b1, b2, b3]);
    let it = m * l * l / 12.0;
    let local = Matrix3::from_diagonal(&Vector3::new(it, it, 0.0));
    let r = 0.5 * (ni + nj);
    Some(
        rot * local * rot.transpose()
            + (Matrix3::identity() * r.norm_squared() - r * r.transpose()) * m,
    )
}

/// Total bar mass (kg).
pub fn wheel_mass(structure: &Structure) -> f64 {
    structure.bars().iter().filter_map(|b| b.mass).sum()
}

/// Inertia tensor of all bars about the origin (the wheel centre).
pub fn wheel_inertia(structure: &Structure) -> Matrix3<f64> {
    let nodes = structure.nodes();
    structure
        .bars()
        .iter()
        .filter_map(|b| {
            b.mass
                .map(|m| bar_inertia(&nodes[b.nodes[0]], &nodes[b.nodes[1]], m))
        })
        .sum()
}
