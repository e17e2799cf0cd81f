//! The scaling series of `bench anchors`: cost against size for the structures whose
//! exponents the project tracks (issue 25), each point the best of `repeats` runs of one
//! library call, one thread:
//!
//! | series | size | call | time |
//! |---|---|---|---|
//! | `toroid` | sides n | [`toroid::toroid_report`] (reference wheel, spokes + inner: build, cyclic statics, prestress, mass) | the whole call |
//! | `towers` | prisms N | the statics report of a free tower of N Snelson prisms ([`tensegrity_statics::statics_report`], the default method) | the whole call |
//! | `michell` | complexity q | the 3-D Michell truss, δ = 0.25, β = π/6, φ = π/q, global solve ([`michell3d::MichellRequest::run`]) | the whole call |
//! | `rolling` | sides n | the toroid rolled down 50° with the full model (penalty contact, RK4 at 0.1 ms) for a few steps ([`toroid::roll`]) | per step (the integration alone) |
//!
//! The cost exponent of each series is fitted on log–log ([`super::fit`]); with an
//! instruction counter (callgrind), the instructions of the same call at every size and their
//! own exponent, which does not depend on the machine's load ([`super::count`]). The timed
//! call's input (request, tower) is built before the clock starts ([`run_counted`] is the
//! same input and call, for the counter).

use crate::fit::{power_law, PowerLaw};
use crate::BenchError;
use serde::Serialize;
use serde_json::json;
use std::time::Instant;
use tensegrity_core::budget::Estimate;
use tensegrity_core::request::Request;
use tensegrity_core::{test_models, Structure};
use tensegrity_statics::{statics_report, StaticsRequest};

/// One scaling series.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SeriesKind {
    /// The toroid's analysis against its number of sides.
    Toroid,
    /// The sparse statics of towers of Snelson prisms against their number of prisms.
    Towers,
    /// The 3-D Michell truss against its complexity.
    Michell,
    /// The toroid's full rolling model, per step, against its number of sides.
    Rolling,
}

impl SeriesKind {
    /// Every series, in the order of the report.
    pub const ALL: [SeriesKind; 4] = [
        SeriesKind::Toroid,
        SeriesKind::Towers,
        SeriesKind::Michell,
        SeriesKind::Rolling,
    ];

    /// The series' name.
    pub fn name(self) -> &'static str {
        match self {
            SeriesKind::Toroid => "toroid",
            SeriesKind::Towers => "towers",
            SeriesKind::Michell => "michell",
            SeriesKind::Rolling => "rolling",
        }
    }

    /// What the size counts.
    pub fn parameter(self) -> &'static str {
        match self {
            SeriesKind::Toroid | SeriesKind::Rolling => "sides n",
            SeriesKind::Towers => "prisms N",
            SeriesKind::Michell => "complexity q",
        }
    }

    /// The sizes measured: the full set, or the `quick` one (small, for tests).
    pub fn sizes(self, quick: bool) -> &'static [usize] {
        match (self, quick) {
            (SeriesKind::Toroid, false) => &[100, 316, 1000, 3162, 10000],
            (SeriesKind::Toroid, true) => &[100, 200, 400],
            (SeriesKind::Towers, false) => &[50, 100, 200, 400, 800, 1600],
            (SeriesKind::Towers, true) => &[5, 10, 20],
            (SeriesKind::Michell, false) => &[10, 20, 40, 80],
            (SeriesKind::Michell, true) => &[4, 6, 8],
            (SeriesKind::Rolling, false) => &[8, 12, 16, 24],
            (SeriesKind::Rolling, true) => &[6, 8],
        }
    }

    /// RK4 steps of a point of a time integration (the rolling series: 200 steps of 0.1 ms,
    /// 20 when quick); `None` for the other series.
    pub fn steps(self, quick: bool) -> Option<u64> {
        match (self, quick) {
            (SeriesKind::Rolling, false) => Some(200),
            (SeriesKind::Rolling, true) => Some(20),
            _ => None,
        }
    }
}

/// One size of a series.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SeriesPoint {
    /// The size (the series' parameter).
    pub size: usize,
    /// Members of the structure, where the call reports them (toroid, towers, Michell).
    pub members: Option<usize>,
    /// Best time of the call over the repeats (s).
    pub best_s: f64,
    /// Steps of a time integration (the rolling series).
    pub steps: Option<u64>,
    /// Best time per step (s), for a time integration.
    pub per_step_s: Option<f64>,
    /// Instructions of the call (callgrind, process start and setup removed; for a time
    /// integration `steps` · `instructions_per_step`), when counted ([`super::count`]).
    pub instructions: Option<f64>,
    /// Instructions per step of a time integration, when counted.
    pub instructions_per_step: Option<f64>,
}

/// A series: its points and the fitted cost exponent (of `per_step_s` for a time
/// integration, of `best_s` otherwise).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Series {
    /// Which series.
    pub series: SeriesKind,
    /// What the size counts.
    pub parameter: &'static str,
    /// One point per size, smallest first.
    pub points: Vec<SeriesPoint>,
    /// The least-squares power law on log–log.
    pub fit: Option<PowerLaw>,
    /// The power law fitted to the instructions (`instructions_per_step` for a time
    /// integration, `instructions` otherwise): an exponent that does not depend on the load.
    pub instructions_fit: Option<PowerLaw>,
    /// Why the instructions are absent (not requested, no counter, a failed count).
    pub instructions_note: Option<String>,
}

/// Measures one series (best of `repeats` per size).
pub fn measure(kind: SeriesKind, quick: bool, repeats: usize) -> Result<Series, BenchError> {
    let mut points = Vec::new();
    for &size in kind.sizes(quick) {
        let mut best: Option<SeriesPoint> = None;
        for _ in 0..repeats.max(1) {
            let p = point(kind, size, quick)?;
            let better = |b: &SeriesPoint| {
                p.per_step_s.unwrap_or(p.best_s) < b.per_step_s.unwrap_or(b.best_s)
            };
            if best.as_ref().is_none_or(better) {
                best = Some(p);
            }
        }
        points.extend(best);
    }
    let xy: Vec<(f64, f64)> = points
        .iter()
        .map(|p| (p.size as f64, p.per_step_s.unwrap_or(p.best_s)))
        .collect();
    Ok(Series {
        series: kind,
        parameter: kind.parameter(),
        fit: power_law(&xy),
        points,
        instructions_fit: None,
        instructions_note: None,
    })
}

/// The input of one call of a series at one size, built before the call is timed or counted.
enum Prepared {
    Toroid(toroid::ToroidRequest),
    Towers(Box<Structure>),
    Michell(Box<michell3d::MichellRequest>),
    Rolling(Box<toroid::RollRequest>),
}

/// The series' input at `size` (rolling: `steps` RK4 steps of its step).
fn prepare(kind: SeriesKind, size: usize, steps: u64) -> Result<Prepared, BenchError> {
    Ok(match kind {
        SeriesKind::Toroid => Prepared::Toroid(toroid::ToroidRequest::from_values([(
            "sides",
            json!(size),
        )])?),
        SeriesKind::Towers => Prepared::Towers(Box::new(test_models::snelson_tower_free(size)?)),
        SeriesKind::Michell => {
            Prepared::Michell(Box::new(michell3d::MichellRequest::from_values([
                ("complexity", json!(size)),
                ("cylindrical", json!(0.25)),
                ("beta", json!(std::f64::consts::PI / 6.0)),
                ("phi", json!(std::f64::consts::PI / size as f64)),
                ("method", json!("global")),
            ])?))
        }
        SeriesKind::Rolling => {
            let mut request = toroid::RollRequest::from_values([
                ("sides", json!(size)),
                ("fidelity", json!("full")),
                ("integrator", json!("rk4")),
                ("convergence_check", json!(false)),
            ])?;
            request.t_end = steps as f64 * request.spec().full_dt();
            Prepared::Rolling(Box::new(request))
        }
    })
}

/// Bytes a joint of a Michell truss holds (nodes, members, forces, sizing), as the engine's
/// estimate of the `michell` commands counts it.
const MICHELL_BYTES_PER_JOINT: f64 = 2048.0;

/// The estimate of one call of the series at `size` (what [`measure`] times once), from the
/// library that runs it ([`crate::estimate`]): the toroid's statics, the tower's statics, the
/// Michell truss's analysis by its joints, the rolling run.
pub fn estimate_point(kind: SeriesKind, size: usize, quick: bool) -> Result<Estimate, BenchError> {
    let steps = kind.steps(quick).unwrap_or(0);
    Ok(match prepare(kind, size, steps)? {
        Prepared::Toroid(request) => toroid::budget::statics(&request),
        Prepared::Towers(tower) => {
            let command = tensegrity_engine::statics::StaticsCommand::default();
            tensegrity_engine::statics::estimate(&tower, &command)
                .unwrap_or_else(|| Estimate::new("the tower's statics", ""))
        }
        Prepared::Michell(_) => {
            let geometry = michell3d::Geometry::Cylindrical { delta: 0.25 };
            let joints = michell3d::optimize::joint_count(geometry, size) as f64;
            Estimate::new(format!("the Michell truss of {joints} joints"), "")
                .memory(MICHELL_BYTES_PER_JOINT * joints)
                .work(tensegrity_engine::estimate::MICHELL_TABLE_S_PER_JOINT * joints)
        }
        Prepared::Rolling(request) => toroid::budget::roll(&request),
    })
}

/// What one call returned: the members where the call reports them, the integration's
/// wall time for the rolling series.
struct Called {
    members: Option<usize>,
    wall_time_s: Option<f64>,
}

/// One call of the series on its prepared input.
fn call(prepared: &Prepared) -> Result<Called, BenchError> {
    let (members, wall_time_s) = match prepared {
        Prepared::Toroid(request) => {
            let r = toroid::toroid_report(request)?;
            (Some(r.bars + r.strings), None)
        }
        Prepared::Towers(tower) => {
            statics_report(tower, &StaticsRequest::default())?;
            (Some(tower.n_members()), None)
        }
        Prepared::Michell(request) => (Some(request.run()?.analysis.report.members.len()), None),
        Prepared::Rolling(request) => (None, Some(toroid::roll(request)?.wall_time_s)),
    };
    Ok(Called {
        members,
        wall_time_s,
    })
}

/// One timed run of the series' call at `size`.
fn point(kind: SeriesKind, size: usize, quick: bool) -> Result<SeriesPoint, BenchError> {
    let steps = kind.steps(quick);
    let prepared = prepare(kind, size, steps.unwrap_or(0))?;
    let t0 = Instant::now();
    let called = call(&prepared)?;
    let elapsed = t0.elapsed().as_secs_f64();
    Ok(match (called.wall_time_s, steps) {
        (Some(wall), Some(steps)) => SeriesPoint {
            size,
            members: called.members,
            best_s: wall,
            steps: Some(steps),
            per_step_s: Some(wall / steps as f64),
            instructions: None,
            instructions_per_step: None,
        },
        _ => SeriesPoint {
            size,
            members: called.members,
            best_s: elapsed,
            steps: None,
            per_step_s: None,
            instructions: None,
            instructions_per_step: None,
        },
    })
}

/// The process an instruction counter runs for one series point (the command line's hidden
/// `bench series-run`): the input at `size` built, then `reps` calls of the series' call
/// (none: the setup alone), or, for the rolling series, one run of `reps` RK4 steps.
pub fn run_counted(kind: SeriesKind, size: usize, reps: u64) -> Result<(), BenchError> {
    if kind == SeriesKind::Rolling {
        let prepared = prepare(kind, size, reps.max(1))?;
        call(&prepared)?;
        return Ok(());
    }
    let prepared = prepare(kind, size, 0)?;
    for _ in 0..reps {
        std::hint::black_box(call(&prepared)?.members);
    }
    Ok(())
}
