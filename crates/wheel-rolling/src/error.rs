//! Errors of the wheel-rolling crate: one enum, structured fields, the core's errors wrapped
//! with `#[from]`.

use tensegrity_core::request::{Categorized, Category, InvalidParameter};
use tensegrity_core::CoreError;
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
            Self::Core(e) => e.category(),
        }
    }
}
