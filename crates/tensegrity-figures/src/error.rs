//! Errors of the figures crate: one enum, structured fields; the errors of the libraries a
//! figure calls are wrapped with `#[from]` and kept as the error's source, so a front end
//! finds the original error (an invalid parameter, an unwritable path) in the chain.

use michell3d::MichellError;
use std::path::PathBuf;
use sweeps::SweepError;
use tbar_wheel::TbarError;
use tensegrity_core::request::{Categorized, Category, InvalidParameter};
use tensegrity_core::CoreError;
use tensegrity_io::IoError;
use thiserror::Error;
use toroid::ToroidError;
use wheel_rolling::RollingError;

/// Result alias of the figures crate.
pub type Result<T, E = FigureError> = std::result::Result<T, E>;

/// Everything that can go wrong while building a figure.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum FigureError {
    /// A parameter of a figure request is out of its valid range (e.g. an unknown figure in
    /// `only`).
    #[error("{0}")]
    InvalidParameter(#[from] InvalidParameter),
    /// The spec of a figure's sweep does not read (a bug of the figure, not of the input).
    #[error("the sweep spec of {name}")]
    SweepSpec {
        /// The figure's sweep (`fig_3_13`, …).
        name: String,
        /// Why (boxed: the other variants stay small).
        #[source]
        source: Box<SweepError>,
    },
    /// Cases of a figure's sweep failed: the curves would have holes.
    #[error("{errors} of {written} cases of {} are error rows", path.display())]
    ErrorRows {
        /// Error rows.
        errors: usize,
        /// Rows written.
        written: usize,
        /// The sweep's CSV.
        path: PathBuf,
    },
    /// A plot of a results table found no row to draw.
    #[error("{}: no ok row with numbers in `{x}` and `{y}`", path.display())]
    EmptyPlot {
        /// The table.
        path: PathBuf,
        /// The x column.
        x: String,
        /// The y column.
        y: String,
    },
    /// The code building the figure panicked (a bug); the other figures are still built.
    #[error("the figure's code panicked")]
    Panicked,
    /// A sweep behind a figure failed (boxed: the other variants stay small).
    #[error("{0}")]
    Sweep(#[source] Box<SweepError>),
    /// A file format or figure error (reading a sweep's CSV, drawing).
    #[error("{0}")]
    Io(#[from] IoError),
    /// An error of the toroid (building, rolling).
    #[error("{0}")]
    Toroid(#[from] ToroidError),
    /// An error of a Michell truss.
    #[error("{0}")]
    Michell(#[from] MichellError),
    /// An error of the T-bar tread or wheel.
    #[error("{0}")]
    Tbar(#[from] TbarError),
    /// An error of the rolling models.
    #[error("{0}")]
    Rolling(#[from] RollingError),
    /// An error of the core model.
    #[error("{0}")]
    Core(#[from] CoreError),
}

impl From<SweepError> for FigureError {
    fn from(e: SweepError) -> Self {
        Self::Sweep(Box::new(e))
    }
}

impl Categorized for FigureError {
    /// The category of the wrapped error; a figure's own failure (a sweep's error rows, a
    /// panic) is numerical.
    fn category(&self) -> Category {
        match self {
            Self::InvalidParameter(_) | Self::EmptyPlot { .. } => Category::Input,
            Self::Io(e) => e.category(),
            Self::Rolling(e) => e.category(),
            Self::Sweep(e) if e.is_interrupted() => Category::Interrupted,
            Self::Sweep(e) if e.is_input_error() => Category::Input,
            Self::Core(e) | Self::Toroid(ToroidError::Core(e)) => core_category(e),
            Self::Toroid(ToroidError::InvalidParameter(_))
            | Self::Toroid(ToroidError::UnknownStabilizeOption { .. })
            | Self::Michell(MichellError::InvalidParameter { .. })
            | Self::Tbar(TbarError::InvalidParameter { .. })
            | Self::Tbar(TbarError::TooLarge { .. }) => Category::Input,
            Self::Michell(MichellError::Core(e)) | Self::Tbar(TbarError::Core(e)) => {
                core_category(e)
            }
            _ => Category::Numerical,
        }
    }
}

fn core_category(e: &CoreError) -> Category {
    match e {
        CoreError::InvalidParameter { .. } | CoreError::TooLarge { .. } => Category::Input,
        CoreError::Interrupted { .. } => Category::Interrupted,
        _ => Category::Numerical,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wrapped_error_is_the_source_and_gives_the_category() {
        let p = InvalidParameter::raw("only", "9.9", "no figure 9.9");
        let e = FigureError::from(ToroidError::InvalidParameter(p.clone()));
        assert_eq!(e.category(), Category::Input);
        let source = std::error::Error::source(&e).expect("the toroid error");
        assert!(source.downcast_ref::<ToroidError>().is_some());
        assert_eq!(e.to_string(), source.to_string());
        assert_eq!(FigureError::from(p).category(), Category::Input);
        assert_eq!(FigureError::Panicked.category(), Category::Numerical);
    }
}
