//! # tensegrity-bench
//!
//! `bench anchors`: the anchor scenes ([`anchors`]: the reference codes' scenes, MOTES and
//! TsgFEM, run by this toolkit) against the reference codes' stored times, the scaling series
//! ([`series`]: towers, lattices, toroids and T-bar wheels of growing size) and their cost
//! exponents (a least-squares power law t = c·sᵖ in log–log, [`fit`]), in time and in
//! instructions counted by callgrind ([`count`]); [`suite`] runs them as one request, whose
//! resources [`estimate`] estimates before it runs (a front end checks them against its
//! limits). The
//! work–precision study of the integrators is the engine's `bench_work_precision` command.
#![warn(missing_docs)]

pub mod anchors;
pub mod count;
pub mod estimate;
pub mod fit;
pub mod series;
pub mod suite;

use tensegrity_engine::scene::SceneError;

use tensegrity_core::request::{Categorized, Category, InvalidParameter};
use tensegrity_core::CoreError;

pub use anchors::Anchor;
pub use count::{CountedRun, InstructionCounter};
pub use suite::{bench_anchors, AnchorsReport, AnchorsRequest};

/// Why `bench anchors` gave no report: the first failed measurement's error.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BenchError {
    /// A request of a series refused its values.
    #[error(transparent)]
    InvalidParameter(#[from] InvalidParameter),
    /// An anchor scene could not be read or run.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A core analysis failed (the towers' statics).
    #[error(transparent)]
    Core(#[from] CoreError),
    /// The toroid's analysis or rolling failed.
    #[error(transparent)]
    Toroid(#[from] toroid::ToroidError),
    /// The Michell truss failed.
    #[error(transparent)]
    Michell(#[from] michell3d::MichellError),
}

impl Categorized for BenchError {
    /// The category of the wrapped error.
    fn category(&self) -> Category {
        match self {
            BenchError::InvalidParameter(_) => Category::Input,
            BenchError::Scene(e) => e.category(),
            BenchError::Core(e) => e.category(),
            BenchError::Toroid(e) => e.category(),
            BenchError::Michell(e) => e.category(),
        }
    }
}

/// The total instruction count in callgrind's summary (`==PID== Collected : N`, on stderr),
/// if present.
///
/// ```
/// use tensegrity_bench::callgrind_total;
/// let err = "==7== Events    : Ir\n==7== Collected : 1470793396\n==7== \n==7== I   refs:      1,470,793,396\n";
/// assert_eq!(callgrind_total(err), Some(1_470_793_396));
/// assert_eq!(callgrind_total("no valgrind here"), None);
/// ```
pub fn callgrind_total(stderr: &str) -> Option<u64> {
    stderr.lines().find_map(|line| {
        let (_, rest) = line.split_once("Collected :")?;
        rest.trim().parse().ok()
    })
}
