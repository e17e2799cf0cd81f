//! A dense primal–dual interior-point solver for small inequality-form LPs,
//! min cᵀz  s.t.  G z ≤ h, with many more rows than columns.
//!
//! Mehrotra's predictor–corrector on the slack form G z + s = h, s ≥ 0, with duals λ ≥ 0
//! (Gᵀλ + c = 0). Each iteration solves the normal equations (Gᵀ diag(λ/s) G) Δz = r by a
//! dense Cholesky factorisation of a p×p matrix (p = columns), so the cost per iteration is
//! O(rows · p²) with matrix–matrix products. This beats a general sparse conic solver on the
//! prestressability LP, whose constraint matrix (an orthonormal self-stress basis) is dense.
//!
//! Starting point: z = 0, s = max(h, 1), λ = 1 (an infeasible start is fine: the residuals are
//! driven to zero together with the gap).

use nalgebra::{DMatrix, DVector};

/// Why the solver stopped without meeting its tolerances.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum DenseLpFailure {
    /// The normal matrix lost positive definiteness.
    Factorisation { iteration: usize },
    /// The gap kept growing (loss of accuracy).
    Stalled { iteration: usize },
    /// The iteration limit was reached.
    MaxIterations,
}

/// Solves min cᵀz s.t. G z ≤ h to relative tolerance `tol`; returns z.
pub(crate) fn solve(
    g: &DMatrix<f64>,
    h: &DVector<f64>,
    c: &DVector<f64>,
    tol: f64,
) -> Result<DVector<f64>, DenseLpFailure> {
    let (r, p) = g.shape();
    let mut z = DVector::zeros(p);
    let mut s = h.map(|v| v.max(1.0));
    let mut lam = DVector::from_element(r, 1.0);
    let h_norm = 1.0 + h.amax();
    let c_norm = 1.0 + c.amax();
    // best iterate with small residuals, by gap: degenerate optima (e.g. a zero margin) let the
    // normal matrix become ill-conditioned before the strict tolerances are met
    let mut best: Option<(f64, DVector<f64>)> = None;
    let mut rising = 0;
    let mut last_gap = f64::INFINITY;
    let accept = |best: Option<(f64, DVector<f64>)>, failure| match best {
        Some((gap, z)) if gap <= ACCEPT_GAP => Ok(z),
        _ => Err(failure),
    };
    for iteration in 0..MAX_ITERATIONS {
        let rd = g.transpose() * &lam + c; // dual residual
        let rp = g * &z + &s - h; // primal residual
        let gap = s.dot(&lam);
        let mu = gap / r as f64;
        let pobj = c.dot(&z);
        let feasible = rp.amax() <= tol * h_norm && rd.amax() <= tol * c_norm;
        if feasible && gap <= tol * (1.0 + pobj.abs()) {
            return Ok(z);
        }
        let nearly_feasible = rp.amax() <= tol * h_norm && rd.amax() <= ACCEPT_DUAL * c_norm;
        if nearly_feasible && best.as_ref().is_none_or(|(g, _)| gap < *g) {
            best = Some((gap, z.clone()));
        }
        rising = if gap > last_gap { rising + 1 } else { 0 };
        last_gap = gap;
        if rising >= 5 {
            return accept(best, DenseLpFailure::Stalled { iteration });
        }
        // normal matrix H = Gᵀ D G, D = λ/s
        let d = lam.component_div(&s);
        let mut gd = g.clone();
        for (i, mut row) in gd.row_iter_mut().enumerate() {
            row *= d[i];
        }
        let mut hmat = g.transpose() * &gd;
        let reg = 1e-14 * (1.0 + hmat.diagonal().amax());
        for i in 0..p {
            hmat[(i, i)] += reg;
        }
        let Some(chol) = hmat.cholesky() else {
            return accept(best, DenseLpFailure::Factorisation { iteration });
        };
        // one Newton direction for complementarity target `rc` (Λ Δs + S Δλ = rc)
        let direction = |rc: &DVector<f64>| {
            // Δλ = (rc + Λ(r_p + G Δz)) / s ; Gᵀ D G Δz = −r_d − Gᵀ (rc + Λ r_p)/s
            let w = (rc + lam.component_mul(&rp)).component_div(&s);
            let dz = chol.solve(&(-&rd - g.transpose() * &w));
            let gdz = g * &dz;
            let ds = -&rp - &gdz;
            let dl = (rc - lam.component_mul(&ds)).component_div(&s);
            (dz, ds, dl)
        };
        let max_step = |v: &DVector<f64>, dv: &DVector<f64>| {
            v.iter()
                .zip(dv.iter())
                .filter(|&(_, &d)| d < 0.0)
                .map(|(&x, &d)| -x / d)
                .fold(1.0f64, f64::min)
        };
        // predictor (affine scaling)
        let rc_aff = -s.component_mul(&lam);
        let (_, ds_a, dl_a) = direction(&rc_aff);
        let alpha_a = max_step(&s, &ds_a).min(max_step(&lam, &dl_a));
        let mu_aff = (&s + &ds_a * alpha_a).dot(&(&lam + &dl_a * alpha_a)) / r as f64;
        let sigma = (mu_aff / mu).powi(3).clamp(0.0, 1.0);
        // corrector
        let rc = &rc_aff + DVector::from_element(r, sigma * mu) - ds_a.component_mul(&dl_a);
        let (dz, ds, dl) = direction(&rc);
        let alpha = (0.99 * max_step(&s, &ds).min(max_step(&lam, &dl))).min(1.0);
        z += &dz * alpha;
        s += &ds * alpha;
        lam += &dl * alpha;
    }
    accept(best, DenseLpFailure::MaxIterations)
}

const MAX_ITERATIONS: usize = 200;
/// Largest duality gap of a best iterate returned when the strict tolerances are not met: the
/// objective is then within this of the optimum.
const ACCEPT_GAP: f64 = 1e-9;
/// Largest relative dual residual of such a best iterate (the normal equations lose accuracy
/// near degenerate optima; the primal iterate, which is all the caller uses, stays feasible).
const ACCEPT_DUAL: f64 = 1e-6;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_small_lp_with_a_known_optimum() {
        // max x + y s.t. x + 2y ≤ 4, 3x + y ≤ 6, x, y ≥ 0  →  (8/5, 6/5), value 14/5
        let g = DMatrix::from_row_slice(4, 2, &[1.0, 2.0, 3.0, 1.0, -1.0, 0.0, 0.0, -1.0]);
        let h = DVector::from_row_slice(&[4.0, 6.0, 0.0, 0.0]);
        let c = DVector::from_row_slice(&[-1.0, -1.0]);
        let z = solve(&g, &h, &c, 1e-12).unwrap();
        assert!(
            (z[0] - 1.6).abs() < 1e-9 && (z[1] - 1.2).abs() < 1e-9,
            "{z}"
        );
    }
}
