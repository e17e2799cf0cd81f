//! Node tuples, their merging, numbering and positions.
//!
//! A 3-D node is the tuple (U, D, L, R) with 𝕏 = L − R, ℤ = U − D and level k = U + D
//! (§4.3.1). The principal node is (0,0,0,0); the children of a node are
//! (U+1, D, L+1, R), (U+1, D, L, R+1) and (U, D+1, L, R). Identical tuples reached from
//! different parents are one node (ERRATA 4.6), so level l holds the tuples with U + D = l and
//! L + R = U: (l+1)(l+2)/2 nodes, (q+1)(q+2)(q+3)/6 in a complexity-q truss.
//!
//! Positions (ERRATA 4.7: r_k of the node's own level):
//!
//! - cylindrical (eq. 4.11): n = r_k [𝕏 δ, cos ℤφ, sin ℤφ];
//! - spherical (eq. 4.12):   n = r_k [cos(ℤφ) tan(𝕏ε), cos ℤφ, sin ℤφ];
//! - planar (Skelton, eq. 4.7): n_ik = r_{i+k} [0, cos((i−k)φ), sin((i−k)φ)], i.e. the 3-D
//!   node with i = U, k = D projected on the y–z plane.
//!
//! Numbering: level by level; inside level l, 3-D nodes by D = 0..l then L = U..0, and planar
//! nodes by k = 0..l. Every lookup is a closed form, so no hash map is needed.

use crate::params::{Geometry, MichellParams};
use nalgebra::Vector3;
use serde::Serialize;

/// A node tuple. For planar trusses only `u` (= i) and `d` (= k) are used and `l = u`, `r = 0`.
#[allow(non_snake_case)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct NodeTuple {
    /// U: steps up (towards +ℤ).
    pub u: usize,
    /// D: steps down.
    pub d: usize,
    /// L: up-steps to the left (+𝕏).
    pub l: usize,
    /// R: up-steps to the right (−𝕏).
    pub r: usize,
}

impl NodeTuple {
    /// The tuple (U, D, L, R).
    pub fn new(u: usize, d: usize, l: usize, r: usize) -> Self {
        Self { u, d, l, r }
    }

    /// The planar node n_ik (i = U, k = D).
    pub fn planar(i: usize, k: usize) -> Self {
        Self {
            u: i,
            d: k,
            l: i,
            r: 0,
        }
    }

    /// Level k = U + D.
    pub fn level(&self) -> usize {
        self.u + self.d
    }

    /// 𝕏 = L − R.
    pub fn x(&self) -> i64 {
        self.l as i64 - self.r as i64
    }

    /// ℤ = U − D.
    pub fn z(&self) -> i64 {
        self.u as i64 - self.d as i64
    }

    /// The three children of a 3-D node: UL = (U+1,D,L+1,R), UR = (U+1,D,L,R+1), D = (U,D+1,L,R).
    pub fn children(&self) -> [NodeTuple; 3] {
        let NodeTuple { u, d, l, r } = *self;
        [
            NodeTuple::new(u + 1, d, l + 1, r),
            NodeTuple::new(u + 1, d, l, r + 1),
            NodeTuple::new(u, d + 1, l, r),
        ]
    }

    /// The two children of a planar node n_ik: n_(i+1)k and n_i(k+1).
    pub fn planar_children(&self) -> [NodeTuple; 2] {
        [
            NodeTuple::planar(self.u + 1, self.d),
            NodeTuple::planar(self.u, self.d + 1),
        ]
    }

    /// The label used in reports: `[U, D, L, R]`, or `[i, k]` when `planar`.
    pub fn label(&self, planar: bool) -> Vec<usize> {
        if planar {
            vec![self.u, self.d]
        } else {
            vec![self.u, self.d, self.l, self.r]
        }
    }
}

/// Nodes in level l of a 3-D truss after merging: (l+1)(l+2)/2.
pub fn nodes_in_level_3d(level: usize) -> usize {
    (level + 1) * (level + 2) / 2
}

/// Nodes of a complexity-q 3-D truss: (q+1)(q+2)(q+3)/6 (eq. 4.10, ERRATA 4.6).
pub fn node_count_3d(q: usize) -> usize {
    (q + 1) * (q + 2) * (q + 3) / 6
}

/// Members of a complexity-q 3-D truss: 3 per non-support node, q(q+1)(q+2)/2.
pub fn member_count_3d(q: usize) -> usize {
    q * (q + 1) * (q + 2) / 2
}

/// Nodes of a complexity-q planar truss: (q+1)(q+2)/2.
pub fn node_count_planar(q: usize) -> usize {
    (q + 1) * (q + 2) / 2
}

/// Members of a complexity-q planar truss: 2 per non-support node, q(q+1).
pub fn member_count_planar(q: usize) -> usize {
    q * (q + 1)
}

/// Index of a 3-D tuple in the node numbering (levels first, then D, then L descending).
/// The tuple must satisfy L + R = U.
pub fn index_3d(t: &NodeTuple) -> usize {
    let lev = t.level();
    let offset = lev * (lev + 1) * (lev + 2) / 6;
    let before_d = t.d * (lev + 1) - t.d * t.d.saturating_sub(1) / 2;
    offset + before_d + (t.u - t.l)
}

/// Index of a planar tuple n_ik in the planar numbering.
pub fn index_planar(t: &NodeTuple) -> usize {
    let lev = t.level();
    lev * (lev + 1) / 2 + t.d
}

/// Every tuple of a complexity-q truss in numbering order.
pub fn tuples(q: usize, planar: bool) -> Vec<NodeTuple> {
    let mut out = Vec::with_capacity(if planar {
        node_count_planar(q)
    } else {
        node_count_3d(q)
    });
    for lev in 0..=q {
        for d in 0..=lev {
            let u = lev - d;
            if planar {
                out.push(NodeTuple::planar(u, d));
            } else {
                for l in (0..=u).rev() {
                    out.push(NodeTuple::new(u, d, l, u - l));
                }
            }
        }
    }
    out
}

/// Position of a node (eq. 4.7, 4.11, 4.12).
pub fn position(params: &MichellParams, t: &NodeTuple) -> Vector3<f64> {
    let r = params.radius(t.level());
    let zphi = t.z() as f64 * params.phi;
    let (s, c) = zphi.sin_cos();
    let x = match params.geometry {
        Geometry::Planar => 0.0,
        Geometry::Cylindrical { delta } => t.x() as f64 * delta,
        Geometry::Spherical { epsilon } => c * (t.x() as f64 * epsilon).tan(),
    };
    r * Vector3::new(x, c, s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::MichellParams;

    #[test]
    fn q1_positions_match_thesis_examples() {
        // §4.3.2/4.3.3: n1010 = r1[δ, cos φ, sin φ], n0100 = r1[0, cos φ, −sin φ],
        // spherical n1001 = r1[cos φ tan(−ε), cos φ, sin φ].
        let (phi, delta, eps) = (0.3, 0.2, 0.15);
        let p = MichellParams::cylindrical(1, 2.0, 0.5, phi, delta);
        let r1 = p.radius(1);
        let n = position(&p, &NodeTuple::new(1, 0, 1, 0));
        assert!((n - r1 * Vector3::new(delta, phi.cos(), phi.sin())).norm() < 1e-15);
        let n = position(&p, &NodeTuple::new(0, 1, 0, 0));
        assert!((n - r1 * Vector3::new(0.0, phi.cos(), -phi.sin())).norm() < 1e-15);
        let s = MichellParams::spherical(1, 2.0, 0.5, phi, eps);
        let n = position(&s, &NodeTuple::new(1, 0, 0, 1));
        let want = r1 * Vector3::new(phi.cos() * (-eps).tan(), phi.cos(), phi.sin());
        assert!((n - want).norm() < 1e-15);
        assert_eq!(
            position(&p, &NodeTuple::new(0, 0, 0, 0)),
            Vector3::new(0.0, 2.0, 0.0)
        );
    }

    #[test]
    fn closed_form_counts() {
        assert_eq!(node_count_3d(35), 8436);
        assert_eq!(member_count_3d(4), 60);
        assert_eq!(
            (1..=5).map(nodes_in_level_3d).collect::<Vec<_>>(),
            [3, 6, 10, 15, 21]
        );
        assert_eq!(tuples(6, false).len(), node_count_3d(6));
        assert_eq!(tuples(6, true).len(), node_count_planar(6));
    }
}
