//! Errors of the toroid crate: one enum, structured fields, the core's and the rolling
//! models' errors wrapped with `#[from]`.

use tensegrity_core::request::{Categorized, Category};
use tensegrity_core::CoreError;
use thiserror::Error;
use wheel_rolling::RollingError;

/// Result alias of the toroid crate.
pub type Result<T, E = ToroidError> = std::result::Result<T, E>;

/// Everything that can go wrong when building or analysing a toroid.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ToroidError {
    /// A geometric or physical parameter is out of its valid range.
    #[error("{0}")]
    InvalidParameter(#[from] tensegrity_core::request::InvalidParameter),
    /// An unknown stabilising option.
    #[error("unknown stabilising option \"{option}\" (use spokes, inner, outer or none)")]
    UnknownStabilizeOption {
        /// The word that is not an option.
        option: String,
    },
    /// The structure has no prestress (needed for a prestress design).
    #[error("the toroid is not prestressable (margin {margin:e}); no prestress design exists")]
    NotPrestressable {
        /// The LP margin found.
        margin: f64,
    },
    /// The dynamic tip-over run (fixed-step RK4, no integrator to choose) ran away: a step too
    /// large for the stiffness of its strings and ground.
    #[error("the RK4 run diverged at t = {t:?} s ({what}): its step ({dt:?} s) is too large for the stiffness of the strings or the ground; use a smaller `dt`")]
    TipoverDiverged {
        /// Time of the last accepted state, or of the detection (s).
        t: f64,
        /// The step (s).
        dt: f64,
        /// What ran away.
        what: String,
    },
    /// An error of the rolling models that is neither a parameter nor a core error (e.g. no
    /// sample recorded).
    #[error(transparent)]
    Rolling(RollingError),
    /// An error of the core analyses or of the dynamics engine (which names the time and
    /// member where it stopped).
    #[error(transparent)]
    Core(#[from] CoreError),
}

impl From<RollingError> for ToroidError {
    /// A bad parameter stays a bad parameter and a core error a core error.
    fn from(e: RollingError) -> Self {
        match e {
            RollingError::InvalidParameter(p) => Self::InvalidParameter(p),
            RollingError::Core(c) => Self::Core(c),
            other => Self::Rolling(other),
        }
    }
}

impl Categorized for ToroidError {
    /// A parameter or option the toroid does not take is bad input, a toroid without
    /// prestress a failed computation; a wrapped error keeps its own category.
    fn category(&self) -> Category {
        match self {
            Self::InvalidParameter(_) | Self::UnknownStabilizeOption { .. } => Category::Input,
            Self::NotPrestressable { .. } | Self::TipoverDiverged { .. } => Category::Numerical,
            Self::Rolling(e) => e.category(),
            Self::Core(e) => e.category(),
        }
    }
}
