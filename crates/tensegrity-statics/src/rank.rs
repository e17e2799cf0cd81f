//! The rank decision of the equilibrium matrix on data that may be rounded or may hold
//! their equilibrium only approximately.
//!
//! Three scales bound the singular values that may count as zero:
//!
//! - the arithmetic's tolerance τ₀ = max(m, n) · ε · σ_max
//!   ([`tensegrity_linalg::rank_tolerance`], or a relative tolerance the caller sets);
//! - the data's rounding e (m): the coordinates' *input precision*, ρ · max|x| for a relative
//!   precision ρ the caller gives, else judged from their digits
//!   ([`tensegrity_core::precision::coordinate_rounding`]: 0 at full precision or for values
//!   typed by hand, ½ a unit of the ninth digit for data written to nine). Each entry of A
//!   (a difference of two coordinates) moves by about e: singular values of that size are
//!   noise;
//! - the worst case of that rounding, τ_d = 2e √(6 n_members): ‖ΔA‖₂ ≤ ‖ΔA‖_F ≤ 2e √(6 per
//!   column · n_members), and by Weyl's inequality no singular value moves by more.
//!
//! The rank r lies between r_max = #{σ > τ₀} (the arithmetic's decision) and r_min = #{σ >
//! τ_w}, with the search window's top τ_w = max(τ_d, 10⁴ τ₀) (four decades above the
//! arithmetic's tolerance also for exact data: a form found by an iteration holds its
//! equilibrium only to the iteration's tolerance). Each candidate r has the gap
//! g(r) = σ_{r−1} / max(σ_r, τ₀, e) (below the noise floor a value is compared with the floor,
//! not with its smaller neighbour). The cut moves below r_max only to the candidate with the
//! largest gap, and only when that gap is clear (g ≥ [`CUT_GAP`] = 10²) and larger than
//! g(r_max); it is then taken at τ = √(σ_{r−1} · max(σ_r, τ₀, e)). Otherwise, and always under
//! a caller's tolerance, the arithmetic decides (τ = τ₀). Whether the decision's gap is clear
//! is [`crate::SpectralGap`]'s rule, which warns with the values on both sides.
//!
//! ```
//! use tensegrity_statics::rank::RankTolerance;
//! // a net written to nine digits: its self-stress carried by σ = 8e-10, below the
//! // rounding e = 5e-9; the gap above it (0.19 / 5e-9) decides
//! let t = RankTolerance { base: 1e-14, rounding: 5e-9, data: 1.2e-7, search: true };
//! let (rank, tol) = t.decide(&[3.0, 0.19, 8e-10]);
//! assert_eq!(rank, 2);
//! assert!(8e-10 < tol && tol < 0.19);
//! // values typed by hand: a small but clear value stays (no gap of 10² above the floor)
//! let exact = RankTolerance { base: 1e-14, rounding: 0.0, data: 0.0, search: true };
//! assert_eq!(exact.decide(&[3.0, 0.19, 8e-3]), (3, 1e-14));
//! ```

use tensegrity_core::precision::coordinate_rounding;
use tensegrity_core::Structure;

/// The multiple of the coordinates' rounding e at which a QR back-end rejects a column
/// ([`RankTolerance::reject_level`]): a rounding of e moves a member's column of A (two
/// nodes' three coordinates, differences of two rounded values) by at most 2√6 e ≈ 4.9 e,
/// and a dof's row by 2√d e for the d members at its node; 10 e covers both up to d = 25.
pub const DATA_REJECT_FACTOR: f64 = 10.0;

/// The smallest gap σ_{r−1} / floor that moves the cut below the arithmetic's decision.
pub const CUT_GAP: f64 = 100.0;

/// The search window reaches this many decades above the arithmetic's tolerance.
pub const SEARCH_DECADES: i32 = 4;

/// The scales of one rank decision (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RankTolerance {
    /// τ₀: the arithmetic's tolerance (absolute).
    pub base: f64,
    /// e: the rounding of the coordinates (m; 0 for exact data or under a caller's
    /// tolerance).
    pub rounding: f64,
    /// τ_d = 2e √(6 n_members): the largest singular value the rounding can create (a
    /// cluster counts each segment i with the weight (L_c / l_i)², the scale of its entries).
    pub data: f64,
    /// Whether the spectrum is searched (false under a caller's tolerance: τ₀ decides).
    pub search: bool,
}

impl RankTolerance {
    /// The scales of an m × n equilibrium matrix with largest singular value `sigma_max` of
    /// `structure`: `rank_tolerance` relative (a caller's: the data's scales are then 0, the
    /// caller decides) and `input_precision` relative to the largest coordinate (`None`:
    /// judged from the digits).
    pub fn of(
        structure: &Structure,
        (m, n): (usize, usize),
        sigma_max: f64,
        rank_tolerance: Option<f64>,
        input_precision: Option<f64>,
    ) -> Self {
        let base = tensegrity_linalg::rank_tolerance(m, n, sigma_max, rank_tolerance);
        let rounding = match rank_tolerance {
            Some(_) => 0.0,
            None => input_rounding(structure, input_precision),
        };
        // a cluster's column holds its segments' vectors scaled by L_c / l_i
        let clustered: f64 = crate::cluster_columns::cluster_geometries(structure)
            .iter()
            .flat_map(|g| g.segments.iter().map(|s| (g.length / s.length).powi(2)))
            .sum();
        let data = 2.0 * rounding * (6.0 * (structure.n_members() as f64 + clustered)).sqrt();
        Self {
            base,
            rounding,
            data,
            search: rank_tolerance.is_none(),
        }
    }

    /// The tolerance of a back-end that sees no full spectrum: the larger of τ₀ and e (a
    /// value at the rounding's size is noise).
    pub fn absolute(&self) -> f64 {
        self.base.max(self.rounding)
    }

    /// The residual at or below which a QR back-end rejects a column: `arithmetic` × τ₀
    /// (the QR's own round-off, κ(A_acc)·ε·‖A‖, exceeds the SVD's) or
    /// [`DATA_REJECT_FACTOR`] × e (what the rounding can leave of a dependent column),
    /// whichever is larger. The factor of the round-off is not applied to e: a rounding
    /// of 10⁻³ of a 10 m grid (e = 1 cm) would otherwise reject every member shorter than
    /// 10 m (rank 0, every member a self-stress).
    ///
    /// ```
    /// use tensegrity_statics::rank::{RankTolerance, DATA_REJECT_FACTOR};
    /// let t = RankTolerance { base: 1e-14, rounding: 1e-2, data: 1.8, search: true };
    /// assert_eq!(t.reject_level(1e3), DATA_REJECT_FACTOR * 1e-2);
    /// let exact = RankTolerance { base: 1e-14, rounding: 0.0, data: 0.0, search: true };
    /// assert_eq!(exact.reject_level(1e3), 1e-11);
    /// ```
    pub fn reject_level(&self, arithmetic: f64) -> f64 {
        (arithmetic * self.base).max(DATA_REJECT_FACTOR * self.rounding)
    }

    /// The rank and its tolerance from the singular values `values` (non-increasing; those
    /// of a structural null space left out), by the gap search of the module docs.
    pub fn decide(&self, values: &[f64]) -> (usize, f64) {
        let count = |tol: f64| values.iter().filter(|&&s| s > tol).count();
        let r_max = count(self.base);
        let top = self
            .data
            .max(self.base * 10f64.powi(SEARCH_DECADES))
            .max(self.base);
        let r_min = count(top).max(1);
        if !self.search || r_min >= r_max {
            return (r_max, self.base);
        }
        let floor = |r: usize| {
            let below = values.get(r).copied().unwrap_or(0.0);
            below.max(self.base).max(self.rounding)
        };
        let gap = |r: usize| values[r - 1] / floor(r);
        let best = (r_min..r_max)
            .max_by(|&a, &b| gap(a).total_cmp(&gap(b)).then(a.cmp(&b)))
            .unwrap_or(r_max);
        if gap(best) >= CUT_GAP && gap(best) > gap(r_max) {
            (best, (values[best - 1] * floor(best)).sqrt())
        } else {
            (r_max, self.base)
        }
    }
}

/// A value counted non-zero that looks like rounding of a zero: the smallest one kept, σ,
/// when it lies at most 10⁻³ σ_max and at least [`ISOLATION`] below the next one up (the
/// coordinates then hold one more self-stress to about σ / σ_max). Returns (σ, that factor).
///
/// ```
/// use tensegrity_statics::rank::near_deficiency;
/// // a net written to four digits: σ = 1.5e-5 under 0.19
/// assert_eq!(near_deficiency(&[1.0, 0.19, 1.5e-5], 3).map(|(s, _)| s), Some(1.5e-5));
/// // a spread spectrum is not flagged
/// assert_eq!(near_deficiency(&[1.0, 0.1, 1e-2, 1e-3, 1e-4], 5), None);
/// ```
pub fn near_deficiency(values: &[f64], rank: usize) -> Option<(f64, f64)> {
    if rank < 2 {
        return None;
    }
    let (above, sigma) = (values[rank - 2], values[rank - 1]);
    let isolated = sigma > 0.0 && above / sigma >= ISOLATION;
    (isolated && sigma <= 1e-3 * values[0]).then_some((sigma, above / sigma))
}

/// How far below the next value a smallest kept singular value must lie to be flagged by
/// [`near_deficiency`].
pub const ISOLATION: f64 = 1e3;

/// The input precision e of `structure`'s coordinates (m): `relative` × the largest
/// coordinate magnitude, or judged from their digits (module docs).
pub fn input_rounding(structure: &Structure, relative: Option<f64>) -> f64 {
    let coords = structure.nodes().iter().flat_map(|p| [p.x, p.y, p.z]);
    match relative {
        Some(rho) => rho * coords.map(f64::abs).fold(0.0, f64::max),
        None => coordinate_rounding(coords),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rounded(rounding: f64) -> RankTolerance {
        RankTolerance {
            base: 1e-14,
            rounding,
            data: 24.0 * rounding,
            search: true,
        }
    }

    #[test]
    fn the_largest_clear_gap_above_the_noise_decides() {
        // six digits: σ = 3.7e-7 lies below the rounding 5e-6 and 0.19 / 5e-6 = 4e4 ≥ 10²
        let (r, tol) = rounded(5e-6).decide(&[1.0, 0.19, 3.7e-7]);
        assert_eq!(r, 2);
        assert!(3.7e-7 < tol && tol < 0.19);
        // the same spectrum at full precision: 3.7e-7 is far above the search window
        assert_eq!(rounded(0.0).decide(&[1.0, 0.19, 3.7e-7]), (3, 1e-14));
        // an exact zero below: the decision does not move
        assert_eq!(rounded(5e-6).decide(&[1.0, 0.19, 1e-17]), (2, 1e-14));
    }

    #[test]
    fn a_gap_that_is_not_clear_leaves_the_arithmetic_decision() {
        // hand-typed data with a coarse rounding: gaps of 2–3 never move the cut
        let t = rounded(0.05);
        assert_eq!(t.decide(&[5.0, 3.0, 2.0, 1.0, 0.3]), (5, 1e-14));
        // a caller's tolerance: no search at all
        let user = RankTolerance {
            base: 1e-10,
            rounding: 0.0,
            data: 0.0,
            search: false,
        };
        assert_eq!(user.decide(&[1.0, 1e-9]), (2, 1e-10));
    }

    #[test]
    fn an_iteration_s_approximate_equilibrium_is_found_at_full_precision() {
        // a dynamic-relaxation form: its self-stress carried by σ = 1e-12, four decades of
        // search above τ₀ = 1e-14 reach it, and the gap above it (1e12) is clear
        let (r, tol) = rounded(0.0).decide(&[2.0, 1.0, 1e-12]);
        assert_eq!(r, 2);
        assert!(1e-12 < tol && tol < 1.0);
    }

    #[test]
    fn data_at_full_precision_have_no_rounding() {
        let s = tensegrity_core::test_models::snelson_tower_free(2).unwrap();
        assert_eq!(input_rounding(&s, None), 0.0);
        let big = s
            .nodes()
            .iter()
            .flat_map(|p| [p.x, p.y, p.z])
            .map(f64::abs)
            .fold(0.0, f64::max);
        assert_eq!(input_rounding(&s, Some(1e-9)), 1e-9 * big);
    }
}
