//! The errors of a load path, each naming the offending item or the point where it stopped.

use thiserror::Error;

/// The result of a load path computation.
pub type Result<T> = std::result::Result<T, PathError>;

/// What went wrong.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PathError {
    /// A member, node, support or load is not usable.
    #[error("{item}: {reason}")]
    InvalidModel {
        /// The offending item (`bar 3`, `support of node 2`, …).
        item: String,
        /// Why.
        reason: String,
    },
    /// A setting is out of its range.
    #[error("invalid value for `{name}`: {value}: {reason}")]
    InvalidSetting {
        /// The setting's name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The rule.
        reason: String,
    },
    /// The tangent stiffness cannot be factored: the structure has a mechanism on its free
    /// directions that the load would move (or is exactly at a limit point).
    #[error("the tangent stiffness is singular at load factor {lambda:.6e}: the structure has a mechanism the load moves (support it further), or the load control met a limit point (follow the path by its arc length)")]
    Singular {
        /// The load factor.
        lambda: f64,
    },
    /// Newton's method did not reach equilibrium.
    #[error("no equilibrium found at load factor {lambda:.6e}: the residual stayed at {residual:.3e} N after {iterations} Newton iterations (tolerance {tolerance:.3e} N){hint}")]
    NotConverged {
        /// The load factor.
        lambda: f64,
        /// The largest residual force component left (N).
        residual: f64,
        /// The tolerance (N).
        tolerance: f64,
        /// The iterations made.
        iterations: usize,
        /// What to try.
        hint: String,
    },
    /// The arc-length step fell below its smallest size.
    #[error("the arc-length step fell below {min_step:.3e} at load factor {lambda:.6e} after {points} points: the corrector found no equilibrium near the path (a branch point or a member that slackens abruptly); the points so far are kept")]
    StepTooSmall {
        /// The load factor of the last point.
        lambda: f64,
        /// The smallest step.
        min_step: f64,
        /// The points computed.
        points: usize,
    },
}

impl PathError {
    /// An [`PathError::InvalidModel`] of `item`.
    pub fn model(item: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::InvalidModel {
            item: item.into(),
            reason: reason.into(),
        }
    }
}
