//! The Snelson prism dropped onto a penalty ground (contact with Coulomb friction).
//!
//! Reference answer: at rest each of the three feet carries a third of the weight 3 m g, so
//! the penetration is δ = m g / k_ground per foot ([`dropped_prism_penetration`]; the ground is
//! `tensegrity_dynamics::test_models::dropped_prism_ground`); the
//! contact forces sum to the weight. Free fall from height z₀ touches down at √(2 z₀ / g).

use super::snelson::{snelson_prism, PrismParams};
use crate::error::Result;
use crate::structure::Structure;

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

/// The rest penetration (m) of each foot of the dropped prism on ground stiffness `k`: the
/// weight of the three 1 kg bars shared by three feet, over k.
pub fn dropped_prism_penetration(k: f64) -> f64 {
    3.0 * DROPPED_PRISM_G / 3.0 / k
}
