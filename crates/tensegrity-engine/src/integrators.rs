//! The `integrators` command (a sweep study): one point of the work–precision study of
//! [`tensegrity_core::dynamics::work_precision`] — a scene (any of [`work_precision::scenes`]:
//! `prism-oscillating`, `double-pendulum`, `prism-dropped` and the stiff ones), an integrator
//! (`rk4`, `rk45`, `rattle`, `sdirk`), its `parameter` (dt in s, or rtol for the adaptive ones)
//! and the timing `repeats` — with the error measure of `tensegrity bench work-precision`:
//! the largest final node distance to a tight RK45 reference of the scene, computed once per
//! sweep ([`Context`]).
//!
//! `wall_time_s` is a measured time: it differs from run to run.

use serde::{Deserialize, Serialize};
use std::sync::OnceLock;
use tensegrity_core::budget::Limits;
use tensegrity_core::dynamics::simulation::SimulationResult;
use tensegrity_core::dynamics::work_precision::{self, max_node_error, run_one, Point, Scene};
use tensegrity_core::dynamics::IntegratorKind;
use tensegrity_core::request::{InvalidParameter, Param, Request, Rule};

/// The RK45 reference of the study (rtol 10⁻¹³), as `bench work-precision` runs it.
const REFERENCE_RTOL: f64 = 1e-13;

/// One point of the work–precision study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct IntegratorsRequest {
    /// The scene (required).
    pub scene: Option<String>,
    /// The integrator (required).
    pub integrator: Option<IntegratorKind>,
    /// dt (s) of a fixed-step integrator, rtol of an adaptive one (required).
    pub parameter: Option<f64>,
    /// Timed repetitions (the best counts).
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

    fn params() -> Vec<Param> {
        vec![
            Param::text("scene", "A scene of the work–precision study").required(),
            Param::choice(
                "integrator",
                &["rk4", "rk45", "rattle", "sdirk"],
                "The integrator",
            )
            .required(),
            Param::number(
                "parameter",
                "",
                "dt (s) of a fixed-step integrator, rtol of an adaptive one",
            )
            .positive()
            .required(),
            Param::count("repeats", "Timed repetitions (the best counts)").rule(Rule::AtLeast(1.0)),
        ]
    }

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

/// What the cases of one sweep share: the reference run of each scene, computed once, by the
/// first case that needs it; and the front end's resource limits, for a run that checks them
/// again once it knows more than its estimate did (the sparse statics, once its rank is known).
#[derive(Debug)]
pub struct Context {
    /// One slot per scene of [`work_precision::scenes`].
    references: Vec<OnceLock<Result<SimulationResult, String>>>,
    /// The limits the runs keep to after their estimate, if any.
    limits: Option<Limits>,
}

impl Default for Context {
    fn default() -> Self {
        Self {
            references: work_precision::scenes()
                .iter()
                .map(|_| OnceLock::new())
                .collect(),
            limits: None,
        }
    }
}

impl Context {
    /// A context whose runs keep to `limits` also where they check again after their
    /// estimate (a sweep's or a Python call's limits).
    ///
    /// ```
    /// use tensegrity_core::budget::Limits;
    /// let ctx = tensegrity_engine::Context::within(Limits::default());
    /// assert_eq!(ctx.limits(), Some(&Limits::default()));
    /// assert_eq!(tensegrity_engine::Context::default().limits(), None);
    /// ```
    pub fn within(limits: Limits) -> Self {
        Self {
            limits: Some(limits),
            ..Self::default()
        }
    }

    /// The limits of [`Context::within`], if any.
    pub fn limits(&self) -> Option<&Limits> {
        self.limits.as_ref()
    }

    fn reference(&self, index: usize, scene: &Scene) -> Result<&SimulationResult, String> {
        self.references[index]
            .get_or_init(|| {
                run_one(scene, IntegratorKind::Rk45, REFERENCE_RTOL, 1)
                    .map(|(r, _)| r)
                    .map_err(|e| format!("reference run of {}: {e}", scene.name))
            })
            .as_ref()
            .map_err(Clone::clone)
    }
}

/// One work–precision point against the sweep's shared reference.
pub fn point(req: &IntegratorsRequest, ctx: &Context) -> Result<Point, crate::RunError> {
    let index = scene_index(req.scene.as_deref().unwrap_or_default())?;
    let scene = &work_precision::scenes()[index];
    let integrator = req.integrator.unwrap_or_default();
    let parameter = req.parameter.unwrap_or(f64::NAN);
    let reference = ctx
        .reference(index, scene)
        .map_err(|e| crate::RunError::Failed(e.clone()))?;
    let (r, wall) =
        run_one(scene, integrator, parameter, req.repeats).map_err(|e| crate::RunError::of(&e))?;
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
