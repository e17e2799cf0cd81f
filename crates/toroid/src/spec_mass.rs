//! The wheel's bar mass from its parameters alone (nothing built): what the fidelity decision
//! of [`crate::roll`] and the resource estimates of [`crate::budget`] read before any run.

use crate::params::ToroidParams;
use crate::report::WheelSpec;

/// Total bar mass of the wheel from the parameters (one prism's bar lengths × n, plus the
/// axle of length T with spokes).
pub fn wheel_mass(wheel: &WheelSpec) -> f64 {
    let p: &ToroidParams = &wheel.geometry();
    let x = crate::builder::prism_nodes(p);
    let prism: f64 = [(0, 3), (1, 4), (2, 5)]
        .iter()
        .map(|&(a, b)| (x[b] - x[a]).norm())
        .sum();
    let axle = if wheel.stabilize.spokes {
        p.outer_tread
    } else {
        0.0
    };
    wheel.bar_density * (p.sides as f64 * prism + axle)
}
