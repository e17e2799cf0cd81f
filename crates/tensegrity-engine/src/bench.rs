//! `bench work-precision`: error against wall time of every integrator on the scenes of
//! [`tensegrity_dynamics::work_precision`] ([`WorkPrecisionRequest`], a request named
//! `bench_work_precision`) — each integrator over its step or tolerance range, the error the
//! largest final node distance to a tight RK45 reference; the `integrators` study is one point
//! of it ([`crate::integrators`]).
//!
//! The report is the list of points (no scalar: a sweep row of it has no result column);
//! `wall_time_s` is a measured time, different from run to run.
//!
//! `bench anchors` ([`suite`]): the anchor scenes ([`anchors`]) against the reference codes'
//! times, the scaling series ([`series`]) and their cost exponents ([`fit`]), in time and in
//! instructions ([`count`]).

pub mod anchors;
pub mod count;
pub mod fit;
pub mod series;
pub mod suite;

use crate::scene::SceneError;
use serde::{Deserialize, Serialize};
use tensegrity_core::request::{Categorized, Category, InvalidParameter, Param, Request};
use tensegrity_core::CoreError;
use tensegrity_dynamics::work_precision::{self, Point, Skipped};

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
/// use tensegrity_engine::bench::callgrind_total;
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

/// The work–precision study, as data (default: every point, three timing repetitions).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct WorkPrecisionRequest {
    /// Fewer points and a single timing repetition (a smoke test).
    pub quick: bool,
}

impl Request for WorkPrecisionRequest {
    const NAME: &'static str = "bench_work_precision";

    fn params() -> Vec<Param> {
        vec![Param::flag(
            "quick",
            "Fewer points and a single timing repetition (for a smoke test)",
        )]
    }
}

/// The points of the study, scene by scene, integrator by integrator.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorkPrecisionReport {
    /// One point per scene, integrator and step or tolerance (failed runs left out).
    pub points: Vec<Point>,
    /// The runs that gave no point, each with its reason (every integrator of
    /// `IntegratorKind::ALL` is run; none is left out without saying why).
    pub skipped: Vec<Skipped>,
}

/// Runs the study ([`work_precision::measure`]).
pub fn work_precision(request: &WorkPrecisionRequest) -> Result<WorkPrecisionReport, CoreError> {
    work_precision_observed(request, &mut |_, _| {})
}

/// [`work_precision`], telling `progress(done, total)` after each point.
pub fn work_precision_observed(
    request: &WorkPrecisionRequest,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<WorkPrecisionReport, CoreError> {
    let study = work_precision::measure_observed(request.quick, progress)?;
    Ok(WorkPrecisionReport {
        points: study.points,
        skipped: study.skipped,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_request_describes_its_fields() {
        tensegrity_core::request::check_description::<WorkPrecisionRequest>().unwrap();
        let r = WorkPrecisionRequest::from_values([("quick", serde_json::json!(true))]).unwrap();
        assert!(r.quick);
    }
}
