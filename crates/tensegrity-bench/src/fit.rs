//! The cost exponent of a scaling series: t ≈ c · nᵖ fitted by least squares on log–log,
//! p = Σ(xᵢ − x̄)(yᵢ − ȳ) / Σ(xᵢ − x̄)², log c = ȳ − p x̄ with xᵢ = ln nᵢ, yᵢ = ln tᵢ.
//!
//! ```
//! use tensegrity_bench::fit::power_law;
//! let points: Vec<(f64, f64)> = [10.0, 20.0, 40.0].iter().map(|&n| (n, 3e-6 * n * n)).collect();
//! let fit = power_law(&points).unwrap();
//! assert!((fit.exponent - 2.0).abs() < 1e-12);
//! assert!((fit.prefactor - 3e-6).abs() < 1e-18);
//! ```

use serde::Serialize;

/// t ≈ prefactor · n^exponent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PowerLaw {
    /// The exponent p (the slope on log–log).
    pub exponent: f64,
    /// The prefactor c (s at n = 1).
    pub prefactor: f64,
    /// The largest |ln tᵢ − ln(c nᵢᵖ)| over the points: how far the points are from a power
    /// law (0.1 ≈ 10 %).
    pub max_log_residual: f64,
}

/// The least-squares power law through `(n, t)` points (module docs); `None` with fewer than
/// two distinct positive sizes or a non-positive time.
pub fn power_law(points: &[(f64, f64)]) -> Option<PowerLaw> {
    if points.len() < 2 || points.iter().any(|&(n, t)| !(n > 0.0 && t > 0.0)) {
        return None;
    }
    let logs: Vec<(f64, f64)> = points.iter().map(|&(n, t)| (n.ln(), t.ln())).collect();
    let k = logs.len() as f64;
    let (mx, my) = logs
        .iter()
        .fold((0.0, 0.0), |(a, b), &(x, y)| (a + x / k, b + y / k));
    let sxx: f64 = logs.iter().map(|&(x, _)| (x - mx).powi(2)).sum();
    if sxx <= 0.0 {
        return None;
    }
    let sxy: f64 = logs.iter().map(|&(x, y)| (x - mx) * (y - my)).sum();
    let exponent = sxy / sxx;
    let log_c = my - exponent * mx;
    let max_log_residual = logs
        .iter()
        .map(|&(x, y)| (y - log_c - exponent * x).abs())
        .fold(0.0, f64::max);
    Some(PowerLaw {
        exponent,
        prefactor: log_c.exp(),
        max_log_residual,
    })
}
