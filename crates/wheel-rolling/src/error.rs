//! Errors of the wheel-rolling crate: one enum, structured fields, the core's errors wrapped
//! with `#[from]`.

use tensegrity_core::request::{Categorized, Category, InvalidParameter};
use tensegrity_core::CoreError;
use tensegrity_core::Warning;
use thiserror::Error;

/// Result alias of the wheel-rolling crate.
pub type Result<T, E = RollingError> = std::result::Result<T, E>;

/// Everything that can go wrong in a rolling run.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum RollingError {
    /// A parameter of the run or of the wheel description is out of its valid range.
    #[error("{0}")]
    InvalidParameter(#[from] InvalidParameter),
    /// A rolling run recorded no sample (the output interval exceeds the run).
    #[error("no sample was recorded: output interval {output_dt} s is longer than the run")]
    NoSamples {
        /// The output interval (s).
        output_dt: f64,
    },
    /// The full model was asked of a wheel description that has none (a bare polygon).
    #[error(
        "the wheel `{wheel}` has no full model (no prestressed structure): use the rigid fidelity"
    )]
    NoFullModel {
        /// What the wheel is.
        wheel: String,
    },
    /// A `strict` request whose result is not valid (outside its model's assumptions, or not
    /// converged): the result's warnings.
    #[error(
        "strict: the result is not valid: {}",
        tensegrity_core::warning::joined(warnings)
    )]
    Strict {
        /// The result's warnings.
        warnings: Vec<Warning>,
    },
    /// An error of the core dynamics (which names the time and member where it stopped).
    #[error(transparent)]
    Core(#[from] CoreError),
}

impl RollingError {
    /// A [`RollingError::InvalidParameter`] of a numeric parameter.
    pub fn invalid(name: &'static str, value: f64, reason: impl Into<String>) -> Self {
        Self::InvalidParameter(InvalidParameter::new(name, value, reason))
    }
}

impl Categorized for RollingError {
    fn category(&self) -> Category {
        match self {
            Self::InvalidParameter(_) | Self::NoFullModel { .. } | Self::NoSamples { .. } => {
                Category::Input
            }
            Self::Strict { .. } => Category::Numerical,
            Self::Core(e) => e.category(),
        }
    }
}

/// The `strict` rule of every dynamic request ([`tensegrity_core::request::RunChecks`]): a
/// result with `warnings` (not valid) is an error when `strict`.
///
/// ```
/// use wheel_rolling::{strict_check, RollingError};
/// assert!(strict_check(true, &[]).is_ok());
/// use tensegrity_core::Warning;
/// let sank = [Warning::SankBelowGround { depth: 0.1, tolerance: 0.01 }];
/// assert!(strict_check(false, &sank).is_ok());
/// let e = strict_check(true, &sank).unwrap_err();
/// assert!(matches!(e, RollingError::Strict { .. }) && e.to_string().contains("sank 0.1000 m"));
/// ```
pub fn strict_check(strict: bool, warnings: &[Warning]) -> Result<()> {
    if strict && !warnings.is_empty() {
        return Err(RollingError::Strict {
            warnings: warnings.to_vec(),
        });
    }
    Ok(())
}
