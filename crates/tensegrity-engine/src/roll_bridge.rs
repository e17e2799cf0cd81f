//! The `roll` study until the rolling branch lands: a flat stand-in for
//! [`toroid::RollRequest`] with the parameters the `roll` study had (the wheel, `incline`,
//! `t_end`, `dt`, `fidelity`, `contact`, `ground_damping`, `ground_stiffness`, `mu`,
//! `restitution`, `string_stiffness`, `min_tension`), converted to the library request. When
//! `RollRequest` is itself a [`Request`] this file goes and its entry becomes
//! `entry(toroid::roll, &columns::ROLL)`.

use serde::{Deserialize, Serialize};
use tensegrity_core::angle::serde_angle;
use tensegrity_core::request::{Param, Request};
use toroid::{ContactKind, FidelityChoice, RollRequest, WheelSpec};

/// The `roll` study's request (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RollStudy {
    /// The wheel.
    #[serde(flatten)]
    pub wheel: WheelSpec,
    /// Slope angle (rad).
    #[serde(with = "serde_angle")]
    pub incline: f64,
    /// Simulated time (s).
    pub t_end: f64,
    /// Integration step (s).
    pub dt: f64,
    /// `rigid`, `full` or `auto`.
    pub fidelity: Fidelity,
    /// `thesis` or `penalty`.
    pub contact: Contact,
    /// Ground damping (N s/m); unset: the library derives it.
    pub ground_damping: Option<f64>,
    /// Penalty ground stiffness per node (N/m).
    pub ground_stiffness: f64,
    /// Static friction coefficient.
    pub mu: f64,
    /// Normal coefficient of restitution.
    pub restitution: f64,
    /// String stiffness of the full model (N/m).
    pub string_stiffness: f64,
    /// Smallest string tension of the full model's prestress (N).
    pub min_tension: f64,
}

/// [`FidelityChoice`] by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[allow(missing_docs)]
pub enum Fidelity {
    Rigid,
    Full,
    Auto,
}

/// [`ContactKind`] by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[allow(missing_docs)]
pub enum Contact {
    Thesis,
    Penalty,
}

impl Default for RollStudy {
    /// [`RollRequest::default`].
    fn default() -> Self {
        let d = RollRequest::default();
        Self {
            wheel: d.wheel,
            incline: d.incline,
            t_end: d.t_end,
            dt: d.dt,
            fidelity: match d.fidelity {
                FidelityChoice::Rigid => Fidelity::Rigid,
                FidelityChoice::Full => Fidelity::Full,
                _ => Fidelity::Auto,
            },
            contact: match d.contact {
                ContactKind::Thesis => Contact::Thesis,
                _ => Contact::Penalty,
            },
            ground_damping: d.ground_damping,
            ground_stiffness: d.ground_stiffness,
            mu: d.mu,
            restitution: d.restitution,
            string_stiffness: d.string_stiffness,
            min_tension: d.min_tension,
        }
    }
}

impl RollStudy {
    /// The library request.
    pub fn request(&self) -> RollRequest {
        RollRequest {
            wheel: self.wheel,
            incline: self.incline,
            t_end: self.t_end,
            dt: self.dt,
            fidelity: match self.fidelity {
                Fidelity::Rigid => FidelityChoice::Rigid,
                Fidelity::Full => FidelityChoice::Full,
                Fidelity::Auto => FidelityChoice::Auto,
            },
            contact: match self.contact {
                Contact::Thesis => ContactKind::Thesis,
                Contact::Penalty => ContactKind::Penalty,
            },
            ground_damping: self.ground_damping,
            ground_stiffness: self.ground_stiffness,
            mu: self.mu,
            restitution: self.restitution,
            string_stiffness: self.string_stiffness,
            min_tension: self.min_tension,
            ..RollRequest::default()
        }
    }

    /// Runs [`toroid::roll`].
    pub fn run(&self) -> toroid::Result<toroid::RollReport> {
        toroid::roll(&self.request())
    }
}

impl Request for RollStudy {
    const NAME: &'static str = "roll";

    fn params() -> Vec<Param> {
        let mut p = toroid::WheelSpec::params();
        p.extend([
            Param::angle("incline", "Slope angle"),
            Param::number("t_end", "s", "Simulated time").positive(),
            Param::number("dt", "s", "Integration step").positive(),
            Param::choice("fidelity", &["rigid", "full", "auto"], "The model"),
            Param::choice("contact", &["thesis", "penalty"], "Ground contact"),
            Param::number("ground_damping", "N s/m", "Ground damping")
                .non_negative()
                .optional(),
            Param::number("ground_stiffness", "N/m", "Penalty ground stiffness").positive(),
            Param::number("mu", "", "Static friction coefficient").non_negative(),
            Param::number("restitution", "", "Normal coefficient of restitution"),
            Param::number("string_stiffness", "N/m", "String stiffness").positive(),
            Param::number("min_tension", "N", "Smallest string tension").positive(),
        ]);
        p
    }
}
