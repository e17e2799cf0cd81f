//! A one-sided, factorisation-only certificate of prestress stability for structures whose
//! flexes are not local (long towers): the penalised stress matrix.
//!
//! With Ω̄ = Ω ⊗ I₃ the stress matrix of force densities q, A the equilibrium matrix (so that
//! Aᵀw are the elongation rates of a velocity w) and P the restriction to the kept (not
//! pinned) dofs,
//!
//! K_μ = P (Ω̄ − σ′ I + μ A Aᵀ) Pᵀ = P [Σ_k q_k (e_i − e_j)(e_i − e_j)ᵀ ⊗ I₃ + μ a_k a_kᵀ] Pᵀ − σ′ I
//!
//! is banded like A Aᵀ, member by member. For every flex w on the kept dofs (Aᵀw = 0),
//! wᵀK_μ w = wᵀΩ̄w − σ′‖w‖², so K_μ positive definite (a sparse Cholesky succeeds) implies
//! wᵀΩ̄w > σ′‖w‖² on every pinned flex, hence on its rigid-motion-free representative (the
//! shortest of its class, Ω̄ annihilating rigid motions): the dense test's "stable". The
//! Cholesky's backward error E is covered by σ′ = σ + (allowance): K_μ + E positive
//! definite with ‖E‖ ≤ 64·c·ε·‖K_μ‖_∞ (c the most entries of a row) still gives
//! wᵀΩ̄w > σ‖w‖². The converse needs μ large enough (Finsler's lemma), so a ladder of μ is
//! tried; when none succeeds the answer is "no decision", never "unstable".
use super::DofMap;
use nalgebra::DVector;
use tensegrity_core::error::Result;
use tensegrity_core::structure::Structure;
use tensegrity_linalg::{self as linalg, CscMatrix};

/// Penalty weights tried, as multiples of max|q| / σ_max(A)².
const MU_LADDER: [f64; 5] = [1e2, 1e3, 1e4, 1e5, 1e6];

/// `Some(true)` when K_μ is positive definite for one μ of the ladder (certified stable),
/// `None` otherwise. `index` numbers the kept dofs among the free rows (`kept` of them),
/// `sigma` is the dense test's threshold and `sigma_a` σ_max(A).
pub(super) fn stable_by_penalty(
    structure: &Structure,
    dofs: &DofMap,
    index: &[Option<usize>],
    kept: usize,
    q: &DVector<f64>,
    sigma: f64,
    sigma_a: f64,
) -> Result<Option<bool>> {
    let q_max = q.amax();
    if kept == 0 || !(sigma_a > 0.0 && q_max.is_finite()) {
        return Ok(None);
    }
    let at = |node: usize, dir: usize| dofs.row[node][dir].and_then(|r| index[r]);
    // per member: the stress part (weight 1) and the penalty part (weight μ) separately
    let (mut t_stress, mut t_pen) = (Vec::new(), Vec::new());
    for (k, [i, j]) in structure.member_nodes().into_iter().enumerate() {
        let e = structure.nodes()[j] - structure.nodes()[i];
        let mut slots = Vec::with_capacity(6);
        for d in 0..3 {
            let (a, b) = (at(i, d), at(j, d));
            for r in [a, b].into_iter().flatten() {
                t_stress.push((r, r, q[k]));
            }
            // −q between axis d of i and the axes of j (axis d alone, weight 1, unless a
            // node has a frame)
            if let Some(a) = a {
                for (c, w) in dofs.coupling(i, d, j).into_iter().enumerate() {
                    if let (Some(b), true) = (at(j, c), w != 0.0) {
                        let (r, s) = if a >= b { (a, b) } else { (b, a) };
                        t_stress.push((r, s, -q[k] * w));
                    }
                }
            }
            if let Some(a) = a {
                slots.push((a, -dofs.component(i, d, &e)));
            }
            if let Some(b) = b {
                slots.push((b, dofs.component(j, d, &e)));
            }
        }
        for &(r, vr) in &slots {
            for &(s, vs) in &slots {
                if r >= s {
                    t_pen.push((r, s, vr * vs));
                }
            }
        }
    }
    let mut t: Vec<(usize, usize, f64)> = (0..kept).map(|r| (r, r, 0.0)).collect();
    t.extend(t_stress.iter().copied());
    t.extend(t_pen.iter().map(|&(r, s, _)| (r, s, 0.0)));
    let pattern = CscMatrix::from_triplets(kept, kept, &t)?;
    let lower = pattern.pattern();
    // the stress and penalty parts summed once into the pattern's slots; every μ then
    // costs one pass over the values and one factorisation (no triplets sorted again)
    let nnz = lower.nnz();
    let (mut v_stress, mut v_pen) = (vec![0.0; nnz], vec![0.0; nnz]);
    for (parts, values) in [(&t_stress, &mut v_stress), (&t_pen, &mut v_pen)] {
        for &(r, c, v) in parts.iter() {
            if let Some(slot) = lower.slot(r, c) {
                values[slot] += v;
            }
        }
    }
    let diagonal: Vec<usize> = (0..kept).filter_map(|r| lower.slot(r, r)).collect();
    let mut chol = linalg::SparseCholesky::new(lower)?;
    for factor in MU_LADDER {
        let mu = factor * q_max / (sigma_a * sigma_a);
        let values: Vec<f64> = v_stress
            .iter()
            .zip(&v_pen)
            .map(|(s, p)| s + mu * p)
            .collect();
        let k0 = CscMatrix::new(lower.clone(), values)?;
        let (norm, widest) = row_norm_and_width(&k0);
        let shift = sigma + 64.0 * widest as f64 * f64::EPSILON * norm;
        let mut values = k0.values().to_vec();
        for &slot in &diagonal {
            values[slot] -= shift;
        }
        if diagonal.len() == kept && chol.factor(&values).is_ok() {
            return Ok(Some(true));
        }
    }
    Ok(None)
}

/// ‖K‖_∞ and the most entries of a row of the symmetric K given by its lower triangle.
fn row_norm_and_width(lower: &CscMatrix) -> (f64, usize) {
    let n = lower.pattern().ncols();
    let (mut sum, mut count) = (vec![0.0; n], vec![0usize; n]);
    let (cp, ri, v) = (
        lower.pattern().col_ptr(),
        lower.pattern().row_idx(),
        lower.values(),
    );
    for c in 0..n {
        for s in cp[c]..cp[c + 1] {
            let r = ri[s];
            sum[r] += v[s].abs();
            count[r] += 1;
            if r != c {
                sum[c] += v[s].abs();
                count[c] += 1;
            }
        }
    }
    let norm = sum.iter().fold(0.0_f64, |m, &x| m.max(x));
    (norm, count.into_iter().max().unwrap_or(0))
}
