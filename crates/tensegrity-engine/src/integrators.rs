//! The `integrators` command (a sweep study): one point of the work–precision study of
//! [`tensegrity_dynamics::work_precision`] — a scene (any of [`work_precision::scenes`]:
//! `prism-oscillating`, `double-pendulum`, `prism-dropped` and the stiff ones), an integrator
//! (`rk4`, `rk45`, `rattle`, `sdirk`), its `parameter` (dt in s, or rtol for the adaptive ones)
//! and the timing `repeats` — with the error measure of `tensegrity bench work-precision`:
//! the largest final node distance to a tight RK45 reference of the scene, computed once per
//! sweep ([`Context`]).
//!
//! `wall_time_s` is a measured time: it differs from run to run.

pub use crate::context::Context;
use crate::run_error::RunError;
use serde::{Deserialize, Serialize};
use tensegrity_core::request::{InvalidParameter, Request};
use tensegrity_derive::Params;
use tensegrity_dynamics::work_precision::{self, max_node_error, run_one, Point};
use tensegrity_dynamics::IntegratorKind;

/// One point of the work–precision study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct IntegratorsRequest {
    /// The scene (required).
    #[param(text, help = "A scene of the work–precision study", required)]
    pub scene: Option<String>,
    /// The integrator (required).
    #[param(choice = IntegratorKind::RIGID_NAMES, help = "The integrator", required)]
    pub integrator: Option<IntegratorKind>,
    /// dt (s) of a fixed-step integrator, rtol of an adaptive one (required).
    #[param(
        number,
        help = "dt (s) of a fixed-step integrator, rtol of an adaptive one",
        positive,
        required
    )]
    pub parameter: Option<f64>,
    /// Timed repetitions (the best counts).
    #[param(count, help = "Timed repetitions (the best counts)", rule = AtLeast(1.0))]
    pub repeats: usize,
}

impl Default for IntegratorsRequest {
    /// Scene, integrator and parameter required; one repetition.
    fn default() -> Self {
        Self {
            scene: None,
            integrator: None,
            parameter: None,
            repeats: 1,
        }
    }
}

impl Request for IntegratorsRequest {
    const NAME: &'static str = "integrators";

    /// The scene is one of [`work_precision::scenes`].
    fn check(&self) -> Result<(), InvalidParameter> {
        let name = self.scene.as_deref().unwrap_or_default();
        scene_index(name).map(|_| ())
    }
}

fn scene_index(name: &str) -> Result<usize, InvalidParameter> {
    let scenes = work_precision::scenes();
    scenes.iter().position(|s| s.name == name).ok_or_else(|| {
        let known: Vec<&str> = scenes.iter().map(|s| s.name).collect();
        InvalidParameter::text(
            "scene",
            name,
            format!("expected one of {}", known.join(", ")),
        )
    })
}

/// One work–precision point against the sweep's shared reference.
pub fn point(req: &IntegratorsRequest, ctx: &Context) -> Result<Point, RunError> {
    let index = scene_index(req.scene.as_deref().unwrap_or_default())?;
    let scene = &work_precision::scenes()[index];
    let integrator = req.integrator.unwrap_or_default();
    let parameter = req.parameter.unwrap_or(f64::NAN);
    let reference = ctx
        .reference(index, scene)
        .map_err(|e| RunError::Failed(e.clone()))?;
    let (r, wall) =
        run_one(scene, integrator, parameter, req.repeats).map_err(|e| RunError::of(&e))?;
    Ok(Point {
        scene: scene.name,
        integrator,
        parameter,
        steps: r.steps,
        rhs_evals: r.rhs_evals,
        error: max_node_error(&r, reference).max(1e-16),
        wall_time_s: wall.max(1e-9),
    })
}
