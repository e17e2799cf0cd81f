//! Prestressability: the largest margin t such that some self-stress q = V x has every string
//! q_s ≥ t, every bar q_b ≤ −t and max|q| ≤ 1.
//!
//! The linear programme `max t  s.t.  V_s x ≥ t,  V_b x ≤ −t,  −1 ≤ V x ≤ 1` (with V an
//! orthonormal self-stress basis) is solved with the Clarabel interior-point solver, written with
//! two rows per member (t ≥ 0 makes the other two bounds redundant); the margin reported is then
//! recomputed exactly from the returned stress scaled to max|q| = 1, so it is a certified lower
//! bound of the optimum (the two agree to the solver tolerance, 1e-10). The structure is prestressable when
//! t > [`PRESTRESS_TOLERANCE`]. The margin is 0 when there is no self-stress.

use super::Statics;
use crate::error::{CoreError, Result};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use nalgebra::DVector;

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

impl Statics<'_> {
    /// Solves the prestressability LP over the self-stress space.
    pub fn prestressability(&self) -> Result<Prestressability> {
        let basis = self.self_stress_basis();
        let m = basis.nrows();
        let d = basis.ncols();
        let nb = self.structure().n_bars();
        if d == 0 {
            return Ok(Prestressability {
                margin: 0.0,
                prestressable: false,
                stress: DVector::zeros(m),
            });
        }
        // Variables z = [x (d), t]; constraints A z + s = b, s ≥ 0.
        let mut ii = Vec::new();
        let mut jj = Vec::new();
        let mut vv = Vec::new();
        let mut b = Vec::new();
        let mut row = 0;
        let mut push_row =
            |coefs: &mut dyn Iterator<Item = (usize, f64)>, rhs: f64, b: &mut Vec<f64>| {
                for (j, v) in coefs {
                    if v != 0.0 {
                        ii.push(row);
                        jj.push(j);
                        vv.push(v);
                    }
                }
                b.push(rhs);
                row += 1;
            };
        // t ≥ 0 (x = 0 achieves it), so q_s ≥ t already bounds strings below by −1 and
        // q_b ≤ −t bounds bars above by 1: two rows per member suffice.
        for k in 0..m {
            let r = basis.row(k);
            let s = if k < nb { 1.0 } else { -1.0 };
            // strings: t − q_k ≤ 0 and q_k ≤ 1; bars: q_k + t ≤ 0 and −q_k ≤ 1
            push_row(
                &mut (0..d)
                    .map(|j| (j, s * r[j]))
                    .chain(std::iter::once((d, 1.0))),
                0.0,
                &mut b,
            );
            push_row(&mut (0..d).map(|j| (j, -s * r[j])), 1.0, &mut b);
        }
        push_row(&mut std::iter::once((d, -1.0)), 0.0, &mut b);
        let n_rows = b.len();
        let a = CscMatrix::new_from_triplets(n_rows, d + 1, ii, jj, vv);
        let p = CscMatrix::zeros((d + 1, d + 1));
        let mut c = vec![0.0; d + 1];
        c[d] = -1.0;
        let cones = [SupportedConeT::NonnegativeConeT(n_rows)];
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .tol_gap_abs(1e-10)
            .tol_gap_rel(1e-10)
            .tol_feas(1e-10)
            .max_iter(500)
            .build()
            .map_err(|e| CoreError::SolverFailed {
                problem: "prestressability LP",
                status: e.to_string(),
            })?;
        let mut solver = DefaultSolver::new(&p, &c, &a, &b, &cones, settings).map_err(|e| {
            CoreError::SolverFailed {
                problem: "prestressability LP",
                status: e.to_string(),
            }
        })?;
        solver.solve();
        let status = solver.solution.status;
        if !matches!(status, SolverStatus::Solved | SolverStatus::AlmostSolved) {
            return Err(CoreError::SolverFailed {
                problem: "prestressability LP",
                status: format!("{status:?}"),
            });
        }
        let x = DVector::from_iterator(d, solver.solution.x[..d].iter().copied());
        let mut q = &basis * x;
        let scale = q.amax();
        if scale <= 0.0 {
            return Ok(Prestressability {
                margin: 0.0,
                prestressable: false,
                stress: DVector::zeros(m),
            });
        }
        q /= scale;
        let margin = (0..m)
            .map(|k| if k < nb { -q[k] } else { q[k] })
            .fold(f64::INFINITY, f64::min)
            .max(0.0);
        Ok(Prestressability {
            margin,
            prestressable: margin > PRESTRESS_TOLERANCE,
            stress: q,
        })
    }
}
