//! The Snelson prism dropped onto a penalty ground (contact with Coulomb friction).
//!
//! Reference answer: at rest each of the three feet carries a third of the weight 3 m g, so
//! the penetration is δ = m g / k_ground per foot ([`dropped_prism_penetration`]); the
//! contact forces sum to the weight. Free fall from height z₀ touches down at √(2 z₀ / g).

use super::snelson::{snelson_prism, PrismParams};
use crate::dynamics::{Ground, GroundModel};
use crate::error::Result;
use crate::structure::Structure;
use nalgebra::Vector3;

/// Gravity of the dropped-prism scenes (m/s², along −z).
pub const DROPPED_PRISM_G: f64 = 9.81;

/// The default prism (1 kg bars) with a stiff prestress (300 N/m, so that the soft twist mode
/// damps within seconds), string damping `damping` (N·s/m), its bottom at height `z0`, under
/// gravity.
pub fn dropped_prism(z0: f64, damping: f64) -> Result<Structure> {
    let s = snelson_prism(&PrismParams {
        z0,
        damping,
        prestress: 300.0,
        ..Default::default()
    })?;
    s.to_builder().gravity([0.0, 0.0, -DROPPED_PRISM_G]).build()
}

/// The penalty ground z = 0 of the dropped-prism scenes: stiffness `k` (N/m), normal damping
/// `damping` (N·s/m), μ_s = 0.6, μ_k = 0.5 and a soft regularisation (0.1 m/s, Stribeck
/// 0.2 m/s) so that the feet creep out of the tangential prestress and the prism really comes
/// to rest.
pub fn dropped_prism_ground(k: f64, damping: f64) -> Ground {
    Ground::new(
        Vector3::zeros(),
        Vector3::z(),
        GroundModel::Penalty {
            stiffness: k,
            damping,
            mu_static: 0.6,
            mu_kinetic: 0.5,
            regularization_velocity: 0.1,
            stribeck_velocity: 0.2,
        },
    )
}

/// The rest penetration (m) of each foot of the dropped prism on ground stiffness `k`: the
/// weight of the three 1 kg bars shared by three feet, over k.
pub fn dropped_prism_penetration(k: f64) -> f64 {
    3.0 * DROPPED_PRISM_G / 3.0 / k
}
