//! Node frames of the rigid model: the toroid's nodes placed by the rigid pose.
//!
//! The rigid model records the axle (s, h) and the spin ω; the wheel's turn is
//! ψ(t) = ∫₀ᵗ ω dt (trapezoidal rule on the samples), positive rolling downhill (a negative
//! turn about the axle x). A node at p₀ in the starting wheel frame (the built wheel turned by
//! −π/n onto its side, hub at the origin) is at
//! (x, s, h) = (0, s_hub(t), h_hub(t)) + R_x(−ψ(t)) p₀ in slope coordinates, the same
//! coordinates as the full model's frames ([`crate::rolling_full::WheelFrame`]).

use crate::rolling::RollingSample;
use crate::rolling_full::WheelFrame;
use crate::Toroid;
use nalgebra::{Rotation3, Vector3};
use std::f64::consts::PI;

/// The rigid wheel's nodes at the sample nearest to each of `times`.
///
/// ```
/// use toroid::roll::rigid_frames;
/// use toroid::rolling::RollingSample;
/// use toroid::{build, ToroidParams};
/// let t = build(&ToroidParams::default(), "spokes,inner".parse().unwrap(), 1.0).unwrap();
/// let r = (std::f64::consts::PI / 8.0).cos();
/// let at_rest = RollingSample { t: 0.0, s: -(std::f64::consts::PI / 8.0).sin(), h: r,
///     pivot: 0.0, omega: 0.0, normal: 0.0, tangential: 0.0, energy: 0.0, slip: 0.0 };
/// let f = rigid_frames(&t, &[at_rest], &[0.0]);
/// // prisms 0 and 1 stand on the slope (h = 0) at s = −2 R_o sin(π/8) and s = 0
/// assert!(f[0].nodes[0].z.abs() < 1e-12 && f[0].nodes[5].z.abs() < 1e-12);
/// assert!(f[0].nodes[5].y.abs() < 1e-12);
/// ```
pub fn rigid_frames(toroid: &Toroid, samples: &[RollingSample], times: &[f64]) -> Vec<WheelFrame> {
    if samples.is_empty() {
        return Vec::new();
    }
    let n = toroid.params.sides;
    let start = Rotation3::from_axis_angle(&Vector3::x_axis(), -PI / n as f64);
    let p0: Vec<Vector3<f64>> = toroid.structure.nodes().iter().map(|p| start * p).collect();
    let mut turn = Vec::with_capacity(samples.len());
    let mut psi = 0.0;
    for (k, s) in samples.iter().enumerate() {
        if k > 0 {
            let p = &samples[k - 1];
            psi += 0.5 * (s.t - p.t) * (s.omega + p.omega);
        }
        turn.push(psi);
    }
    times
        .iter()
        .map(|&t| {
            let k = samples
                .iter()
                .enumerate()
                .min_by(|a, b| (a.1.t - t).abs().total_cmp(&(b.1.t - t).abs()))
                .map_or(0, |(k, _)| k);
            let s = &samples[k];
            let r = Rotation3::from_axis_angle(&Vector3::x_axis(), -turn[k]);
            let hub = Vector3::new(0.0, s.s, s.h);
            WheelFrame {
                t: s.t,
                nodes: p0.iter().map(|p| hub + r * p).collect(),
            }
        })
        .collect()
}
