//! The work–precision study: error against wall time for every integrator on five scenes.
//!
//! Scenes (from [`crate::test_models`]): a prestressed Snelson prism oscillating (one vertical
//! string 1 % short, 1 s), the compound double pendulum (class-2 joint, pinned support, 2 s),
//! a prism dropped on a penalty ground (contact and friction, no normal damping, 0.5 s), and
//! two stiff scenes: the prism with 10⁸ N/m strings (1000 N·s/m string damping) spinning at
//! one revolution per second (0.25 s), and the prism released on a 10⁵ N/m ground with
//! 3000 N·s/m normal damping (0.5 s). The error of a run is the largest node-position
//! difference at the end time against a tight RK45 reference (rtol = 1e-13, atol = 1e-15);
//! the fixed-step methods sweep dt, the adaptive ones (RK45, SDIRK) sweep rtol
//! (atol = rtol/100, largest step t_end). Timings are the best of several repetitions of the
//! integration alone.

use super::integrator::IntegratorKind;
use super::simulation::{Simulation, SimulationResult, SimulationSettings};
use crate::test_models;
use serde::Serialize;
use tensegrity_core::error::CoreError;
use tensegrity_derive::Columns;

/// One measured point.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct Point {
    /// Scene name.
    pub scene: &'static str,
    /// Integrator.
    pub integrator: IntegratorKind,
    /// dt (s, fixed step) or rtol (rk45, sdirk).
    pub parameter: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Force evaluations.
    pub rhs_evals: u64,
    /// Max node-position error at the end time (m), at least 1e-16.
    #[column(unit = "m")]
    pub error: f64,
    /// Best-of-N integration wall time (s), at least 1e-9.
    #[column(unit = "s")]
    pub wall_time_s: f64,
}

/// A run of the study that gave no point, and why (an explicit method that blew up on a stiff
/// scene, a step too long for the contact): the report lists it instead of dropping it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Skipped {
    /// Scene name.
    pub scene: &'static str,
    /// Integrator.
    pub integrator: IntegratorKind,
    /// dt (s, fixed step) or rtol (rk45, sdirk).
    pub parameter: f64,
    /// The run's error, as its message.
    pub reason: String,
}

/// The whole study: the measured points and the runs that gave none.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Study {
    /// One point per scene, integrator and step or tolerance that ran.
    pub points: Vec<Point>,
    /// The runs that failed, with their reason.
    pub skipped: Vec<Skipped>,
}

/// A scene of the study.
#[derive(Debug, Clone, Copy)]
pub struct Scene {
    /// Name used in the points.
    pub name: &'static str,
    /// End time (s).
    pub t_end: f64,
    make: fn() -> Result<Simulation, CoreError>,
}

impl Scene {
    /// A fresh simulation of the scene (default settings).
    pub fn simulation(&self) -> Result<Simulation, CoreError> {
        (self.make)()
    }
}

fn oscillating_prism() -> Result<Simulation, CoreError> {
    Simulation::new(
        &test_models::oscillating_prism()?,
        SimulationSettings::default(),
    )
}

fn pendulum() -> Result<Simulation, CoreError> {
    let s = test_models::double_pendulum(std::f64::consts::FRAC_PI_4)?;
    Simulation::new(&s, SimulationSettings::default())
}

fn dropped_prism() -> Result<Simulation, CoreError> {
    let s = test_models::dropped_prism(0.02, 50.0)?;
    let mut sim = Simulation::new(&s, SimulationSettings::default())?;
    // No normal damping here: with it the contact force jumps by c·v_n at touchdown, a true
    // discontinuity that no tolerance-based reference can resolve to 1e-13 (the string
    // damping still dissipates; the normal force has only a kink).
    sim.model
        .set_ground(test_models::dropped_prism_ground(1e4, 0.0))?;
    Ok(sim)
}

/// The prism with 10⁸ N/m strings (damping 1000 N·s/m, prestress 1000 N/m) spinning about
/// its axis at one revolution per second.
fn stiff_strings() -> Result<Simulation, CoreError> {
    let s = test_models::snelson_prism(&test_models::PrismParams {
        stiffness: 1e8,
        prestress: 1000.0,
        damping: 1000.0,
        ..Default::default()
    })?;
    let w = nalgebra::Vector3::new(0.0, 0.0, 2.0 * std::f64::consts::PI);
    let vel: Vec<[f64; 3]> = s
        .nodes()
        .iter()
        .map(|n| {
            let v = w.cross(n);
            [v.x, v.y, v.z]
        })
        .collect();
    let s = s.to_builder().velocities(vel).build()?;
    Simulation::new(&s, SimulationSettings::default())
}

/// The prism released with its feet on a 10⁵ N/m penalty ground with 3000 N·s/m normal
/// damping: it sinks to its rest penetration and its feet creep out of the tangential
/// prestress. (Released from above, the damper force would jump by c·v_n at touchdown, which
/// no 1e-13 reference resolves.)
fn damped_ground() -> Result<Simulation, CoreError> {
    let s = test_models::dropped_prism(0.0, 50.0)?;
    let mut sim = Simulation::new(&s, SimulationSettings::default())?;
    sim.model
        .set_ground(test_models::dropped_prism_ground(1e5, 3000.0))?;
    Ok(sim)
}

/// The five scenes of the study (the last two stiff).
pub fn scenes() -> [Scene; 5] {
    [
        Scene {
            name: "prism-oscillating",
            t_end: 1.0,
            make: oscillating_prism,
        },
        Scene {
            name: "double-pendulum",
            t_end: 2.0,
            make: pendulum,
        },
        Scene {
            name: "prism-dropped",
            t_end: 0.5,
            make: dropped_prism,
        },
        Scene {
            name: "prism-stiff-strings",
            t_end: 0.25,
            make: stiff_strings,
        },
        Scene {
            name: "prism-damped-ground",
            t_end: 0.5,
            make: damped_ground,
        },
    ]
}

/// Runs `scene` with `integrator` at `parameter` (dt, or rtol for rk45 and sdirk) `repeats`
/// times;
/// returns the last result and the best wall time.
pub fn run_one(
    scene: &Scene,
    integrator: IntegratorKind,
    parameter: f64,
    repeats: usize,
) -> Result<(SimulationResult, f64), CoreError> {
    let mut sim = scene.simulation()?;
    sim.settings.t_end = scene.t_end;
    sim.settings.integrator = integrator;
    match integrator {
        IntegratorKind::Rk45 | IntegratorKind::Sdirk => {
            sim.settings.rtol = parameter;
            sim.settings.atol = parameter * 1e-2;
            sim.settings.dt = scene.t_end;
        }
        _ => sim.settings.dt = parameter,
    }
    let mut r = sim.run()?;
    let mut best = r.wall_time_s;
    for _ in 1..repeats.max(1) {
        r = sim.run()?;
        best = best.min(r.wall_time_s);
    }
    Ok((r, best))
}

/// The parameter sweeps: (dt values, rtol values); `quick` gives two of each.
pub fn parameters(quick: bool) -> (Vec<f64>, Vec<f64>) {
    if quick {
        (vec![4e-3, 1e-3], vec![1e-5, 1e-8])
    } else {
        (
            vec![8e-3, 4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4],
            vec![1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11],
        )
    }
}

/// The rtol sweep of SDIRK: a third-order method with position error control is meant for
/// moderate tolerances (at tight ones it resolves every string vibration above them).
pub fn sdirk_tolerances(quick: bool) -> Vec<f64> {
    if quick {
        vec![1e-4, 1e-6]
    } else {
        vec![1e-3, 1e-4, 1e-5, 1e-6, 1e-7]
    }
}

/// Runs every integrator of [`IntegratorKind::ALL`] over its parameter range on every scene
/// (`quick`: fewer points and one timing repetition instead of three). Runs that fail (the
/// explicit methods blow up on the stiff scenes, RK4 on the contact scene at the largest
/// steps) give no point rather than aborting the study; [`measure_observed`] lists them.
pub fn measure(quick: bool) -> Result<Vec<Point>, CoreError> {
    Ok(measure_observed(quick, &mut |_, _| {})?.points)
}

/// [`measure`] with the failed runs ([`Study::skipped`]), telling `progress(done, total)` after
/// each run (a progress report).
pub fn measure_observed(
    quick: bool,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Study, CoreError> {
    let repeats = if quick { 1 } else { 3 };
    let (dts, tols) = parameters(quick);
    let sdirk_tols = sdirk_tolerances(quick);
    let per_scene: usize = IntegratorKind::ALL
        .iter()
        .map(|i| match i {
            IntegratorKind::Rk45 => tols.len(),
            IntegratorKind::Sdirk => sdirk_tols.len(),
            _ => dts.len(),
        })
        .sum();
    let scenes = scenes();
    let (total, mut done) = (per_scene * scenes.len(), 0);
    progress(done, total);
    let (mut points, mut skipped) = (Vec::new(), Vec::new());
    for scene in &scenes {
        let (reference, _) = run_one(scene, IntegratorKind::Rk45, 1e-13, 1)?;
        for integrator in IntegratorKind::ALL {
            let params = match integrator {
                IntegratorKind::Rk45 => &tols,
                IntegratorKind::Sdirk => &sdirk_tols,
                _ => &dts,
            };
            for &p in params {
                done += 1;
                let run = run_one(scene, integrator, p, repeats);
                progress(done, total);
                let (r, wall) = match run {
                    Ok(run) => run,
                    Err(e) => {
                        skipped.push(Skipped {
                            scene: scene.name,
                            integrator,
                            parameter: p,
                            reason: e.to_string(),
                        });
                        continue;
                    }
                };
                points.push(Point {
                    scene: scene.name,
                    integrator,
                    parameter: p,
                    steps: r.steps,
                    rhs_evals: r.rhs_evals,
                    error: max_node_error(&r, &reference).max(1e-16),
                    wall_time_s: wall.max(1e-9),
                });
            }
        }
    }
    Ok(Study { points, skipped })
}

/// Largest distance between the final nodes of two runs (m).
pub fn max_node_error(r: &SimulationResult, reference: &SimulationResult) -> f64 {
    r.final_nodes
        .iter()
        .zip(&reference.final_nodes)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max)
}
