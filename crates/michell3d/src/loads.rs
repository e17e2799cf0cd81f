//! External loads.
//!
//! The tip load of magnitude w₀ with azimuth φ_w and polar angle γ (eq. 4.13; ERRATA 4.22: γ is
//! measured from ι̂₃):
//!
//! w = w₀ [cos φ_w sin γ, sin φ_w sin γ, cos γ].
//!
//! φ_w = 0, γ = π gives w = [0, 0, −w₀], the bending load of §4.4.1 and §4.5 (ERRATA 4.5: it is
//! −ι̂₃, not −ι̂₂). A planar truss carries only loads in the y–z plane; there the in-plane angle
//! θ of Fig. 4.4 gives w = w₀ [0, cos θ, sin θ].

use crate::error::{invalid, MichellError, Result};
use crate::truss::MichellTruss;
use nalgebra::Vector3;

/// Out-of-plane load components below this fraction of |w| are treated as round-off for a
/// planar truss (cos(0)·sin(π) ≈ 1.2e-16).
const PLANAR_X_RTOL: f64 = 1e-9;

/// The tip load w₀ [cos φ sin γ, sin φ sin γ, cos γ] (eq. 4.13).
///
/// ```
/// let w = michell3d::tip_load(1000.0, 0.0, std::f64::consts::PI).unwrap();
/// assert!((w.z + 1000.0).abs() < 1e-9 && w.x.abs() < 1e-9);
/// ```
pub fn tip_load(w0: f64, azimuth: f64, polar: f64) -> Result<Vector3<f64>> {
    check_magnitude_and_azimuth(w0, azimuth)?;
    if !polar.is_finite() {
        return Err(invalid("polar", polar, "must be finite"));
    }
    let (sa, ca) = azimuth.sin_cos();
    let (sg, cg) = polar.sin_cos();
    Ok(w0 * Vector3::new(ca * sg, sa * sg, cg))
}

/// An in-plane load w₀ [0, cos θ, sin θ] at angle θ from ι̂₂ towards ι̂₃ (Fig. 4.4's θ₀₀).
pub fn in_plane_load(w0: f64, theta: f64) -> Vector3<f64> {
    let (s, c) = theta.sin_cos();
    w0 * Vector3::new(0.0, c, s)
}

/// Point loads on nodes (N).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct NodalLoads {
    entries: Vec<(usize, Vector3<f64>)>,
}

impl NodalLoads {
    /// No load.
    pub fn new() -> Self {
        Self::default()
    }

    /// A single load on the principal node (index 0).
    pub fn tip(w: Vector3<f64>) -> Self {
        Self {
            entries: vec![(0, w)],
        }
    }

    /// Adds a load on node `node` (loads on the same node add up).
    pub fn add(mut self, node: usize, w: Vector3<f64>) -> Self {
        self.entries.push((node, w));
        self
    }

    /// The (node, force) entries.
    pub fn entries(&self) -> &[(usize, Vector3<f64>)] {
        &self.entries
    }

    /// The loads as one vector per node, checked against the truss: node indices must exist,
    /// components must be finite, and a planar truss takes no out-of-plane (x) component.
    pub fn dense(&self, truss: &MichellTruss) -> Result<Vec<Vector3<f64>>> {
        let n = truss.nodes().len();
        let mut w = vec![Vector3::zeros(); n];
        for &(node, f) in &self.entries {
            if node >= n {
                return Err(MichellError::UnknownNode {
                    index: node,
                    count: n,
                });
            }
            if let Some(bad) = f.iter().find(|v| !v.is_finite()) {
                return Err(invalid(
                    "load",
                    *bad,
                    format!("non-finite component on node {node}"),
                ));
            }
            w[node] += f;
        }
        if truss.is_planar() {
            for (node, f) in w.iter_mut().enumerate() {
                if f.x.abs() > PLANAR_X_RTOL * f.norm() {
                    return Err(MichellError::OutOfPlaneLoad { node, w_x: f.x });
                }
                f.x = 0.0;
            }
        }
        Ok(w)
    }
}

/// Checks a load magnitude w₀ (finite, > 0) and azimuth (finite), naming the bad one.
pub(crate) fn check_magnitude_and_azimuth(w0: f64, azimuth: f64) -> Result<()> {
    if !(w0.is_finite() && w0 > 0.0) {
        return Err(invalid(
            "load",
            w0,
            "the load magnitude w0 must be finite and > 0",
        ));
    }
    if !azimuth.is_finite() {
        return Err(invalid("azimuth", azimuth, "must be finite"));
    }
    Ok(())
}
