//! Convergence of a dynamic result: each headline quantity re-estimated at a refined
//! resolution (a second run at half the step, and for a penalty contact twice the ground
//! stiffness) and compared with the result's own value.
//!
//! For a quantity q with value q_h at the run's resolution and q_{h/2} at the refined one, the
//! relative change is
//!
//! > r = |q_{h/2} − q_h| / max(|q_h|, |q_{h/2}|, s)
//!
//! with s the quantity's scale floor (so that a quantity near zero is compared absolutely,
//! e.g. s = 1 for a fraction of the run). A quantity compared as a whole (the final nodes or
//! velocities of a run, [`Convergence::compare_change`]) takes the largest difference d
//! between the two runs against its magnitude m (e.g. the largest final speed) and its
//! scale s, r = d / max(m, s): a quantity near zero (a structure come to rest) is judged
//! against the scale the problem states (a speed √(g L) of its size L), not against its own
//! noise. Each caller states its scales (`tensegrity_engine::simulate`: the structure's size
//! and the speeds of its motion). It is `converged` when r ≤ τ/2 for its tolerance τ:
//! for a method of order p ≥ 1 the errors at h, h/2, h/4, … fall geometrically, so the change
//! from q_h to the converged value (and to any finer run, a quarter of the step included) is at
//! most r (1 + 2⁻ᵖ + 2⁻²ᵖ + …) ≤ 2 r ≤ τ. A quantity that moves more is `converged: false`,
//! and so is the whole result ([`Convergence::converged`]), which a result then reports as not
//! valid.

use serde::{Deserialize, Serialize};
use tensegrity_core::warning::Warning;
use tensegrity_derive::Columns;

/// One headline quantity at the run's and at the refined resolution.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuantityConvergence {
    /// The quantity's report key (e.g. `mean_speed`, `first_impact.t`).
    pub name: String,
    /// Its value in the result (null when the run has none, e.g. no impact).
    pub value: Option<f64>,
    /// Its value at the refined resolution.
    pub refined: Option<f64>,
    /// |refined − value| / max(|value|, |refined|, scale) (module docs); null when one of the
    /// two is missing.
    pub relative_change: Option<f64>,
    /// The tolerance τ of this quantity: converged when the relative change is at most τ/2.
    pub tolerance: f64,
    /// Whether the quantity held within its tolerance.
    pub converged: bool,
}

/// The convergence of a result's headline quantities (module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Columns, Deserialize)]
pub struct Convergence {
    /// What the refined run changed, e.g. `dt/2, ground stiffness x2`.
    pub refinement: String,
    /// Whether every quantity held within its tolerance.
    pub converged: bool,
    /// Each headline quantity.
    pub quantities: Vec<QuantityConvergence>,
}

impl Convergence {
    /// An empty comparison for the refinement described by `refinement`.
    pub fn new(refinement: impl Into<String>) -> Self {
        Self {
            refinement: refinement.into(),
            converged: true,
            quantities: Vec::new(),
        }
    }

    /// Compares `value` with `refined` (module docs): relative to the larger of the two and of
    /// `scale`, within `tolerance`. Both missing counts as converged (nothing to compare), one
    /// missing as not converged (the refined run found, or lost, an event).
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::Convergence;
    /// let mut c = Convergence::new("dt/2");
    /// c.compare("mean_speed", Some(10.0), Some(10.05), 0.02, 0.0);
    /// assert!(c.converged);
    /// c.compare("final_speed", Some(10.0), Some(10.2), 0.02, 0.0);
    /// assert!(!c.converged && !c.quantities[1].converged);
    /// assert_eq!(c.warnings().len(), 1);
    /// ```
    pub fn compare(
        &mut self,
        name: &str,
        value: Option<f64>,
        refined: Option<f64>,
        tolerance: f64,
        scale: f64,
    ) -> &mut Self {
        let relative_change = match (value, refined) {
            (Some(a), Some(b)) => {
                let denominator = a.abs().max(b.abs()).max(scale);
                Some(if denominator > 0.0 {
                    (b - a).abs() / denominator
                } else {
                    0.0
                })
            }
            _ => None,
        };
        let converged = match (value, refined, relative_change) {
            (None, None, _) => true,
            // NaN changes count as unconverged
            (_, _, Some(r)) => r <= 0.5 * tolerance,
            _ => false,
        };
        self.converged &= converged;
        self.quantities.push(QuantityConvergence {
            name: name.to_string(),
            value,
            refined,
            relative_change,
            tolerance,
            converged,
        });
        self
    }

    /// Records a quantity whose change was measured directly (e.g. the largest distance
    /// between two runs' final nodes): `change` against the larger of its `magnitude` and
    /// its `scale` (module docs), within `tolerance`, with no single value to show. A NaN
    /// change counts as unconverged; a zero denominator as no change.
    ///
    /// ```
    /// use tensegrity_dynamics::convergence::Convergence;
    /// let mut c = Convergence::new("dt/2");
    /// // final speeds of 1 mm/s that moved by 0.5 mm/s, judged against a 3 m/s scale
    /// c.compare_change("final_velocities", 5e-4, 1e-3, 3.0, 0.02);
    /// assert!(c.converged);
    /// assert!((c.quantities[0].relative_change.unwrap() - 5e-4 / 3.0).abs() < 1e-15);
    /// // the same change against the speeds alone: 50 %
    /// c.compare_change("final_velocities", 5e-4, 1e-3, 0.0, 0.02);
    /// assert!(!c.converged);
    /// ```
    pub fn compare_change(
        &mut self,
        name: &str,
        change: f64,
        magnitude: f64,
        scale: f64,
        tolerance: f64,
    ) -> &mut Self {
        let denominator = magnitude.abs().max(scale);
        let relative_change = if denominator > 0.0 {
            change / denominator
        } else if change == 0.0 {
            0.0
        } else {
            f64::INFINITY
        };
        let converged = relative_change <= 0.5 * tolerance;
        self.converged &= converged;
        self.quantities.push(QuantityConvergence {
            name: name.to_string(),
            value: None,
            refined: None,
            relative_change: Some(relative_change),
            tolerance,
            converged,
        });
        self
    }

    /// One warning per quantity that did not converge ([`Warning::NotConverged`]); for a
    /// result marked unconverged with no such quantity (its refined run failed), one
    /// [`Warning::RefinementFailed`] naming the refinement.
    pub fn warnings(&self) -> Vec<Warning> {
        if !self.converged && self.quantities.iter().all(|q| q.converged) {
            return vec![Warning::RefinementFailed {
                refinement: self.refinement.clone(),
            }];
        }
        self.quantities
            .iter()
            .filter(|q| !q.converged)
            .map(|q| Warning::NotConverged {
                quantity: q.name.clone(),
                value: q.value,
                refined: q.refined,
                relative_change: q.relative_change,
                tolerance: q.tolerance,
                refinement: self.refinement.clone(),
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_change_within_half_the_tolerance_converges() {
        let mut c = Convergence::new("dt/2");
        c.compare("a", Some(1.0), Some(1.004), 0.01, 0.0);
        assert!(c.converged);
        c.compare("b", Some(1.0), Some(1.006), 0.01, 0.0);
        assert!(!c.converged);
        // a fraction near zero is compared on its scale
        let mut f = Convergence::new("dt/2");
        f.compare("airborne_fraction", Some(0.0), Some(0.004), 0.01, 1.0);
        assert!(f.converged, "{f:?}");
        // an event found by one run only
        let mut e = Convergence::new("dt/2");
        e.compare("first_impact.t", None, Some(0.7), 0.01, 0.0);
        assert!(!e.converged && e.warnings()[0].to_string().contains("none"));
        e.compare("x", None, None, 0.01, 0.0);
        assert_eq!(e.quantities.len(), 2);
        let nan = Convergence::new("dt/2")
            .compare("n", Some(f64::NAN), Some(1.0), 0.01, 0.0)
            .converged;
        assert!(!nan);
    }

    #[test]
    fn a_change_near_zero_is_judged_against_its_scale() {
        // velocities of a structure come to rest: 0.5 mm/s moved at the refined run of a
        // largest final speed of 2 mm/s (25 %), on a scale of 3 m/s
        let mut c = Convergence::new("dt/2");
        c.compare_change("final_velocities", 5e-4, 2e-3, 3.0, 0.02);
        assert!(c.converged, "{c:?}");
        let r = c.quantities[0].relative_change.unwrap();
        assert!((r - 5e-4 / 3.0).abs() < 1e-15, "{r}");
        // a change as large as the scale does not converge
        c.compare_change("final_nodes", 0.5, 0.0, 1.0, 0.01);
        assert!(!c.converged);
        // nothing to compare: converged; a NaN change: not
        let mut z = Convergence::new("dt/2");
        z.compare_change("x", 0.0, 0.0, 0.0, 0.01);
        assert!(z.converged && z.quantities[0].relative_change == Some(0.0));
        z.compare_change("y", f64::NAN, 1.0, 1.0, 0.01);
        assert!(!z.converged);
    }
}
