//! The `integrators` study: one point of the work–precision study of
//! [`tensegrity_core::dynamics::work_precision`] per case — a scene (any of
//! [`work_precision::scenes`]: `prism-oscillating`, `double-pendulum`, `prism-dropped` and
//! the stiff ones), an integrator (`rk4`, `rk45`, `rattle`, `sdirk`), its `parameter` (dt in
//! s, or rtol for the adaptive ones) and the timing `repeats` (default 1) — with the
//! same error measure as `tensegrity bench work-precision`: the largest final node distance
//! to a tight RK45 reference of the scene, computed once per sweep ([`Context`]).
//!
//! `wall_time_s` is a measured time: it differs from run to run, so a file with it is not
//! byte-reproducible; leave it out with `[output] columns` where that matters.

use super::{col, Column};
use crate::error::{Result, SweepError};
use crate::params::{param, required, Kind, ParamDef, Params};
use std::sync::OnceLock;
use tensegrity_core::dynamics::simulation::SimulationResult;
use tensegrity_core::dynamics::work_precision::{self, max_node_error, run_one, Point, Scene};
use tensegrity_core::dynamics::IntegratorKind;

/// Parameters of `integrators`.
pub const PARAMS: [ParamDef; 4] = [
    required("scene", Kind::Text, ""),
    required("integrator", Kind::Text, ""),
    required("parameter", Kind::Number, ""),
    param("repeats", Kind::Count, ""),
];

/// The fields of [`Point`].
pub const COLUMNS: [Column; 7] = [
    col("scene", ""),
    col("integrator", ""),
    col("parameter", ""),
    col("steps", ""),
    col("rhs_evals", ""),
    col("error", "m"),
    col("wall_time_s", "s"),
];

/// The RK45 reference of the study (rtol 10⁻¹³), as `bench work-precision` runs it.
const REFERENCE_RTOL: f64 = 1e-13;

/// What the cases of one sweep share: the reference run of each scene, computed once, by
/// the first case that needs it.
#[derive(Debug)]
pub struct Context {
    /// One slot per scene of [`work_precision::scenes`].
    references: Vec<OnceLock<std::result::Result<SimulationResult, String>>>,
}

impl Default for Context {
    fn default() -> Self {
        Self {
            references: work_precision::scenes()
                .iter()
                .map(|_| OnceLock::new())
                .collect(),
        }
    }
}

impl Context {
    fn reference(
        &self,
        index: usize,
        scene: &Scene,
    ) -> std::result::Result<&SimulationResult, String> {
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

fn text(p: &Params, name: &'static str) -> Result<String> {
    p.text(name).ok_or(SweepError::MissingParameter {
        study: "integrators",
        name,
    })
}

fn invalid(name: &str, value: String, reason: String) -> String {
    SweepError::InvalidValue {
        name: name.into(),
        value,
        reason,
    }
    .to_string()
}

/// One work–precision point.
pub fn point(p: &Params, ctx: &Context) -> std::result::Result<Point, String> {
    let scenes = work_precision::scenes();
    let name = text(p, "scene")?;
    let index = scenes.iter().position(|s| s.name == name).ok_or_else(|| {
        let known: Vec<&str> = scenes.iter().map(|s| s.name).collect();
        invalid(
            "scene",
            name.clone(),
            format!("expected one of {}", known.join(", ")),
        )
    })?;
    let integrator: IntegratorKind = p
        .parsed("integrator", str::parse::<IntegratorKind>)?
        .ok_or(SweepError::MissingParameter {
            study: "integrators",
            name: "integrator",
        })?;
    let parameter = p.number("parameter")?.ok_or(SweepError::MissingParameter {
        study: "integrators",
        name: "parameter",
    })?;
    let repeats = p.count("repeats")?.unwrap_or(1);
    if repeats == 0 {
        return Err(invalid("repeats", "0".into(), "must be at least 1".into()));
    }
    let scene = &scenes[index];
    let reference = ctx.reference(index, scene)?;
    let (r, wall) = run_one(scene, integrator, parameter, repeats).map_err(|e| e.to_string())?;
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
