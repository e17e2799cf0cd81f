//! The compound double pendulum: two uniform 1 kg, 1 m rods sharing a class-2 joint, the
//! first end pinned at the origin, released from rest under g = 9.8 m/s² along −y.
//!
//! Reference answer: for both rods at 45° from the downward vertical, the published tip
//! position at t = 5 s is (1.3403149308, −1.4793519015) ([`DOUBLE_PENDULUM_TIP_5S`]; the value
//! quoted in `examples/double_pendulum.toml` and the README, reproduced to 1e-6 by RK4 at
//! dt = 5e-4 and by RK45 at rtol = 1e-12).

use crate::error::Result;
use crate::structure::{Bar, Structure, Support};

/// Gravity of the published double-pendulum problem (m/s², along −y).
pub const DOUBLE_PENDULUM_G: f64 = 9.8;

/// Published (x, y) of the tip (node 2) at t = 5 s for a release angle of π/4.
pub const DOUBLE_PENDULUM_TIP_5S: [f64; 2] = [1.3403149308, -1.4793519015];

/// The double pendulum with both rods at `angle` from the downward vertical −y, from rest.
/// Node 0 is the pin, node 1 the joint, node 2 the tip.
pub fn double_pendulum(angle: f64) -> Result<Structure> {
    let (s, c) = angle.sin_cos();
    Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [s, -c, 0.0], [2.0 * s, -2.0 * c, 0.0]])
        .bar(Bar::new(0, 1).mass(1.0))
        .bar(Bar::new(1, 2).mass(1.0))
        .support(Support::pinned(0))
        .gravity([0.0, -DOUBLE_PENDULUM_G, 0.0])
        .build()
}
