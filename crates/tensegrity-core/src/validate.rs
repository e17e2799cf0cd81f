//! Validation of scalar parameters, shared by the libraries' request types, the scene
//! reader and the command-line flags, so that a value is judged the same way wherever it
//! comes from. Each check returns the value or [`CoreError::InvalidParameter`] naming the
//! parameter (by its flag name with `_` for `-`, e.g. `ground_stiffness`), the value and the
//! rule it breaks.
//!
//! ```
//! use tensegrity_core::validate;
//! assert_eq!(validate::positive("dt", 1e-3).unwrap(), 1e-3);
//! let e = validate::non_negative("ground_damping", -5.0).unwrap_err();
//! assert_eq!(e.to_string(), "ground_damping = -5: must be finite and non-negative");
//! assert!(validate::positive("ground_stiffness", 0.0).is_err());
//! assert!(validate::finite("load", f64::NAN).is_err());
//! assert!(validate::count_at_least("grid_points", 1, 2).is_err());
//! ```

use crate::error::{CoreError, Result};

/// `value` must be finite.
pub fn finite(name: &'static str, value: f64) -> Result<f64> {
    check(name, value, value.is_finite(), "must be finite")
}

/// `value` must be finite and strictly positive (a length, stiffness, step, time…).
pub fn positive(name: &'static str, value: f64) -> Result<f64> {
    check(
        name,
        value,
        value.is_finite() && value > 0.0,
        "must be finite and positive",
    )
}

/// `value` must be finite and ≥ 0 (a damping, a friction coefficient, an offset…).
pub fn non_negative(name: &'static str, value: f64) -> Result<f64> {
    check(
        name,
        value,
        value.is_finite() && value >= 0.0,
        "must be finite and non-negative",
    )
}

/// `value` must lie in the closed interval [lo, hi].
pub fn in_range(name: &'static str, value: f64, lo: f64, hi: f64) -> Result<f64> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(CoreError::invalid_parameter(
            name,
            value,
            format!("must lie in [{lo}, {hi}]"),
        ))
    }
}

/// A count (grid points, sides, steps…) must be at least `min`.
pub fn count_at_least(name: &'static str, value: usize, min: usize) -> Result<usize> {
    if value >= min {
        Ok(value)
    } else {
        Err(CoreError::invalid_parameter(
            name,
            value as f64,
            format!("must be at least {min}"),
        ))
    }
}

fn check(name: &'static str, value: f64, ok: bool, reason: &'static str) -> Result<f64> {
    if ok {
        Ok(value)
    } else {
        Err(CoreError::invalid_parameter(name, value, reason))
    }
}
