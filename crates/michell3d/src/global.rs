//! Global sparse equilibrium solve (independent check of the recursion).
//!
//! Unknowns: every member force density q_j. Equations: for each non-support node n and each
//! axis (x, y, z; y, z for a planar truss)
//!
//! Σ_{j ∋ n} q_j (n_other − n) = −w_n,
//!
//! where member j (parent p → child c, m_j = n_p − n_c) contributes −m_j at p and +m_j at c. The
//! truss is statically determinate (3 members per free node in 3-D, 2 in the plane), so the
//! system is square; it is factorised by the core's sparse LU with partial pivoting
//! ([`tensegrity_core::linalg::lu_solve`]) and the solution is accepted only if it is finite and
//! its relative residual is below 1e-9.

use crate::error::{MichellError, Result};
use crate::loads::NodalLoads;
use crate::solution::ForceSolution;
use crate::truss::MichellTruss;
use nalgebra::Vector3;
use tensegrity_core::linalg::{lu_solve, CscMatrix};

/// Relative residual ‖A q + w‖ / (‖A‖_max·‖q‖₁ + ‖w‖) accepted from the sparse LU.
const RESIDUAL_RTOL: f64 = 1e-9;

/// Solves the assembled equilibrium of all non-support nodes with one sparse LU.
pub fn solve_global(truss: &MichellTruss, loads: &NodalLoads) -> Result<ForceSolution> {
    let w = loads.dense(truss)?;
    let planar = truss.is_planar();
    let dim = if planar { 2 } else { 3 };
    // Planar rows use the y and z components.
    let axes: &[usize] = if planar { &[1, 2] } else { &[0, 1, 2] };
    let n_free = truss.n_free();
    let n = dim * n_free;
    let members = truss.members();
    debug_assert_eq!(members.len(), n);

    let mut triplets = Vec::with_capacity(2 * dim * members.len());
    let mut a_max = 0.0f64;
    for (j, m) in members.iter().enumerate() {
        for (r, &ax) in axes.iter().enumerate() {
            let v = m.vector[ax];
            a_max = a_max.max(v.abs());
            if v != 0.0 {
                triplets.push((dim * m.parent + r, j, -v));
                if m.child < n_free {
                    triplets.push((dim * m.child + r, j, v));
                }
            }
        }
    }
    // Factorisation failures (structurally singular matrix) come back as the core's
    // `CoreError::Factorization` inside `MichellError::Core`.
    let a = CscMatrix::from_triplets(n, n, &triplets)?;
    let mut rhs = vec![0.0; n];
    let mut w_norm = 0.0;
    for node in 0..n_free {
        for (r, &ax) in axes.iter().enumerate() {
            rhs[dim * node + r] = -w[node][ax];
            w_norm += w[node][ax].abs();
        }
    }
    let q = lu_solve(&a, &rhs)?;

    // Residual check: a numerically singular matrix factorises but gives garbage.
    let ax = a.mul_vec(&q);
    let res: f64 = ax.iter().zip(&rhs).map(|(l, r)| (l - r).abs()).sum();
    let q_norm: f64 = q.iter().map(|v| v.abs()).sum();
    let scale = a_max * q_norm + w_norm;
    if !(q_norm.is_finite() && res <= RESIDUAL_RTOL * scale.max(f64::MIN_POSITIVE)) {
        return Err(MichellError::SingularSystem {
            relative_residual: res / scale,
        });
    }

    // Reactions: R_s = −(w_s + Σ_parents q_p m_p).
    let mut acc: Vec<Vector3<f64>> = w[n_free..].to_vec();
    for (j, m) in members.iter().enumerate() {
        if m.child >= n_free {
            acc[m.child - n_free] += q[j] * m.vector;
        }
    }
    Ok(ForceSolution {
        force_density: q,
        reactions: acc.into_iter().map(|a| -a).collect(),
    })
}
