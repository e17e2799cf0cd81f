//! [`RollReport`]: one toroid rolling run as `roll --json` shows it — the request's echo,
//! the wheel, the model and contact that ran, wheel-rolling's [`RunSummary`] (flattened) and
//! the impact log; the sampled history and node frames ride along unserialised.

use super::RollRequest;
use serde::Serialize;
use tensegrity_derive::Columns;
use tensegrity_dynamics::IntegratorKind;
use wheel_rolling::{
    Fidelity, GroundContact, ImpactRecord, Rolled, RollingSample, RunSummary, WheelFrame,
};

/// The summary of one rolling run; serialises to the JSON of `tensegrity roll`.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct RollReport {
    /// The model that ran.
    pub fidelity: Fidelity,
    /// Why that model (the `auto` decision's reasoning, or "requested").
    pub fidelity_reason: String,
    /// The ground contact of the run: `penalty` or `thesis` for the full model, `rigid` for
    /// the rigid model's unilateral impacts.
    pub contact: GroundContact,
    /// Number of sides n.
    pub sides: usize,
    /// Slope angle (rad).
    #[column(unit = "rad")]
    pub incline_rad: f64,
    /// Simulated time asked for (s).
    #[column(unit = "s")]
    pub t_end: f64,
    /// Wheel mass (kg).
    #[column(unit = "kg")]
    pub mass_kg: f64,
    /// I₁ about the rolling axis (kg m²).
    #[serde(rename = "I1")]
    #[column(unit = "kg m^2")]
    pub i1: f64,
    /// Static friction coefficient μ_s (μ_k = 0.75 μ_s).
    pub mu: f64,
    /// Normal coefficient of restitution.
    pub restitution: f64,
    /// Normal ground damping per node of the full model (N·s/m; null for the rigid model).
    #[column(unit = "N s/m")]
    pub ground_damping: Option<f64>,
    /// The full model's integrator (null for the rigid model, which steps its one degree of
    /// freedom by RK4 between exactly located events).
    pub integrator: Option<IntegratorKind>,
    /// The step the model ran at (s): the request's `dt`, or the model's default
    /// ([`wheel_rolling::RunSpec::rigid_dt`], [`wheel_rolling::RunSpec::full_dt`]).
    #[column(unit = "s")]
    pub dt: f64,
    /// Validity and summary figures of the run (`valid`, `warnings`, `stopped_at`,
    /// `impacts`, `first_impact`, `mean_speed`, …).
    #[serde(flatten)]
    pub summary: RunSummary,
    /// Every impact: t, ω before and after, normal and tangential impulse (N·s).
    pub impact_log: Vec<ImpactRecord>,
    /// With `ensemble` ≥ 2: the perturbed copies' statistics (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[column(skip)]
    pub ensemble: Option<wheel_rolling::Ensemble>,
    /// With `ensemble` ≥ 2: each copy's sampled history, for bands over time
    /// ([`wheel_rolling::ensemble::band`]); not serialised.
    #[serde(skip)]
    pub ensemble_samples: Vec<Vec<RollingSample>>,
    /// Wall-clock time of the run (s); not serialised, so that the JSON (and a sweep's rows)
    /// depend on the mechanics only.
    #[serde(skip)]
    pub wall_time_s: f64,
    /// The sampled history (1 ms), for CSV and figures; not serialised.
    #[serde(skip)]
    pub samples: Vec<RollingSample>,
    /// Node frames at the requested times (slope coordinates); not serialised.
    #[serde(skip)]
    pub frames: Vec<WheelFrame>,
}

impl RollReport {
    /// The report of `rolled`, the run of `request`.
    pub fn of(request: &RollRequest, rolled: Rolled) -> Self {
        let r = rolled.result;
        let spec = request.spec();
        let (integrator, dt) = match rolled.fidelity {
            Fidelity::Rigid => (None, spec.rigid_dt()),
            Fidelity::Full => (Some(request.integrator), spec.full_dt()),
        };
        Self {
            fidelity: rolled.fidelity,
            fidelity_reason: rolled.reason,
            contact: rolled.contact,
            sides: request.wheel.params.sides,
            incline_rad: request.settings.incline,
            t_end: request.t_end,
            mass_kg: rolled.polygon.mass,
            i1: rolled.polygon.i1,
            mu: request.mu,
            restitution: request.settings.restitution,
            ground_damping: rolled.ground_damping,
            integrator,
            dt,
            summary: RunSummary::of(&r, request.t_end),
            impact_log: r.impact_log,
            ensemble: None,
            ensemble_samples: Vec::new(),
            wall_time_s: rolled.wall_time_s,
            samples: r.samples,
            frames: rolled.frames,
        }
    }
}
