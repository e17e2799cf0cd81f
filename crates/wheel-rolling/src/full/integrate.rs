//! The integration of a full run: a [`WheelScene`] under the settings of a [`FullRolling`]
//! (the tilted gravity, the ground of its contact model, the start at rest), every step
//! through the monitor, the samples and frames handed to the observer (equations in the
//! parent module).

use super::monitor::{Geometry, Monitor};
use super::rest::settle;
use super::scene::WheelScene;
use super::{FullRolling, FullRun};
use crate::contact::ContactModel;
use crate::defaults;
use crate::error::{Result, RollingError};
use crate::observer::{interrupted_warning, Observer};
use nalgebra::Vector3;
use tensegrity_core::Warning;
use tensegrity_core::{CoreError, Structure};
use tensegrity_dynamics::{
    Ground, GroundModel, IntegratorKind, Quantities, Simulation, SimulationSettings,
};

/// Integrates the scene (validated) with the settings of `model`: every step through the
/// monitor, the samples and frames handed to `observer`.
pub(super) fn run(
    model: &FullRolling,
    scene: &WheelScene,
    t_end: f64,
    observer: Option<&mut dyn Observer>,
) -> Result<FullRun> {
    let (mut structure, ground) = scene_model(model, scene)?;
    let mut settled = None;
    if model.start.at_rest(scene, model.gravity) {
        // a relaxation that fails (a step too large for the stiffness: the run itself will
        // say so) leaves the wheel unloaded
        if let Ok(Some((rest, how))) = settle(&structure, scene, &model.contact, model.dt) {
            structure = rest;
            settled = Some(how);
        }
    }
    let d = SimulationSettings::default();
    let adaptive = model.integrator.is_adaptive();
    let flight = model.integrator == IntegratorKind::Rk4Flight;
    let settings = SimulationSettings {
        t_end,
        integrator: model.integrator,
        dt: model.dt,
        rtol: if adaptive {
            defaults::ADAPTIVE_RTOL
        } else {
            d.rtol
        },
        atol: if adaptive {
            defaults::ADAPTIVE_ATOL
        } else {
            d.atol
        },
        // every step is seen by the monitor (energy budget, validity, impacts): the
        // fixed-step methods land on every point of the dt grid, flight steps are sampled
        // where they end
        output_interval: Some(if flight {
            model.output_dt
        } else {
            model.dt.min(model.output_dt)
        }),
        sample_every_step: flight,
        quantities: Quantities {
            nodes: true,
            velocities: true,
            contact_forces: true,
            energy: true,
            // member forces only for the frames' outputs (they cost a pass over the members)
            member_forces: !model.frame_times.is_empty(),
        },
        // RK4 alone drifts the bar lengths (~10⁻³ over seconds): project every step
        project: true,
        ..d
    };
    let mut sim = Simulation::new(&structure, settings)?;
    sim.model.set_ground(ground)?;
    let geometry = Geometry::of(scene, model.contact.stiffness(), model.gravity);
    let mut monitor = Monitor::new(geometry, model.output_dt, &model.frame_times, observer);
    let start = std::time::Instant::now();
    let outcome = sim.run_streaming(&mut monitor);
    if monitor.samples.is_empty() {
        outcome?;
        return Err(RollingError::NoSamples {
            output_dt: model.output_dt,
        });
    }
    let stopped = monitor.stopped();
    let (wall_time_s, drift, failure) = match outcome {
        Ok(stats) => (stats.wall_time_s, stats.warnings, None),
        // the observer asked to stop: what was computed is the result
        Err(CoreError::Interrupted { .. }) if stopped => {
            (start.elapsed().as_secs_f64(), Vec::new(), None)
        }
        // keep what was computed: the run up to the failure, flagged
        Err(e) => (start.elapsed().as_secs_f64(), Vec::new(), Some(e)),
    };
    let mut run = monitor.finish(model.output_dt, wall_time_s);
    run.settled = settled;
    let validity = &mut run.result.validity;
    validity.warnings.extend(drift.iter().map(|&w| w.into()));
    let t = run.result.samples.last().map_or(0.0, |s| s.t);
    if let Some(e) = failure {
        validity.stopped_at = Some(t);
        validity.warnings.push(Warning::StoppedEarly {
            t,
            t_end,
            reason: e.to_string(),
        });
    } else if stopped {
        validity.stopped_at = Some(t);
        validity.warnings.push(interrupted_warning(t, t_end));
    }
    Ok(run)
}

/// The scene's structure under the tilted gravity, and the slope under groups 0 and 1.
pub(super) fn scene_model(model: &FullRolling, scene: &WheelScene) -> Result<(Structure, Ground)> {
    let (sin, cos) = model.incline.sin_cos();
    let structure = scene
        .structure
        .to_builder()
        .gravity([0.0, model.gravity * sin, -model.gravity * cos])
        .build()?;
    let ground_model = match model.contact {
        ContactModel::Thesis { damping } => GroundModel::Thesis {
            damping,
            tolerance: 1e-6 * scene.outer_radius,
        },
        ContactModel::Penalty {
            stiffness,
            damping,
            mu_static,
            mu_kinetic,
        } => GroundModel::Penalty {
            stiffness,
            damping,
            mu_static,
            mu_kinetic,
            regularization_velocity: defaults::FRICTION_REGULARIZATION_VELOCITY,
            stribeck_velocity: defaults::STRIBECK_VELOCITY,
        },
        ContactModel::Stick {
            stiffness,
            damping,
            mu_static,
            mu_kinetic,
            tangential_stiffness,
            tangential_damping,
        } => GroundModel::Stick {
            stiffness,
            damping,
            mu_static,
            mu_kinetic,
            tangential_stiffness,
            tangential_damping,
        },
    };
    let plane = Vector3::new(0.0, 0.0, scene.plane_z());
    let mut ground = Ground::new(plane, Vector3::z(), ground_model);
    ground.nodes = Some(scene.contact_groups.iter().flatten().copied().collect());
    Ok((structure, ground))
}
