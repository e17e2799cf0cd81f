//! Prestressability: the largest margin t such that some self-stress q = V x has every string
//! q_s ≥ t, every bar q_b ≤ −t and max|q| ≤ 1.
//!
//! The linear programme `max t  s.t.  V_s x ≥ t,  V_b x ≤ −t,  −1 ≤ V x ≤ 1` (with V an
//! orthonormal self-stress basis) is written with two rows per member (t ≥ 0 makes the other two
//! bounds redundant) and solved by the dense interior-point method of `dense_lp` (default) or
//! by the Clarabel conic solver ([`crate::statics::LpSolver`]); the margin reported is then
//! recomputed exactly from the returned stress scaled to max|q| = 1, so it is a certified lower
//! bound of the optimum (the two agree to the solver tolerance, 1e-10). The structure is prestressable when
//! t > [`PRESTRESS_TOLERANCE`]. The margin is 0 when there is no self-stress.

use super::{dense_lp, LpSolver, Statics};
use crate::error::{CoreError, Result};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use nalgebra::{DMatrix, DVector};

/// Margins at or below this value count as "not prestressable".
pub const PRESTRESS_TOLERANCE: f64 = 1e-8;

/// The result of the prestressability LP.
#[derive(Debug, Clone, PartialEq)]
pub struct Prestressability {
    /// The margin t ∈ [0, 1].
    pub margin: f64,
    /// Whether t > [`PRESTRESS_TOLERANCE`].
    pub prestressable: bool,
    /// The maximising self-stress, scaled to max|q| = 1 (zero when there is no self-stress).
    pub stress: DVector<f64>,
}

impl Prestressability {
    /// No prestress: margin 0 and a zero stress of `members` entries.
    pub(crate) fn none(members: usize) -> Self {
        Self {
            margin: 0.0,
            prestressable: false,
            stress: DVector::zeros(members),
        }
    }

    /// From the LP's self-stress q (bars first, `nb` of them): scaled to max|q| = 1, margin
    /// min(−q_bars, q_strings) clipped at 0 (none when q = 0).
    pub(crate) fn from_stress(mut q: DVector<f64>, nb: usize) -> Self {
        let scale = q.amax();
        if scale <= 0.0 {
            return Self::none(q.len());
        }
        q /= scale;
        let margin = q
            .iter()
            .enumerate()
            .map(|(k, &v)| if k < nb { -v } else { v })
            .fold(f64::INFINITY, f64::min)
            .max(0.0);
        Self {
            margin,
            prestressable: margin > PRESTRESS_TOLERANCE,
            stress: q,
        }
    }
}

impl Statics<'_> {
    /// Solves the prestressability LP over the self-stress space.
    pub fn prestressability(&self) -> Result<Prestressability> {
        let basis = self.self_stress_basis();
        let m = basis.nrows();
        let d = basis.ncols();
        let nb = self.structure().n_bars();
        if d == 0 {
            return Ok(Prestressability::none(m));
        }
        // Variables z = [x (d), t]; constraints G z ≤ h. t ≥ 0 (x = 0 achieves it), so
        // q_s ≥ t already bounds strings below by −1 and q_b ≤ −t bounds bars above by 1: two
        // rows per member suffice. Strings: t − q_k ≤ 0, q_k ≤ 1; bars: q_k + t ≤ 0, −q_k ≤ 1.
        let rows = 2 * m + 1;
        let mut g = DMatrix::zeros(rows, d + 1);
        let mut h = DVector::zeros(rows);
        for k in 0..m {
            let sign = if k < nb { 1.0 } else { -1.0 };
            for j in 0..d {
                g[(2 * k, j)] = sign * basis[(k, j)];
                g[(2 * k + 1, j)] = -sign * basis[(k, j)];
            }
            g[(2 * k, d)] = 1.0;
            h[2 * k + 1] = 1.0;
        }
        g[(2 * m, d)] = -1.0;
        let mut c = DVector::zeros(d + 1);
        c[d] = -1.0;
        let dense = match self.settings.lp_solver {
            LpSolver::DenseInteriorPoint => dense_lp::solve(&g, &h, &c, 1e-10).ok(),
            LpSolver::Clarabel => None,
        };
        let z = match dense {
            Some(z) => z,
            None => solve_clarabel(&g, &h, &c, "prestressability LP")?,
        };
        let x = z.rows(0, d).into_owned();
        Ok(Prestressability::from_stress(&basis * x, nb))
    }
}

/// Solves a small dense linear programme `min cᵀz  s.t.  G z ≤ h` (G: rows × p, rows ≥ p):
/// the dense interior-point method of the prestressability LP first, Clarabel when it fails.
/// `problem` names the LP in the error ([`CoreError::SolverFailed`]) when both fail, e.g.
/// because the programme is infeasible or unbounded.
///
/// ```
/// use nalgebra::{dmatrix, dvector};
/// // min −x − y  s.t.  x ≤ 1, y ≤ 2, x + y ≤ 2.5, −x ≤ 0, −y ≤ 0  →  optimum −2.5
/// let g = dmatrix![1.0, 0.0; 0.0, 1.0; 1.0, 1.0; -1.0, 0.0; 0.0, -1.0];
/// let h = dvector![1.0, 2.0, 2.5, 0.0, 0.0];
/// let z = tensegrity_core::statics::solve_lp(&g, &h, &dvector![-1.0, -1.0], "example").unwrap();
/// assert!((z[0] + z[1] - 2.5).abs() < 1e-8);
/// ```
pub fn solve_lp(
    g: &DMatrix<f64>,
    h: &DVector<f64>,
    c: &DVector<f64>,
    problem: &'static str,
) -> Result<DVector<f64>> {
    match dense_lp::solve(g, h, c, 1e-10) {
        Ok(z) => Ok(z),
        Err(_) => solve_clarabel(g, h, c, problem),
    }
}

/// The margin LP over the member force densities of a structure with `nb` bars (bars first),
/// the self-stress space given by the r × n equations `r_eq` q = 0 of full row rank:
/// `max t  s.t.  r_eq q = 0, q_s ≥ t, q_b ≤ −t, |q| ≤ 1, t ≥ 0`, by Clarabel (sparse). Returns
/// z = [q, t].
pub(super) fn solve_member_lp(r_eq: &crate::linalg::CscMatrix, nb: usize) -> Result<Vec<f64>> {
    let problem = "prestressability LP (sparse)";
    let (r, n) = (r_eq.pattern().nrows(), r_eq.pattern().ncols());
    let (mut ii, mut jj, mut vv) = (Vec::new(), Vec::new(), Vec::new());
    let (cp, ri, vals) = (
        r_eq.pattern().col_ptr(),
        r_eq.pattern().row_idx(),
        r_eq.values(),
    );
    for k in 0..n {
        for s in cp[k]..cp[k + 1] {
            ii.push(ri[s]);
            jj.push(k);
            vv.push(vals[s]);
        }
    }
    // inequalities A z + s = b, s ≥ 0 (same rows as the dense LP)
    let mut b = vec![0.0; r + 2 * n + 1];
    for k in 0..n {
        let sign = if k < nb { 1.0 } else { -1.0 };
        let row = r + 2 * k;
        ii.extend([row, row, row + 1]);
        jj.extend([k, n, k]);
        vv.extend([sign, 1.0, -sign]);
        b[row + 1] = 1.0;
    }
    ii.push(r + 2 * n);
    jj.push(n);
    vv.push(-1.0);
    let a = CscMatrix::new_from_triplets(r + 2 * n + 1, n + 1, ii, jj, vv);
    let mut c = vec![0.0; n + 1];
    c[n] = -1.0;
    let cones = [
        SupportedConeT::ZeroConeT(r),
        SupportedConeT::NonnegativeConeT(2 * n + 1),
    ];
    run_clarabel(&a, &c, &b, &cones, problem)
}

/// Solves min cᵀz s.t. G z ≤ h with Clarabel.
fn solve_clarabel(
    g: &DMatrix<f64>,
    h: &DVector<f64>,
    c: &DVector<f64>,
    problem: &'static str,
) -> Result<DVector<f64>> {
    let (rows, cols) = g.shape();
    let (mut ii, mut jj, mut vv) = (Vec::new(), Vec::new(), Vec::new());
    for j in 0..cols {
        for i in 0..rows {
            if g[(i, j)] != 0.0 {
                ii.push(i);
                jj.push(j);
                vv.push(g[(i, j)]);
            }
        }
    }
    let a = CscMatrix::new_from_triplets(rows, cols, ii, jj, vv);
    let cones = [SupportedConeT::NonnegativeConeT(rows)];
    let x = run_clarabel(&a, c.as_slice(), h.as_slice(), &cones, problem)?;
    Ok(DVector::from_column_slice(&x))
}

/// min cᵀz s.t. A z + s = b, s ∈ `cones` (no quadratic term) with Clarabel at the tolerances
/// of both LPs (10⁻¹⁰ on gap and feasibility, at most 500 iterations).
fn run_clarabel(
    a: &CscMatrix<f64>,
    c: &[f64],
    b: &[f64],
    cones: &[SupportedConeT<f64>],
    problem: &'static str,
) -> Result<Vec<f64>> {
    let failed = |status: String| CoreError::SolverFailed { problem, status };
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-10)
        .tol_gap_rel(1e-10)
        .tol_feas(1e-10)
        .max_iter(500)
        .build()
        .map_err(|e| failed(e.to_string()))?;
    let p = CscMatrix::zeros((c.len(), c.len()));
    let mut solver =
        DefaultSolver::new(&p, c, a, b, cones, settings).map_err(|e| failed(e.to_string()))?;
    solver.solve();
    let status = solver.solution.status;
    if !matches!(status, SolverStatus::Solved | SolverStatus::AlmostSolved) {
        return Err(failed(format!("{status:?}")));
    }
    Ok(solver.solution.x.clone())
}
