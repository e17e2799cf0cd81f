//! Rolling down an incline: the full tensegrity model.
//!
//! The prestressed toroid (bars rigid with mass = bar density × length, strings linear elastic
//! with the rest lengths that realise a prestress design) is integrated with the core's
//! rigid-bar dynamics N̈M + NK = W + ΩPᵀ (class-2 rim joints as constrained class-1 copies).
//! In the wheel frame the wheel turns about the x axis and gravity is tilted by the slope
//! angle φ: g = g₀ (0, sin φ, −cos φ), so the wheel rolls towards +y. Only the outer tread
//! nodes (n1, n2 of every prism) can touch the slope.
//!
//! **Rigid bars.** RK4 alone lets bar lengths drift (5·10⁻³ relative in 3 s of the default
//! run), so the state is projected back onto the bar lengths and joints after every step
//! (`SimulationSettings::project`), and the integrator's drift warnings (bar lengths,
//! N P = D) are part of the run's [`crate::validity::RollValidity::warnings`].
//!
//! The model does not depend on the toroid: [`wheel::WheelScene`] carries any prestressed
//! wheel in its starting pose with its contact groups, and [`FullRolling::run_scene`] runs it
//! (the toroid's [`FullRolling::run_full`] builds its scene with [`FullRolling::scene`]; the
//! T-bar wheel enters the same way).
//!
//! **Start** (the same state as the rigid model): at rest on a side of the contact polygon,
//! prism 0 (uphill) and prism 1 (downhill) on the slope, i.e. the wheel is turned by −π/n
//! about x and the slope is the plane z = −R_o cos(π/n). The contact nodes start at zero
//! penetration (not at the static penetration m g cos φ / (4 k), a fraction of a millimetre
//! for the defaults); the wheel then pivots about the downhill pair. Recorded coordinates
//! are those of the rigid model: s = y − R_o sin(π/n) along the slope (0 at the downhill
//! pair), h = z + R_o cos(π/n) above it.
//!
//! **Contact.** [`ContactModel::Penalty`] (the default): per node, for penetration δ > 0,
//! N = max(0, k δ − c δ̇ₙ) (never negative: a damper that would pull is clipped) and
//! regularised Coulomb friction F_t = −μ(v) N tanh(v/v_reg) v̂ with a Stribeck transition
//! from μ_s to μ_k (see `tensegrity_core::dynamics::Ground`). The normal damping follows
//! from a coefficient of restitution e ([`penalty_damping`]): a linear spring–damper of
//! damping ratio ζ rebounds with e = exp(−ζπ/√(1−ζ²)), so ζ = −ln e / √(π² + ln² e) (ζ = 1
//! for e = 0), and c = ζ √(2 k m_eff) per node for a pair of nodes landing on a rigid wheel
//! of effective mass m_eff = 1 / (1/m + R_o² sin²(π/n) / I₁) at the landing pair.
//! [`ContactModel::Thesis`] reproduces §3.2.2 (weight-based normal reaction plus velocity
//! damping); it can pull and sink, and its runs say so.
//!
//! **Validity** ([`crate::validity::RollValidity`]), from every integration step:
//! the smallest normal force of any loaded contact node, the fraction of time with no node
//! loaded (airborne), the fraction with a loaded node sliding faster than the Stribeck
//! velocity (slip), the deepest penetration, and the energy budget. The budget is
//! E(t) − E(0) = W_nc(t), with E = kinetic + string elastic + gravity + ground-spring
//! (½ k δ²) energy and W_nc = ∫ Σ_contact (F·v − k δ v_n) dt the work of the ground's damping
//! (normal) and friction (tangential); W_nc is integrated by the trapezoidal rule at every
//! step, so the residual max|E − E(0) − W_nc| over the largest energy term (kinetic energy,
//! |E − E(0)|, |W_nc|, and at least the wheel's scale m g R_o) measures the integrator's
//! accuracy. Explicit steps resolve the regularised friction's stick (stiffness
//! μ N / v_reg on a light node) only coarsely: that, not the physics, dominates the residual. A run is flagged when a node sinks deeper than
//! [`defaults::PENETRATION_TOLERANCE`] R_o, the ground pulls, or the budget misses by more
//! than [`defaults::ENERGY_BALANCE_TOLERANCE`].
//!
//! **Impacts**: a contact pair that loads after [`defaults::CONTACT_REARM_TIME`] off the
//! ground is a new contact, unless it leaves the ground again while the previously loaded
//! pairs still carry the wheel (a graze, which takes nothing over). Its record holds the touch-down time, ω (about the axle: the mean
//! over rim joints of ((r − hub) × (v − v_hub))ₓ / ‖r − hub‖², positive rolling downhill)
//! just before, ω at the end of the contact transient (when the previously loaded pairs have
//! left the slope and the new pair's spring has had half a period π √(m_eff / 2k) to take the
//! wheel over, or when the new pair bounces off; at most [`defaults::IMPACT_WINDOW`] after
//! the touch-down), and the integral of the new
//! pair's contact force over that transient (normal and tangential impulse).

mod monitor;
pub mod wheel;

use crate::analysis::{prestress_design, prestressed_structure};
use crate::builder::Toroid;
use crate::defaults;
use crate::error::{Result, ToroidError};
use crate::rolling::RollingResult;
use nalgebra::{Rotation3, Vector3};
use std::f64::consts::PI;
use tensegrity_core::dynamics::IntegratorKind;
pub use wheel::WheelScene;

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
}

/// Relative tolerance of the adaptive integrators (rk45, sdirk) in a rolling run: positions
/// to about 1 µm on a metre-sized wheel.
pub const ADAPTIVE_RTOL: f64 = 1e-6;
/// Absolute tolerance of the adaptive integrators in a rolling run.
pub const ADAPTIVE_ATOL: f64 = 1e-8;

/// Settings of a full-model rolling run.
#[derive(Debug, Clone, PartialEq)]
pub struct FullRolling {
    /// Slope angle φ (rad).
    pub incline: f64,
    /// Gravity g₀ (m/s²).
    pub gravity: f64,
    /// Ground contact.
    pub contact: ContactModel,
    /// String stiffness (N/m).
    pub string_stiffness: f64,
    /// Smallest string tension of the prestress design (N).
    pub min_string_tension: f64,
    /// Integrator.
    pub integrator: IntegratorKind,
    /// Step of the fixed-step integrators, largest step of RK45 (s).
    pub dt: f64,
    /// Output interval (s).
    pub output_dt: f64,
    /// Times (s) at which to keep the node positions (see [`FullRun::frames`]).
    pub frame_times: Vec<f64>,
}

impl ContactModel {
    /// The thesis contact with the default damping [`defaults::GROUND_DAMPING`].
    pub const THESIS: ContactModel = ContactModel::Thesis {
        damping: defaults::GROUND_DAMPING,
    };

    /// The penalty ground with the defaults of [`crate::defaults`]: stiffness 10⁵ N/m,
    /// damping 200 N·s/m, μ_s = 0.8 and μ_k = 0.75 μ_s = 0.6 (the request-level default,
    /// [`crate::RollRequest`], derives the damping from e = 0 instead).
    pub const PENALTY: ContactModel = ContactModel::Penalty {
        stiffness: defaults::GROUND_STIFFNESS,
        damping: defaults::GROUND_DAMPING,
        mu_static: defaults::STATIC_FRICTION,
        mu_kinetic: defaults::KINETIC_FRICTION_RATIO * defaults::STATIC_FRICTION,
    };
}

/// The damping ratio ζ of a linear spring–damper that rebounds with restitution `e`
/// (e = exp(−ζπ/√(1−ζ²)) inverted; ζ = 1 for e = 0, the clipped critical damper).
///
/// ```
/// use toroid::rolling_full::damping_ratio;
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
/// use toroid::rolling_full::penalty_damping;
/// // e = 0: critical damping of the pair, 2c = 2√(2k m)
/// assert!((penalty_damping(0.0, 1e5, 10.0) - (2e6f64).sqrt()).abs() < 1e-9);
/// ```
pub fn penalty_damping(e: f64, stiffness: f64, effective_mass: f64) -> f64 {
    damping_ratio(e) * (2.0 * stiffness * effective_mass).sqrt()
}

impl Default for FullRolling {
    /// 50° slope, penalty ground ([`ContactModel::PENALTY`]), strings 2·10⁴ N/m with a 20 N
    /// minimum prestress, RK4 at 0.1 ms, 1 ms output (the values of [`crate::defaults`]).
    fn default() -> Self {
        Self {
            incline: defaults::INCLINE_DEG.to_radians(),
            gravity: defaults::GRAVITY,
            contact: ContactModel::PENALTY,
            string_stiffness: defaults::STRING_STIFFNESS,
            min_string_tension: defaults::ROLL_MIN_TENSION,
            integrator: IntegratorKind::Rk4,
            dt: defaults::ROLL_DT,
            output_dt: defaults::ROLL_OUTPUT_DT,
            frame_times: Vec::new(),
        }
    }
}

/// A snapshot of the wheel's nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct WheelFrame {
    /// Time (s).
    pub t: f64,
    /// Node positions (file numbering of the toroid) in slope coordinates: x along the axle,
    /// y = s along the slope (downhill, 0 at the starting downhill pair), z = h above it (m).
    pub nodes: Vec<Vector3<f64>>,
}

/// A full-model run: the rolling result plus what only this model measures.
#[derive(Debug, Clone, PartialEq)]
pub struct FullRun {
    /// Samples, summary, impacts and validity.
    pub result: RollingResult,
    /// Node frames at the requested [`FullRolling::frame_times`] (the nearest step).
    pub frames: Vec<WheelFrame>,
    /// Work of the ground's normal damping (J, ≤ 0 when it dissipates).
    pub damping_work: f64,
    /// Work of the ground's friction (J).
    pub friction_work: f64,
    /// Wall-clock time of the integration (s).
    pub wall_time_s: f64,
}

impl FullRolling {
    /// Rolls `toroid` for `t_end` seconds from rest on a side (see the module docs).
    pub fn run(&self, toroid: &Toroid, t_end: f64) -> Result<RollingResult> {
        Ok(self.run_full(toroid, t_end)?.result)
    }

    /// As [`FullRolling::run`], with frames and the ground's work: the toroid's
    /// [`WheelScene`] ([`FullRolling::scene`]) run by [`FullRolling::run_scene`].
    pub fn run_full(&self, toroid: &Toroid, t_end: f64) -> Result<FullRun> {
        self.validate(t_end)?;
        let scene = self.scene(toroid)?;
        self.run_scene(&scene, t_end)
    }

    fn validate(&self, t_end: f64) -> Result<()> {
        for (name, v) in [
            ("gravity", self.gravity),
            ("dt", self.dt),
            ("output_dt", self.output_dt),
            ("t_end", t_end),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(ToroidError::InvalidParameter(
                    tensegrity_core::request::InvalidParameter::new(name, v, "must be positive"),
                ));
            }
        }
        if !(self.incline.is_finite() && self.incline.abs() < std::f64::consts::FRAC_PI_2) {
            return Err(ToroidError::InvalidParameter(
                tensegrity_core::request::InvalidParameter::new(
                    "incline",
                    self.incline,
                    "must lie in (−π/2, π/2)",
                ),
            ));
        }
        Ok(())
    }

    /// The toroid as a [`WheelScene`]: the prestressed structure (prestress design with
    /// [`FullRolling::min_string_tension`], strings of [`FullRolling::string_stiffness`])
    /// turned by −π/n about x onto the side of prisms 0 and 1; contact group k = the outer
    /// tread nodes n1, n2 of prism k; ω from the rim joints n3; the axle ends as the hub.
    pub fn scene(&self, toroid: &Toroid) -> Result<WheelScene> {
        let design = prestress_design(toroid, self.min_string_tension)?;
        let n = toroid.params.sides;
        let turn = Rotation3::from_axis_angle(&Vector3::x_axis(), -PI / n as f64);
        let prestressed = prestressed_structure(toroid, &design, self.string_stiffness)?;
        let nodes = prestressed.nodes().iter().map(|p| turn * p).collect();
        let s = &toroid.structure;
        Ok(WheelScene {
            structure: prestressed.with_nodes(nodes)?,
            contact_groups: (0..n).map(|k| vec![5 * k, 5 * k + 1]).collect(),
            rim: (0..n).map(|k| 5 * k + 2).collect(),
            axle: toroid.axle,
            outer_radius: toroid.params.outer_radius,
            mass: crate::wheel_mass(s),
            i1: crate::wheel_inertia(s)[(0, 0)],
        })
    }
}

/// Which model a rolling run uses; serialises as `"rigid"` or `"full"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Fidelity {
    /// The reduced rigid polygon ([`crate::rolling::RigidRolling`]).
    Rigid,
    /// The full tensegrity dynamics ([`FullRolling`]).
    Full,
}

/// The strain ε = m g / (k R_o) that one string of stiffness k would take carrying the whole
/// wheel weight over the wheel radius: a cheap measure of how much the wheel deforms.
pub fn deformation_measure(
    mass: f64,
    gravity: f64,
    string_stiffness: f64,
    outer_radius: f64,
) -> f64 {
    mass * gravity / (string_stiffness * outer_radius)
}

/// Below this [`deformation_measure`] the `auto` fidelity considers the rigid model.
pub const RIGID_THRESHOLD: f64 = 1e-3;

/// The fidelity the stiffness alone allows: rigid when [`deformation_measure`] <
/// [`RIGID_THRESHOLD`] (`auto` also needs the rigid run to be valid, see [`crate::roll`]).
///
/// ```
/// use toroid::rolling_full::{auto_fidelity, Fidelity};
/// assert_eq!(auto_fidelity(14.4, 9.81, 2e4, 1.0), Fidelity::Full);
/// assert_eq!(auto_fidelity(14.4, 9.81, 2e6, 1.0), Fidelity::Rigid);
/// ```
pub fn auto_fidelity(
    mass: f64,
    gravity: f64,
    string_stiffness: f64,
    outer_radius: f64,
) -> Fidelity {
    if deformation_measure(mass, gravity, string_stiffness, outer_radius) < RIGID_THRESHOLD {
        Fidelity::Rigid
    } else {
        Fidelity::Full
    }
}
