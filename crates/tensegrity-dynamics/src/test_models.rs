//! The test models of the dynamics: every structure of the core's `test_models` (re-exported)
//! and the grounds of its contact scenes ([`dropped_prism_ground`]).

pub use tensegrity_core::test_models::*;

use crate::{Ground, GroundModel};
use nalgebra::Vector3;

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
