//! One rolling run of any wheel under the fidelity decision: [`roll_wheel`].
//!
//! A topology crate describes its wheel through [`Wheel`]: the rigid [`Polygon`] (n, R_o, m,
//! I₁), the nodes in the starting pose (for the rigid model's node frames; may be empty), and
//! the full model's [`WheelScene`], built only when the plan runs the full model (it needs a
//! prestress design, which costs far more than the polygon). [`roll_wheel`] makes the
//! [`Decision`] (module [`crate::fidelity`]) from the polygon and the run's settings, follows
//! its [`Plan`] and returns the run with the model that ran and why.
//!
//! With an observer, `auto` on a stiff wheel first runs the rigid model unobserved (it costs
//! milliseconds); if that run is the answer ([`Decision::rigid_answers`]: valid, and its
//! scene class one where the models agree) it is run again, observed (bit-identical: the
//! model is deterministic), else the full run is observed. So an observer sees one model's history.

use crate::contact::GroundContact;
use crate::error::RollingError;
use crate::fidelity::{Decision, Fidelity, Plan};
use crate::full::{FullRolling, WheelFrame, WheelScene};
use crate::observer::Observer;
use crate::rigid::{Polygon, RigidRolling, RigidRun};
use crate::sample::RollingResult;
use crate::settings::RunSpec;
use nalgebra::Vector3;

/// A wheel as the rolling models see it (module docs).
pub trait Wheel {
    /// The error of building the full model's scene (it takes [`RollingError`]s too).
    type Error: From<RollingError>;

    /// The rigid wheel: contact polygon, mass and I₁.
    fn polygon(&self) -> Polygon;

    /// The wheel's nodes in the starting pose (hub at the origin, axle along x, standing on
    /// the side of contact groups 0 and 1), for the rigid model's node frames; empty when the
    /// wheel has none to show.
    fn start_pose(&self) -> Vec<Vector3<f64>> {
        Vec::new()
    }

    /// The prestressed structure for the full model.
    fn scene(&self) -> Result<WheelScene, Self::Error>;
}

/// A bare polygon rolls with the rigid model only.
impl Wheel for Polygon {
    type Error = RollingError;

    fn polygon(&self) -> Polygon {
        *self
    }

    fn scene(&self) -> Result<WheelScene, RollingError> {
        Err(RollingError::NoFullModel {
            wheel: format!(
                "polygon of {} sides (R_o = {} m)",
                self.sides, self.outer_radius
            ),
        })
    }
}

/// A rolling run and how it was chosen.
#[derive(Debug, Clone, PartialEq)]
pub struct Rolled {
    /// The model that ran.
    pub fidelity: Fidelity,
    /// Why that model ("requested", or the `auto` decision's reasoning).
    pub reason: String,
    /// The contact the run used (`rigid` for the rigid model).
    pub contact: GroundContact,
    /// The full model's ground damping per node (N·s/m); `None` for the rigid model.
    pub ground_damping: Option<f64>,
    /// The wheel that rolled (the polygon of the description).
    pub polygon: Polygon,
    /// Samples, summary, impacts and validity.
    pub result: RollingResult,
    /// Node frames at the requested times.
    pub frames: Vec<WheelFrame>,
    /// Wall-clock time of the model that ran (s).
    pub wall_time_s: f64,
}

/// Rolls `wheel` as `spec` asks (module docs), keeping node frames at `frame_times` and
/// handing every sample and frame to `observer`: [`roll_decided`] with the decision
/// [`Decision::of`] the wheel's polygon.
///
/// ```
/// use wheel_rolling::{roll_wheel, Fidelity, FidelityChoice, Polygon, RunSpec};
/// let octagon = Polygon { sides: 8, outer_radius: 1.0, mass: 12.0, i1: 7.5 };
/// let spec = RunSpec { fidelity: FidelityChoice::Rigid, t_end: 1.0, ..RunSpec::default() };
/// let r = roll_wheel(&octagon, &spec, &[], None).unwrap();
/// assert_eq!((r.fidelity, r.reason.as_str()), (Fidelity::Rigid, "requested"));
/// assert!(r.result.validity.valid() && r.result.impacts > 0);
/// ```
pub fn roll_wheel<W: Wheel>(
    wheel: &W,
    spec: &RunSpec,
    frame_times: &[f64],
    observer: Option<&mut dyn Observer>,
) -> Result<Rolled, W::Error> {
    let decision = Decision::of(spec, &wheel.polygon());
    roll_decided(wheel, spec, &decision, frame_times, observer)
}

/// As [`roll_wheel`] under a decision the caller made (the same one its resource estimate
/// used, e.g. from a mass computed without building the wheel).
pub fn roll_decided<W: Wheel>(
    wheel: &W,
    spec: &RunSpec,
    decision: &Decision,
    frame_times: &[f64],
    mut observer: Option<&mut dyn Observer>,
) -> Result<Rolled, W::Error> {
    let polygon = wheel.polygon();
    let rigid = RigidRolling::new(&polygon, spec);
    let pose = if frame_times.is_empty() || !decision.plan.runs_rigid() {
        Vec::new()
    } else {
        wheel.start_pose()
    };
    // the rigid run (if the plan makes one), whether it is the result, and the reasoning of
    // `auto` on the probe
    let (rigid_done, rigid_is_result, probe) = match decision.plan {
        Plan::Rigid => (
            Some(timed_rigid(
                &rigid,
                spec.t_end,
                &pose,
                frame_times,
                reborrow(&mut observer),
            )?),
            true,
            None,
        ),
        Plan::Full => (None, false, None),
        Plan::RigidThenFullIfInvalid => {
            // the probe's frames are the result's only when nobody observes the run (else the
            // observed run makes them again)
            let probe_times = if observer.is_some() {
                &[][..]
            } else {
                frame_times
            };
            // the observer sees none of the probe, but may stop it (an interrupt): the probe
            // so far is then the result
            let mut watch = reborrow(&mut observer).map(Watch);
            let watching = watch.as_mut().map(|w| w as &mut dyn Observer);
            let probe = timed_rigid(&rigid, spec.t_end, &pose, probe_times, watching)?;
            let stopped = reborrow(&mut observer).is_some_and(|o| !o.keep_going());
            let answers = decision.rigid_answers(&probe.0.result, spec.settings.ground_stiffness);
            let reason = decision.reason(Some((&probe.0.result, spec.settings.ground_stiffness)));
            let run = match (answers && !stopped, reborrow(&mut observer)) {
                (true, Some(obs)) => {
                    timed_rigid(&rigid, spec.t_end, &pose, frame_times, Some(obs))?
                }
                _ => probe,
            };
            (Some(run), answers || stopped, Some(reason))
        }
    };
    let reason = probe.unwrap_or_else(|| decision.reason(None));
    if let (true, Some((run, wall))) = (rigid_is_result, rigid_done) {
        return Ok(Rolled {
            fidelity: Fidelity::Rigid,
            reason,
            contact: GroundContact::Rigid,
            ground_damping: None,
            polygon,
            result: run.result,
            frames: run.frames,
            wall_time_s: wall,
        });
    }
    let scene = wheel.scene()?;
    let model = FullRolling {
        frame_times: frame_times.to_vec(),
        ..FullRolling::new(spec, &polygon)
    };
    let full = model.run_scene_observed(&scene, spec.t_end, observer)?;
    Ok(Rolled {
        fidelity: Fidelity::Full,
        reason,
        contact: model.contact.kind(),
        ground_damping: Some(model.contact.damping()),
        polygon,
        result: full.result,
        frames: full.frames,
        wall_time_s: full.wall_time_s,
    })
}

/// The observer for one more call, leaving it for the next.
fn reborrow<'a>(observer: &'a mut Option<&mut dyn Observer>) -> Option<&'a mut dyn Observer> {
    match observer {
        Some(o) => Some(&mut **o),
        None => None,
    }
}

/// Forwards only [`Observer::keep_going`]: the probe of `auto` stops when the observer says
/// so, and shows it nothing.
struct Watch<'a>(&'a mut dyn Observer);

impl Observer for Watch<'_> {
    fn keep_going(&mut self) -> bool {
        self.0.keep_going()
    }
}

/// A rigid run and its wall-clock time (s).
fn timed_rigid(
    rigid: &RigidRolling,
    t_end: f64,
    pose: &[Vector3<f64>],
    frame_times: &[f64],
    observer: Option<&mut dyn Observer>,
) -> Result<(RigidRun, f64), RollingError> {
    let start = std::time::Instant::now();
    let run = rigid.run_observed(t_end, pose, frame_times, observer)?;
    Ok((run, start.elapsed().as_secs_f64()))
}
