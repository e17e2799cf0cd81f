//! A wheel the full model rolls without knowing its topology: [`WheelScene`] (run by
//! [`FullRolling::run_scene`](super::FullRolling::run_scene)).
//!
//! The topology crates supply their wheels through these fields (the toroid's `toroid::scene`,
//! the T-bar wheel's `tbar_wheel::rolling_full`), so every wheel is integrated, monitored and
//! judged by the one code path of the parent module (equations there).
//!
//! **Contract of a scene** (checked by [`WheelScene::validate`]):
//!
//! - the structure is prestressed (strings with stiffness and rest lengths, bars with mass), has
//!   no supports and no gravity (the run sets g = g₀(0, sin φ, −cos φ)), and is given in its
//!   **starting pose**: the axle along x through the origin, the contact polygon (n sides,
//!   circumradius R_o about the axle) standing on the side of groups 0 and 1, i.e. every node
//!   of those two groups on the slope z = −R_o cos(π/n), group 0 uphill (y < 0), group 1
//!   downhill (y > 0), every other contact node above the slope (only contact nodes meet
//!   the ground);
//! - `contact_groups[k]` are the nodes of side k of the polygon that can touch the slope (the
//!   toroid: a prism's two outer tread nodes; the extended T-bar wheel: tread k's tip in each
//!   copy), numbered in the rolling order (rolling towards +y brings group k + 1 down after
//!   group k);
//! - ω is the mean spin of the `rim` nodes about the hub (the midpoint of the `axle` nodes,
//!   else the centroid of the rim nodes); `mass` and `i1` (about the axle) set the contact's
//!   effective mass and the energy budget's scale m g R_o.

use crate::error::{Result, RollingError};
use crate::polygon::Polygon;
use std::f64::consts::PI;
use tensegrity_core::Structure;

/// A prestressed wheel in its starting pose, with what the monitor needs of it.
#[derive(Debug, Clone, PartialEq)]
pub struct WheelScene {
    /// The prestressed structure in the starting pose (see the module docs).
    pub structure: Structure,
    /// The nodes that can touch the slope, one group per side of the contact polygon, in
    /// rolling order.
    pub contact_groups: Vec<Vec<usize>>,
    /// The nodes whose mean spin about the hub is ω.
    pub rim: Vec<usize>,
    /// The two axle end nodes (the hub is their midpoint), if any.
    pub axle: Option<[usize; 2]>,
    /// Circumradius of the contact polygon R_o (m).
    pub outer_radius: f64,
    /// Mass of the wheel (kg).
    pub mass: f64,
    /// Moment of inertia about the axle I₁ (kg m²).
    pub i1: f64,
}

impl WheelScene {
    /// Sides n of the contact polygon (the number of contact groups).
    pub fn sides(&self) -> usize {
        self.contact_groups.len()
    }

    /// The rigid polygon of this wheel (n, R_o, m, I₁).
    pub fn polygon(&self) -> Polygon {
        Polygon {
            sides: self.sides(),
            outer_radius: self.outer_radius,
            mass: self.mass,
            i1: self.i1,
        }
    }

    /// z of the slope in the starting pose, −R_o cos(π/n) (m).
    pub fn plane_z(&self) -> f64 {
        -self.outer_radius * (PI / self.sides() as f64).cos()
    }

    /// The group of every node (`None` for a node that cannot touch the slope).
    pub fn group_of(&self) -> Vec<Option<usize>> {
        let mut out = vec![None; self.structure.n_nodes()];
        for (k, group) in self.contact_groups.iter().enumerate() {
            for &i in group {
                if let Some(slot) = out.get_mut(i) {
                    *slot = Some(k);
                }
            }
        }
        out
    }

    /// Checks the contract of the module docs: sizes and indices, positive R_o, mass and I₁,
    /// and the starting pose (groups 0 and 1 on the slope to 10⁻⁹ R_o, uphill and downhill,
    /// every other contact node above it).
    pub fn validate(&self) -> Result<()> {
        let bad = |name: &'static str, value: f64, reason: String| {
            Err(RollingError::invalid(name, value, reason))
        };
        let n = self.sides();
        for (name, v) in [
            ("outer_radius", self.outer_radius),
            ("mass", self.mass),
            ("i1", self.i1),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return bad(name, v, "must be finite and > 0".into());
            }
        }
        if n < 2 || self.contact_groups.iter().any(Vec::is_empty) {
            return bad(
                "contact_groups",
                n as f64,
                "a wheel needs at least two non-empty contact groups".into(),
            );
        }
        let nodes = self.structure.nodes();
        let listed = self.contact_groups.iter().flatten().chain(&self.rim);
        let axle = self.axle.iter().flatten();
        if let Some(&i) = listed.chain(axle).find(|&&i| i >= nodes.len()) {
            return bad(
                "node",
                i as f64,
                format!("the structure has {} nodes", nodes.len()),
            );
        }
        if self.rim.is_empty() {
            return bad("rim", 0.0, "ω needs at least one rim node".into());
        }
        self.check_pose()
    }

    /// Groups 0 and 1 on the slope (uphill, downhill), every other contact node above it.
    fn check_pose(&self) -> Result<()> {
        let nodes = self.structure.nodes();
        let (z0, tol) = (self.plane_z(), 1e-9 * self.outer_radius);
        for (k, side) in [(0usize, -1.0), (1, 1.0)] {
            for &i in &self.contact_groups[k] {
                let p = nodes[i];
                if (p.z - z0).abs() > tol || side * p.y <= 0.0 {
                    return Err(RollingError::invalid(
                        "contact_groups",
                        i as f64,
                        format!(
                            "node {i} of group {k} is not on the starting side: ({:.6}, {:.6}) against the slope z = {z0:.6} and {} y",
                            p.y,
                            p.z,
                            if k == 0 { "negative" } else { "positive" }
                        ),
                    ));
                }
            }
        }
        let below = self
            .contact_groups
            .iter()
            .flatten()
            .find(|&&i| nodes[i].z < z0 - tol);
        if let Some(&i) = below {
            return Err(RollingError::invalid(
                "contact_groups",
                i as f64,
                format!(
                    "contact node {i} starts {:.3e} m below the slope",
                    z0 - nodes[i].z
                ),
            ));
        }
        Ok(())
    }
}
