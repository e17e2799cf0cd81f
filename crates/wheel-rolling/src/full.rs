//! The full tensegrity model: a prestressed wheel rolling down an incline.
//!
//! The prestressed wheel of a [`WheelScene`] (bars rigid with mass, strings linear elastic
//! with the rest lengths that realise a prestress) is integrated with the core's rigid-bar
//! dynamics N̈M + NK = W + ΩPᵀ (class-k joints as constrained class-1 copies). In the wheel
//! frame the wheel turns about the x axis and gravity is tilted by the slope angle φ:
//! g = g₀ (0, sin φ, −cos φ), so the wheel rolls towards +y. Only the nodes of the scene's
//! contact groups (the toroid: the outer tread nodes n1, n2 of every prism; the T-bar wheel:
//! the tread tips) can touch the slope.
//!
//! **Rigid bars.** RK4 alone lets bar lengths drift (5·10⁻³ relative in 3 s of the default
//! run), so the state is projected back onto the bar lengths and joints after every step
//! (`SimulationSettings::project`), and the integrator's drift warnings (bar lengths,
//! N P = D) are part of the run's [`crate::validity::RollValidity::warnings`].
//!
//! The model does not know the wheel's topology: [`WheelScene`] carries any prestressed
//! wheel in its starting pose with its contact groups, and [`FullRolling::run_scene`] runs it
//! (the toroid and the T-bar wheel each build their scene).
//!
//! **Start** (the same state as the rigid model): at rest on a side of the contact polygon,
//! contact group 0 (uphill) and group 1 (downhill) on the slope (the toroid: its prisms 0 and
//! 1, the wheel turned by −π/n about x), the slope the plane z = −R_o cos(π/n). A stiff wheel
//! ([`FullStart::Auto`], the default: m g/(k R_o) < 10⁻³) starts **at rest in its deformed
//! shape under gravity** (module `rest`): where it pivots, the shape in which every node
//! accelerates as the rigid pivot about the downhill pair with the uphill pair just touching;
//! where it rests, its static equilibrium on both pairs. A flexible wheel (and
//! [`FullStart::Unloaded`], and the thesis contact) starts in the scene's unloaded shape at
//! zero penetration and sags into the ground at the release. Recorded coordinates
//! are those of the rigid model: s = y − R_o sin(π/n) along the slope (0 at the downhill
//! pair), h = z + R_o cos(π/n) above it.
//!
//! **Contact.** [`crate::ContactModel::Stick`] (`contact = stick`) is the penalty normal force below
//! with friction that sticks: an elastic–plastic tangential spring per node, anchored where the
//! node touched, capped at μ_s N (μ_k N while it slides), with k_t =
//! [`defaults::TANGENTIAL_STIFFNESS_RATIO`] k and the critical c_t
//! ([`crate::contact::stick_damping`]); equations in `tensegrity_dynamics::stick`.
//! [`crate::ContactModel::Penalty`] (the default): per node, for penetration δ > 0,
//! N = max(0, k δ − c δ̇ₙ) (never negative: a damper that would pull is clipped) and
//! regularised Coulomb friction F_t = −μ(v) N tanh(v/v_reg) v̂ with a Stribeck transition
//! from μ_s to μ_k (see `tensegrity_dynamics::Ground`). The normal damping follows
//! from a coefficient of restitution e ([`crate::contact::penalty_damping`]): a linear spring–damper of
//! damping ratio ζ rebounds with e = exp(−ζπ/√(1−ζ²)), so ζ = −ln e / √(π² + ln² e) (ζ = 1
//! for e = 0), and c = ζ √(2 k m_eff) per node for a pair of nodes landing on a rigid wheel
//! of effective mass m_eff = 1 / (1/m + R_o² sin²(π/n) / I₁) at the landing pair.
//! [`crate::ContactModel::Thesis`] reproduces §3.2.2 (weight-based normal reaction plus velocity
//! damping); it can pull and sink, and its runs say so.
//!
//! **Validity** ([`crate::validity::RollValidity`]), from every integration step:
//! the smallest normal force of any loaded contact node, the fraction of time with no node
//! loaded (airborne), the fraction with the contact sliding — its load-weighted slip speed
//! Σ f_n |v_t| / Σ f_n over the loaded nodes faster than the Stribeck velocity (slip; a
//! landing or lifting node carries no load, and its slide under a vanishing cap μ f_n, whose
//! duration follows the penalty's stiffness, is not the wheel's) — the deepest penetration, and the energy budget. The budget is
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
//! ground is a new contact (a pair that carried the wheel before a flight needs
//! [`defaults::IMPACT_WINDOW`] off: a sliding pivot's short hops are not impacts), unless it
//! leaves the ground again, for at least that re-arm time, while the previously loaded pairs
//! still carry the wheel (a graze, which takes nothing over and is never recorded; a shorter
//! lift-off is the penalty spring's chatter at the touch-down and the impact goes on). Its
//! record holds the touch-down time, ω (about the axle: the mean
//! over rim joints of ((r − hub) × (v − v_hub))ₓ / ‖r − hub‖², positive rolling downhill)
//! just before, ω at the end of the contact transient (when the previously loaded pairs have
//! left the slope and the new pair's spring has had half a period π √(m_eff / 2k) to take the
//! wheel over, or when the new pair bounces off; at most [`defaults::IMPACT_WINDOW`] after
//! the touch-down), and the integral of the new
//! pair's contact force over that transient (normal and tangential impulse).

mod integrate;
mod monitor;
mod rest;
mod scene;

use crate::contact::ContactModel;
use crate::defaults;
pub use crate::frame::WheelFrame;
use crate::observer::Observer;
use crate::polygon::Polygon;
use crate::sample::RollingResult;
use crate::settings::RunSpec;
pub use rest::{FullStart, Settled};
pub use scene::WheelScene;
use tensegrity_dynamics::IntegratorKind;

/// Settings of a full-model rolling run.
#[derive(Debug, Clone, PartialEq)]
pub struct FullRolling {
    /// Slope angle φ (rad).
    pub incline: f64,
    /// Gravity g₀ (m/s²).
    pub gravity: f64,
    /// Ground contact.
    pub contact: ContactModel,
    /// Integrator.
    pub integrator: IntegratorKind,
    /// Step of the fixed-step integrators, largest step of RK45 (s).
    pub dt: f64,
    /// Output interval (s).
    pub output_dt: f64,
    /// Times (s) at which to keep the node positions (see [`FullRun::frames`]).
    pub frame_times: Vec<f64>,
    /// How the wheel starts: at rest in its deformed shape under gravity, or released from
    /// its unloaded shape; by default ([`FullStart::Auto`]) at rest when the wheel is stiff
    /// (module `rest`).
    pub start: FullStart,
}

impl Default for FullRolling {
    /// 50° slope, penalty ground ([`ContactModel::PENALTY`]), RK4 at 0.1 ms, 1 ms output (the
    /// values of [`crate::defaults`]).
    fn default() -> Self {
        Self {
            incline: defaults::INCLINE_DEG.to_radians(),
            gravity: defaults::GRAVITY,
            contact: ContactModel::PENALTY,
            integrator: IntegratorKind::Rk4,
            dt: defaults::ROLL_DT,
            output_dt: defaults::ROLL_OUTPUT_DT,
            frame_times: Vec::new(),
            start: FullStart::Auto,
        }
    }
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
    /// The relaxation to the start at rest ([`FullStart::Rest`]); `None` when the wheel
    /// started unloaded.
    pub settled: Option<Settled>,
}

impl FullRolling {
    /// The full model of `spec` for a wheel of `polygon` (its contact from
    /// [`ContactModel::of`]).
    pub fn new(spec: &RunSpec, polygon: &Polygon) -> Self {
        Self {
            incline: spec.settings.incline,
            gravity: spec.settings.gravity,
            contact: ContactModel::of(spec, polygon),
            integrator: spec.integrator,
            dt: spec.full_dt(),
            output_dt: spec.output_dt,
            frame_times: Vec::new(),
            start: FullStart::Auto,
        }
    }

    /// Rolls the wheel of `scene` for `t_end` seconds from rest on its starting side (see
    /// the module docs).
    pub fn run_scene(&self, scene: &WheelScene, t_end: f64) -> crate::Result<FullRun> {
        self.run_scene_observed(scene, t_end, None)
    }

    /// As [`FullRolling::run_scene`], handing every sample and frame to `observer` as it is
    /// made (see [`crate::observer`]).
    pub fn run_scene_observed(
        &self,
        scene: &WheelScene,
        t_end: f64,
        observer: Option<&mut dyn Observer>,
    ) -> crate::Result<FullRun> {
        self.validate(t_end)?;
        scene.validate()?;
        integrate::run(self, scene, t_end, observer)
    }

    /// The fastest rate λ (1/s) the explicit part of its integrator must resolve on the wheel
    /// of `scene` under its ground ([`tensegrity_dynamics::convergence::explicit_rate`]): the
    /// strings and the ground's springs, and the ground's dampers where the method treats them
    /// explicitly (not under IMEX and IMEX-ARK). What decides whether the convergence check's
    /// coarse companion serves ([`crate::convergence`]).
    pub fn explicit_rate(&self, scene: &WheelScene) -> crate::Result<f64> {
        let (structure, ground) = integrate::scene_model(self, scene)?;
        let model = tensegrity_dynamics::Model::new(&structure, Some(ground))?;
        Ok(tensegrity_dynamics::convergence::explicit_rate(
            &model,
            self.integrator,
        ))
    }

    fn validate(&self, t_end: f64) -> crate::Result<()> {
        for (name, v) in [
            ("gravity", self.gravity),
            ("dt", self.dt),
            ("output_dt", self.output_dt),
            ("t_end", t_end),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(crate::RollingError::invalid(name, v, "must be positive"));
            }
        }
        if !(self.incline.is_finite() && self.incline.abs() < std::f64::consts::FRAC_PI_2) {
            return Err(crate::RollingError::invalid(
                "incline",
                self.incline,
                "must lie in (−π/2, π/2)",
            ));
        }
        Ok(())
    }
}
