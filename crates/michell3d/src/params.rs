//! Truss parameters and their validation.
//!
//! Skelton's planar parameters (thesis §4.1, eq. 4.1–4.3): complexity q, initial radius r₀,
//! departure angle β and segmentation angle φ, with
//!
//! - a = sin β / sin(β+φ), c = sin φ / sin(β+φ),
//! - r_k = r₀ aᵏ (radius of level k), and every member between levels k and k+1 has an in-plane
//!   length c r_k.
//!
//! The 3-D truss adds one out-of-plane parameter (§4.3): δ for the cylindrical parameterisation
//! (eq. 4.11) or ε for the spherical one (eq. 4.12). Validity (ERRATA 4.8, 4.9, 4.12):
//! β, φ > 0, β + φ < π, β ≠ π/2 (otherwise the two in-plane members of a node are collinear,
//! det A ∝ sin 2β), δ ≠ 0, 0 < |qε| < π/2 and cos(Zφ) ≠ 0 for every |Z| ≤ q (spherical).

use crate::error::{invalid, Result};
use serde::Serialize;
use std::f64::consts::{FRAC_PI_2, PI};
use tensegrity_derive::Columns;

/// The largest offset |δ| of the cylindrical parameterisation (in radii): beyond it the
/// axial coordinate r δ dwarfs the other two past double precision (10⁸ keeps 8 digits).
pub const MAX_DELTA: f64 = 1e8;

/// Largest complexity accepted for a 3-D truss ((q+1)(q+2)(q+3)/6 = 176 851 nodes at q = 100).
pub const MAX_COMPLEXITY_3D: usize = 100;
/// Largest complexity accepted for a planar truss ((q+1)(q+2)/2 = 501 501 nodes at q = 1000).
pub const MAX_COMPLEXITY_PLANAR: usize = 1000;

/// Relative tolerance for "cos(Zφ) = 0" and "sin 2β = 0".
const ANGLE_TOL: f64 = 1e-9;

/// How the nodes leave the y–z plane.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Columns)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Geometry {
    /// Skelton's planar truss: two-index nodes n_ik in the y–z plane.
    Planar,
    /// Cylindrical parameterisation, x = r_k 𝕏 δ (eq. 4.11).
    Cylindrical {
        /// Dimensionless out-of-plane offset δ (ERRATA 4.7).
        delta: f64,
    },
    /// Spherical parameterisation, x = r_k cos(ℤφ) tan(𝕏ε) (eq. 4.12).
    Spherical {
        /// Out-of-plane segmentation angle ε (rad).
        #[column(unit = "rad")]
        epsilon: f64,
    },
}

impl Geometry {
    /// True for [`Geometry::Planar`].
    pub fn is_planar(&self) -> bool {
        matches!(self, Geometry::Planar)
    }
}

/// The parameters of a discrete Michell truss.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Columns)]
pub struct MichellParams {
    /// Complexity q (number of member levels); level-q nodes are supports.
    pub complexity: usize,
    /// Initial radius r₀ (m): distance of the tip node n₀₀₀₀ = [0, r₀, 0] from the origin.
    #[column(unit = "m")]
    pub r0: f64,
    /// Departure angle β (rad).
    #[column(unit = "rad")]
    pub beta: f64,
    /// Segmentation angle φ (rad).
    #[column(unit = "rad")]
    pub phi: f64,
    /// Planar, cylindrical (δ) or spherical (ε).
    #[column(nested)]
    pub geometry: Geometry,
}

impl MichellParams {
    /// Planar (Skelton) truss parameters.
    pub fn planar(complexity: usize, r0: f64, beta: f64, phi: f64) -> Self {
        Self {
            complexity,
            r0,
            beta,
            phi,
            geometry: Geometry::Planar,
        }
    }

    /// 3-D truss, cylindrical parameterisation with offset δ.
    pub fn cylindrical(complexity: usize, r0: f64, beta: f64, phi: f64, delta: f64) -> Self {
        Self {
            geometry: Geometry::Cylindrical { delta },
            ..Self::planar(complexity, r0, beta, phi)
        }
    }

    /// 3-D truss, spherical parameterisation with angle ε.
    pub fn spherical(complexity: usize, r0: f64, beta: f64, phi: f64, epsilon: f64) -> Self {
        Self {
            geometry: Geometry::Spherical { epsilon },
            ..Self::planar(complexity, r0, beta, phi)
        }
    }

    /// The same truss with another complexity.
    pub fn with_complexity(self, complexity: usize) -> Self {
        Self { complexity, ..self }
    }

    /// Radius ratio a = sin β / sin(β+φ) (eq. 4.2).
    pub fn a(&self) -> f64 {
        self.beta.sin() / (self.beta + self.phi).sin()
    }

    /// Member length ratio c = sin φ / sin(β+φ) (eq. 4.3).
    pub fn c(&self) -> f64 {
        self.phi.sin() / (self.beta + self.phi).sin()
    }

    /// Radius of level k, r_k = r₀ aᵏ (eq. 4.1; ERRATA 4.7: the node's own level).
    pub fn radius(&self, level: usize) -> f64 {
        self.r0 * self.a().powi(level as i32)
    }

    /// The largest complexity accepted for this geometry.
    pub fn max_complexity(&self) -> usize {
        if self.geometry.is_planar() {
            MAX_COMPLEXITY_PLANAR
        } else {
            MAX_COMPLEXITY_3D
        }
    }

    /// Checks every parameter; the error names the first offending one.
    pub fn validate(&self) -> Result<()> {
        let q = self.complexity;
        if q == 0 {
            return Err(invalid(
                "complexity",
                0.0,
                "must be at least 1 (q = 0 is the bare principal node, which is a support)",
            ));
        }
        if q > self.max_complexity() {
            return Err(invalid(
                "complexity",
                q as f64,
                format!(
                    "must be at most {} for this geometry (node count grows as q³/6)",
                    self.max_complexity()
                ),
            ));
        }
        if !(self.r0.is_finite() && self.r0 > 0.0) {
            return Err(invalid("r0", self.r0, "must be finite and > 0"));
        }
        if !(self.beta.is_finite() && self.beta > 0.0) {
            return Err(invalid("beta", self.beta, "must be finite and > 0"));
        }
        if !(self.phi.is_finite() && self.phi > 0.0) {
            return Err(invalid("phi", self.phi, "must be finite and > 0"));
        }
        if self.beta + self.phi >= PI {
            return Err(invalid(
                "beta",
                self.beta,
                format!("beta + phi = {} must be < π", self.beta + self.phi),
            ));
        }
        if (2.0 * self.beta).sin().abs() < ANGLE_TOL {
            return Err(invalid(
                "beta",
                self.beta,
                "must differ from π/2: the two in-plane members of every node would be collinear",
            ));
        }
        let r_q = self.radius(q);
        if !(r_q.is_normal() && (1.0 / r_q).is_finite()) {
            return Err(invalid(
                "complexity",
                q as f64,
                format!("the support radius r0·a^q = {r_q:e} under- or overflows"),
            ));
        }
        match self.geometry {
            Geometry::Planar => {}
            Geometry::Cylindrical { delta } => {
                if !delta.is_finite() || delta == 0.0 {
                    return Err(invalid(
                        "delta",
                        delta,
                        "must be finite and non-zero (δ = 0 collapses the 3-D truss onto the plane)",
                    ));
                }
                if delta.abs() > MAX_DELTA {
                    return Err(invalid(
                        "delta",
                        delta,
                        format!(
                            "|δ| must be at most {MAX_DELTA:e}: a node's offset of |δ| radii along the axis would leave its other two coordinates below double precision"
                        ),
                    ));
                }
            }
            Geometry::Spherical { epsilon } => {
                let qe = (q as f64 * epsilon).abs();
                if !epsilon.is_finite() || qe == 0.0 || qe >= FRAC_PI_2 {
                    return Err(invalid(
                        "epsilon",
                        epsilon,
                        format!("need 0 < |q·epsilon| < π/2, got |q·epsilon| = {qe}"),
                    ));
                }
                for z in 0..=q {
                    if (z as f64 * self.phi).cos().abs() < ANGLE_TOL {
                        return Err(invalid(
                            "phi",
                            self.phi,
                            format!(
                                "cos(Zφ) = 0 at Z = ±{z} (≤ q = {q}): the spherical nodes of that \
                                 Z collapse onto x = 0 and the node equations are singular"
                            ),
                        ));
                    }
                }
            }
        }
        Ok(())
    }
}
