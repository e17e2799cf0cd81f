//! The rolling study: one wheel down an incline with the model chosen by the fidelity policy
//! ([`roll`]), and the series of wheels of thesis Fig. 3.10 ([`rolling_series`]).
//!
//! Fidelity policy (one place): `Rigid` runs the reduced polygon model
//! ([`RigidRolling`]), `Full` the prestressed tensegrity dynamics ([`FullRolling`]), and
//! `Auto` picks the rigid model when the strain measure m g / (k R_o) of the wheel's weight
//! on one string of stiffness k is below [`RIGID_THRESHOLD`] (see
//! [`auto_fidelity`]), with the request's gravity and string stiffness.

use crate::analysis::analyse;
use crate::defaults;
use crate::error::Result;
use crate::report::WheelSpec;
use crate::rolling::{RigidRolling, RollingResult, RollingSample};
#[cfg(doc)]
use crate::rolling_full::RIGID_THRESHOLD;
use crate::rolling_full::{auto_fidelity, ContactModel, Fidelity, FullRolling};
use serde::Serialize;
use tensegrity_core::dynamics::IntegratorKind;

/// The model a rolling request asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FidelityChoice {
    /// The reduced rigid polygon.
    Rigid,
    /// The full tensegrity dynamics.
    Full,
    /// Rigid when the strings barely stretch under the wheel's weight, else full.
    #[default]
    Auto,
}

/// The ground contact of the full model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactKind {
    /// Thesis §3.2.2: weight-based normal reaction plus velocity damping.
    #[default]
    Thesis,
    /// Penalty spring–damper with regularised Coulomb friction.
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
    /// Ground damping (N·s/m): contact-velocity damping (thesis) or normal damping (penalty).
    pub ground_damping: f64,
    /// Penalty ground stiffness (N/m).
    pub ground_stiffness: f64,
    /// Static friction coefficient μ_s of the penalty ground; μ_k = 0.75 μ_s
    /// ([`defaults::KINETIC_FRICTION_RATIO`]).
    pub mu: f64,
    /// String stiffness of the full model (N/m).
    pub string_stiffness: f64,
    /// Smallest string tension of the full model's prestress (N).
    pub min_tension: f64,
    /// Integrator of the full model (`dt` is its step, or its largest step when adaptive).
    pub integrator: IntegratorKind,
}

impl Default for RollRequest {
    /// The reference wheel down 50° for 10 s at a 0.1 ms step (RK4 for the full model),
    /// `auto` fidelity, thesis contact, and the contact and string defaults of
    /// [`crate::defaults`].
    fn default() -> Self {
        Self {
            wheel: WheelSpec::default(),
            incline: defaults::INCLINE_DEG.to_radians(),
            t_end: defaults::ROLL_T_END,
            dt: defaults::ROLL_DT,
            gravity: defaults::GRAVITY,
            fidelity: FidelityChoice::Auto,
            contact: ContactKind::Thesis,
            ground_damping: defaults::GROUND_DAMPING,
            ground_stiffness: defaults::GROUND_STIFFNESS,
            mu: defaults::STATIC_FRICTION,
            string_stiffness: defaults::STRING_STIFFNESS,
            min_tension: defaults::ROLL_MIN_TENSION,
            integrator: IntegratorKind::Rk4,
        }
    }
}

impl RollRequest {
    /// The model this request runs for a wheel of `mass` (kg) and outer radius R_o (m).
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
    /// and tension; non-negative damping and friction; an incline in [0, π/2).
    ///
    /// ```
    /// use toroid::RollRequest;
    /// assert!(RollRequest::default().validate().is_ok());
    /// let bad = RollRequest { ground_damping: -5.0, ..RollRequest::default() };
    /// assert!(bad.validate().unwrap_err().to_string().contains("ground_damping = -5"));
    /// let bad = RollRequest { mu: -1.0, ..RollRequest::default() };
    /// assert!(bad.validate().unwrap_err().to_string().contains("mu = -1"));
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
        non_negative("ground_damping", self.ground_damping)?;
        non_negative("mu", self.mu)?;
        if !(self.incline.is_finite() && (0.0..std::f64::consts::FRAC_PI_2).contains(&self.incline))
        {
            return Err(tensegrity_core::CoreError::invalid_parameter(
                "incline",
                self.incline,
                "must lie in [0, π/2) rad",
            )
            .into());
        }
        self.wheel.params.validate()
    }

    /// The contact model of the full run.
    pub fn contact_model(&self) -> ContactModel {
        match self.contact {
            ContactKind::Thesis => ContactModel::Thesis {
                damping: self.ground_damping,
            },
            ContactKind::Penalty => ContactModel::Penalty {
                stiffness: self.ground_stiffness,
                damping: self.ground_damping,
                mu_static: self.mu,
                mu_kinetic: defaults::KINETIC_FRICTION_RATIO * self.mu,
            },
        }
    }
}

/// The summary of one rolling run; serialises to the JSON of `tensegrity roll`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RollReport {
    /// The model that ran.
    pub fidelity: Fidelity,
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
    /// Number of contact-pair impacts.
    pub impacts: usize,
    /// RMS deviation of the axle height about its mean, after the first second (m).
    pub axle_height_oscillation: f64,
    /// Mean downhill speed of the axle after the first second (m/s).
    pub mean_speed: f64,
    /// Largest contact force magnitude (N).
    pub max_reaction: f64,
    /// Smallest normal force (N); negative means the real wheel would lift off.
    pub min_normal_force: f64,
    /// Sampled time with a negative normal force (s).
    pub lift_off_time: f64,
    /// Largest |F_t|/N: the friction coefficient rolling without slip needs.
    pub required_friction: f64,
    /// Mean sliding speed of the loaded contact nodes (m/s).
    pub mean_slip_speed: f64,
    /// The sampled history (1 ms), for CSV and figures; not serialised.
    #[serde(skip)]
    pub samples: Vec<RollingSample>,
}

/// Builds the wheel, chooses the model ([`RollRequest::fidelity_for`]) and rolls it.
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
    request.validate()?;
    let t = request.wheel.build()?;
    let a = analyse(&t)?;
    let fidelity = request.fidelity_for(a.mass_kg, t.params.outer_radius);
    let r = match fidelity {
        Fidelity::Rigid => RigidRolling {
            gravity: request.gravity,
            dt: request.dt,
            ..RigidRolling::of(&t, &a, request.incline)
        }
        .run(request.t_end)?,
        Fidelity::Full => FullRolling {
            incline: request.incline,
            gravity: request.gravity,
            contact: request.contact_model(),
            string_stiffness: request.string_stiffness,
            min_string_tension: request.min_tension,
            dt: request.dt,
            integrator: request.integrator,
            ..FullRolling::default()
        }
        .run(&t, request.t_end)?,
    };
    Ok(report_of(request, fidelity, a.mass_kg, a.i1, r))
}

fn report_of(
    request: &RollRequest,
    fidelity: Fidelity,
    mass_kg: f64,
    i1: f64,
    r: RollingResult,
) -> RollReport {
    RollReport {
        fidelity,
        sides: request.wheel.params.sides,
        incline_rad: request.incline,
        t_end: request.t_end,
        mass_kg,
        i1,
        impacts: r.impacts,
        axle_height_oscillation: r.axle_height_oscillation,
        mean_speed: r.mean_speed,
        max_reaction: r.max_reaction,
        min_normal_force: r.min_normal,
        lift_off_time: r.lift_off_time,
        required_friction: r.required_friction,
        mean_slip_speed: r.mean_slip_speed,
        samples: r.samples,
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
        // 100 times stiffer strings bring it below 10⁻³: rigid
        let t = WheelSpec::default().build().unwrap();
        let m = analyse(&t).unwrap().mass_kg;
        let req = RollRequest::default();
        let strain = m * req.gravity / (req.string_stiffness * t.params.outer_radius);
        assert!(strain > crate::rolling_full::RIGID_THRESHOLD, "{strain}");
        assert_eq!(req.fidelity_for(m, 1.0), Fidelity::Full);
        let stiff = RollRequest {
            string_stiffness: 100.0 * req.string_stiffness,
            t_end: 1.5,
            ..req
        };
        assert_eq!(stiff.fidelity_for(m, 1.0), Fidelity::Rigid);
        let r = roll(&stiff).unwrap();
        assert_eq!(r.fidelity, Fidelity::Rigid);
        assert_eq!(r.samples.len(), 1501);
        assert!(r.mean_speed > 0.0);
    }

    #[test]
    fn the_penalty_contact_uses_three_quarters_of_mu_as_kinetic_friction() {
        let req = RollRequest {
            contact: ContactKind::Penalty,
            mu: 0.5,
            ..Default::default()
        };
        let ContactModel::Penalty {
            mu_static,
            mu_kinetic,
            stiffness,
            ..
        } = req.contact_model()
        else {
            panic!("penalty expected");
        };
        assert_eq!((mu_static, mu_kinetic, stiffness), (0.5, 0.375, 1e5));
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
        assert_eq!(runs[1], twelve);
    }
}
