//! Why a command's run gave no report ([`RunError`]): a refused value, a failed library call
//! or a refused one, each with the category a front end maps to an exit code or an exception.

use std::fmt::Display;
use tensegrity_core::request::{Categorized, Category, InvalidParameter};

/// Why a run gave no report.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RunError {
    /// A value the request refuses (the request was never run).
    #[error(transparent)]
    InvalidParameter(#[from] InvalidParameter),
    /// The library call failed numerically: its message.
    #[error("{0}")]
    Failed(String),
    /// The library call refused its input, was over a resource limit or was interrupted:
    /// its message and the category of its error (what a front end maps to an exit code
    /// or an exception).
    #[error("{message}")]
    Refused {
        /// The library error's message.
        message: String,
        /// Its category ([`Category::Input`], [`Category::Resource`] or
        /// [`Category::Interrupted`]).
        category: Category,
    },
}

impl Categorized for RunError {
    /// A refused value is bad input; a failed library call keeps its error's category.
    fn category(&self) -> Category {
        match self {
            Self::InvalidParameter(_) => Category::Input,
            Self::Failed(_) => Category::Numerical,
            Self::Refused { category, .. } => *category,
        }
    }
}

impl RunError {
    /// The error of a failed library call, by its category.
    pub fn of<E: Display + Categorized>(e: &E) -> Self {
        match e.category() {
            Category::Numerical => Self::Failed(e.to_string()),
            category => Self::Refused {
                message: e.to_string(),
                category,
            },
        }
    }
}
