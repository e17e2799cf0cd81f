//! The rolling study: one wheel down an incline with the model chosen by the fidelity policy
//! ([`roll`]), and the series of wheels of thesis Fig. 3.10 ([`rolling_series`]).
//!
//! Fidelity policy (one place): `Rigid` runs the reduced polygon model
//! ([`RigidRolling`]), `Full` the prestressed tensegrity dynamics ([`FullRolling`]), and
//! `Auto` the cheapest model whose assumptions hold: the rigid model when the strain measure
//! m g / (k R_o) of the wheel's weight on one string of stiffness k is below
//! [`RIGID_THRESHOLD`] (see [`auto_fidelity`]) **and** the rigid run is valid (its
//! [`crate::validity::RollValidity`] has no warning); otherwise the full model. The report
//! says which model ran and why (`fidelity_reason`).
//!
//! Both models start from the same state, at rest on a side of the contact polygon about to
//! pivot about its downhill pair, and report the same coordinates (s along the slope from
//! that pair, h above the slope), so their histories compare from t = 0.

mod frames;

use crate::analysis::analyse;
use crate::defaults;
use crate::error::Result;
use crate::report::WheelSpec;
use crate::rolling::{RigidRolling, RollingResult, RollingSample};
#[cfg(doc)]
use crate::rolling_full::RIGID_THRESHOLD;
use crate::rolling_full::{
    auto_fidelity, contact_effective_mass, deformation_measure, penalty_damping, ContactModel,
    Fidelity, FullRolling, WheelFrame,
};
use crate::validity::ImpactRecord;
use crate::Toroid;
pub use frames::rigid_frames;
use serde::Serialize;
use tensegrity_core::dynamics::IntegratorKind;

/// The model a rolling request asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FidelityChoice {
    /// The reduced rigid polygon.
    Rigid,
    /// The full tensegrity dynamics.
    Full,
    /// The cheapest valid model: rigid when the strings barely stretch under the wheel's
    /// weight and the rigid run is valid, else full.
    #[default]
    Auto,
}

/// The ground contact of the full model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactKind {
    /// Thesis §3.2.2: weight-based normal reaction plus velocity damping (it can pull and
    /// sink; its runs are flagged when they do).
    Thesis,
    /// Penalty spring–damper (never pulling) with regularised Coulomb friction.
    #[default]
    Penalty,
}

/// What [`roll`] runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollRequest {
    /// The wheel.
    pub wheel: WheelSpec,
    /// Slope angle φ (rad).
    pub incline: f64,
    /// Simulated time (s).
    pub t_end: f64,
    /// Integration step (s).
    pub dt: f64,
    /// Gravity (m/s²).
    pub gravity: f64,
    /// The model.
    pub fidelity: FidelityChoice,
    /// Ground contact of the full model.
    pub contact: ContactKind,
    /// Ground damping (N·s/m): contact-velocity damping (thesis) or normal damping per node
    /// (penalty). `None`: [`defaults::GROUND_DAMPING`] for the thesis contact, and for the
    /// penalty contact the damping that gives [`RollRequest::restitution`]
    /// ([`penalty_damping`]).
    pub ground_damping: Option<f64>,
    /// Penalty ground stiffness per node (N/m).
    pub ground_stiffness: f64,
    /// Static friction coefficient μ_s; μ_k = 0.75 μ_s
    /// ([`defaults::KINETIC_FRICTION_RATIO`]).
    pub mu: f64,
    /// Normal coefficient of restitution e of an impact (rigid model; the penalty damping
    /// unless `ground_damping` is given).
    pub restitution: f64,
    /// String stiffness of the full model (N/m).
    pub string_stiffness: f64,
    /// Smallest string tension of the full model's prestress (N).
    pub min_tension: f64,
    /// Integrator of the full model (`dt` is its step, or its largest step when adaptive).
    pub integrator: IntegratorKind,
}

impl Default for RollRequest {
    /// The reference wheel down 50° for 10 s at a 0.1 ms step (RK4 for the full model),
    /// `auto` fidelity, penalty contact with e = 0, and the contact and string defaults of
    /// [`crate::defaults`].
    fn default() -> Self {
        Self {
            wheel: WheelSpec::default(),
            incline: defaults::INCLINE_DEG.to_radians(),
            t_end: defaults::ROLL_T_END,
            dt: defaults::ROLL_DT,
            gravity: defaults::GRAVITY,
            fidelity: FidelityChoice::Auto,
            contact: ContactKind::Penalty,
            ground_damping: None,
            ground_stiffness: defaults::GROUND_STIFFNESS,
            mu: defaults::STATIC_FRICTION,
            restitution: defaults::RESTITUTION,
            string_stiffness: defaults::STRING_STIFFNESS,
            min_tension: defaults::ROLL_MIN_TENSION,
            integrator: IntegratorKind::Rk4,
        }
    }
}

impl RollRequest {
    /// The model the stiffness allows for a wheel of `mass` (kg) and outer radius R_o (m)
    /// (`auto` also needs a valid rigid run, see [`roll`]).
    ///
    /// ```
    /// use toroid::rolling_full::Fidelity;
    /// use toroid::{FidelityChoice, RollRequest};
    /// let auto = RollRequest::default();
    /// // 14.4 kg on 2·10⁴ N/m strings: m g / (k R_o) ≈ 7·10⁻³ > 10⁻³, the wheel deforms
    /// assert_eq!(auto.fidelity_for(14.4, 1.0), Fidelity::Full);
    /// let stiff = RollRequest { string_stiffness: 2e6, ..auto };
    /// assert_eq!(stiff.fidelity_for(14.4, 1.0), Fidelity::Rigid);
    /// let full = RollRequest { fidelity: FidelityChoice::Full, ..stiff };
    /// assert_eq!(full.fidelity_for(14.4, 1.0), Fidelity::Full);
    /// ```
    pub fn fidelity_for(&self, mass: f64, outer_radius: f64) -> Fidelity {
        match self.fidelity {
            FidelityChoice::Rigid => Fidelity::Rigid,
            FidelityChoice::Full => Fidelity::Full,
            FidelityChoice::Auto => {
                auto_fidelity(mass, self.gravity, self.string_stiffness, outer_radius)
            }
        }
    }

    /// Checks every scalar of the request with the core's shared rules (named as the flags
    /// of `tensegrity roll`, with `_` for `-`): positive times, step, gravity, stiffnesses
    /// and tension; non-negative damping and friction; restitution in [0, 1]; an incline in
    /// [0, π/2).
    ///
    /// ```
    /// use toroid::RollRequest;
    /// assert!(RollRequest::default().validate().is_ok());
    /// let bad = RollRequest { ground_damping: Some(-5.0), ..RollRequest::default() };
    /// assert!(bad.validate().unwrap_err().to_string().contains("ground_damping = -5"));
    /// let bad = RollRequest { mu: -1.0, ..RollRequest::default() };
    /// assert!(bad.validate().unwrap_err().to_string().contains("mu = -1"));
    /// let bad = RollRequest { restitution: 1.5, ..RollRequest::default() };
    /// assert!(bad.validate().unwrap_err().to_string().contains("restitution"));
    /// let bad = RollRequest { ground_stiffness: 0.0, ..RollRequest::default() };
    /// assert!(bad.validate().is_err());
    /// ```
    pub fn validate(&self) -> Result<()> {
        use tensegrity_core::validate::{non_negative, positive};
        positive("t_end", self.t_end)?;
        positive("dt", self.dt)?;
        positive("gravity", self.gravity)?;
        positive("ground_stiffness", self.ground_stiffness)?;
        positive("string_stiffness", self.string_stiffness)?;
        positive("min_tension", self.min_tension)?;
        if let Some(c) = self.ground_damping {
            non_negative("ground_damping", c)?;
        }
        non_negative("mu", self.mu)?;
        let bad = |name, value, reason| {
            Err(tensegrity_core::CoreError::invalid_parameter(name, value, reason).into())
        };
        if !(self.restitution.is_finite() && (0.0..=1.0).contains(&self.restitution)) {
            return bad("restitution", self.restitution, "must lie in [0, 1]");
        }
        if !(self.incline.is_finite() && (0.0..std::f64::consts::FRAC_PI_2).contains(&self.incline))
        {
            return bad("incline", self.incline, "must lie in [0, π/2) rad");
        }
        self.wheel.params.validate()
    }

    /// The contact model of the full run for a wheel of `mass` (kg), I₁ (kg m²): the penalty
    /// damping follows from the restitution unless `ground_damping` is given.
    pub fn contact_model(&self, mass: f64, i1: f64) -> ContactModel {
        match self.contact {
            ContactKind::Thesis => ContactModel::Thesis {
                damping: self.ground_damping.unwrap_or(defaults::GROUND_DAMPING),
            },
            ContactKind::Penalty => {
                let p = &self.wheel.params;
                let m_eff = contact_effective_mass(mass, i1, p.outer_radius, p.sides);
                ContactModel::Penalty {
                    stiffness: self.ground_stiffness,
                    damping: self.ground_damping.unwrap_or_else(|| {
                        penalty_damping(self.restitution, self.ground_stiffness, m_eff)
                    }),
                    mu_static: self.mu,
                    mu_kinetic: defaults::KINETIC_FRICTION_RATIO * self.mu,
                }
            }
        }
    }

    /// The rigid model of this request for a built wheel.
    pub fn rigid_model(&self, toroid: &Toroid, analysis: &crate::ToroidAnalysis) -> RigidRolling {
        RigidRolling {
            gravity: self.gravity,
            dt: self.dt,
            mu_static: self.mu,
            mu_kinetic: defaults::KINETIC_FRICTION_RATIO * self.mu,
            restitution: self.restitution,
            ..RigidRolling::of(toroid, analysis, self.incline)
        }
    }

    /// The full model of this request for a built wheel.
    pub fn full_model(&self, mass: f64, i1: f64) -> FullRolling {
        FullRolling {
            incline: self.incline,
            gravity: self.gravity,
            contact: self.contact_model(mass, i1),
            string_stiffness: self.string_stiffness,
            min_string_tension: self.min_tension,
            dt: self.dt,
            integrator: self.integrator,
            ..FullRolling::default()
        }
    }
}

/// The first impact of a run (the JSON's `first_impact`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FirstImpact {
    /// Time (s).
    pub t: f64,
    /// Angular velocity about the axle before the impact (rad/s).
    pub omega_before: f64,
    /// Angular velocity about the axle after it (rad/s).
    pub omega_after: f64,
}

/// The summary of one rolling run; serialises to the JSON of `tensegrity roll`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RollReport {
    /// The model that ran.
    pub fidelity: Fidelity,
    /// Why that model (the `auto` policy's reasoning, or "requested").
    pub fidelity_reason: String,
    /// The ground contact of the full model (`penalty` or `thesis`; `rigid` for the rigid
    /// model's unilateral impacts).
    pub contact: &'static str,
    /// Whether the run stayed inside its model's assumptions (no warning).
    pub valid: bool,
    /// What the run violated, one sentence each.
    pub warnings: Vec<String>,
    /// Set when the integration failed before `t_end`: the time (s) of the last state kept;
    /// every figure covers [0, stopped_at] only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped_at: Option<f64>,
    /// Number of sides n.
    pub sides: usize,
    /// Slope angle (rad).
    pub incline_rad: f64,
    /// Simulated time (s).
    pub t_end: f64,
    /// Wheel mass (kg).
    pub mass_kg: f64,
    /// I₁ about the rolling axis (kg m²).
    #[serde(rename = "I1")]
    pub i1: f64,
    /// Static friction coefficient μ_s (μ_k = 0.75 μ_s).
    pub mu: f64,
    /// Normal coefficient of restitution.
    pub restitution: f64,
    /// Normal ground damping per node of the full model (N·s/m; null for the rigid model).
    pub ground_damping: Option<f64>,
    /// Number of contact-pair impacts.
    pub impacts: usize,
    /// The first impact (null if none).
    pub first_impact: Option<FirstImpact>,
    /// Every impact: t, ω before and after, normal and tangential impulse (N·s).
    pub impact_log: Vec<ImpactRecord>,
    /// RMS deviation of the axle height about its mean, after the first second (m).
    pub axle_height_oscillation: f64,
    /// Mean axle height above the slope after the first second (m).
    pub mean_axle_height: f64,
    /// Mean downhill speed of the axle after the first second (m/s).
    pub mean_speed: f64,
    /// Downhill speed of the axle at the end (m/s).
    pub final_speed: f64,
    /// Largest contact force magnitude (N).
    pub max_reaction: f64,
    /// Smallest normal force (N); negative means the ground pulled.
    pub min_normal_force: f64,
    /// Fraction of the time with no contact.
    pub airborne_fraction: f64,
    /// Fraction of the time in contact and sliding.
    pub slip_fraction: f64,
    /// Deepest penetration of a contact node below the slope (m).
    pub max_penetration: f64,
    /// Energy-budget residual over the budget's largest term (dimensionless).
    pub energy_balance_error: f64,
    /// Sampled time with a negative normal force (s).
    pub lift_off_time: f64,
    /// Largest |F_t|/N: the friction coefficient rolling without slip needs.
    pub required_friction: f64,
    /// Mean sliding speed of the loaded contact nodes (m/s).
    pub mean_slip_speed: f64,
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

/// Builds the wheel, chooses the model (the `auto` policy of the module docs) and rolls it.
///
/// ```
/// use toroid::rolling_full::Fidelity;
/// use toroid::{roll, FidelityChoice, RollRequest};
/// let request = RollRequest { fidelity: FidelityChoice::Rigid, t_end: 2.0, ..Default::default() };
/// let r = roll(&request).unwrap();
/// assert_eq!(r.fidelity, Fidelity::Rigid);
/// assert!(r.mean_speed > 0.0 && r.impacts > 0);
/// ```
pub fn roll(request: &RollRequest) -> Result<RollReport> {
    roll_with_frames(request, &[])
}

/// As [`roll`], keeping the wheel's nodes at `frame_times` (s) in [`RollReport::frames`]
/// (the rigid model places the rigid wheel by its pose, see [`rigid_frames`]).
pub fn roll_with_frames(request: &RollRequest, frame_times: &[f64]) -> Result<RollReport> {
    request.validate()?;
    let t = request.wheel.build()?;
    let a = analyse(&t)?;
    let outer = t.params.outer_radius;
    let strain = deformation_measure(a.mass_kg, request.gravity, request.string_stiffness, outer);
    let run_rigid = || -> Result<TimedRun> {
        let start = std::time::Instant::now();
        let r = request.rigid_model(&t, &a).run(request.t_end)?;
        Ok((r, start.elapsed().as_secs_f64()))
    };
    let (fidelity, reason, rigid) = match request.fidelity {
        FidelityChoice::Rigid => (Fidelity::Rigid, "requested".to_string(), Some(run_rigid()?)),
        FidelityChoice::Full => (Fidelity::Full, "requested".to_string(), None),
        FidelityChoice::Auto => auto_choice(request, strain, run_rigid)?,
    };
    let model = Ran {
        fidelity,
        reason,
        mass: a.mass_kg,
        i1: a.i1,
    };
    match rigid {
        Some((r, wall)) if fidelity == Fidelity::Rigid => {
            let frames = rigid_frames(&t, &r.samples, frame_times);
            Ok(report_of(request, model, r, frames, wall))
        }
        _ => {
            let full = FullRolling {
                frame_times: frame_times.to_vec(),
                ..request.full_model(a.mass_kg, a.i1)
            }
            .run_full(&t, request.t_end)?;
            let wall = full.wall_time_s;
            Ok(report_of(request, model, full.result, full.frames, wall))
        }
    }
}

/// A rigid run and its wall-clock time (s).
type TimedRun = (RollingResult, f64);

/// The model chosen, why, and the rigid run if one was made.
type Choice = (Fidelity, String, Option<TimedRun>);

/// The `auto` policy.
fn auto_choice(
    request: &RollRequest,
    strain: f64,
    run_rigid: impl Fn() -> Result<TimedRun>,
) -> Result<Choice> {
    let k = request.string_stiffness;
    if strain >= crate::rolling_full::RIGID_THRESHOLD {
        let reason = format!(
            "the strings stretch: m g / (k R_o) = {strain:.2e} ≥ {:.0e} with k = {k} N/m",
            crate::rolling_full::RIGID_THRESHOLD
        );
        return Ok((Fidelity::Full, reason, None));
    }
    let rigid = run_rigid()?;
    if rigid.0.validity.valid() {
        let reason = format!(
            "the wheel is stiff (m g / (k R_o) = {strain:.2e} < {:.0e}) and the rigid run is valid",
            crate::rolling_full::RIGID_THRESHOLD
        );
        Ok((Fidelity::Rigid, reason, Some(rigid)))
    } else {
        let reason = format!(
            "the wheel is stiff (m g / (k R_o) = {strain:.2e}) but the rigid run is not valid: {}",
            rigid.0.validity.warnings.join("; ")
        );
        Ok((Fidelity::Full, reason, Some(rigid)))
    }
}

/// The model that ran and the wheel it ran for.
struct Ran {
    fidelity: Fidelity,
    reason: String,
    mass: f64,
    i1: f64,
}

fn report_of(
    request: &RollRequest,
    ran: Ran,
    r: RollingResult,
    frames: Vec<WheelFrame>,
    wall_time_s: f64,
) -> RollReport {
    let v = &r.validity;
    let (contact, ground_damping) = match (ran.fidelity, request.contact_model(ran.mass, ran.i1)) {
        (Fidelity::Rigid, _) => ("rigid", None),
        (Fidelity::Full, ContactModel::Penalty { damping, .. }) => ("penalty", Some(damping)),
        (Fidelity::Full, ContactModel::Thesis { damping }) => ("thesis", Some(damping)),
    };
    let skip = if request.t_end > 1.0 { 1.0 } else { 0.0 };
    let tail: Vec<f64> = r
        .samples
        .iter()
        .filter(|s| s.t >= skip - 1e-12)
        .map(|s| s.h)
        .collect();
    RollReport {
        fidelity: ran.fidelity,
        fidelity_reason: ran.reason,
        contact,
        valid: v.valid(),
        warnings: v.warnings.clone(),
        stopped_at: v.stopped_at,
        sides: request.wheel.params.sides,
        incline_rad: request.incline,
        t_end: request.t_end,
        mass_kg: ran.mass,
        i1: ran.i1,
        mu: request.mu,
        restitution: request.restitution,
        ground_damping,
        impacts: r.impacts,
        first_impact: r.impact_log.first().map(|i| FirstImpact {
            t: i.t,
            omega_before: i.omega_before,
            omega_after: i.omega_after,
        }),
        impact_log: r.impact_log.clone(),
        axle_height_oscillation: r.axle_height_oscillation,
        mean_axle_height: tail.iter().sum::<f64>() / tail.len().max(1) as f64,
        mean_speed: r.mean_speed,
        final_speed: r.final_speed,
        max_reaction: r.max_reaction,
        min_normal_force: v.min_normal_force,
        airborne_fraction: v.airborne_fraction,
        slip_fraction: v.slip_fraction,
        max_penetration: v.max_penetration,
        energy_balance_error: v.energy_balance_error,
        lift_off_time: r.lift_off_time,
        required_friction: r.required_friction,
        mean_slip_speed: r.mean_slip_speed,
        wall_time_s,
        samples: r.samples,
        frames,
    }
}

/// Rolls `request` once per wheel size in `sides` (the rest of the request unchanged), e.g.
/// the four wheels of thesis Fig. 3.10 with [`defaults::FIG_3_10_SIDES`].
pub fn rolling_series(request: &RollRequest, sides: &[usize]) -> Result<Vec<RollReport>> {
    sides
        .iter()
        .map(|&n| {
            let mut r = *request;
            r.wheel.params.sides = n;
            roll(&r)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn auto_fidelity_follows_the_documented_threshold() {
        // m g / (k R_o) of the reference wheel (≈ 14 kg) at 2·10⁴ N/m is ≈ 7·10⁻³: full;
        // 100 times stiffer strings bring it below 10⁻³: rigid if the rigid run is valid
        let t = WheelSpec::default().build().unwrap();
        let m = analyse(&t).unwrap().mass_kg;
        let req = RollRequest::default();
        let strain = m * req.gravity / (req.string_stiffness * t.params.outer_radius);
        assert!(strain > crate::rolling_full::RIGID_THRESHOLD, "{strain}");
        assert_eq!(req.fidelity_for(m, 1.0), Fidelity::Full);
        let stiff = RollRequest {
            string_stiffness: 100.0 * req.string_stiffness,
            ..req
        };
        assert_eq!(stiff.fidelity_for(m, 1.0), Fidelity::Rigid);
    }

    #[test]
    fn the_penalty_contact_uses_three_quarters_of_mu_as_kinetic_friction() {
        let req = RollRequest {
            mu: 0.5,
            ground_damping: Some(300.0),
            ..Default::default()
        };
        let ContactModel::Penalty {
            mu_static,
            mu_kinetic,
            stiffness,
            damping,
        } = req.contact_model(10.0, 5.0)
        else {
            panic!("penalty expected");
        };
        assert_eq!(
            (mu_static, mu_kinetic, stiffness, damping),
            (0.5, 0.375, 1e5, 300.0)
        );
    }

    #[test]
    fn the_penalty_damping_follows_the_restitution_unless_given() {
        // n = 8, R_o = 1: m_eff = 1/(1/m + sin²(π/8)/I₁); e = 0 gives ζ = 1
        let (m, i1) = (10.0, 5.0);
        let s = (std::f64::consts::PI / 8.0).sin();
        let m_eff = 1.0 / (1.0 / m + s * s / i1);
        let req = RollRequest::default();
        let ContactModel::Penalty { damping, .. } = req.contact_model(m, i1) else {
            panic!("penalty expected");
        };
        assert!((damping - (2.0 * 1e5 * m_eff).sqrt()).abs() < 1e-9 * damping);
    }

    #[test]
    fn a_rolling_series_keeps_the_request_and_changes_the_sides() {
        let req = RollRequest {
            fidelity: FidelityChoice::Rigid,
            t_end: 1.0,
            ..Default::default()
        };
        let runs = rolling_series(&req, &[8, 12]).unwrap();
        assert_eq!(runs.iter().map(|r| r.sides).collect::<Vec<_>>(), [8, 12]);
        assert!(runs.iter().all(|r| r.fidelity == Fidelity::Rigid));
        // the single run of n = 12 is the same as its place in the series
        let twelve = roll(&RollRequest {
            wheel: WheelSpec::with_sides(12),
            ..req
        })
        .unwrap();
        let same = |r: &RollReport| (r.samples.clone(), r.impacts, r.mean_speed);
        assert_eq!(same(&runs[1]), same(&twelve));
    }
}
