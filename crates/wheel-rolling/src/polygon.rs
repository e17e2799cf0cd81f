//! The rigid wheel as both rolling models see it: its contact polygon, mass and moment of
//! inertia about the axle ([`Polygon`]), to which every topology reduces. A leaf of the
//! crate: it names nothing else of it.

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The rigid wheel: its contact polygon (n vertices on a circle of radius R_o about the
/// axle), its mass and its moment of inertia about the axle. Every topology reduces to this.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Polygon {
    /// Number of contact pairs (sides) n.
    pub sides: usize,
    /// Outer radius R_o (m): the circumradius of the contact polygon.
    pub outer_radius: f64,
    /// Wheel mass m (kg).
    pub mass: f64,
    /// Moment of inertia about the axle I₁ (kg m²).
    #[serde(rename = "I1")]
    pub i1: f64,
}

impl Polygon {
    /// ω⁺/ω⁻ at a plastic pair-to-pair impact: (I₁ + m R_o² cos(2π/n)) / (I₁ + m R_o²).
    ///
    /// ```
    /// use wheel_rolling::Polygon;
    /// // a ring (I₁ = m R²) of 4 sides: (1 + cos(π/2)) / 2
    /// let p = Polygon { sides: 4, outer_radius: 1.0, mass: 1.0, i1: 1.0 };
    /// assert!((p.impact_ratio() - 0.5).abs() < 1e-15);
    /// ```
    pub fn impact_ratio(&self) -> f64 {
        let mr2 = self.mass * self.outer_radius.powi(2);
        (self.i1 + mr2 * (2.0 * PI / self.sides as f64).cos()) / (self.i1 + mr2)
    }
}
