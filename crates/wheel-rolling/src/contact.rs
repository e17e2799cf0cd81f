//! The ground contact of the rolling models: the kinds a request chooses, the contact model
//! of a full run, and the penalty damping that gives a coefficient of restitution.
//!
//! **Penalty damping from the restitution.** A linear spring–damper of damping ratio ζ
//! rebounds with e = exp(−ζπ/√(1−ζ²)), so ζ = −ln e / √(π² + ln² e) (ζ = 1 for e = 0: the
//! clipped critical damper, [`damping_ratio`]). A pair of contact nodes of stiffness k each
//! landing on a rigid wheel (mass m, I₁ about its axle, n contact pairs on radius R_o) meets
//! the effective mass m_eff = 1 / (1/m + R_o² sin²(π/n) / I₁) at the landing pair
//! ([`contact_effective_mass`]), so the per-node damping is c = ζ √(2 k m_eff)
//! ([`penalty_damping`]).

pub use crate::contact_kind::ContactKind;
use crate::defaults;
use crate::polygon::Polygon;
use crate::settings::RunSpec;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The contact a run used, as reports name it: `"rigid"` (the rigid model's unilateral
/// impacts), `"penalty"` or `"thesis"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GroundContact {
    /// The rigid model's unilateral contact with impacts.
    Rigid,
    /// The full model's penalty ground.
    Penalty,
    /// The full model's thesis contact.
    Thesis,
    /// The full model's penalty ground with friction that sticks.
    Stick,
}

impl std::fmt::Display for GroundContact {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Rigid => "rigid",
            Self::Penalty => "penalty",
            Self::Thesis => "thesis",
            Self::Stick => "stick",
        })
    }
}

/// The ground contact of the full model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ContactModel {
    /// Thesis §3.2.2: damping c (N·s/m) drives contact-node velocities to zero.
    Thesis {
        /// Damping of the contact-node velocities (N·s/m).
        damping: f64,
    },
    /// Penalty normal spring–damper with regularised Coulomb friction.
    Penalty {
        /// Normal stiffness per node (N/m).
        stiffness: f64,
        /// Normal damping per node (N·s/m).
        damping: f64,
        /// Static friction coefficient.
        mu_static: f64,
        /// Kinetic friction coefficient.
        mu_kinetic: f64,
    },
    /// Penalty normal spring–damper with an elastic–plastic tangential spring per node
    /// (friction that sticks up to μ_s N; `tensegrity_dynamics::stick`).
    Stick {
        /// Normal stiffness per node (N/m).
        stiffness: f64,
        /// Normal damping per node (N·s/m).
        damping: f64,
        /// Static friction coefficient.
        mu_static: f64,
        /// Kinetic friction coefficient.
        mu_kinetic: f64,
        /// Tangential spring stiffness per node (N/m).
        tangential_stiffness: f64,
        /// Tangential damping per node (N·s/m).
        tangential_damping: f64,
    },
}

impl ContactModel {
    /// The thesis contact with the default damping [`defaults::GROUND_DAMPING`].
    pub const THESIS: ContactModel = ContactModel::Thesis {
        damping: defaults::GROUND_DAMPING,
    };

    /// The penalty ground with the defaults of [`crate::defaults`]: stiffness 10⁵ N/m,
    /// damping 200 N·s/m, μ_s = 0.8 and μ_k = 0.75 μ_s = 0.6 (a request's default derives the
    /// damping from e = 0 instead, see [`ContactModel::of`]).
    pub const PENALTY: ContactModel = ContactModel::Penalty {
        stiffness: defaults::GROUND_STIFFNESS,
        damping: defaults::GROUND_DAMPING,
        mu_static: defaults::STATIC_FRICTION,
        mu_kinetic: defaults::KINETIC_FRICTION_RATIO * defaults::STATIC_FRICTION,
    };

    /// The contact of `spec` for a wheel of `polygon`: the penalty damping follows from the
    /// restitution unless `ground_damping` is given; the thesis contact's damping defaults to
    /// [`defaults::GROUND_DAMPING`]. The stick contact's tangential spring is
    /// k_t = [`defaults::TANGENTIAL_STIFFNESS_RATIO`] k and its damper the critical
    /// c_t = [`defaults::TANGENTIAL_DAMPING_RATIO`] √(2 k_t m_eff) ([`stick_damping`]).
    ///
    /// ```
    /// use wheel_rolling::{ContactModel, Polygon, RunSpec};
    /// let p = Polygon { sides: 8, outer_radius: 1.0, mass: 10.0, i1: 5.0 };
    /// let spec = RunSpec { contact: wheel_rolling::ContactKind::Penalty, ..RunSpec::default() };
    /// let ContactModel::Penalty { damping, mu_kinetic, .. } = ContactModel::of(&spec, &p)
    /// else { unreachable!() };
    /// // e = 0: ζ = 1, c = √(2 k m_eff)
    /// let s = (std::f64::consts::PI / 8.0).sin();
    /// let m_eff = 1.0 / (1.0 / 10.0 + s * s / 5.0);
    /// assert!((damping - (2.0 * 1e5 * m_eff).sqrt()).abs() < 1e-9 * damping);
    /// assert!((mu_kinetic - 0.75 * 0.8).abs() < 1e-15);
    /// ```
    pub fn of(spec: &RunSpec, polygon: &Polygon) -> Self {
        let s = &spec.settings;
        match spec.contact {
            ContactKind::Thesis => ContactModel::Thesis {
                damping: s.ground_damping.unwrap_or(defaults::GROUND_DAMPING),
            },
            ContactKind::Penalty => {
                let m_eff = contact_effective_mass(
                    polygon.mass,
                    polygon.i1,
                    polygon.outer_radius,
                    polygon.sides,
                );
                ContactModel::Penalty {
                    stiffness: s.ground_stiffness,
                    damping: s.ground_damping.unwrap_or_else(|| {
                        penalty_damping(s.restitution, s.ground_stiffness, m_eff)
                    }),
                    mu_static: spec.mu_static,
                    mu_kinetic: spec.mu_kinetic,
                }
            }
            ContactKind::Stick => {
                let m_eff = contact_effective_mass(
                    polygon.mass,
                    polygon.i1,
                    polygon.outer_radius,
                    polygon.sides,
                );
                let kt = defaults::TANGENTIAL_STIFFNESS_RATIO * s.ground_stiffness;
                ContactModel::Stick {
                    stiffness: s.ground_stiffness,
                    damping: s.ground_damping.unwrap_or_else(|| {
                        penalty_damping(s.restitution, s.ground_stiffness, m_eff)
                    }),
                    mu_static: spec.mu_static,
                    mu_kinetic: spec.mu_kinetic,
                    tangential_stiffness: kt,
                    tangential_damping: stick_damping(kt, m_eff),
                }
            }
        }
    }

    /// The normal damping per node (N·s/m).
    pub fn damping(&self) -> f64 {
        match *self {
            ContactModel::Thesis { damping }
            | ContactModel::Penalty { damping, .. }
            | ContactModel::Stick { damping, .. } => damping,
        }
    }

    /// The penalty stiffness per node (N/m; 0 for the thesis contact).
    pub fn stiffness(&self) -> f64 {
        match *self {
            ContactModel::Penalty { stiffness, .. } | ContactModel::Stick { stiffness, .. } => {
                stiffness
            }
            ContactModel::Thesis { .. } => 0.0,
        }
    }

    /// The name reports give it.
    pub fn kind(&self) -> GroundContact {
        match self {
            ContactModel::Thesis { .. } => GroundContact::Thesis,
            ContactModel::Penalty { .. } => GroundContact::Penalty,
            ContactModel::Stick { .. } => GroundContact::Stick,
        }
    }
}

/// The damping ratio ζ of a linear spring–damper that rebounds with restitution `e`
/// (e = exp(−ζπ/√(1−ζ²)) inverted; ζ = 1 for e = 0, the clipped critical damper).
///
/// ```
/// use wheel_rolling::contact::damping_ratio;
/// let z = damping_ratio(0.5);
/// let e = (-z * std::f64::consts::PI / (1.0 - z * z).sqrt()).exp();
/// assert!((e - 0.5).abs() < 1e-12);
/// assert_eq!(damping_ratio(0.0), 1.0);
/// ```
pub fn damping_ratio(e: f64) -> f64 {
    if e <= 0.0 {
        return 1.0;
    }
    let l = e.min(1.0).ln();
    -l / (PI * PI + l * l).sqrt()
}

/// Effective mass (kg) of a rigid wheel (mass m, I₁ about its axle, n contact pairs on radius
/// R_o) at a landing pair: 1 / (1/m + R_o² sin²(π/n) / I₁).
pub fn contact_effective_mass(mass: f64, i1: f64, outer_radius: f64, sides: usize) -> f64 {
    let arm = outer_radius * (PI / sides as f64).sin();
    1.0 / (1.0 / mass + arm * arm / i1)
}

/// Per-node normal damping (N·s/m) of the penalty ground that gives restitution `e` to a pair
/// of nodes of stiffness `stiffness` each landing with effective mass `effective_mass`:
/// c = ζ(e) √(2 k m_eff).
///
/// ```
/// use wheel_rolling::contact::penalty_damping;
/// // e = 0: critical damping of the pair, 2c = 2√(2k m)
/// assert!((penalty_damping(0.0, 1e5, 10.0) - (2e6f64).sqrt()).abs() < 1e-9);
/// ```
pub fn penalty_damping(e: f64, stiffness: f64, effective_mass: f64) -> f64 {
    damping_ratio(e) * (2.0 * stiffness * effective_mass).sqrt()
}

/// Per-node tangential damping (N·s/m) of the stick contact for a tangential spring of
/// stiffness `tangential_stiffness` on a wheel of effective mass `effective_mass` at a pair:
/// c_t = [`defaults::TANGENTIAL_DAMPING_RATIO`] √(2 k_t m_eff) (critical for the pair).
///
/// ```
/// use wheel_rolling::contact::stick_damping;
/// assert!((stick_damping(1e5, 10.0) - (2e6f64).sqrt()).abs() < 1e-9);
/// ```
pub fn stick_damping(tangential_stiffness: f64, effective_mass: f64) -> f64 {
    defaults::TANGENTIAL_DAMPING_RATIO * (2.0 * tangential_stiffness * effective_mass).sqrt()
}
