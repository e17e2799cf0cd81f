//! The slack map of a prestress state (see [`super`]): every sampled load direction on every
//! loaded tip, checked for a slack string or a bar in tension; the sphere sample and the
//! scaled state.

use super::{angles, EnvelopeSolution, LoadResponse};
use crate::error::{invalid, Result};
use nalgebra::Vector3;
use serde::Serialize;
use std::f64::consts::PI;

/// `n` quasi-uniform unit vectors (Fibonacci sphere): z_i = 1 − (2i+1)/n, azimuth i·π(3 − √5).
///
/// ```
/// let d = tbar_wheel::envelope::sphere_directions(500);
/// assert_eq!(d.len(), 500);
/// let mean: nalgebra::Vector3<f64> = d.iter().sum::<nalgebra::Vector3<f64>>() / 500.0;
/// assert!(mean.norm() < 1e-2 && d.iter().all(|v| (v.norm() - 1.0).abs() < 1e-12));
/// ```
pub fn sphere_directions(n: usize) -> Vec<Vector3<f64>> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - (2 * i + 1) as f64 / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let a = i as f64 * golden;
            Vector3::new(r * a.cos(), r * a.sin(), z)
        })
        .collect()
}

/// One direction of the slack map.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SlackPoint {
    /// Azimuth in the ι̂₁ι̂₂ plane (rad).
    pub azimuth: f64,
    /// Polar angle from ι̂₃ (rad).
    pub polar: f64,
    /// Smallest margin over members and tips (N): string tension, or bar compression.
    pub margin: f64,
    /// Whether some string slackens or some bar goes into tension.
    pub slack: bool,
}

/// The slack map of one prestress level.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SlackMap {
    /// Bar compression P of the state (N).
    pub prestress: f64,
    /// Fraction of the sampled directions that slacken a string or put a bar in tension.
    pub slack_fraction: f64,
    /// Whether every bar stays in compression for every sampled direction and tip.
    pub bar_always_compressed: bool,
    /// The fewest strings whose force a load changes (|Δt| above 1e-9 of the largest change),
    /// over the sampled directions and tips (the thesis: a load is carried by the bar and at
    /// least two strings).
    pub min_strings_carrying: usize,
    /// Whether the bar's force changes for every sampled direction (it carries every load).
    pub bar_always_carries: bool,
    /// Every sampled direction.
    pub points: Vec<SlackPoint>,
}

/// Member forces of a state under load `load` in direction `d` on tip `t`.
pub fn loaded_forces(
    response: &LoadResponse,
    state: &[f64],
    load: f64,
    t: usize,
    d: &Vector3<f64>,
) -> Vec<f64> {
    forces_with(&response.tip_response(t), state, load, d)
}

/// state + load · g·d, member by member.
fn forces_with(g: &[Vector3<f64>], state: &[f64], load: f64, d: &Vector3<f64>) -> Vec<f64> {
    state
        .iter()
        .zip(g)
        .map(|(s, g)| s + load * g.dot(d))
        .collect()
}

/// Checks a prestress state (member forces, N) under `load` in every direction of `dirs`,
/// on every tip.
pub fn slack_map(
    response: &LoadResponse,
    state: &[f64],
    load: f64,
    dirs: &[Vector3<f64>],
) -> SlackMap {
    let nb = response.n_bars;
    let prestress = (0..nb).map(|b| -state[b]).fold(0.0f64, f64::max);
    let mut margins = vec![f64::INFINITY; dirs.len()];
    let mut bar_ok = true;
    let mut min_tight = usize::MAX;
    let mut bar_carries = true;
    // tip by tip (a rotated response is built once per tip on the cyclic path)
    for t in 0..response.tips.len() {
        let g = response.tip_response(t);
        for (d, margin) in dirs.iter().zip(margins.iter_mut()) {
            let f = forces_with(&g, state, load, d);
            for (k, v) in f.iter().enumerate() {
                *margin = margin.min(if k < nb { -v } else { *v });
                bar_ok &= k >= nb || *v <= 0.0;
            }
            let scale = g.iter().fold(0.0f64, |m, g| m.max(g.dot(d).abs()));
            let carrying = |g: &Vector3<f64>| g.dot(d).abs() > 1e-9 * scale;
            let tight = g[nb..].iter().filter(|g| carrying(g)).count();
            min_tight = min_tight.min(tight);
            bar_carries &= g[..nb].iter().any(carrying);
        }
    }
    let points: Vec<SlackPoint> = dirs
        .iter()
        .zip(margins)
        .map(|(d, margin)| {
            let (azimuth, polar) = angles(d);
            SlackPoint {
                azimuth,
                polar,
                margin,
                slack: margin < 0.0,
            }
        })
        .collect();
    let slack = points.iter().filter(|p| p.slack).count();
    SlackMap {
        prestress,
        slack_fraction: if dirs.is_empty() {
            0.0
        } else {
            slack as f64 / dirs.len() as f64
        },
        bar_always_compressed: bar_ok,
        min_strings_carrying: if min_tight == usize::MAX {
            0
        } else {
            min_tight
        },
        bar_always_carries: bar_carries,
        points,
    }
}

/// The optimal state of `solution` scaled to bar compression `prestress` (N).
pub fn scaled_state(solution: &EnvelopeSolution, prestress: f64) -> Result<Vec<f64>> {
    if !(prestress.is_finite() && prestress > 0.0) {
        return Err(invalid("prestress", prestress, "must be finite and > 0"));
    }
    let f = prestress / solution.min_prestress;
    Ok(solution.prestress_force.iter().map(|v| v * f).collect())
}
