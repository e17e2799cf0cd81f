//! The scaling series of `bench anchors`: cost against size for the structures whose
//! exponents the project tracks (issue 25), each point the best of `repeats` runs of one
//! library call, one thread:
//!
//! | series | size | call | time |
//! |---|---|---|---|
//! | `toroid` | sides n | [`toroid::toroid_report`] (reference wheel, spokes + inner: build, cyclic statics, prestress, mass) | the whole call |
//! | `towers` | prisms N | the statics report of a free tower of N Snelson prisms ([`tensegrity_core::statics_report`], the default method) | the whole call |
//! | `michell` | complexity q | the 3-D Michell truss, δ = 0.25, β = π/6, φ = π/q, global solve ([`michell3d::MichellRequest::run`]) | the whole call |
//! | `rolling` | sides n | the toroid rolled down 50° with the full model (penalty contact, RK4 at 0.1 ms) for a few steps ([`toroid::roll`]) | per step (the integration alone) |
//!
//! The cost exponent of each series is fitted on log–log ([`super::fit`]).

use super::fit::{power_law, PowerLaw};
use super::BenchError;
use serde::Serialize;
use serde_json::json;
use std::time::Instant;
use tensegrity_core::request::Request;
use tensegrity_core::{statics_report, test_models, StaticsRequest};

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
            (SeriesKind::Toroid, true) => &[8, 16, 32],
            (SeriesKind::Towers, false) => &[50, 100, 200, 400],
            (SeriesKind::Towers, true) => &[5, 10, 20],
            (SeriesKind::Michell, false) => &[10, 20, 40, 80],
            (SeriesKind::Michell, true) => &[4, 6, 8],
            (SeriesKind::Rolling, false) => &[8, 12, 16, 24],
            (SeriesKind::Rolling, true) => &[6, 8],
        }
    }

    /// Simulated time of a rolling point (s): 200 steps of 0.1 ms, 20 when quick.
    fn rolling_t_end(quick: bool) -> f64 {
        if quick {
            2e-3
        } else {
            2e-2
        }
    }
}

/// One size of a series.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SeriesPoint {
    /// The size (the series' parameter).
    pub size: usize,
    /// Members of the structure, where the call reports them.
    pub members: Option<usize>,
    /// Best time of the call over the repeats (s).
    pub best_s: f64,
    /// Steps of a time integration (the rolling series).
    pub steps: Option<u64>,
    /// Best time per step (s), for a time integration.
    pub per_step_s: Option<f64>,
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
    })
}

/// One timed run of the series' call at `size`.
fn point(kind: SeriesKind, size: usize, quick: bool) -> Result<SeriesPoint, BenchError> {
    let timed = |members: Option<usize>, t0: Instant| SeriesPoint {
        size,
        members,
        best_s: t0.elapsed().as_secs_f64(),
        steps: None,
        per_step_s: None,
    };
    match kind {
        SeriesKind::Toroid => {
            let request = toroid::ToroidRequest::from_values([("sides", json!(size))])?;
            let t0 = Instant::now();
            let r = toroid::toroid_report(&request)?;
            Ok(timed(Some(r.bars + r.strings), t0))
        }
        SeriesKind::Towers => {
            let tower = test_models::snelson_tower_free(size)?;
            let t0 = Instant::now();
            statics_report(&tower, &StaticsRequest::default())?;
            Ok(timed(Some(tower.n_members()), t0))
        }
        SeriesKind::Michell => {
            let request = michell3d::MichellRequest::from_values([
                ("complexity", json!(size)),
                ("cylindrical", json!(0.25)),
                ("beta", json!(std::f64::consts::PI / 6.0)),
                ("phi", json!(std::f64::consts::PI / size as f64)),
                ("method", json!("global")),
            ])?;
            let t0 = Instant::now();
            request.run()?;
            Ok(timed(None, t0))
        }
        SeriesKind::Rolling => {
            let t_end = SeriesKind::rolling_t_end(quick);
            let request = toroid::RollRequest::from_values([
                ("sides", json!(size)),
                ("fidelity", json!("full")),
                ("t_end", json!(t_end)),
                ("convergence_check", json!(false)),
            ])?;
            let r = toroid::roll(&request)?;
            let steps = (t_end / request.settings.dt).round() as u64;
            Ok(SeriesPoint {
                size,
                members: None,
                best_s: r.wall_time_s,
                steps: Some(steps),
                per_step_s: Some(r.wall_time_s / steps as f64),
            })
        }
    }
}
