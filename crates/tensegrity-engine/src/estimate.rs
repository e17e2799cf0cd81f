//! Resource estimates of the commands: memory, work and output from the request alone,
//! before anything is allocated ([`tensegrity_core::budget::Estimate`]), for a front end to
//! check against its limits ([`tensegrity_core::budget::Limits::check`]) — the CLI before a
//! command, the sweeps before every case.
//!
//! [`Estimated`] is the estimate of a request, one per command, from the libraries' estimate
//! functions: `toroid` ([`toroid::budget::statics`]: the symmetry-adapted blocks), `roll`
//! ([`toroid::budget::roll`]: the statics, then the runs of the fidelity decision's plan),
//! `tipover_dynamic` and `tipover_rolling` ([`toroid::budget::tipover_dynamic`],
//! [`toroid::budget::tipover_rolling`]: the timed runs of the prestressed wheel),
//! `tbar_roll` ([`crate::tbar_roll::estimate`]: the runs of every row), `tbar` (the
//! statics of every tread by its nodes, [`TBAR_S_PER_TREAD_NODE2`]), `formfind`
//! ([`crate::formfind::estimate`]: the topology read or built, then the library's estimate), `statics`
//! ([`crate::statics::estimate`]: the dense SVD when the method takes it, else the sparse
//! QR's memory), `simulate` ([`crate::simulate::estimate`]: steps × right-hand sides,
//! samples), `michell_table` (rows by joints, its output) and `michell_optimize` (the
//! complexity search up to [`michell3d::optimize::search_bound`], analyses by joints); the
//! registry's [`crate::Command::estimate`] runs it on named values. Every other command is
//! cheap or bounded by its own parameter rules, and has none.
//!
//! The rest estimate outputs a front end adds to a command: [`rolling_series`] (the wheels of
//! Figs. 3.10–3.11 rolled at once), [`sign_map`] (Michell sign maps), [`friction_grid`] (the
//! Fig. 3.13 map). Each estimate names the parameters that drive its size as the requests
//! name them (`sides = 100000`, `t_end = 1e9, dt = 0.0001`), which a front end maps to its
//! own spelling.

use crate::formfind::FormfindRequest;
use crate::run_error::RunError;
use crate::simulate::SimulateCommand;
use crate::statics::StaticsCommand;
use michell3d::{MichellOptimizeRequest, MichellTableRequest};
use tbar_wheel::{TbarRollRequest, TbarStaticRequest};
use tensegrity_core::budget::{self, Estimate};
use tensegrity_core::request::Request;
use toroid::{RollRequest, TipoverDynamicRequest, TipoverRollingRequest, ToroidRequest};

/// A request whose resources are estimated before it runs (module docs).
pub trait Estimated: Request {
    /// The estimate of running this request; `None` when it has none (a rigid `tbar_roll`:
    /// milliseconds). Fails only when the request cannot be estimated (an unreadable scene).
    fn estimate(&self) -> Result<Option<Estimate>, RunError>;
}

fn failed<E: std::fmt::Display + tensegrity_core::request::Categorized>(e: E) -> RunError {
    RunError::of(&e)
}

impl Estimated for ToroidRequest {
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        Ok(Some(toroid::budget::statics(self)))
    }
}

impl Estimated for RollRequest {
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        Ok(Some(toroid::budget::roll(self)))
    }
}

impl Estimated for TipoverDynamicRequest {
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        Ok(Some(toroid::budget::tipover_dynamic(self)))
    }
}

impl Estimated for TipoverRollingRequest {
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        Ok(Some(toroid::budget::tipover_rolling(self)))
    }
}

/// Seconds of the T-bar statics per tread and squared tread node (the per-block
/// factorisations and the load envelope): calibrated on q = 20, 8 treads (3311 nodes a
/// tread), 2.33 s of CPU, release (2.7·10⁻⁸; q = 15 with 8 and 16 treads, q = 10 with 32
/// within 30 % of it), rounded up to 1.5×.
pub const TBAR_S_PER_TREAD_NODE2: f64 = 4e-8;
/// Bytes a tread node holds (its blocks, bases and envelope rows; 57 MB measured at q = 20,
/// 8 treads: 2.1 kB a node).
const TBAR_BYTES_PER_TREAD_NODE: f64 = 4096.0;

impl Estimated for TbarStaticRequest {
    /// Every tread of the wheel (π/φ, twice for the extended wheel; one for a single tread)
    /// by the square of its (q+1)(q+2)(2q+3)/6 nodes; none for a request the library refuses
    /// (complexity above [`tbar_wheel::params::MAX_COMPLEXITY`], a φ that is no wheel).
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        let q = self.complexity;
        if q > tbar_wheel::params::MAX_COMPLEXITY {
            return Ok(None);
        }
        let treads = if self.wheel || self.extended.is_some() {
            match self.phi.map(tbar_wheel::params::treads_for) {
                Some(Ok(n)) => n * if self.extended.is_some() { 2 } else { 1 },
                _ => return Ok(None),
            }
        } else {
            1
        };
        let nodes = ((q + 1) * (q + 2) * (2 * q + 3) / 6) as f64;
        let t = treads as f64;
        let phi = self.phi.map_or(String::new(), |p| format!(", phi = {p}"));
        Ok(Some(
            Estimate::new(
                format!("the statics of {treads} T-bar tread(s) of {nodes} nodes"),
                format!("complexity = {q}{phi}"),
            )
            .memory(8e6 + TBAR_BYTES_PER_TREAD_NODE * t * nodes)
            .work(TBAR_S_PER_TREAD_NODE2 * t * nodes * nodes),
        ))
    }
}

impl Estimated for TbarRollRequest {
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        crate::tbar_roll::estimate(self).map_err(failed)
    }
}

impl Estimated for StaticsCommand {
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        let scene = self.source()?.load().map_err(failed)?;
        // the linear response, asked or driven by a support's displacement, counts too
        let asked = StaticsCommand {
            response: crate::statics::wants_response(self, &scene),
            ..self.clone()
        };
        Ok(crate::statics::estimate(&scene.structure, &asked))
    }
}

impl Estimated for crate::solve::SolveCommand {
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        let scene = self.source()?.load().map_err(failed)?;
        Ok(Some(crate::solve::estimate(&scene.structure, self)))
    }
}

impl Estimated for SimulateCommand {
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        let scene = self.source()?.load().map_err(failed)?;
        if crate::simulate::elastic::is_elastic(&scene) {
            let run = self.elastic(&scene, false).map_err(failed)?;
            return run
                .estimate(self.convergence_check, false, false)
                .map(Some)
                .map_err(failed);
        }
        let simulation = self.simulation(&scene, false).map_err(failed)?;
        crate::simulate::estimate_checked(self, &simulation, false, false)
            .map(Some)
            .map_err(failed)
    }
}

impl Estimated for FormfindRequest {
    /// A built-in sized from its name before it is built, a topology from its file
    /// ([`crate::formfind::estimate`]).
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        crate::formfind::estimate(self).map_err(failed)
    }
}

/// Seconds of one Michell analysis per joint in `michell optimize` (force propagation and
/// sizing; calibrated on the issue's measured run of 215 s for `--cylindrical 0.25
/// --radius-ratio 0.01 --joint-mass 1e-6 --max-complexity 100`, release build, rounded up).
pub const MICHELL_S_PER_JOINT: f64 = 3e-7;
/// Seconds of one `michell-table` row per joint (the sizing and the sign comparison with the
/// planar family; 43 s measured up to q = 100, rounded up).
pub const MICHELL_TABLE_S_PER_JOINT: f64 = 3e-6;
/// Bytes a joint of the largest truss holds (nodes, members, forces, sizing).
const MICHELL_BYTES_PER_JOINT: f64 = 2048.0;
/// Bytes of one `michell-table` CSV row.
const MICHELL_TABLE_ROW_BYTES: f64 = 120.0;

/// Joints of the 3-D truss of complexity q (an upper bound of the planar one).
fn joints_3d(q: usize) -> f64 {
    michell3d::optimize::joint_count(michell3d::Geometry::Cylindrical { delta: 0.25 }, q) as f64
}

impl Estimated for MichellTableRequest {
    /// The rows q = 2..=Q of the four families: work by joints, output by rows.
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        let qs = self.complexities();
        let families = 1 + michell3d::complexity::FIG_4_18_DELTAS.len();
        let joints: f64 = qs.iter().map(|&q| joints_3d(q)).sum();
        let rows = (qs.len() * families) as f64;
        let largest = qs.last().copied().unwrap_or(2);
        Ok(Some(
            Estimate::new(
                format!("the Michell mass table of {rows} rows"),
                format!("max_complexity = {}", self.max_complexity),
            )
            .memory(MICHELL_BYTES_PER_JOINT * joints_3d(largest) * families as f64)
            .work(MICHELL_TABLE_S_PER_JOINT * families as f64 * joints)
            .output(MICHELL_TABLE_ROW_BYTES * rows),
        ))
    }
}

impl Estimated for MichellOptimizeRequest {
    /// The complexity search up to its bound ([`michell3d::optimize::search_bound`]): every
    /// analysis of every q by its joints; none for a request the search refuses.
    fn estimate(&self) -> Result<Option<Estimate>, RunError> {
        let req = self.optimize_request();
        // a request the search refuses (no joint mass, a bad ratio) is the run's to report
        let Ok(bound) = michell3d::optimize::search_bound(&req) else {
            return Ok(None);
        };
        let per_q = michell3d::optimize::analyses_per_complexity(req.geometry) as f64;
        let first = if req.complexity.is_some() { bound } else { 1 };
        let joints_of = |q| michell3d::optimize::joint_count(req.geometry, q) as f64;
        let joints: f64 = (first..=bound).map(joints_of).sum();
        let parameters = match req.complexity {
            Some(q) => format!("complexity = {q}"),
            None => format!(
                "max_complexity = {}, joint_mass = {}",
                req.max_complexity, req.joint_mass
            ),
        };
        Ok(Some(
            Estimate::new(
                format!("the Michell complexity search up to q = {bound}"),
                parameters,
            )
            .memory(MICHELL_BYTES_PER_JOINT * joints_of(bound))
            .work(MICHELL_S_PER_JOINT * per_q * joints),
        ))
    }
}

/// `roll` of one wheel per number of sides in `sides`, the wheels rolled at once, one thread
/// each on this machine's cores ([`toroid::budget::rolling_series`]); `None` for no wheel.
pub fn rolling_series(request: &RollRequest, sides: &[usize]) -> Option<Estimate> {
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    toroid::budget::rolling_series(request, sides, cores)
}

/// Michell sign maps of `members` members over an azimuth × polar `grid` of load directions:
/// every value kept in memory (16 bytes), written (~80 bytes a row) and computed (~30 flops
/// a value); named `map_grid = A x P`.
///
/// ```
/// let e = tensegrity_engine::estimate::sign_map((100_000, 100_000), 1);
/// assert_eq!(e.parameters.to_string(), "map_grid = 100000x100000");
/// assert_eq!(e.memory_bytes, 16e10);
/// ```
pub fn sign_map(grid: (usize, usize), members: usize) -> Estimate {
    let points = grid.0 as f64 * grid.1 as f64 * members.max(1) as f64;
    Estimate::new(
        format!("a sign map of {points:.3e} (member, load direction) values"),
        format!("map_grid = {}x{}", grid.0, grid.1),
    )
    .memory(16.0 * points)
    .output(80.0 * points)
    .work(30.0 * points / budget::SCALAR_FLOP_RATE)
}

/// The friction map of Fig. 3.13: n × n rows of (σ, ε, F_f/F_e), kept in memory (24 bytes),
/// written (~75 bytes) and computed (~200 flops a row); named `grid_points = n`.
///
/// ```
/// let e = tensegrity_engine::estimate::friction_grid(1000);
/// assert_eq!((e.memory_bytes, e.output_bytes), (24e6, 75e6));
/// assert_eq!(e.parameters.to_string(), "grid_points = 1000");
/// ```
pub fn friction_grid(points: usize) -> Estimate {
    let rows = points as f64 * points as f64;
    let e = budget::table(rows, 24.0, true, format!("grid_points = {points}"));
    Estimate {
        output_bytes: 75.0 * rows,
        work_s: 200.0 * rows / budget::SCALAR_FLOP_RATE,
        ..e
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::command;
    use serde_json::{json, Map, Value};
    use tensegrity_core::budget::{Limits, Resource};

    fn values(v: Value) -> Map<String, Value> {
        v.as_object().unwrap().clone()
    }

    #[test]
    fn a_hundred_million_sided_toroid_is_over_the_default_memory_limit() {
        // moved from the CLI's guard: `toroid --sides 100000000` is refused, naming `sides`
        let c = command("toroid").unwrap();
        let e = c.estimate(values(json!({"sides": 100_000_000}))).unwrap();
        let over = Limits::default().check(&e.unwrap()).unwrap_err();
        assert_eq!(over.resource, Resource::Memory);
        assert!(
            over.to_string().starts_with("sides = 100000000: "),
            "{over}"
        );
        let small = c.estimate(values(json!({"sides": 8}))).unwrap().unwrap();
        assert!(Limits::default().check(&small).is_ok());
    }

    #[test]
    fn a_billion_seconds_of_rolling_is_over_the_work_limit() {
        let e = command("roll")
            .unwrap()
            .estimate(values(json!({"t_end": 1e9})))
            .unwrap()
            .unwrap();
        assert!(
            e.parameters.to_string().starts_with("t_end = 1000000000, "),
            "{e:?}"
        );
        assert!(Limits::default().check(&e).is_err());
        // the series of Figs. 3.10–3.11: one wheel per side count, at most the sum of the runs
        let r = RollRequest::default();
        let one = r.estimate().unwrap().unwrap();
        let series = rolling_series(&r, &[8, 8]).unwrap();
        assert!(series.work_s <= 2.0 * one.work_s * (1.0 + 1e-12));
        assert!(rolling_series(&r, &[]).is_none());
    }

    #[test]
    fn the_scene_commands_are_estimated_from_their_scenes() {
        let s = command("statics").unwrap();
        let e = s
            .estimate(values(json!({"scene": "../../examples/prism.toml"})))
            .unwrap();
        assert!(e.unwrap().work_s < 1e-3);
        let sim = command("simulate").unwrap();
        let v = json!({"scene": "../../examples/double_pendulum.toml", "t_end": 1e4, "integrator": "rk4", "dt": 1e-4});
        let e = sim.estimate(values(v)).unwrap().unwrap();
        assert!(e
            .parameters
            .to_string()
            .starts_with("t_end = 10000 s, dt = 0.0001 s"));
        assert_eq!(
            Limits::default().check(&e).unwrap_err().resource,
            Resource::Work
        );
        let missing = json!({"scene": "no/such/scene.toml"});
        assert!(matches!(
            s.estimate(values(missing)),
            Err(RunError::Refused { message, category: tensegrity_core::request::Category::Input })
                if message.contains("no/such/scene.toml")
        ));
        // commands without an estimate
        assert!(command("tipover")
            .unwrap()
            .estimate(Map::new())
            .unwrap()
            .is_none());
    }

    #[test]
    fn the_michell_searches_and_tables_are_estimated_before_they_run() {
        // the issue's 215 s search: over the minute, named by its cap and joint mass
        let c = command("michell_optimize").unwrap();
        let v = json!({"cylindrical": 0.25, "radius_ratio": 0.01, "joint_mass": 1e-6,
                       "max_complexity": 100});
        let e = c.estimate(values(v)).unwrap().unwrap();
        assert_eq!(
            Limits::default().check(&e).unwrap_err().resource,
            Resource::Work
        );
        assert!(e.parameters.to_string().starts_with("max_complexity = 100"));
        // a heavy joint stops the search within a few q: milliseconds
        let v = json!({"planar": true, "radius_ratio": 0.3, "joint_mass": 0.1});
        assert!(c.estimate(values(v)).unwrap().unwrap().work_s < 0.1);
        // no joint mass: the run refuses it, not the estimate
        let v = json!({"planar": true, "radius_ratio": 0.3});
        assert!(c.estimate(values(v)).unwrap().is_none());
        // the table: 4 families × (Q − 1) rows of output
        let t = command("michell_table").unwrap();
        let e = t
            .estimate(values(json!({"max_complexity": 35})))
            .unwrap()
            .unwrap();
        assert_eq!(e.output_bytes, MICHELL_TABLE_ROW_BYTES * 4.0 * 34.0);
        assert!(Limits::default().check(&e).is_ok());
    }

    #[test]
    fn front_end_grids_are_estimated_by_their_size() {
        // 10¹⁰ sign-map values: 160 GB in memory, refused; a 10⁴-point friction map is not
        let over = Limits::default()
            .check(&sign_map((100_000, 100_000), 1))
            .unwrap_err();
        assert_eq!(over.resource, Resource::Memory);
        assert!(Limits::default().check(&friction_grid(100)).is_ok());
        assert!(Limits::default().check(&friction_grid(100_000)).is_err());
    }
}
