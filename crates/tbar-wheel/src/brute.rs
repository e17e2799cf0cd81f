//! An independent brute-force check of the minimum prestress (issue 11, "Must show").
//!
//! It shares only the structure and the self-stress space with the LP of
//! [`crate::envelope`], and differs in every other step:
//!
//! 1. the stiffness is assembled member by member from 3×3 blocks (EA/L) e eᵀ on the free
//!    nodes (not from the equilibrium matrix), factored once;
//! 2. every member's worst case is **searched** over load directions instead of taken from the
//!    closed form ‖g‖: one displacement solve K u = w₀d per direction and member forces
//!    (EA/L) eᵀ(u_j − u_i), on a quasi-uniform sphere, then refined by a compass search in a
//!    tangent chart around the best sample (steps down to 1e-10 rad);
//! 3. the prestress state is **searched** instead of optimised by an LP: with the bar force
//!    normalised to −1, the states form an affine space σ(β) = S(α₀ + Nβ) of dimension
//!    (self-stress dim − 1); the smallest admissible bar compression of a state is
//!    P(β) = w₀ max(D_bar, max_strings D_k / σ_k(β)) (∞ when a string has σ_k ≤ 0), with D_k
//!    the worst force drop of string k (rise of the bar) per newton, and it is minimised by a
//!    zooming grid search (convex in β, so the zoom converges to the minimum).
//!
//! It handles one bar and one loaded tip (a single tread) with at most two free state
//! parameters (self-stress dimension ≤ 3), which covers the q = 1 tread (dimension 2).

use crate::error::{invalid, Result, TbarError};
use nalgebra::{DMatrix, DVector, Vector3};
use tensegrity_core::Structure;
use tensegrity_statics::Statics;

/// Directions of the coarse sphere sample of the brute force.
pub const COARSE_DIRECTIONS: usize = 600;

/// The brute-force minimum prestress (N) of a one-bar structure for a load of magnitude
/// `load` on node `tip` in any direction, with axial stiffness `ea` for every member.
pub fn brute_force_min_prestress(
    structure: &Structure,
    tip: usize,
    ea: f64,
    load: f64,
) -> Result<f64> {
    if structure.n_bars() != 1 {
        return Err(TbarError::BruteForceUnsupported {
            reason: format!(
                "needs exactly one bar, the structure has {}",
                structure.n_bars()
            ),
        });
    }
    let solver = DirectSolver::new(structure, tip, ea)?;
    let worst = worst_changes(&solver);
    let statics = Statics::new(structure)?;
    let v = statics.self_stress_basis();
    let lengths = structure.member_lengths();
    let mut s = v.clone();
    for (k, mut row) in s.row_iter_mut().enumerate() {
        row *= lengths[k];
    }
    search_states(&s, &worst, load)
}

/// Displacement solves for a load on one node.
struct DirectSolver {
    chol: nalgebra::Cholesky<f64, nalgebra::Dyn>,
    free: Vec<Option<usize>>,
    tip_row: usize,
    members: Vec<([usize; 2], Vector3<f64>, f64)>,
}

impl DirectSolver {
    fn new(structure: &Structure, tip: usize, ea: f64) -> Result<Self> {
        let fixed = structure.fixed_dofs();
        let mut free = vec![None; structure.n_nodes()];
        let mut n = 0;
        for (i, f) in fixed.iter().enumerate() {
            if f.iter().any(|x| *x) {
                continue;
            }
            free[i] = Some(n);
            n += 1;
        }
        let tip_row = free
            .get(tip)
            .copied()
            .flatten()
            .ok_or_else(|| invalid("tip", tip as f64, "the loaded tip must be a free node"))?;
        let mut k = DMatrix::zeros(3 * n, 3 * n);
        let mut members = Vec::new();
        for (m, [i, j]) in structure.member_nodes().into_iter().enumerate() {
            let v = structure.member_vector(m);
            let l = v.norm();
            let e = v / l;
            let block = (ea / l) * e * e.transpose();
            for (a, sa) in [(i, -1.0), (j, 1.0)] {
                for (b, sb) in [(i, -1.0), (j, 1.0)] {
                    if let (Some(ra), Some(rb)) = (free[a], free[b]) {
                        let mut view = k.fixed_view_mut::<3, 3>(3 * ra, 3 * rb);
                        view += sa * sb * block;
                    }
                }
            }
            members.push(([i, j], e, ea / l));
        }
        let chol = k.cholesky().ok_or(TbarError::Mechanism {
            structure: "tread",
            mechanisms: 1,
        })?;
        Ok(Self {
            chol,
            free,
            tip_row,
            members,
        })
    }

    /// Member force changes (N) for a unit load along `d` on the tip.
    fn forces(&self, d: &Vector3<f64>) -> Vec<f64> {
        let mut w = DVector::zeros(3 * self.free.iter().flatten().count());
        for c in 0..3 {
            w[3 * self.tip_row + c] = d[c];
        }
        let u = self.chol.solve(&w);
        let disp = |i: usize| {
            self.free[i].map_or(Vector3::zeros(), |r| {
                Vector3::new(u[3 * r], u[3 * r + 1], u[3 * r + 2])
            })
        };
        self.members
            .iter()
            .map(|([i, j], e, k)| k * e.dot(&(disp(*j) - disp(*i))))
            .collect()
    }
}

/// Worst change per newton for every member: the largest force drop of a string, the largest
/// force rise of the bar (member 0), searched over directions.
fn worst_changes(solver: &DirectSolver) -> Vec<f64> {
    let dirs = crate::envelope::sphere_directions(COARSE_DIRECTIONS);
    let samples: Vec<Vec<f64>> = dirs.iter().map(|d| solver.forces(d)).collect();
    let m = solver.members.len();
    (0..m)
        .map(|k| {
            let sign = if k == 0 { 1.0 } else { -1.0 };
            let f = |d: &Vector3<f64>| sign * solver.forces(d)[k];
            let best = (0..dirs.len())
                .max_by(|&a, &b| (sign * samples[a][k]).total_cmp(&(sign * samples[b][k])))
                .unwrap_or(0);
            refine_on_sphere(dirs[best], f).max(0.0)
        })
        .collect()
}

/// Maximises f over unit vectors near `d0` by compass search in a tangent chart.
fn refine_on_sphere(d0: Vector3<f64>, f: impl Fn(&Vector3<f64>) -> f64) -> f64 {
    let helper = if d0.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let e1 = d0.cross(&helper).normalize();
    let e2 = d0.cross(&e1);
    let at = |a: f64, b: f64| (d0 + a * e1 + b * e2).normalize();
    let (mut a, mut b) = (0.0, 0.0);
    let mut best = f(&at(a, b));
    let mut step = 0.2;
    while step > 1e-10 {
        let mut moved = false;
        for (da, db) in [(step, 0.0), (-step, 0.0), (0.0, step), (0.0, -step)] {
            let v = f(&at(a + da, b + db));
            if v > best {
                best = v;
                a += da;
                b += db;
                moved = true;
                break;
            }
        }
        if !moved {
            step *= 0.5;
        }
    }
    best
}

/// Minimises P(β) over the prestress states with bar force −1.
fn search_states(s: &DMatrix<f64>, worst: &[f64], load: f64) -> Result<f64> {
    let dim = s.ncols();
    if dim == 0 || dim > 3 {
        return Err(TbarError::BruteForceUnsupported {
            reason: format!("self-stress dimension {dim} (supported: 1 to 3)"),
        });
    }
    // α₀: minimal-norm coefficients with bar force −1; N: the complement of the bar row
    let bar_row = s.row(0).transpose();
    let norm2 = bar_row.norm_squared();
    if norm2 == 0.0 {
        return Err(TbarError::BruteForceUnsupported {
            reason: "no self-stress loads the bar".into(),
        });
    }
    let alpha0 = -&bar_row / norm2;
    let mut complement = DMatrix::identity(dim, dim) - &bar_row * bar_row.transpose() / norm2;
    let svd = complement.clone().svd(true, false);
    let u = svd.u.unwrap_or_else(|| DMatrix::identity(dim, dim));
    complement = u.columns(0, dim - 1).into_owned();
    let p_of = |beta: &[f64]| -> f64 {
        let alpha = &alpha0 + &complement * DVector::from_column_slice(beta);
        let sigma = s * alpha;
        let mut p = worst[0];
        for k in 1..sigma.len() {
            if sigma[k] <= 0.0 {
                return f64::INFINITY;
            }
            p = p.max(worst[k] / sigma[k]);
        }
        load * p
    };
    let radius = 10.0 * (1.0 + alpha0.norm());
    let best = zoom_grid(dim - 1, radius, &p_of);
    if best.is_finite() {
        Ok(best)
    } else {
        Err(TbarError::NotPrestressable {
            structure: "tread",
            self_stress_dim: dim,
        })
    }
}

/// Minimises a convex function of `n` ≤ 2 variables on [−r, r]ⁿ by zooming grids.
fn zoom_grid(n: usize, r: f64, f: &dyn Fn(&[f64]) -> f64) -> f64 {
    if n == 0 {
        return f(&[]);
    }
    let pts = if n == 1 { 4001 } else { 201 };
    let mut center = vec![0.0; n];
    let mut half = r;
    let mut best = f64::INFINITY;
    while half > 1e-14 * r {
        let h = 2.0 * half / (pts - 1) as f64;
        let mut next = center.clone();
        let count = if n == 1 { pts } else { pts * pts };
        for idx in 0..count {
            let i = idx % pts;
            let j = idx / pts;
            let mut x = vec![center[0] - half + i as f64 * h];
            if n == 2 {
                x.push(center[1] - half + j as f64 * h);
            }
            let v = f(&x);
            if v < best {
                best = v;
                next = x;
            }
        }
        center = next;
        half = 4.0 * h;
    }
    best
}
