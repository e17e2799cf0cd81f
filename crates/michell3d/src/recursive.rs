//! Recursive method of joints (§4.4.3, corrected).
//!
//! Equilibrium of node n with load w_n, tension-positive force densities and member vectors
//! m = n_parent − n_child (eq. 4.32–4.35):
//!
//! Σ_children q_c m_c = Σ_parents q_p m_p + w_n,
//!
//! i.e. A X^k r_k = B X^{k−1} r_{k−1} + w of eq. 4.35/4.47, with the columns of A and B exactly the
//! member vectors (ERRATA 4.14). The right side is known once the levels above are solved, so the
//! truss is solved level by level from the tip with one fixed-size 3×3 solve per node (2×2 for the
//! planar truss, in the y–z plane): O(nodes). Instead of the closed-form A⁻¹ of eq. 4.38 (which
//! needs ERRATA 4.15–4.17) each node matrix is factorised directly. The level-q supports take
//! the reactions R_s = −(Σ_parents q_p m_p + w_s).

use crate::error::{MichellError, Result};
use crate::loads::NodalLoads;
use crate::solution::ForceSolution;
use crate::truss::MichellTruss;
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

/// A node whose |det| / Π‖m‖ is below this is reported as singular.
pub const SINGULAR_RTOL: f64 = 1e-12;

/// Above this relative determinant a node is solved by Cramer's rule, below it by LU with
/// partial pivoting.
const CRAMER_MIN_RDET: f64 = 1e-3;

/// The recursive method of joints (see the module docs).
///
/// ```
/// use michell3d::*;
/// let t = MichellTruss::new(MichellParams::cylindrical(1, 1.0, 0.5, 0.4, 0.2)).unwrap();
/// let w = tip_load(100.0, 0.0, std::f64::consts::PI).unwrap();
/// let s = propagate_recursive(&t, &NodalLoads::tip(w)).unwrap();
/// // eq. 4.18/4.20: λ₁₀₁₀ = w₀/(4 r₀ c sin β), λ₀₁₀₀ = −2 λ₁₀₁₀
/// let c = t.params().c();
/// assert!((s.force_density[0] - 100.0 / (4.0 * c * 0.5f64.sin())).abs() < 1e-9);
/// assert!((s.force_density[2] + 2.0 * s.force_density[0]).abs() < 1e-9);
/// ```
pub fn propagate_recursive(truss: &MichellTruss, loads: &NodalLoads) -> Result<ForceSolution> {
    // acc[n] = w_n + Σ_parents q_p m_p, filled as the levels above are solved.
    let mut acc = loads.dense(truss)?;
    let members = truss.members();
    let mut q = vec![0.0; members.len()];
    let k = truss.children_per_node();
    for p in 0..truss.n_free() {
        let ms = &members[k * p..k * p + k];
        let rhs = acc[p];
        if k == 3 {
            let (m0, m1, m2) = (&ms[0].vector, &ms[1].vector, &ms[2].vector);
            let (c12, c20, c01) = (m1.cross(m2), m2.cross(m0), m0.cross(m1));
            let det = m0.dot(&c12);
            let rel = check_det(truss, p, det, ms[0].length * ms[1].length * ms[2].length)?;
            let x = if rel > CRAMER_MIN_RDET {
                // Cramer's rule: cheap and accurate for a well-conditioned 3×3.
                Vector3::new(rhs.dot(&c12), rhs.dot(&c20), rhs.dot(&c01)) / det
            } else {
                Matrix3::from_columns(&[*m0, *m1, *m2])
                    .lu()
                    .solve(&rhs)
                    .ok_or_else(|| singular(truss, p, rel))?
            };
            for s in 0..3 {
                q[3 * p + s] = x[s];
                acc[ms[s].child] += x[s] * ms[s].vector;
            }
        } else {
            // Planar: the y–z components only.
            let a = Matrix2::new(
                ms[0].vector.y,
                ms[1].vector.y,
                ms[0].vector.z,
                ms[1].vector.z,
            );
            let _ = check_det(truss, p, a.determinant(), ms[0].length * ms[1].length)?;
            let x = a
                .lu()
                .solve(&Vector2::new(rhs.y, rhs.z))
                .ok_or_else(|| singular(truss, p, 0.0))?;
            for s in 0..2 {
                q[2 * p + s] = x[s];
                acc[ms[s].child] += x[s] * ms[s].vector;
            }
        }
    }
    if let Some(j) = q.iter().position(|v| !v.is_finite()) {
        return Err(MichellError::NonFinite {
            node: truss.label(truss.members()[j].parent),
        });
    }
    let reactions = acc[truss.n_free()..].iter().map(|a| -a).collect();
    Ok(ForceSolution {
        force_density: q,
        reactions,
    })
}

/// Returns |det| / Π‖m‖, or the singular-node error.
fn check_det(truss: &MichellTruss, node: usize, det: f64, scale: f64) -> Result<f64> {
    let rel = det.abs() / scale;
    if rel.is_finite() && rel > SINGULAR_RTOL {
        Ok(rel)
    } else {
        Err(singular(truss, node, rel))
    }
}

fn singular(truss: &MichellTruss, node: usize, relative_det: f64) -> MichellError {
    MichellError::SingularNode {
        node: truss.label(node),
        relative_det,
    }
}
