//! The error type of the crate: every failure names the offending parameter or item.

use tensegrity_core::request::{Categorized, Category};
use thiserror::Error;

/// Result alias of the crate.
pub type Result<T> = std::result::Result<T, TbarError>;

/// Everything that can go wrong when building or analysing a T-bar tread or wheel.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum TbarError {
    /// A user parameter is outside its valid range.
    #[error("{0}")]
    InvalidParameter(#[from] tensegrity_core::request::InvalidParameter),
    /// The structure is too large for the dense analyses.
    #[error(
        "{what}: {size} exceeds the limit {limit}; reduce the complexity or the number of treads"
    )]
    TooLarge {
        /// What was counted (e.g. `free degrees of freedom`).
        what: &'static str,
        /// The count.
        size: usize,
        /// The largest accepted count.
        limit: usize,
    },
    /// The linear elastic stiffness is singular: the load response is not defined.
    #[error("the elastic stiffness of the {structure} is singular ({mechanisms} internal mechanism(s)): the small-displacement load response needs a first-order rigid structure")]
    Mechanism {
        /// `tread`, `wheel` or `extended wheel`.
        structure: &'static str,
        /// Number of internal first-order mechanisms.
        mechanisms: usize,
    },
    /// No self-stress keeps every string in tension and every bar in compression.
    #[error("the {structure} is not prestressable (self-stress dimension {self_stress_dim}): no prestress can carry a load from every direction")]
    NotPrestressable {
        /// `tread`, `wheel` or `extended wheel`.
        structure: &'static str,
        /// Dimension of its self-stress space.
        self_stress_dim: usize,
    },
    /// The brute-force check supports a narrower class of structures than the LP.
    #[error("brute-force check: {reason}")]
    BruteForceUnsupported {
        /// Why.
        reason: String,
    },
    /// An error of the Michell parameterisation (e.g. an invalid β, δ or ε).
    #[error(transparent)]
    Michell(#[from] michell3d::MichellError),
    /// An error of the core (statics, LP, sizing, materials).
    #[error(transparent)]
    Core(#[from] tensegrity_core::CoreError),
    /// An error of the rolling models that is neither a parameter nor a core error.
    #[error(transparent)]
    Rolling(wheel_rolling::RollingError),
}

impl From<wheel_rolling::RollingError> for TbarError {
    /// A bad parameter stays a bad parameter and a core error a core error.
    fn from(e: wheel_rolling::RollingError) -> Self {
        use wheel_rolling::RollingError as R;
        match e {
            R::InvalidParameter(p) => Self::InvalidParameter(p),
            R::Core(c) => Self::Core(c),
            other => Self::Rolling(other),
        }
    }
}

/// Shorthand for [`TbarError::InvalidParameter`].
pub(crate) fn invalid(name: &'static str, value: f64, reason: impl Into<String>) -> TbarError {
    TbarError::InvalidParameter(tensegrity_core::request::InvalidParameter::new(
        name, value, reason,
    ))
}

impl Categorized for TbarError {
    /// A parameter out of range or a structure the brute-force check does not support is bad
    /// input, a structure above the dense limits a resource refusal, a mechanism or no
    /// prestress a failed computation; a wrapped error keeps its own category.
    fn category(&self) -> Category {
        match self {
            Self::InvalidParameter(_) | Self::BruteForceUnsupported { .. } => Category::Input,
            Self::TooLarge { .. } => Category::Resource,
            Self::Mechanism { .. } | Self::NotPrestressable { .. } => Category::Numerical,
            Self::Michell(e) => e.category(),
            Self::Core(e) => e.category(),
            Self::Rolling(e) => e.category(),
        }
    }
}
