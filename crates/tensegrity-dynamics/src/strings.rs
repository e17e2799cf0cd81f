//! Tension-only strings: linear elastic with a rest length, optionally damped (ERRATA 2.7).
//!
//! For a string with member vector s = n_end − n_start, rest length s0, stiffness k and
//! damping c the force density is
//!
//! γ = max(0, k (1 − s0/‖s‖) + c (sᵀṡ)/‖s‖²)  if ‖s‖ > s0,   γ = 0 otherwise (slack),
//!
//! so γ is never negative; the tension is γ‖s‖ and the potential energy ½ k (‖s‖ − s0)₊².
//! The force on the start node is +γ s, on the end node −γ s (F = W − S γ̂ C_s).

use nalgebra::Vector3;

/// The constants of one string as the dynamics uses them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StringLaw {
    /// Axial stiffness k (N/m).
    pub stiffness: f64,
    /// Rest length s0 (m) at t = 0 (actuation may change it in time).
    pub rest_length: f64,
    /// Damping coefficient c (N·s/m).
    pub damping: f64,
}

impl StringLaw {
    /// Force density γ (N/m) for member vector `s`, its rate `s_dot` and rest length `s0`.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use tensegrity_dynamics::StringLaw;
    /// let law = StringLaw { stiffness: 100.0, rest_length: 1.0, damping: 0.0 };
    /// let g = law.force_density(&Vector3::new(2.0, 0.0, 0.0), &Vector3::zeros(), 1.0);
    /// assert!((g - 50.0).abs() < 1e-12); // tension 100 N over length 2 m
    /// assert_eq!(law.force_density(&Vector3::new(0.5, 0.0, 0.0), &Vector3::zeros(), 1.0), 0.0);
    /// ```
    #[inline]
    pub fn force_density(&self, s: &Vector3<f64>, s_dot: &Vector3<f64>, s0: f64) -> f64 {
        let l2 = s.norm_squared();
        let l = l2.sqrt();
        if l <= s0 {
            return 0.0;
        }
        let mut g = self.stiffness * (1.0 - s0 / l);
        if self.damping != 0.0 {
            g += self.damping * s.dot(s_dot) / l2;
        }
        g.max(0.0)
    }

    /// Elastic potential ½ k (‖s‖ − s0)₊² (J).
    #[inline]
    pub fn potential(&self, s: &Vector3<f64>, s0: f64) -> f64 {
        let stretch = (s.norm() - s0).max(0.0);
        0.5 * self.stiffness * stretch * stretch
    }
}
