//! A free rigid bar spinning in its plane: the simplest closed-form check of the bar dynamics
//! (ERRATA conservation checks: RK4 at dt = 1e-3 follows it to ~2e-12 over 1 s).

use crate::error::Result;
use crate::structure::{Bar, Structure};
use nalgebra::Vector3;

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

/// The exact position and velocity of node 1 at time `t` (node 0 is its mirror image):
/// x = (l/2)(cos ωt, sin ωt, 0), v = (ωl/2)(−sin ωt, cos ωt, 0).
pub fn spinning_bar_exact(l: f64, omega: f64, t: f64) -> (Vector3<f64>, Vector3<f64>) {
    let th = omega * t;
    (
        Vector3::new(th.cos(), th.sin(), 0.0) * (l / 2.0),
        Vector3::new(-th.sin(), th.cos(), 0.0) * (omega * l / 2.0),
    )
}
