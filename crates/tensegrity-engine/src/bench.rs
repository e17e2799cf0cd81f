//! `bench work-precision`: error against wall time of every integrator on the scenes of
//! [`tensegrity_dynamics::work_precision`] ([`WorkPrecisionRequest`], a request named
//! `bench_work_precision`) — each integrator over its step or tolerance range, the error the
//! largest final node distance to a tight RK45 reference; the `integrators` study is one point
//! of it ([`crate::integrators`]).
//!
//! The report is the list of points (no scalar: a sweep row of it has no result column);
//! `wall_time_s` is a measured time, different from run to run.
//!
//! `bench anchors` is the `tensegrity-bench` crate (the anchor scenes, the scaling series and
//! their cost exponents).

use serde::{Deserialize, Serialize};
use tensegrity_core::request::Request;
use tensegrity_core::CoreError;
use tensegrity_derive::{Columns, Params};
use tensegrity_dynamics::work_precision::{self, Point, Skipped};

/// The work–precision study, as data (default: every point, three timing repetitions).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct WorkPrecisionRequest {
    /// Fewer points and a single timing repetition (a smoke test).
    #[param(
        flag,
        help = "Fewer points and a single timing repetition (for a smoke test)"
    )]
    pub quick: bool,
}

impl Request for WorkPrecisionRequest {
    const NAME: &'static str = "bench_work_precision";
}

/// The points of the study, scene by scene, integrator by integrator.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
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

/// [`work_precision()`], telling `progress(done, total)` after each point.
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
