//! The MOTES D-bar: a square D-bar (the four bars form a square, 45° to the span) with its
//! left end pinned, 1 kg bars and soft strings k = 100 N/m, 5 % (span) and 10 % (height)
//! short, integrated for 5000 RK4 steps of 1 ms as in the MOTES comparison.
//!
//! Reference answer: the invariants of the method (ERRATA 2.8 and the conservation checks):
//! the linear constraints N P = D (class-2 joints and the pin) hold to round-off
//! (‖N P − D‖ ≤ 1e-12) for every Runge–Kutta method, the pinned node does not move, and
//! without damping the energy is conserved to the integrator's accuracy.

use super::dbar::dbar;
use crate::error::Result;
use crate::structure::{Structure, Support};

/// Number of RK4 steps of the MOTES comparison run.
pub const MOTES_DBAR_STEPS: u64 = 5000;

/// Step of the MOTES comparison run (s).
pub const MOTES_DBAR_DT: f64 = 1e-3;

/// The square D-bar spanning `span` (m), node 0 pinned, k = 100 N/m, 1 kg bars.
pub fn motes_dbar(span: f64) -> Result<Structure> {
    dbar(span, span, 1.0, 100.0, 0.05)?
        .to_builder()
        .support(Support::pinned(0))
        .build()
}

/// The MOTES anchor D-bar exactly as the MOTES reference code runs it (the scene
/// `examples/anchors/motes_dbar.toml`): nodes (−1,0,0), (0,−1,0), (1,0,0), (0,1,0); bars 3–0,
/// 0–1, 1–2, 2–3 of 1 kg; strings 1–3 (rest length 1) and 0–2 (rest length 0.5) with
/// k = 100 N/m; node 0 pinned; no gravity. Run it for [`MOTES_DBAR_STEPS`] RK4 steps of
/// [`MOTES_DBAR_DT`].
pub fn motes_anchor_dbar() -> Result<Structure> {
    use crate::structure::{Bar, StringMember};
    Structure::builder()
        .nodes([
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
        ])
        .bar(Bar::new(3, 0).mass(1.0))
        .bar(Bar::new(0, 1).mass(1.0))
        .bar(Bar::new(1, 2).mass(1.0))
        .bar(Bar::new(2, 3).mass(1.0))
        .string(StringMember::new(1, 3).stiffness(100.0).rest_length(1.0))
        .string(StringMember::new(0, 2).stiffness(100.0).rest_length(0.5))
        .support(Support::pinned(0))
        .build()
}
