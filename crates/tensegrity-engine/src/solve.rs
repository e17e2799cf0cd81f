//! `solve`: the load path of a scene ([`SolveCommand`], a request named `solve`) — its bars
//! elastic (EA = E π r² from their material and radius), its strings tension-only (their
//! stiffness and rest length), the scene's loads scaled by the load factor λ from 0 to a
//! target: followed by its arc length through limit points ([`tensegrity_path::follow`]), or
//! in K load steps with Newton at each ([`tensegrity_path::load_steps()`]).
//!
//! Its estimate ([`estimate`]): per path point about ten factorisations of the m × m tangent
//! stiffness (m the free coordinates); up to [`tensegrity_path::factor::DENSE_MAX`] dense
//! with one symmetric eigendecomposition, (10 · m³/3 + 9 m³) flops at
//! [`budget::DENSE_FLOP_RATE`] and 3 m² numbers held; above, sparse, linear in m
//! ([`SPARSE_S_PER_COORDINATE`], [`SPARSE_BYTES_PER_COORDINATE`], calibrated on towers).
//! The points: K + 1 in load steps; on the arc-length path, whose count is not known in
//! advance, `max_steps` but at most [`EXPECTED_PATH_POINTS`] — and the path itself stops at
//! the front end's work limit, keeping its points (`stop = "max_work"`, with a warning).
//!
//! ```
//! use tensegrity_core::request::Request;
//! use tensegrity_engine::solve::{solve, SolveCommand};
//! let c = SolveCommand::from_values([("scene", serde_json::json!("../../examples/von_mises.toml")), ("target", serde_json::json!(2.0))])?;
//! let r = solve(&c)?;
//! assert_eq!(r.limit_points, 2);
//! assert_eq!(r.final_load_factor, 2.0);
//! // the limit point of the closed form (examples/von_mises.toml)
//! assert!((r.first_limit_load_factor.unwrap() - 1.2058608).abs() < 1e-6);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::scene::{required, SceneError, SceneSource};
use crate::Context;
use serde::{Deserialize, Serialize};
use tensegrity_core::budget::{self, Estimate, Limits};
use tensegrity_core::request::{InvalidParameter, Request};
use tensegrity_core::Structure;
use tensegrity_derive::{Columns, Params};
use tensegrity_io::scene::Scene;
use tensegrity_path::point::{Event, Stop};
use tensegrity_path::stability::Stability;
use tensegrity_path::{ElasticModel, PathReport, PathSettings};

/// The load path of a scene, as data.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct SolveCommand {
    /// The scene: a TOML file, or its text (required).
    #[param(
        text,
        help = "The scene file (TOML), or the scene's TOML text: bars with a material and a radius (elastic, EA = E π r²), strings with a stiffness and a rest length, supports and loads",
        required
    )]
    pub scene: Option<SceneSource>,
    /// Load steps of load control (`None`: the arc-length path).
    #[param(
        count,
        help = "Load control in K equal steps of the load factor, Newton at each (it cannot pass a limit point; default: the arc-length path, which can)",
        optional
    )]
    pub load_steps: Option<usize>,
    /// The load factor to reach.
    #[param(
        number,
        help = "The load factor λ to reach: the load is λ times the scene's loads (negative: reversed)"
    )]
    pub target: f64,
    /// The largest number of path points.
    #[param(count, help = "The largest number of points of the arc-length path")]
    pub max_steps: usize,
    /// At the first bifurcation, follow the other branch.
    #[param(
        flag,
        help = "At the first bifurcation of the arc-length path, leave it along the critical mode and follow the other branch (dense and sparse tangents alike: the mode is computed on both)"
    )]
    pub switch_branch: bool,
}

impl Default for SolveCommand {
    /// λ up to 1 by the arc-length path, at most 500 points.
    fn default() -> Self {
        Self {
            scene: None,
            load_steps: None,
            target: 1.0,
            max_steps: 500,
            switch_branch: false,
        }
    }
}

impl Request for SolveCommand {
    const NAME: &'static str = "solve";

    /// A target of zero or not finite, and zero steps, are refused.
    fn check(&self) -> Result<(), InvalidParameter> {
        if !self.target.is_finite() || self.target == 0.0 {
            return Err(InvalidParameter::new(
                "target",
                self.target,
                "must be finite and not zero",
            ));
        }
        if self.load_steps == Some(0) {
            return Err(InvalidParameter::new(
                "load_steps",
                0.0,
                "must be at least 1",
            ));
        }
        if self.switch_branch && self.load_steps.is_some() {
            return Err(InvalidParameter::text(
                "switch_branch",
                "true",
                "load steps follow no branch: switching needs the arc-length path (drop load_steps)",
            ));
        }
        if self.max_steps == 0 {
            return Err(InvalidParameter::new(
                "max_steps",
                0.0,
                "must be at least 1",
            ));
        }
        Ok(())
    }
}

/// The report of `solve`: the path's summary (its result columns) and the path itself.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct SolveReport {
    /// `path` (arc length) or `load_steps`.
    pub method: String,
    /// The load factor of the last point.
    pub final_load_factor: f64,
    /// The largest node displacement at the last point (m).
    #[column(unit = "m")]
    pub max_displacement: f64,
    /// The number of points.
    pub points: usize,
    /// The number of limit points passed.
    pub limit_points: usize,
    /// The load factor of the first limit point (null when none).
    pub first_limit_load_factor: Option<f64>,
    /// The number of bifurcations found.
    pub bifurcations: usize,
    /// The load factor where a string first went slack (null when none did).
    pub first_slack_load_factor: Option<f64>,
    /// The slack strings at the last point.
    pub slack_strings: usize,
    /// The last point's stability: `stable`, `unstable`, `neutral` or `unknown`.
    pub stability: Stability,
    /// Why the path stopped: `reached_target`, `max_steps`, `step_too_small` or `max_work`
    /// (the work limit spent before the target; the points so far are kept).
    pub stop: String,
    /// The path: its points and events (not a column).
    #[column(skip)]
    pub path: PathReport,
}

impl SolveReport {
    /// The summary of `path` made by `method`.
    pub fn of(method: &str, path: PathReport) -> Self {
        let last = path.points.last();
        let folds: Vec<f64> = path
            .events
            .iter()
            .filter_map(|e| match e {
                Event::LimitPoint { lambda, .. } => Some(*lambda),
                _ => None,
            })
            .collect();
        let first_slack = path.events.iter().find_map(|e| match e {
            Event::Slackened { lambda, .. } => Some(*lambda),
            _ => None,
        });
        let stop = match &path.stop {
            Stop::ReachedTarget => "reached_target",
            Stop::MaxSteps => "max_steps",
            Stop::StepTooSmall { .. } => "step_too_small",
            Stop::WorkLimit { .. } => "max_work",
        };
        Self {
            method: method.to_string(),
            final_load_factor: last.map_or(0.0, |p| p.lambda),
            max_displacement: last.map_or(0.0, |p| p.max_displacement),
            points: path.points.len(),
            limit_points: folds.len(),
            first_limit_load_factor: folds.first().copied(),
            bifurcations: path
                .events
                .iter()
                .filter(|e| matches!(e, Event::Bifurcation { .. }))
                .count(),
            first_slack_load_factor: first_slack,
            slack_strings: last.map_or(0, |p| p.slack.len()),
            stability: last.map_or(Stability::Unknown, |p| p.stability),
            stop: stop.to_string(),
            path,
        }
    }
}

impl SolveCommand {
    /// The scene (required).
    pub fn source(&self) -> Result<&SceneSource, InvalidParameter> {
        required(&self.scene)
    }

    /// The path of `scene` (already read): its structure's model
    /// ([`ElasticModel::from_structure`], the bars' `rest_length` where given; under
    /// `[gravity]` the weight of the bars, the strings' `mass` and the `[[masses]]` as the
    /// dead load) with the scene's drivers, `rest_length_change` on
    /// bars and strings and `displacement` on supports ([`tensegrity_io::scene::SceneFile::path_drivers`]),
    /// and its supports along directions of any orientation (`along`) and elastic ones
    /// (`stiffness`, N/m: a spring along each held direction).
    pub fn report(&self, scene: &Scene) -> Result<SolveReport, SceneError> {
        self.report_within(scene, None)
    }

    /// [`SolveCommand::report`] under a front end's `limits`: the arc-length path, whose
    /// number of points is not known in advance ([`estimate`] counts
    /// [`EXPECTED_PATH_POINTS`]), stops at the work limit keeping its points
    /// (`stop = "max_work"`).
    pub fn report_within(
        &self,
        scene: &Scene,
        limits: Option<&Limits>,
    ) -> Result<SolveReport, SceneError> {
        // every bar of a load path is elastic: a rigid one (`simulate`'s) would be ignored
        let bars = &scene.file.bars;
        if let Some(k) = bars.iter().position(|b| b.get_ref().elastic == Some(false)) {
            return Err(InvalidParameter::text(
                "scene",
                format!("bar {k}: elastic"),
                format!("bar {k}: elastic = false is read by `simulate` only; `solve` models every bar elastic: remove it"),
            )
            .into());
        }
        let mut model = ElasticModel::from_structure(&scene.structure)?;
        crate::simulate::elastic::with_bar_rest_lengths(&mut model, scene);
        crate::simulate::elastic::with_string_and_point_weights(&mut model, scene)?;
        let (changes, motion) = scene.file.path_drivers(model.nodes.len());
        if changes.iter().any(|&c| c != 0.0) {
            model.drivers.rest_length_changes = changes;
        }
        let reels = scene.file.cluster_rest_length_changes();
        if reels.iter().any(|&c| c != 0.0) {
            model.drivers.cluster_rest_length_changes = reels;
        }
        if motion.iter().any(|m| m.iter().any(|&v| v != 0.0)) {
            model.drivers.displacements = motion.iter().map(|&m| m.into()).collect();
        }
        if self.switch_branch && model.has_friction() {
            return Err(InvalidParameter::new(
                "switch_branch",
                1.0,
                "a path with pulley friction follows load steps, which switch no branch (drop switch_branch)",
            )
            .into());
        }
        // pulley friction depends on the path's history: load control, each step settled
        let load_steps = self
            .load_steps
            .or(model.has_friction().then_some(FRICTION_LOAD_STEPS));
        Ok(match load_steps {
            Some(k) => SolveReport::of(
                "load_steps",
                tensegrity_path::load_steps(&model, k, self.target)?,
            ),
            None => {
                let settings = PathSettings {
                    target: self.target,
                    max_steps: self.max_steps,
                    switch_branch: self.switch_branch,
                    max_seconds: limits.map(|l| l.work_s),
                    ..PathSettings::default()
                };
                SolveReport::of("path", tensegrity_path::follow(&model, &settings)?)
            }
        })
    }
}

/// The load steps of a path whose clusters have pulley friction when `load_steps` is not
/// given: the arc-length path does not take friction (its sliding depends on the history),
/// load control does, each step settled to the capstan law (`tensegrity_path::load_steps`).
pub const FRICTION_LOAD_STEPS: usize = 20;

/// Runs `solve`: reads the scene, one path.
pub fn solve(command: &SolveCommand) -> Result<SolveReport, SceneError> {
    solve_in(command, &Context::default())
}

/// [`solve`] under the limits of `ctx` ([`SolveCommand::report_within`]).
pub fn solve_in(command: &SolveCommand, ctx: &Context) -> Result<SolveReport, SceneError> {
    let scene = command.source()?.load()?;
    command.report_within(&scene, ctx.limits())
}

/// The points an arc-length path is estimated with when `max_steps` allows more: the
/// bundled examples take 9–64 points to their targets (the two-bar truss through both folds
/// to λ = 2: 64; to λ = 10: 99), the 9,999-member tower 10. A path that needs more stops at
/// the work limit with its points ([`SolveCommand::report_within`]).
pub const EXPECTED_PATH_POINTS: usize = 100;

/// The resource estimate of the path of `structure` (module docs).
///
/// ```
/// use tensegrity_core::test_models::oscillating_prism;
/// use tensegrity_engine::solve::{estimate, SolveCommand};
/// let e = estimate(&oscillating_prism().unwrap(), &SolveCommand::default());
/// assert!(e.work_s < 1e-2, "{}", e.work_s);
/// ```
pub fn estimate(structure: &Structure, command: &SolveCommand) -> Estimate {
    let m = 3.0 * structure.n_nodes() as f64;
    let points = match command.load_steps {
        Some(k) => k as f64 + 1.0,
        None => command.max_steps.min(EXPECTED_PATH_POINTS) as f64,
    };
    let parameter = match command.load_steps {
        Some(k) => format!("load_steps = {k} ({} nodes)", structure.n_nodes()),
        None => format!(
            "max_steps = {} ({} nodes)",
            command.max_steps,
            structure.n_nodes()
        ),
    };
    if m <= tensegrity_path::factor::DENSE_MAX as f64 {
        let flops = points * (10.0 * m * m * m / 3.0 + 9.0 * m * m * m);
        return Estimate::new(
            format!("a load path of {points} point(s), each dense on {m} coordinates"),
            parameter,
        )
        .memory(3.0 * m * m * 8.0)
        .work(flops / budget::DENSE_FLOP_RATE);
    }
    Estimate::new(
        format!("a load path of {points} point(s), each sparse on {m} coordinates"),
        parameter,
    )
    .memory(SPARSE_BYTES_PER_COORDINATE * m)
    .work(points * 10.0 * SPARSE_S_PER_COORDINATE * m)
}

/// Seconds per free coordinate of one sparse factorisation with its assembly and solves,
/// calibrated on truss towers (`scripts/truss-tower`, 1,111 stages, 10,008 coordinates: 5.2 s
/// for 101 points of about four factorisations, 1.3 µs a coordinate), doubled; a structure
/// of wide band (a lattice) costs more per coordinate.
pub const SPARSE_S_PER_COORDINATE: f64 = 3e-6;

/// Bytes per free coordinate of a sparse path (measured 6.6 kB on the same tower, whole
/// process).
pub const SPARSE_BYTES_PER_COORDINATE: f64 = 8e3;
