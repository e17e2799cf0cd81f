//! Global sparse equilibrium solve (independent check of the recursion).
//!
//! Unknowns: every member force density q_j. Equations: for each non-support node n and each
//! axis (x, y, z; y, z for a planar truss)
//!
//! Σ_{j ∋ n} q_j (n_other − n) = −w_n,
//!
//! where member j (parent p → child c, m_j = n_p − n_c) contributes −m_j at p and +m_j at c. The
//! truss is statically determinate (3 members per free node in 3-D, 2 in the plane), so the
//! assembled system A q = b is square.
//!
//! # Level-by-level elimination
//!
//! A general sparse LU with a fill-reducing column ordering (COLAMD) fills in badly on this
//! lattice: q = 100 took 219 s. The lattice gives a better order. Give every equation the
//! level k of its node and every unknown the level of its member's parent. Members run from
//! level k to level k + 1, so an equation of level k only involves unknowns of levels k
//! (the node's own members, to its children) and k − 1 (the members from its parents): with
//! equations and unknowns grouped by level, A is block lower bidiagonal,
//!
//! ```text
//! D₀ q₀                 = b₀
//! E₁ q₀ + D₁ q₁         = b₁
//!         E₂ q₁ + D₂ q₂ = b₂ …
//! ```
//!
//! and is solved by block forward substitution, D_k q_k = b_k − E_k q_{k−1}, each square
//! diagonal block D_k factored by the core's sparse LU with partial pivoting
//! ([`tensegrity_linalg::SparseLu`]). Nothing here assumes D_k's inner structure (it
//! happens to be block diagonal, one 3×3 block per node): the blocks are read off the assembled
//! matrix, and an assembled matrix that is not block lower triangular by levels (or a diagonal
//! block that is not square) falls back to one LU of the whole system. The cost is linear in
//! the number of members. The solution is accepted only if it is finite and the relative
//! residual of the whole assembled system is below 1e-9.

use crate::error::{MichellError, Result};
use crate::loads::NodalLoads;
use crate::solution::ForceSolution;
use crate::truss::MichellTruss;
use nalgebra::Vector3;
use tensegrity_linalg::{lu_solve, CscMatrix, SparseLu};

/// Relative residual ‖A q + w‖ / (‖A‖_max·‖q‖₁ + ‖w‖) accepted from the sparse LU.
const RESIDUAL_RTOL: f64 = 1e-9;

/// The assembled global system: triplets of A, the right-hand side, max|A| and ‖w‖₁.
struct Assembled {
    n: usize,
    triplets: Vec<(usize, usize, f64)>,
    rhs: Vec<f64>,
    a_max: f64,
    w_norm: f64,
    /// Level of each equation (its node's level).
    row_level: Vec<usize>,
    /// Level of each unknown (its member's parent level).
    col_level: Vec<usize>,
}

/// Assembles A q = b over the non-support nodes.
fn assemble(truss: &MichellTruss, w: &[Vector3<f64>]) -> Assembled {
    let planar = truss.is_planar();
    let dim = if planar { 2 } else { 3 };
    // Planar rows use the y and z components.
    let axes: &[usize] = if planar { &[1, 2] } else { &[0, 1, 2] };
    let n_free = truss.n_free();
    let members = truss.members();
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
    let n = dim * n_free;
    let mut rhs = vec![0.0; n];
    let mut w_norm = 0.0;
    for node in 0..n_free {
        for (r, &ax) in axes.iter().enumerate() {
            rhs[dim * node + r] = -w[node][ax];
            w_norm += w[node][ax].abs();
        }
    }
    let level = |node: usize| truss.nodes()[node].tuple.level();
    Assembled {
        n,
        triplets,
        rhs,
        a_max,
        w_norm,
        row_level: (0..n).map(|r| level(r / dim)).collect(),
        col_level: members.iter().map(|m| level(m.parent)).collect(),
    }
}

/// Solves the assembled equilibrium of all non-support nodes (see the module documentation).
pub fn solve_global(truss: &MichellTruss, loads: &NodalLoads) -> Result<ForceSolution> {
    let w = loads.dense(truss)?;
    let sys = assemble(truss, &w);
    debug_assert_eq!(truss.members().len(), sys.n);
    // Factorisation failures (structurally singular matrix) come back as the core's
    // `NumericsError::Factorization` inside `MichellError::Core`.
    let a = CscMatrix::from_triplets(sys.n, sys.n, &sys.triplets)?;
    let q = match solve_by_levels(&sys)? {
        Some(q) => q,
        None => lu_solve(&a, &sys.rhs)?,
    };

    // Residual check: a numerically singular matrix factorises but gives garbage.
    let ax = a.mul_vec(&q);
    let res: f64 = ax.iter().zip(&sys.rhs).map(|(l, r)| (l - r).abs()).sum();
    let q_norm: f64 = q.iter().map(|v| v.abs()).sum();
    let scale = sys.a_max * q_norm + sys.w_norm;
    if !(q_norm.is_finite() && res <= RESIDUAL_RTOL * scale.max(f64::MIN_POSITIVE)) {
        return Err(MichellError::SingularSystem {
            relative_residual: res / scale,
        });
    }

    // Reactions: R_s = −(w_s + Σ_parents q_p m_p).
    let n_free = truss.n_free();
    let mut acc: Vec<Vector3<f64>> = w[n_free..].to_vec();
    for (j, m) in truss.members().iter().enumerate() {
        if m.child >= n_free {
            acc[m.child - n_free] += q[j] * m.vector;
        }
    }
    Ok(ForceSolution {
        force_density: q,
        reactions: acc.into_iter().map(|a| -a).collect(),
    })
}

/// One level of the block forward substitution: its equations and unknowns (global indices),
/// the diagonal block D_k and the coupling entries E_k (local row, global unknown, value).
#[derive(Default)]
struct Level {
    rows: Vec<usize>,
    cols: Vec<usize>,
    diagonal: Vec<(usize, usize, f64)>,
    coupling: Vec<(usize, usize, f64)>,
}

/// Splits the assembled matrix into levels; `None` when it is not block lower triangular by
/// levels or a diagonal block is not square.
fn split_levels(sys: &Assembled) -> Option<Vec<Level>> {
    let n_levels = sys.row_level.iter().chain(&sys.col_level).max()? + 1;
    let mut levels: Vec<Level> = (0..n_levels).map(|_| Level::default()).collect();
    let mut local = vec![0usize; sys.n];
    let mut local_col = vec![0usize; sys.n];
    for (r, &k) in sys.row_level.iter().enumerate() {
        local[r] = levels[k].rows.len();
        levels[k].rows.push(r);
    }
    for (j, &k) in sys.col_level.iter().enumerate() {
        local_col[j] = levels[k].cols.len();
        levels[k].cols.push(j);
    }
    if levels.iter().any(|l| l.rows.len() != l.cols.len()) {
        return None;
    }
    for &(r, j, v) in &sys.triplets {
        let (kr, kc) = (sys.row_level[r], sys.col_level[j]);
        if kc == kr {
            levels[kr].diagonal.push((local[r], local_col[j], v));
        } else if kc < kr {
            levels[kr].coupling.push((local[r], j, v));
        } else {
            return None;
        }
    }
    Some(levels)
}

/// Block forward substitution D_k q_k = b_k − E_k q_{k−1} over the levels; `None` when the
/// matrix does not have the level structure.
fn solve_by_levels(sys: &Assembled) -> Result<Option<Vec<f64>>> {
    let Some(levels) = split_levels(sys) else {
        return Ok(None);
    };
    let mut q = vec![0.0; sys.n];
    let mut b = Vec::new();
    for level in levels.iter().filter(|l| !l.rows.is_empty()) {
        let size = level.rows.len();
        let d = CscMatrix::from_triplets(size, size, &level.diagonal)?;
        let mut lu = SparseLu::new(&d)?;
        b.clear();
        b.extend(level.rows.iter().map(|&r| sys.rhs[r]));
        for &(r, j, v) in &level.coupling {
            b[r] -= v * q[j];
        }
        lu.solve_in_place(&mut b);
        for (&j, &x) in level.cols.iter().zip(&b) {
            q[j] = x;
        }
    }
    Ok(Some(q))
}
