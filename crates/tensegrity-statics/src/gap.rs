//! [`SpectralGap`]: the singular values on either side of the rank tolerance, behind every
//! rank decision of a statics back-end, and the rule that certifies it.
//!
//! A rank decision counts the singular values above the absolute tolerance τ. It is
//! *certified* (a clear gap) when no singular value lies within a factor [`GAP_FACTOR`] = 10
//! of τ: the smallest value counted non-zero exceeds 10 τ and the largest counted as zero is
//! below τ / 10 (an exact 0 always is), so the two differ by more than 10² and rounding of
//! order τ cannot move one across. Otherwise the decision is reported with a warning
//! (`statics_warning`) instead of as fact.

use serde::Serialize;
use tensegrity_derive::Columns;

/// No singular value within this factor of the tolerance: the gap rule (see the module docs).
pub const GAP_FACTOR: f64 = 10.0;

/// The singular values on either side of the rank tolerance of one decision (for the cyclic
/// back-end: of the block with the narrowest gap).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Columns)]
pub struct SpectralGap {
    /// The absolute rank tolerance τ of this decision.
    pub tolerance: f64,
    /// The smallest singular value counted non-zero (> τ); `None` at rank 0.
    pub sigma_above: Option<f64>,
    /// The largest singular value counted as zero (≤ τ); `None` when every computed value
    /// is above τ (the remaining null space, if any, is structural: more columns than rows).
    pub sigma_below: Option<f64>,
    /// `sigma_above / sigma_below`; `None` when either is missing or `sigma_below` is 0.
    pub ratio: Option<f64>,
    /// The representation index k of the block (cyclic back-end only).
    pub block: Option<usize>,
}

impl SpectralGap {
    /// The gap of the singular values `values` (any order) at tolerance `tolerance`.
    ///
    /// ```
    /// use tensegrity_statics::SpectralGap;
    /// let g = SpectralGap::from_values([2.0, 1.0, 1e-3, 1e-17], 1e-14, None);
    /// assert_eq!((g.sigma_above, g.sigma_below), (Some(1e-3), Some(1e-17)));
    /// assert!(g.is_clear());
    /// // a value within a factor 10 of the tolerance: no clear gap
    /// assert!(!SpectralGap::from_values([2.0, 5e-14, 1e-17], 1e-14, None).is_clear());
    /// ```
    pub fn from_values(
        values: impl IntoIterator<Item = f64>,
        tolerance: f64,
        block: Option<usize>,
    ) -> Self {
        let (mut above, mut below) = (None::<f64>, None::<f64>);
        for s in values {
            if s > tolerance {
                above = Some(above.map_or(s, |a| a.min(s)));
            } else {
                below = Some(below.map_or(s, |b| b.max(s)));
            }
        }
        let ratio = match (above, below) {
            (Some(a), Some(b)) if b > 0.0 => Some(a / b),
            _ => None,
        };
        Self {
            tolerance,
            sigma_above: above,
            sigma_below: below,
            ratio,
            block,
        }
    }

    /// How far the nearest singular value lies from τ, as a factor ≥ 1 (+∞ when none is
    /// near: no value on either side, or only exact zeros below).
    pub fn margin(&self) -> f64 {
        let up = self
            .sigma_above
            .map_or(f64::INFINITY, |a| a / self.tolerance);
        let down = match self.sigma_below {
            Some(b) if b > 0.0 => self.tolerance / b,
            _ => f64::INFINITY,
        };
        up.min(down)
    }

    /// Whether the gap is clear: no singular value within [`GAP_FACTOR`] of τ.
    pub fn is_clear(&self) -> bool {
        self.margin() > GAP_FACTOR
    }

    /// The gap in words (for warnings).
    pub fn describe(&self) -> String {
        let opt = |x: Option<f64>| x.map_or("none".to_string(), |v| format!("{v:.3e}"));
        let block = self
            .block
            .map_or(String::new(), |k| format!(" in block k = {k}"));
        format!(
            "singular values {} above and {} below the tolerance {:.3e}{block}",
            opt(self.sigma_above),
            opt(self.sigma_below),
            self.tolerance
        )
    }

    /// The warning of a decision without a clear gap by `who` (a back-end's name).
    pub fn warning(&self, who: &str) -> String {
        format!(
            "the {who} rank decision is not certified ({}: a singular value lies within a factor {GAP_FACTOR} of it): rank, self-stress dimension and mechanisms may be wrong",
            self.describe()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_clear_gap_is_certified_and_a_value_near_the_tolerance_is_not() {
        let tol = 1e-13;
        // rank 3 of 4, five decades on either side
        let g = SpectralGap::from_values([1.0, 0.5, 1e-8, 1e-18], tol, None);
        assert_eq!((g.sigma_above, g.sigma_below), (Some(1e-8), Some(1e-18)));
        assert!((g.ratio.unwrap() - 1e10).abs() < 1.0);
        assert!((g.margin() - 1e5).abs() < 1e-6);
        assert!(g.is_clear());
        // full rank (no value below) and exact zeros are clear
        assert!(SpectralGap::from_values([1.0, 1e-11], tol, None).is_clear());
        let zero = SpectralGap::from_values([1.0, 0.0], tol, None);
        assert_eq!((zero.ratio, zero.is_clear()), (None, true));
        // a value 5 τ above or 5 τ below: no clear gap
        let up = SpectralGap::from_values([1.0, 5e-13, 1e-18], tol, Some(2));
        assert!((up.margin() - 5.0).abs() < 1e-9);
        assert!(!up.is_clear());
        let down = SpectralGap::from_values([1.0, 1e-6, 2e-14], tol, None);
        assert!(!down.is_clear());
        // ratio 10² exactly at the band edges: not clear (strictly beyond 10 required)
        assert!(!SpectralGap::from_values([1e-12, 1e-14], tol, None).is_clear());
        let w = up.warning("cyclic");
        assert!(w.contains("5.000e-13") && w.contains("block k = 2"), "{w}");
    }
}
