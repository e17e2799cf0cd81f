//! σ_min of a triangular factor R by inverse iteration on RᵀR: x ← (RᵀR)⁻¹ x / ‖x‖, so that
//! ‖(RᵀR)⁻¹ x‖ → 1/σ_min², and σ ≈ 1/√‖(RᵀR)⁻¹ x‖. The iteration converges from above: an
//! upper estimate of σ_min(R), accurate to a small factor after a few steps.

/// An estimate of σ_min(R) for an r × r factor, with `solve_normal` applying (RᵀR)⁻¹ in
/// place (a forward solve with Rᵀ, then a back solve with R). +∞ at r = 0; 0 when a solve
/// overflows or vanishes (R numerically singular).
pub(crate) fn sigma_min_by_inverse_iteration(
    r: usize,
    iterations: usize,
    mut solve_normal: impl FnMut(&mut [f64]),
) -> f64 {
    if r == 0 {
        return f64::INFINITY;
    }
    // a start vector with every component present
    let mut x: Vec<f64> = (0..r)
        .map(|i| 1.0 + 0.5 * ((i * 7919) % 13) as f64)
        .collect();
    let mut sigma = f64::INFINITY;
    for _ in 0..iterations.max(1) {
        let norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        x.iter_mut().for_each(|v| *v /= norm);
        solve_normal(&mut x);
        let grow = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !grow.is_finite() || grow == 0.0 {
            return 0.0;
        }
        sigma = 1.0 / grow.sqrt();
    }
    sigma
}
