//! Prestressability: the largest margin t such that some self-stress q = V x has every string
//! q_s ≥ t, every bar q_b ≤ −t and max|q| ≤ 1.
//!
//! The linear programme `max t  s.t.  V_s x ≥ t,  V_b x ≤ −t,  −1 ≤ V x ≤ 1` (with V an
//! orthonormal self-stress basis) is written with two rows per member (t ≥ 0 makes the other two
//! bounds redundant) and solved by the dense interior-point method of `dense_lp` (default) or
//! by the Clarabel conic solver ([`crate::LpSolver`]); the margin reported is then
//! recomputed exactly from the returned stress scaled to max|q| = 1, so it is a certified lower
//! bound of the optimum (the two agree to the solver tolerance, 1e-10). The structure is prestressable when
//! t > [`PRESTRESS_TOLERANCE`]. The margin is 0 when there is no self-stress.
//!
//! The same LP with other member signs ([`MemberSign`]: a member may also be sign-free, e.g. a
//! bar of a rigid body, bounded only by |q| ≤ 1) is [`Statics::prestressability_with`]; the
//! sparse and the cyclic back-ends build the same rows ([`margin_lp`]).

use super::{dense_lp, LpSolver, Statics};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use nalgebra::{DMatrix, DVector};
use tensegrity_core::error::{CoreError, ModelError, NumericsError, Result};

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
}

/// The sign a member's force density must take in the margin LP.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MemberSign {
    /// q ≥ t: a string.
    Tension,
    /// q ≤ −t: a bar.
    Compression,
    /// Either sign, only |q| ≤ 1 (e.g. a bar of a rigid body, whose members carry either sign).
    Free,
}

impl MemberSign {
    /// σ = +1 for tension, −1 for compression; `None` when the sign is free.
    pub fn sigma(self) -> Option<f64> {
        match self {
            MemberSign::Tension => Some(1.0),
            MemberSign::Compression => Some(-1.0),
            MemberSign::Free => None,
        }
    }

    /// The prestressability signs of a structure: bars in compression, strings and clusters
    /// (after the strings) in tension.
    ///
    /// ```
    /// use tensegrity_statics::MemberSign;
    /// use tensegrity_core::{Bar, StringMember, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    ///     .bar(Bar::new(0, 1))
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(MemberSign::standard(&s), vec![MemberSign::Compression]);
    /// ```
    pub fn standard(structure: &tensegrity_core::structure::Structure) -> Vec<MemberSign> {
        (0..crate::n_columns(structure))
            .map(|k| {
                if crate::cluster_columns::is_tension_only(structure, k) {
                    MemberSign::Tension
                } else {
                    MemberSign::Compression
                }
            })
            .collect()
    }
}

impl Prestressability {
    /// From the LP's self-stress q with the member signs of the LP: scaled to max|q| = 1,
    /// margin min over the signed members of σ q, clipped at 0 (none when q = 0 or no member
    /// has a sign).
    pub(crate) fn from_signed(mut q: DVector<f64>, signs: &[MemberSign]) -> Self {
        let scale = q.amax();
        if scale <= 0.0 {
            return Self::none(q.len());
        }
        q /= scale;
        let margin = q
            .iter()
            .zip(signs)
            .filter_map(|(&v, s)| s.sigma().map(|sigma| sigma * v))
            .fold(f64::INFINITY, f64::min);
        let margin = if margin.is_finite() {
            margin.max(0.0)
        } else {
            0.0
        };
        Self {
            margin,
            prestressable: margin > PRESTRESS_TOLERANCE,
            stress: q,
        }
    }
}

/// Solves the margin LP over the columns of `basis` (rows: members, or member orbits of a
/// symmetric basis; columns: self-stress states) and returns the coefficients x of the
/// maximising state q = basis · x.
///
/// Variables z = [x (d), t]; constraints G z ≤ h. t ≥ 0 (x = 0 achieves it), so a signed
/// member needs two rows: t − σ q_k ≤ 0 and σ q_k ≤ 1 (σ q_k ≥ t ≥ 0 already bounds it below
/// by −1); a free member needs q_k ≤ 1 and −q_k ≤ 1.
pub(crate) fn margin_lp(
    basis: &DMatrix<f64>,
    signs: &[MemberSign],
    solver: LpSolver,
    problem: &'static str,
) -> Result<DVector<f64>> {
    let (m, d) = (basis.nrows(), basis.ncols());
    let rows = 2 * m + 1;
    let mut g = DMatrix::zeros(rows, d + 1);
    let mut h = DVector::zeros(rows);
    for k in 0..m {
        let (first, t) = match signs[k].sigma() {
            Some(sigma) => (-sigma, 1.0),
            None => (1.0, 0.0),
        };
        for j in 0..d {
            g[(2 * k, j)] = first * basis[(k, j)];
            g[(2 * k + 1, j)] = -first * basis[(k, j)];
        }
        g[(2 * k, d)] = t;
        h[2 * k] = 1.0 - t;
        h[2 * k + 1] = 1.0;
    }
    g[(2 * m, d)] = -1.0;
    let mut c = DVector::zeros(d + 1);
    c[d] = -1.0;
    let dense = match solver {
        LpSolver::DenseInteriorPoint => dense_lp::solve(&g, &h, &c, 1e-10).ok(),
        LpSolver::Clarabel => None,
    };
    let z = match dense {
        Some(z) => z,
        None => solve_clarabel(&g, &h, &c, problem)?,
    };
    Ok(z.rows(0, d).into_owned())
}

impl Statics<'_> {
    /// Solves the prestressability LP over the self-stress space (bars compressed, strings
    /// in tension).
    pub fn prestressability(&self) -> Result<Prestressability> {
        self.prestressability_with(&MemberSign::standard(self.structure()))
    }

    /// The margin LP over the self-stress space with the given member signs (see
    /// [`MemberSign`]): the largest t such that some self-stress with max|q| = 1 has
    /// σ q_k ≥ t for every signed member.
    pub fn prestressability_with(&self, signs: &[MemberSign]) -> Result<Prestressability> {
        let basis = self.self_stress_basis();
        check_signs(signs, basis.nrows())?;
        if basis.ncols() == 0 {
            return Ok(Prestressability::none(basis.nrows()));
        }
        let x = margin_lp(
            &basis,
            signs,
            self.settings.lp_solver,
            "prestressability LP",
        )?;
        Ok(Prestressability::from_signed(&basis * x, signs))
    }
}

/// Refuses a sign list whose length is not the number of members.
pub(crate) fn check_signs(signs: &[MemberSign], members: usize) -> Result<()> {
    if signs.len() != members {
        return Err(ModelError::LengthMismatch {
            what: "member signs of the margin LP".into(),
            expected: members,
            found: signs.len(),
        }
        .into());
    }
    Ok(())
}

/// Solves a small dense linear programme `min cᵀz  s.t.  G z ≤ h` (G: rows × p, rows ≥ p):
/// the dense interior-point method of the prestressability LP first, Clarabel when it fails.
/// `problem` names the LP in the error ([`NumericsError::SolverFailed`](tensegrity_core::error::NumericsError::SolverFailed)) when both fail, e.g.
/// because the programme is infeasible or unbounded.
///
/// ```
/// use nalgebra::{dmatrix, dvector};
/// // min −x − y  s.t.  x ≤ 1, y ≤ 2, x + y ≤ 2.5, −x ≤ 0, −y ≤ 0  →  optimum −2.5
/// let g = dmatrix![1.0, 0.0; 0.0, 1.0; 1.0, 1.0; -1.0, 0.0; 0.0, -1.0];
/// let h = dvector![1.0, 2.0, 2.5, 0.0, 0.0];
/// let z = tensegrity_statics::solve_lp(&g, &h, &dvector![-1.0, -1.0], "example").unwrap();
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

/// The margin LP over a sparse self-stress basis N (members × s, not necessarily
/// orthonormal): `max t  s.t.  σ_k (N c)_k ≥ t,  σ_k (N c)_k ≤ 1` for signed members and
/// `|(N c)_k| ≤ 1` for free ones, t ≥ 0; the same rows as [`margin_lp`] with q = N c, so the
/// optimum (scale-free after q is rescaled to max|q| = 1) is the same. The constraint matrix
/// has N's sparsity (three entries per stored entry of N at most), so Clarabel's sparse
/// interior point costs about what a factorisation of N's pattern does. Returns c.
pub(super) fn solve_null_space_lp(
    basis: &tensegrity_linalg::CscMatrix,
    signs: &[MemberSign],
) -> Result<Vec<f64>> {
    let problem = "prestressability LP (sparse self-stress basis)";
    let (n, s) = (basis.pattern().nrows(), basis.pattern().ncols());
    let (cp, ri, vals) = (
        basis.pattern().col_ptr(),
        basis.pattern().row_idx(),
        basis.values(),
    );
    let (mut ii, mut jj, mut vv) = (Vec::new(), Vec::new(), Vec::new());
    for c in 0..s {
        for slot in cp[c]..cp[c + 1] {
            let (k, v) = (ri[slot], vals[slot]);
            let first = signs[k].sigma().map_or(1.0, |sigma| -sigma);
            ii.extend([2 * k, 2 * k + 1]);
            jj.extend([c, c]);
            vv.extend([first * v, -first * v]);
        }
    }
    let mut b = vec![0.0; 2 * n + 1];
    for k in 0..n {
        match signs[k].sigma() {
            Some(_) => {
                ii.push(2 * k);
                jj.push(s);
                vv.push(1.0);
            }
            None => b[2 * k] = 1.0,
        }
        b[2 * k + 1] = 1.0;
    }
    ii.push(2 * n);
    jj.push(s);
    vv.push(-1.0);
    let a = CscMatrix::new_from_triplets(2 * n + 1, s + 1, ii, jj, vv);
    let mut c = vec![0.0; s + 1];
    c[s] = -1.0;
    let cones = [SupportedConeT::NonnegativeConeT(2 * n + 1)];
    let mut z = run_clarabel(&a, &c, &b, &cones, problem)?;
    z.truncate(s);
    Ok(z)
}

/// The margin LP over the member force densities themselves, with the equilibrium as
/// equality rows: `max t  s.t.  A q = 0,  σ_k q_k ≥ t,  σ_k q_k ≤ 1` for signed members,
/// `|q_k| ≤ 1` for free ones, t ≥ 0 — the rows of [`solve_null_space_lp`] without a
/// self-stress basis (for a structure whose basis is large and not local, e.g. a lattice).
/// The constraint matrix has A's sparsity plus two entries per member, so Clarabel's sparse
/// LDL costs about a factorisation of A's pattern. Returns q (A q = 0 to the solver's
/// feasibility tolerance, 10⁻¹⁰).
pub(super) fn solve_equilibrium_lp(
    a: &tensegrity_linalg::CscMatrix,
    signs: &[MemberSign],
) -> Result<Vec<f64>> {
    let problem = "prestressability LP (equilibrium rows)";
    let (m, n) = (a.pattern().nrows(), a.pattern().ncols());
    let (cp, ri, vals) = (a.pattern().col_ptr(), a.pattern().row_idx(), a.values());
    let (mut ii, mut jj, mut vv) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..n {
        for slot in cp[k]..cp[k + 1] {
            ii.push(ri[slot]);
            jj.push(k);
            vv.push(vals[slot]);
        }
    }
    // inequality rows m + 2k (σ_k q_k ≥ t, or q_k ≤ 1 when free) and m + 2k + 1 (σ_k q_k ≤ 1,
    // or −q_k ≤ 1 when free); the last row −t ≤ 0
    let mut b = vec![0.0; m + 2 * n + 1];
    for k in 0..n {
        let first = signs[k].sigma().map_or(1.0, |sigma| -sigma);
        ii.extend([m + 2 * k, m + 2 * k + 1]);
        jj.extend([k, k]);
        vv.extend([first, -first]);
        match signs[k].sigma() {
            Some(_) => {
                ii.push(m + 2 * k);
                jj.push(n);
                vv.push(1.0);
            }
            None => b[m + 2 * k] = 1.0,
        }
        b[m + 2 * k + 1] = 1.0;
    }
    ii.push(m + 2 * n);
    jj.push(n);
    vv.push(-1.0);
    let g = CscMatrix::new_from_triplets(m + 2 * n + 1, n + 1, ii, jj, vv);
    let mut c = vec![0.0; n + 1];
    c[n] = -1.0;
    let cones = [
        SupportedConeT::ZeroConeT(m),
        SupportedConeT::NonnegativeConeT(2 * n + 1),
    ];
    let mut z = run_clarabel(&g, &c, &b, &cones, problem)?;
    z.truncate(n);
    Ok(z)
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
    let failed =
        |status: String| CoreError::Numerics(NumericsError::SolverFailed { problem, status });
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
