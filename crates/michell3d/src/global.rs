//! Global sparse equilibrium solve (independent check of the recursion).
//!
//! Unknowns: every member force density q_j. Equations: for each non-support node n and each
//! axis (x, y, z; y, z for a planar truss)
//!
//! Σ_{j ∋ n} q_j (n_other − n) = −w_n,
//!
//! where member j (parent p → child c, m_j = n_p − n_c) contributes −m_j at p and +m_j at c. The
//! truss is statically determinate (3 members per free node in 3-D, 2 in the plane), so the
//! system is square; it is factorised with faer's sparse LU (partial pivoting) and the solution
//! is accepted only if it is finite and its relative residual is below 1e-9.

use crate::error::{MichellError, Result};
use crate::loads::NodalLoads;
use crate::propagation::ForceSolution;
use crate::truss::MichellTruss;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuSymbolicParams, NumericLu};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMat, Triplet};
use faer::Mat;
use faer::{Conj, Par};
use nalgebra::Vector3;

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
                triplets.push(Triplet::new(dim * m.parent + r, j, -v));
                if m.child < n_free {
                    triplets.push(Triplet::new(dim * m.child + r, j, v));
                }
            }
        }
    }
    let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets).map_err(|e| {
        MichellError::SingularSystem {
            reason: format!("assembling the sparse matrix: {e:?}"),
        }
    })?;
    let mut rhs = Mat::<f64>::zeros(n, 1);
    let mut w_norm = 0.0;
    for node in 0..n_free {
        for (r, &ax) in axes.iter().enumerate() {
            rhs[(dim * node + r, 0)] = -w[node][ax];
            w_norm += w[node][ax].abs();
        }
    }
    let x = lu_solve(&a, &rhs)?;
    let q: Vec<f64> = (0..n).map(|i| x[(i, 0)]).collect();

    // Residual check: a numerically singular matrix factorises but gives garbage.
    let ax = &a * &x;
    let res: f64 = (0..n).map(|i| (ax[(i, 0)] - rhs[(i, 0)]).abs()).sum();
    let q_norm: f64 = q.iter().map(|v| v.abs()).sum();
    let scale = a_max * q_norm + w_norm;
    if !(q_norm.is_finite() && res <= RESIDUAL_RTOL * scale.max(f64::MIN_POSITIVE)) {
        return Err(MichellError::SingularSystem {
            reason: format!(
                "relative residual {:.3e} (matrix numerically singular)",
                res / scale
            ),
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

/// Sparse LU with partial pivoting (faer: COLAMD column ordering, supernodal or simplicial
/// numeric factorisation chosen by faer), run sequentially (DESIGN.md: parallelism belongs to
/// the sweeps).
fn lu_solve(a: &SparseColMat<usize, f64>, rhs: &Mat<f64>) -> Result<Mat<f64>> {
    let fail = |what: &str, e: &dyn std::fmt::Debug| MichellError::SingularSystem {
        reason: format!("sparse LU ({what}): {e:?}"),
    };
    let symbolic = factorize_symbolic_lu(
        a.symbolic(),
        LuSymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::AUTO,
            ..Default::default()
        },
    )
    .map_err(|e| fail("symbolic", &e))?;
    let mut numeric = NumericLu::<usize, f64>::new();
    let scratch = symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default());
    let mut buf = MemBuffer::try_new(scratch).map_err(|e| fail("memory", &e))?;
    let lu = symbolic
        .factorize_numeric_lu(
            &mut numeric,
            a.as_ref(),
            Par::Seq,
            MemStack::new(&mut buf),
            Default::default(),
        )
        .map_err(|e| fail("numeric", &e))?;
    let mut x = rhs.clone();
    let scratch = symbolic.solve_in_place_scratch::<f64>(x.ncols(), Par::Seq);
    let mut buf = MemBuffer::try_new(scratch).map_err(|e| fail("memory", &e))?;
    lu.solve_in_place_with_conj(Conj::No, x.as_mut(), Par::Seq, MemStack::new(&mut buf));
    Ok(x)
}
