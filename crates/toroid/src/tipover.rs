//! Out-of-plane stability: tip-over under a lateral force on the axle (thesis §3.3.2 with
//! ERRATA 3.12–3.15).
//!
//! With ρ = T/R_o, ε = t/T and σ = R_i/R_o, the wheel (weight m g, on flat ground) tips about
//! its far contact node when the lateral force F_e > (m g/2) ρ (eq. 3.25–3.26). The contact
//! bar meets the ground at θ with cot θ = (ρ/2)(1+ε)/(1−σ) (eq. 3.27 corrected: a factor ½ was
//! lost and the ratio is a cotangent), and at the tipping threshold the friction needed,
//! normalised by F_e, is F_f' = 1 − (1+ε)/(1−σ) = −(σ+ε)/(1−σ) (eq. 3.29), always negative;
//! |F_f'| < 1 ⇔ ε + 2σ < 1. Classically, the wheel tips before it slides when the static
//! friction coefficient μ_s > F_e/(m g) = ρ/2 (ERRATA 3.15).

use crate::error::{Result, ToroidError};
use crate::params::ToroidParams;

/// Tip-over figures of one wheel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TipOver {
    /// ρ = T/R_o.
    pub rho: f64,
    /// ε = t/T.
    pub epsilon: f64,
    /// σ = R_i/R_o.
    pub sigma: f64,
    /// cot θ of the contact bar with the ground.
    pub cot_theta: f64,
    /// Lateral force at which the wheel tips (N).
    pub critical_lateral_force: f64,
    /// F_f/F_e at the threshold (eq. 3.29).
    pub normalized_friction: f64,
    /// Smallest static friction coefficient for which the wheel tips before sliding (ρ/2).
    pub min_friction_to_tip: f64,
}

/// F_f' = 1 − (1+ε)/(1−σ) (eq. 3.29).
///
/// ```
/// use toroid::normalized_friction;
/// let f = normalized_friction(0.6, 0.75).unwrap();
/// assert!((f - (-(0.6 + 0.75) / (1.0 - 0.6))).abs() < 1e-15);
/// assert!(normalized_friction(1.0, 0.5).is_err());
/// ```
pub fn normalized_friction(sigma: f64, epsilon: f64) -> Result<f64> {
    if !(sigma.is_finite() && sigma > 0.0 && sigma < 1.0) {
        return Err(ToroidError::InvalidParameter(
            tensegrity_core::request::InvalidParameter::new(
                "sigma",
                sigma,
                "σ = R_i/R_o must lie in (0, 1)",
            ),
        ));
    }
    if !(epsilon.is_finite() && epsilon > 0.0) {
        return Err(ToroidError::InvalidParameter(
            tensegrity_core::request::InvalidParameter::new(
                "epsilon",
                epsilon,
                "ε = t/T must be positive",
            ),
        ));
    }
    Ok(1.0 - (1.0 + epsilon) / (1.0 - sigma))
}

/// Tip-over figures for a wheel of the given geometry, mass (kg) and gravity (m/s²).
///
/// ```
/// use toroid::{tipover, ToroidParams};
/// let t = tipover(&ToroidParams::default(), 10.0, 9.81).unwrap();
/// assert!((t.critical_lateral_force - 0.5 * 10.0 * 9.81 * 0.4).abs() < 1e-12);
/// assert!((t.min_friction_to_tip - 0.2).abs() < 1e-15);
/// ```
pub fn tipover(p: &ToroidParams, mass: f64, gravity: f64) -> Result<TipOver> {
    p.validate()?;
    for (name, value) in [("mass", mass), ("gravity", gravity)] {
        if !(value.is_finite() && value > 0.0) {
            return Err(ToroidError::InvalidParameter(
                tensegrity_core::request::InvalidParameter::new(name, value, "must be positive"),
            ));
        }
    }
    let rho = p.outer_tread / p.outer_radius;
    let epsilon = p.inner_tread / p.outer_tread;
    let sigma = p.inner_radius / p.outer_radius;
    Ok(TipOver {
        rho,
        epsilon,
        sigma,
        cot_theta: 0.5 * rho * (1.0 + epsilon) / (1.0 - sigma),
        critical_lateral_force: 0.5 * mass * gravity * rho,
        normalized_friction: normalized_friction(sigma, epsilon)?,
        min_friction_to_tip: 0.5 * rho,
    })
}

/// F_f' over a σ × ε grid (Fig. 3.13): rows `(σ, ε, F_f')`, σ and ε each on `n` points of
/// the open intervals (0, 1) and (0, `eps_max`].
pub fn friction_grid(n: usize, eps_max: f64) -> Result<Vec<(f64, f64, f64)>> {
    tensegrity_core::validate::count_at_least("grid_points", n, 2)?;
    tensegrity_core::validate::positive("eps_max", eps_max)?;
    let mut out = Vec::with_capacity(n * n);
    for i in 1..=n {
        let sigma = i as f64 / (n + 1) as f64;
        for j in 1..=n {
            let eps = eps_max * j as f64 / n as f64;
            out.push((sigma, eps, normalized_friction(sigma, eps)?));
        }
    }
    Ok(out)
}
