//! Rigid bars beside elastic members in the node-mass dynamics ([`crate::transient`]): a
//! rigid bar k from node i to node j keeps its length L_k through the holonomic constraint
//!
//! > g_k(x) = ½ (‖x_j − x_i‖² − L_k²) = 0,
//!
//! whose gradient on the free coordinates q (x = x₀ + Q q) is row k of G: d_kᵀ e_b on a free
//! direction e_b of node j and −d_kᵀ e_b on one of node i, d_k = x_j − x_i. The bar acts on
//! its nodes only through the constraint force Gᵀμ (μ d_k on node j, −μ d_k on node i), so
//! its tension — the force reported for it, tension positive — is t_k = −μ_k ‖d_k‖ = −μ_k L_k:
//! a compressed bar pushes its ends apart, μ_k > 0.
//!
//! **Mass.** A rigid bar's mass m is distributed by the consistent matrix
//! (m/6) [[2, 1], [1, 2]] ⊗ I₃ whatever the scene's `mass_matrix`: with the velocity linear
//! along a rigid rod, ½ q̇ᵀ M q̇ is its exact kinetic energy — translation of the centre plus
//! rotation about it with the inertia m L²/12 —, where the lumped matrix would give m L²/4.
//!
//! **Explicit methods** (RK4, RK45). Every acceleration solves the index-1 saddle system
//!
//! > [M Gᵀ; G 0] [q̈; −μ] = [F; −Ġ q̇],   Ġ q̇ = (‖ẋ_j − ẋ_i‖²)_k,
//!
//! by its Schur complement S = G M⁻¹ Gᵀ (one row per rigid bar, dense Cholesky):
//! S μ = −Ġ q̇ − G M⁻¹ F, q̈ = M⁻¹ (F + Gᵀ μ). After each accepted step the state is projected
//! back ([`RigidBars::project`]): positions by Newton on g(q + M⁻¹ Gᵀ δ) = 0 (the nearest
//! point in the mass metric) until every |g_k| is at round-off (the length to about 10⁻¹⁵
//! relative), then velocities onto G q̇ = 0 in the same metric.
//!
//! **Newmark** ([`crate::newmark`]) solves the step with the multipliers as unknowns: the
//! residual M a₁ − F(q₁, q̇₁) − G(q₁)ᵀ μ₁ = 0 beside g(q₁) = 0, Newton on
//!
//! > [M + (h²/4)(K_T − Σ μ_k H_k) + (h/2) C_T, −Gᵀ; (h²/4) G, 0],   H_k = ∇²g_k = [[I, −I], [−I, I]],
//!
//! until both residuals are at round-off; the velocities are then projected as above. A rigid
//! bar has no axial mode: RK4's stability limit counts the elastic members only.

use crate::dofs::Dofs;
use crate::error::{PathError, Result};
use crate::mass::MassSolver;
use crate::model::{ElasticModel, MemberKind};
use nalgebra::{DMatrix, DVector, Vector3};
use tensegrity_core::error::{CoreError, DynamicsError};

/// Newton iterations of the position projection.
pub const PROJECTION_ITERATIONS: usize = 12;

/// One row of G: (free coordinate, value) pairs.
pub type Row = Vec<(usize, f64)>;

/// The rigid bars of an elastic model (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct RigidBars {
    /// Whether each member of the model is a rigid bar.
    pub is_rigid: Vec<bool>,
    /// The constrained bars' member indices (a rigid bar whose both nodes are held in every
    /// direction has no constraint row: its supports keep its length).
    pub members: Vec<usize>,
    /// Their lengths L_k (m).
    pub lengths: Vec<f64>,
}

impl RigidBars {
    /// The members `rigid` of `model` as rigid bars, their lengths those of the model's
    /// nodes; a member that is not a bar, repeated, out of range or of zero length is an
    /// error naming it.
    pub fn new(model: &ElasticModel, dofs: &Dofs, rigid: &[usize]) -> Result<Self> {
        let mut is_rigid = vec![false; model.members.len()];
        let (mut members, mut lengths) = (Vec::new(), Vec::new());
        for &k in rigid {
            let Some(m) = model.members.get(k) else {
                return Err(PathError::model(
                    format!("rigid member {k}"),
                    format!("does not exist ({} members)", model.members.len()),
                ));
            };
            let name = || format!("member {k} (bar)");
            if m.kind != MemberKind::Bar {
                return Err(PathError::model(
                    format!("member {k} (string)"),
                    "only a bar can be rigid",
                ));
            }
            if is_rigid[k] {
                return Err(PathError::model(name(), "listed twice as rigid"));
            }
            is_rigid[k] = true;
            let [i, j] = m.nodes;
            let l = (model.nodes[j] - model.nodes[i]).norm();
            if !(l.is_finite() && l > 0.0) {
                return Err(PathError::model(
                    name(),
                    format!("a rigid bar of length {l} m: its two nodes must be apart"),
                ));
            }
            if dofs.of_node[i].1 + dofs.of_node[j].1 > 0 {
                members.push(k);
                lengths.push(l);
            }
        }
        Ok(Self {
            is_rigid,
            members,
            lengths,
        })
    }

    /// The number of constraint rows.
    pub fn len(&self) -> usize {
        self.members.len()
    }

    /// Whether no rigid bar is constrained.
    pub fn is_empty(&self) -> bool {
        self.members.is_empty()
    }

    /// The rows of G at node positions `x`.
    pub fn rows(&self, model: &ElasticModel, dofs: &Dofs, x: &[Vector3<f64>]) -> Vec<Row> {
        self.members
            .iter()
            .map(|&k| {
                let [i, j] = model.members[k].nodes;
                let d = x[j] - x[i];
                let mut row = Vec::with_capacity(6);
                for (node, sign) in [(i, -1.0), (j, 1.0)] {
                    let (first, count) = dofs.of_node[node];
                    row.extend((first..first + count).map(|b| (b, sign * d.dot(&dofs.free[b].1))));
                }
                row
            })
            .collect()
    }

    /// The constraint values g_k at positions `x` (m²).
    pub fn residuals(&self, model: &ElasticModel, x: &[Vector3<f64>]) -> DVector<f64> {
        DVector::from_iterator(
            self.len(),
            self.members.iter().zip(&self.lengths).map(|(&k, &l)| {
                let [i, j] = model.members[k].nodes;
                0.5 * ((x[j] - x[i]).norm_squared() - l * l)
            }),
        )
    }

    /// The round-off level of each g_k at positions `x`: 16 ε L_k (L_k + ‖x_i‖ + ‖x_j‖).
    pub fn tolerances(&self, model: &ElasticModel, x: &[Vector3<f64>]) -> DVector<f64> {
        DVector::from_iterator(
            self.len(),
            self.members.iter().zip(&self.lengths).map(|(&k, &l)| {
                let [i, j] = model.members[k].nodes;
                16.0 * f64::EPSILON * l * (l + x[i].norm() + x[j].norm())
            }),
        )
    }

    /// Ġ q̇ = (‖ẋ_j − ẋ_i‖²)_k at node velocities `v`.
    pub fn bias(&self, model: &ElasticModel, v: &[Vector3<f64>]) -> DVector<f64> {
        DVector::from_iterator(
            self.len(),
            self.members.iter().map(|&k| {
                let [i, j] = model.members[k].nodes;
                (v[j] - v[i]).norm_squared()
            }),
        )
    }

    /// The tension of every constrained bar, −μ_k ‖x_j − x_i‖ (N), as (member, tension).
    pub fn tensions<'a>(
        &'a self,
        model: &'a ElasticModel,
        x: &'a [Vector3<f64>],
        mu: &'a DVector<f64>,
    ) -> impl Iterator<Item = (usize, f64)> + 'a {
        self.members.iter().zip(mu.iter()).map(move |(&k, &mu)| {
            let [i, j] = model.members[k].nodes;
            (k, -mu * (x[j] - x[i]).norm())
        })
    }

    /// The accelerations under the constraints (module docs): `a` holds the reduced forces F
    /// on entry and q̈ on return; the multipliers μ are returned. A singular S (dependent
    /// rigid bars) is an error.
    pub fn accelerations(
        &self,
        solver: &MassSolver,
        rows: &[Row],
        bias: &DVector<f64>,
        a: &mut [f64],
    ) -> std::result::Result<DVector<f64>, CoreError> {
        solver.solve_in_place(a);
        if self.is_empty() {
            return Ok(DVector::zeros(0));
        }
        let (w, s) = schur(solver, rows, a.len());
        let rhs = DVector::from_iterator(rows.len(), rows.iter().map(|r| dot(r, a)));
        let rhs = -(bias + rhs);
        let mu = solve_schur(s, &rhs)?;
        for (wk, &mk) in w.iter().zip(mu.iter()) {
            for (ab, wb) in a.iter_mut().zip(wk.iter()) {
                *ab += wb * mk;
            }
        }
        Ok(mu)
    }

    /// Projects the free coordinates `q` onto g = 0 and the velocities `qd` onto G q̇ = 0
    /// in the mass metric (module docs); `expand` gives the node positions of a `q`. Whether
    /// the positions' Newton iteration converged (a singular S is an error).
    pub fn project(
        &self,
        model: &ElasticModel,
        dofs: &Dofs,
        solver: &MassSolver,
        expand: impl Fn(&[f64]) -> Vec<Vector3<f64>>,
        q: &mut [f64],
        qd: &mut [f64],
    ) -> std::result::Result<bool, CoreError> {
        if self.is_empty() {
            return Ok(true);
        }
        let mut converged = false;
        for _ in 0..PROJECTION_ITERATIONS {
            let x = expand(q);
            let g = self.residuals(model, &x);
            let tol = self.tolerances(model, &x);
            if g.iter().zip(tol.iter()).all(|(g, t)| g.abs() <= *t) {
                converged = true;
                break;
            }
            let rows = self.rows(model, dofs, &x);
            let (w, s) = schur(solver, &rows, q.len());
            let delta = solve_schur(s, &g)?;
            for (wk, &dk) in w.iter().zip(delta.iter()) {
                for (qb, wb) in q.iter_mut().zip(wk.iter()) {
                    *qb -= wb * dk;
                }
            }
        }
        if !converged {
            return Ok(false);
        }
        let x = expand(q);
        self.project_velocities(model, dofs, solver, &x, qd)?;
        Ok(true)
    }

    /// Projects `qd` onto G(x) q̇ = 0 in the mass metric: q̇ − M⁻¹Gᵀ S⁻¹ G q̇.
    pub fn project_velocities(
        &self,
        model: &ElasticModel,
        dofs: &Dofs,
        solver: &MassSolver,
        x: &[Vector3<f64>],
        qd: &mut [f64],
    ) -> std::result::Result<(), CoreError> {
        if self.is_empty() {
            return Ok(());
        }
        let rows = self.rows(model, dofs, x);
        let (w, s) = schur(solver, &rows, qd.len());
        let c = DVector::from_iterator(rows.len(), rows.iter().map(|r| dot(r, qd)));
        let delta = solve_schur(s, &c)?;
        for (wk, &dk) in w.iter().zip(delta.iter()) {
            for (vb, wb) in qd.iter_mut().zip(wk.iter()) {
                *vb -= wb * dk;
            }
        }
        Ok(())
    }
}

/// The row `r` times the vector `v`.
pub fn dot(r: &Row, v: &[f64]) -> f64 {
    r.iter().map(|&(b, g)| g * v[b]).sum()
}

/// The columns M⁻¹ G_kᵀ and S = G M⁻¹ Gᵀ on `m` free coordinates.
fn schur(solver: &MassSolver, rows: &[Row], m: usize) -> (Vec<Vec<f64>>, DMatrix<f64>) {
    let w: Vec<Vec<f64>> = rows
        .iter()
        .map(|r| {
            let mut col = vec![0.0; m];
            for &(b, g) in r {
                col[b] += g;
            }
            solver.solve_in_place(&mut col);
            col
        })
        .collect();
    let n = rows.len();
    let s = DMatrix::from_fn(n, n, |k, l| dot(&rows[k], &w[l]));
    (w, s)
}

/// S⁻¹ b by Cholesky; a singular S (dependent rigid bars) is an error.
fn solve_schur(s: DMatrix<f64>, b: &DVector<f64>) -> std::result::Result<DVector<f64>, CoreError> {
    let n = s.nrows();
    let Some(chol) = s.cholesky() else {
        return Err(DynamicsError::SingularConstraint {
            rank: 0,
            expected: n,
        }
        .into());
    };
    Ok(chol.solve(b))
}
