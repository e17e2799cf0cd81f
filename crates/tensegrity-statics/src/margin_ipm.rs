//! The prestressability margin LP over the force densities of a large structure, by a
//! primal-dual interior-point method whose linear systems are the equilibrium normal
//! matrix A D⁻¹ Aᵀ (free dofs × free dofs, the sparsity of a stiffness matrix), factored by
//! the sparse supernodal Cholesky.
//!
//! With p_k = σ_k q_k (σ_k = −1 for a compressed member, +1 otherwise) and A' = A diag(σ):
//!
//! `min −t  s.t.  A' p = 0,  s1 = p − e t − l ≥ 0,  s2 = 1 − p ≥ 0`
//!
//! e_k = 1 and l_k = 0 for a signed member (t ≤ p_k ≤ 1), e_k = 0 and l_k = −1 for a free
//! one (|q_k| ≤ 1). Dual variables y (equilibrium), z1, z2 ≥ 0; optimality:
//! A'ᵀy + z1 − z2 = 0, eᵀz1 = 1, s∘z = 0. Each Newton step eliminates the slacks and duals
//! member by member (D = Z1/S1 + Z2/S2, d1 = e∘Z1/S1), leaving
//!
//! `[M  u; −uᵀ  c] [dy; dt] = [f1; f2]`,  M = A' D⁻¹ A'ᵀ, u = A' D⁻¹ d1, c = Σd1 − d1ᵀD⁻¹d1,
//!
//! solved by one factorisation of M (+ δI, δ = 10⁻¹³·max diag, for the mechanisms) and a
//! Schur complement on t; then dp = D⁻¹(A'ᵀdy + d1 dt + w). Mehrotra's predictor-corrector
//! (the step a fraction max(0.99, 1 − 10μ) of the way to the boundary), at most
//! [`MAX_ITERATIONS`] steps, stopping when the equilibrium residual, the dual
//! residual and the complementarity are below 10⁻¹¹ (relative). The stress returned is
//! q = σ∘p; the caller recomputes its margin.

use super::prestress::MemberSign;
use tensegrity_core::error::{CoreError, NumericsError, Result};
use tensegrity_linalg::{CscMatrix, CscPattern, SparseCholesky};

/// Most interior-point steps.
pub const MAX_ITERATIONS: usize = 80;
const TOL: f64 = 1e-11;
/// The step goes a fraction max(0.99, 1 − 10 μ) of the way to the boundary.
const STEP_CLOSENESS: f64 = 10.0;

/// Solves the margin LP (module documentation) for the equilibrium matrix `a` (dofs ×
/// members); returns q. `ordering` (`fwd[new] = old` over the dofs, e.g. the structure's
/// nested dissection) orders the normal matrix's Cholesky factor; AMD's when `None`.
pub fn solve(a: &CscMatrix, signs: &[MemberSign], ordering: Option<&[usize]>) -> Result<Vec<f64>> {
    let failed = |status: &str| {
        CoreError::Numerics(NumericsError::SolverFailed {
            problem: "prestressability LP (interior point on A D⁻¹ Aᵀ)",
            status: status.to_string(),
        })
    };
    let (m, n) = (a.pattern().nrows(), a.pattern().ncols());
    let (cp, ri, av) = (a.pattern().col_ptr(), a.pattern().row_idx(), a.values());
    let sigma: Vec<f64> = signs.iter().map(|s| s.sigma().unwrap_or(1.0)).collect();
    let e: Vec<f64> = signs
        .iter()
        .map(|s| f64::from(u8::from(s.sigma().is_some())))
        .collect();
    let l: Vec<f64> = e.iter().map(|&e| e - 1.0).collect();
    let n_signed: f64 = e.iter().sum();
    if n_signed == 0.0 {
        return Err(failed("no signed member"));
    }
    let normal = NormalPattern::of(a)?;
    let (pattern, diag) = (&normal.pattern, &normal.diag);
    let mut chol = match ordering {
        Some(fwd) => SparseCholesky::with_ordering(pattern, fwd)?,
        None => SparseCholesky::new(pattern)?,
    };
    // A' x and A'ᵀ y
    let apply = |x: &[f64]| -> Vec<f64> {
        let mut y = vec![0.0; m];
        for k in 0..n {
            let xk = sigma[k] * x[k];
            for s in cp[k]..cp[k + 1] {
                y[ri[s]] += av[s] * xk;
            }
        }
        y
    };
    let apply_t = |y: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|k| sigma[k] * (cp[k]..cp[k + 1]).map(|s| av[s] * y[ri[s]]).sum::<f64>())
            .collect()
    };
    // start: p midway, t = 0, unit slacks and duals (eᵀz1 = 1 is reached on the way)
    let mut p: Vec<f64> = l.iter().map(|&l| 0.5 * (1.0 + l)).collect();
    let mut tt = 0.0;
    let mut y = vec![0.0; m];
    let (mut s1, mut s2) = (vec![1.0; n], vec![1.0; n]);
    let (mut z1, mut z2) = (vec![1.0; n], vec![1.0; n]);
    let mut values = vec![0.0; pattern.nnz()];
    for _ in 0..MAX_ITERATIONS {
        let atp = apply(&p);
        let aty = apply_t(&y);
        let r_p = atp;
        let r_d: Vec<f64> = (0..n).map(|k| aty[k] + z1[k] - z2[k]).collect();
        let r_t = (0..n).map(|k| e[k] * z1[k]).sum::<f64>() - 1.0;
        let r1: Vec<f64> = (0..n).map(|k| p[k] - e[k] * tt - l[k] - s1[k]).collect();
        let r2: Vec<f64> = (0..n).map(|k| 1.0 - p[k] - s2[k]).collect();
        let mu = (0..n).map(|k| s1[k] * z1[k] + s2[k] * z2[k]).sum::<f64>() / (2 * n) as f64;
        let norm = |v: &[f64]| v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        if norm(&r_p) < TOL
            && norm(&r_d) < TOL
            && r_t.abs() < TOL
            && norm(&r1) < TOL
            && norm(&r2) < TOL
            && mu < TOL
        {
            return Ok((0..n).map(|k| sigma[k] * p[k]).collect());
        }
        // the normal matrix
        let dd: Vec<f64> = (0..n).map(|k| z1[k] / s1[k] + z2[k] / s2[k]).collect();
        let d1: Vec<f64> = (0..n).map(|k| e[k] * z1[k] / s1[k]).collect();
        values.iter_mut().for_each(|v| *v = 0.0);
        let w: Vec<f64> = dd.iter().map(|d| 1.0 / d).collect();
        for &(slot, k, product) in &normal.entries {
            values[slot] += w[k] * product;
        }
        let dmax = diag.iter().fold(0.0f64, |a, &s| a.max(values[s]));
        for &s in diag {
            values[s] += 1e-13 * dmax.max(f64::MIN_POSITIVE);
        }
        chol.factor(&values)
            .map_err(|_| failed("normal matrix not positive definite"))?;
        let mut mu_inv_u: Vec<f64> = apply(&(0..n).map(|k| d1[k] / dd[k]).collect::<Vec<_>>());
        let u = mu_inv_u.clone();
        chol.solve_in_place(&mut mu_inv_u);
        let c = (0..n).map(|k| d1[k] - d1[k] * d1[k] / dd[k]).sum::<f64>();
        let ut_minv_u: f64 = u.iter().zip(&mu_inv_u).map(|(a, b)| a * b).sum();
        // one Newton direction for the complementarity targets rc1, rc2
        let mut direction = |rc1: &[f64], rc2: &[f64]| {
            let g: Vec<f64> = (0..n)
                .map(|k| {
                    -rc1[k] / s1[k] - z1[k] / s1[k] * r1[k] + rc2[k] / s2[k] + z2[k] / s2[k] * r2[k]
                })
                .collect();
            let w: Vec<f64> = (0..n).map(|k| g[k] + r_d[k]).collect();
            let h1: f64 = (0..n)
                .map(|k| e[k] * (-rc1[k] / s1[k] - z1[k] / s1[k] * r1[k]))
                .sum();
            let aw = apply(&(0..n).map(|k| w[k] / dd[k]).collect::<Vec<_>>());
            let mut f1: Vec<f64> = (0..m).map(|i| -r_p[i] - aw[i]).collect();
            let f2 = -r_t - h1 + (0..n).map(|k| d1[k] * w[k] / dd[k]).sum::<f64>();
            let u_f1: f64 = {
                chol.solve_in_place(&mut f1);
                u.iter().zip(&f1).map(|(a, b)| a * b).sum()
            };
            let dt = (f2 + u_f1) / (c + ut_minv_u);
            let dy: Vec<f64> = (0..m).map(|i| f1[i] - mu_inv_u[i] * dt).collect();
            let atdy = apply_t(&dy);
            let dp: Vec<f64> = (0..n)
                .map(|k| (atdy[k] + d1[k] * dt + w[k]) / dd[k])
                .collect();
            let ds1: Vec<f64> = (0..n).map(|k| dp[k] - e[k] * dt + r1[k]).collect();
            let ds2: Vec<f64> = (0..n).map(|k| -dp[k] + r2[k]).collect();
            let dz1: Vec<f64> = (0..n).map(|k| (-rc1[k] - z1[k] * ds1[k]) / s1[k]).collect();
            let dz2: Vec<f64> = (0..n).map(|k| (-rc2[k] - z2[k] * ds2[k]) / s2[k]).collect();
            (dp, dt, dy, ds1, ds2, dz1, dz2)
        };
        let step = |x: &[f64], dx: &[f64]| {
            x.iter()
                .zip(dx)
                .filter(|&(_, &d)| d < 0.0)
                .fold(1.0f64, |a, (&x, &d)| a.min(-x / d))
        };
        // predictor
        let rc1: Vec<f64> = (0..n).map(|k| s1[k] * z1[k]).collect();
        let rc2: Vec<f64> = (0..n).map(|k| s2[k] * z2[k]).collect();
        let (_, _, _, ds1, ds2, dz1, dz2) = direction(&rc1, &rc2);
        let alpha = step(&s1, &ds1)
            .min(step(&s2, &ds2))
            .min(step(&z1, &dz1))
            .min(step(&z2, &dz2));
        let mu_aff = (0..n)
            .map(|k| {
                (s1[k] + alpha * ds1[k]) * (z1[k] + alpha * dz1[k])
                    + (s2[k] + alpha * ds2[k]) * (z2[k] + alpha * dz2[k])
            })
            .sum::<f64>()
            / (2 * n) as f64;
        let centre = (mu_aff / mu).powi(3) * mu;
        // corrector
        let rc1: Vec<f64> = (0..n)
            .map(|k| s1[k] * z1[k] + ds1[k] * dz1[k] - centre)
            .collect();
        let rc2: Vec<f64> = (0..n)
            .map(|k| s2[k] * z2[k] + ds2[k] * dz2[k] - centre)
            .collect();
        let (dp, dt, dy, ds1, ds2, dz1, dz2) = direction(&rc1, &rc2);
        // the fraction of the way to the boundary: 0.99 while far from the optimum, closer
        // to 1 as the complementarity falls (the iterate is then well centred), which takes
        // the lattices' LP from 8–9 steps to 5
        let eta = (1.0 - STEP_CLOSENESS * mu).max(0.99);
        let alpha = eta
            * step(&s1, &ds1)
                .min(step(&s2, &ds2))
                .min(step(&z1, &dz1))
                .min(step(&z2, &dz2));
        let alpha = alpha.min(1.0);
        for k in 0..n {
            p[k] += alpha * dp[k];
            s1[k] += alpha * ds1[k];
            s2[k] += alpha * ds2[k];
            z1[k] += alpha * dz1[k];
            z2[k] += alpha * dz2[k];
        }
        tt += alpha * dt;
        for i in 0..m {
            y[i] += alpha * dy[i];
        }
        if !tt.is_finite() {
            return Err(failed("diverged"));
        }
    }
    Err(failed("no convergence"))
}

/// The lower triangle of the pattern of A Aᵀ (A dofs × members) and, column by column, the
/// contribution of each member to each of its slots: (slot, member, a_ik a_jk).
struct NormalPattern {
    pattern: CscPattern,
    entries: Vec<(usize, usize, f64)>,
    diag: Vec<usize>,
}

impl NormalPattern {
    /// Built in one pass over the rows of A (linear in the entries of A Aᵀ, no sort of them).
    fn of(a: &CscMatrix) -> Result<Self> {
        let (m, n) = (a.pattern().nrows(), a.pattern().ncols());
        let (cp, ri, av) = (a.pattern().col_ptr(), a.pattern().row_idx(), a.values());
        // the members of each row, with the position of the row in the member's column
        let mut row_ptr = vec![0usize; m + 1];
        for &i in ri {
            row_ptr[i + 1] += 1;
        }
        for i in 0..m {
            row_ptr[i + 1] += row_ptr[i];
        }
        let mut fill = row_ptr.clone();
        let mut row_members = vec![(0usize, 0usize); ri.len()];
        for k in 0..n {
            for s in cp[k]..cp[k + 1] {
                row_members[fill[ri[s]]] = (k, s);
                fill[ri[s]] += 1;
            }
        }
        let mut col_ptr = vec![0usize];
        let mut row_idx = Vec::new();
        let mut diag = Vec::with_capacity(m);
        let mut entries = Vec::new();
        let mut mark = vec![usize::MAX; m];
        let mut slot_of = vec![0usize; m];
        for j in 0..m {
            let start = row_idx.len();
            mark[j] = j;
            row_idx.push(j);
            for &(k, _) in &row_members[row_ptr[j]..row_ptr[j + 1]] {
                for &i in &ri[cp[k]..cp[k + 1]] {
                    if i > j && mark[i] != j {
                        mark[i] = j;
                        row_idx.push(i);
                    }
                }
            }
            row_idx[start..].sort_unstable();
            for (slot, &i) in row_idx.iter().enumerate().skip(start) {
                slot_of[i] = slot;
            }
            diag.push(slot_of[j]);
            for &(k, s2) in &row_members[row_ptr[j]..row_ptr[j + 1]] {
                for s1 in cp[k]..cp[k + 1] {
                    if ri[s1] >= j {
                        entries.push((slot_of[ri[s1]], k, av[s1] * av[s2]));
                    }
                }
            }
            col_ptr.push(row_idx.len());
        }
        Ok(Self {
            pattern: CscPattern::new(m, col_ptr, row_idx)?,
            entries,
            diag,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prestress::{solve_equilibrium_lp, Prestressability};
    use crate::sparse::equilibrium_matrix_sparse;
    use crate::DofMap;
    use nalgebra::DVector;

    /// The interior point (AMD and the dissection's order) against Clarabel on the same rows,
    /// for the standard signs, some members free, every sign flipped and a pseudo-random mix
    /// (not prestressable: the interior point must still end, at the same margin).
    #[test]
    fn the_interior_point_matches_clarabel_on_hard_sign_patterns() {
        let s = tensegrity_core::test_models::double_layer_grid(6).unwrap();
        let dofs = DofMap::of(&s);
        let a = equilibrium_matrix_sparse(&s, &dofs).unwrap();
        let order = crate::nested::dof_fronts(&s, &dofs).0.concat();
        let standard = MemberSign::standard(&s);
        let flip = |x: MemberSign| match x {
            MemberSign::Tension => MemberSign::Compression,
            MemberSign::Compression => MemberSign::Tension,
            MemberSign::Free => MemberSign::Free,
        };
        let patterns: Vec<Vec<MemberSign>> = vec![
            standard.clone(),
            (standard.iter().enumerate())
                .map(|(k, &x)| if k % 7 == 0 { MemberSign::Free } else { x })
                .collect(),
            standard.iter().map(|&x| flip(x)).collect(),
            (standard.iter().enumerate())
                .map(|(k, &x)| if (k * 7919) % 13 < 3 { flip(x) } else { x })
                .collect(),
        ];
        let margin = |q: Vec<f64>, signs: &[MemberSign]| {
            Prestressability::from_signed(DVector::from_vec(q), signs).margin
        };
        let mut margins = Vec::new();
        for signs in &patterns {
            let reference = margin(solve_equilibrium_lp(&a, signs).unwrap(), signs);
            for ordering in [None, Some(order.as_slice())] {
                let q = solve(&a, signs, ordering).unwrap();
                let eq = a.mul_vec(&q).iter().fold(0.0f64, |m, x| m.max(x.abs()));
                assert!(eq < 1e-9, "A q = {eq}");
                let ours = margin(q, signs);
                assert!(
                    (ours - reference).abs() < 1e-7,
                    "{ours} against Clarabel's {reference}"
                );
            }
            margins.push(reference);
        }
        // the uniform stress is optimal for the standard signs, and its negative for the
        // flipped ones (−q is a self-stress too); the mix is not prestressable
        assert!((margins[0] - 1.0).abs() < 1e-9, "{margins:?}");
        assert!((margins[2] - margins[0]).abs() < 1e-9, "{margins:?}");
        assert!(margins[3] <= 1e-9, "{margins:?}");
    }
}
